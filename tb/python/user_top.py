"""A user's design around a generated unit, in Amaranth or LiteX, converted to Verilog.

    python3 user_top.py amaranth|litex UNIT_DIR OUT_DIR [--wrong-width]

The top drives the unit's sink from a counter (cos_g, n and the colours step through their
codes) whenever a pseudo-random bit says the producer has a pixel, and takes the source's
results when another pseudo-random bit says the consumer is ready (back-pressure). It writes
OUT_DIR/user_top.v (the top, converted by the package's own back end) and OUT_DIR/user_tb.v,
an Icarus testbench that prints every accepted input ("I cos_g n ks_r ks_g ks_b") and every
accepted result ("O intensity spec_r spec_g spec_b done") in order, and "S" for each cycle the
consumer held a valid result back. With --wrong-width the producer's cos_g is one bit wider
than the unit's: the connection is refused at elaboration.
"""
import importlib.util
import json
import sys
from pathlib import Path

kind, unit_dir, out_dir = sys.argv[1], Path(sys.argv[2]).resolve(), Path(sys.argv[3])
wrong = "--wrong-width" in sys.argv
manifest = next(p for p in unit_dir.glob("*.json"))
top_name = json.loads(manifest.read_text())["top"]
spec = importlib.util.spec_from_file_location("unit_wrapper", unit_dir / f"{top_name}_{kind}.py")
wrapper = importlib.util.module_from_spec(spec)
spec.loader.exec_module(wrapper)
UNIT = wrapper.UNIT
fields_in = [f for f in UNIT["sink"]]
fields_out = [f for f in UNIT["source"]]
LOG_IN = ["cos_g", "n", "ks_r", "ks_g", "ks_b"]
LOG_OUT = ["intensity", "spec_r", "spec_g", "spec_b", "done"]
width = {f["field"]: f["width"] for f in fields_in + fields_out}
# the wrapper's one class: the unit
unit_class = next(v for v in vars(wrapper).values() if isinstance(v, type) and v.__module__ == wrapper.__name__)

if kind == "amaranth":
    from amaranth.hdl import Module, Signal, Cat
    from amaranth.lib import data, stream, wiring
    from amaranth.lib.wiring import In, Out
    from amaranth.back import verilog

    class Top(wiring.Component):
        def __init__(self):
            members = {"in_fire": Out(1), "out_fire": Out(1), "stall": Out(1)}
            for f in LOG_IN + LOG_OUT:
                members[f"log_{f}"] = Out(width[f])
            super().__init__(members)

        def elaborate(self, platform):
            m = Module()
            m.submodules.spec = spec = unit_class()
            layout = {f["field"]: f["width"] + (1 if wrong and f["field"] == "cos_g" else 0) for f in fields_in}
            producer = stream.Signature(data.StructLayout(layout)).create()
            lfsr = Signal(16, init=0xACE1)
            m.d.sync += lfsr.eq(Cat(lfsr[1:], lfsr[0] ^ lfsr[2] ^ lfsr[3] ^ lfsr[5]))
            count = Signal(24)
            m.d.comb += producer.valid.eq(lfsr[0] | lfsr[7])
            for f in fields_in:
                if f["field"] == "cos_g":
                    m.d.comb += producer.payload.cos_g.eq(count)
                elif f["field"] == "n":
                    m.d.comb += producer.payload.n.eq(count >> width["cos_g"] - 2)
                elif f["field"].startswith("ks"):
                    m.d.comb += getattr(producer.payload, f["field"]).eq(count * 7 + {"ks_r": 1, "ks_g": 3, "ks_b": 5}[f["field"]])
            with m.If(producer.valid & producer.ready):
                m.d.sync += count.eq(count + 1)
            wiring.connect(m, producer, spec.sink)
            if not spec.source.signature.always_ready:
                m.d.comb += spec.source.ready.eq(lfsr[3] | lfsr[11])
            m.d.comb += [
                self.in_fire.eq(spec.sink.valid & spec.sink.ready),
                self.out_fire.eq(spec.source.valid & spec.source.ready),
                self.stall.eq(spec.source.valid & ~spec.source.ready),
            ]
            for f in LOG_IN:
                m.d.comb += getattr(self, f"log_{f}").eq(getattr(spec.sink.payload, f))
            for f in LOG_OUT:
                m.d.comb += getattr(self, f"log_{f}").eq(getattr(spec.source.payload, f))
            return m

    text = verilog.convert(Top(), name="user_top")
    clock, reset = "clk", "rst"
else:
    from migen import Module, Signal, Cat, If
    from migen.fhdl.verilog import convert
    from litex.soc.interconnect import stream


    class Top(Module):
        def __init__(self):
            self.submodules.spec = spec = unit_class()
            layout = [(f["field"], f["width"] + (1 if wrong and f["field"] == "cos_g" else 0)) for f in fields_in if f["field"] != "last"]
            producer = stream.Endpoint(layout)
            lfsr = Signal(16, reset=0xACE1)
            self.sync += lfsr.eq(Cat(lfsr[1:], lfsr[0] ^ lfsr[2] ^ lfsr[3] ^ lfsr[5]))
            count = Signal(24)
            self.comb += producer.valid.eq(lfsr[0] | lfsr[7])
            for f in fields_in:
                if f["field"] == "cos_g":
                    self.comb += producer.cos_g.eq(count)
                elif f["field"] == "n":
                    self.comb += producer.n.eq(count >> width["cos_g"] - 2)
                elif f["field"].startswith("ks"):
                    self.comb += getattr(producer, f["field"]).eq(count * 7 + {"ks_r": 1, "ks_g": 3, "ks_b": 5}[f["field"]])
            self.sync += If(producer.valid & producer.ready, count.eq(count + 1))
            self.comb += spec.connect_from(producer)
            self.comb += spec.source.ready.eq(lfsr[3] | lfsr[11] if UNIT["out_ready"] else 1)
            self.in_fire, self.out_fire, self.stall = Signal(name="in_fire"), Signal(name="out_fire"), Signal(name="stall")
            self.comb += [
                self.in_fire.eq(spec.sink.valid & spec.sink.ready),
                self.out_fire.eq(spec.source.valid & spec.source.ready),
                self.stall.eq(spec.source.valid & ~spec.source.ready),
            ]
            self.logs = {}
            for f in LOG_IN:
                s = Signal(width[f], name=f"log_{f}")
                self.comb += s.eq(getattr(spec.sink, f))
                self.logs[f] = s
            for f in LOG_OUT:
                s = Signal(width[f], name=f"log_{f}")
                self.comb += s.eq(getattr(spec.source, f))
                self.logs[f] = s

    t = Top()
    ios = {t.in_fire, t.out_fire, t.stall, *t.logs.values()}
    out = convert(t, ios=ios, name="user_top")
    text = str(out)
    clock, reset = "sys_clk", "sys_rst"

out_dir.mkdir(parents=True, exist_ok=True)
(out_dir / "user_top.v").write_text(text)
conns = ", ".join([f".{clock}(clk)", f".{reset}(rst)", ".in_fire(in_fire)", ".out_fire(out_fire)", ".stall(stall)"] + [f".log_{f}(log_{f})" for f in LOG_IN + LOG_OUT])
decls = "\n".join(f"  wire [{width[f] - 1}:0] log_{f};" for f in LOG_IN + LOG_OUT)
ins = " ".join("%0d" for _ in LOG_IN)
outs = " ".join("%0d" for _ in LOG_OUT)
(out_dir / "user_tb.v").write_text(f"""`timescale 1ns/1ps
module user_tb;
  reg clk = 0, rst = 1;
  wire in_fire, out_fire, stall;
{decls}
  user_top dut ({conns});
  integer cycle = 0;
  always #5 clk = ~clk;
  always @(posedge clk) begin
    cycle <= cycle + 1;
    if (cycle == 4) rst <= 0;
    if (!rst) begin
      if (in_fire) $display("I {ins}", {", ".join("log_" + f for f in LOG_IN)});
      if (out_fire) $display("O {outs}", {", ".join("log_" + f for f in LOG_OUT)});
      if (stall) $display("S");
    end
    if (cycle == 3000) $finish;
  end
endmodule
""")
print(f"wrote {out_dir / 'user_top.v'} and user_tb.v")
