"""A generated unit built into an iCEBreaker (UP5K) bitstream through Amaranth's own platform.

    python3 icebreaker_top.py UNIT_DIR BUILD_DIR MHZ SEED

The top feeds the unit from a free-running LFSR (every input field a slice of it) and folds every
result, in registered steps, into one register shown on an LED, so nothing of the unit is optimised away and the
wrapper's own logic is a few dozen cells. The unit's clock is the board's oscillator pin,
constrained at MHZ (as `specgen synth` constrains the unit's clock) and placed with SEED,
and the hard multipliers are on (`synth_ice40 -dsp`, as `synth --dsp`). Prints the build
directory's nextpnr log name; the bitstream is BUILD_DIR/top.bin.
"""
import importlib.util
import json
import sys
from pathlib import Path

import copy

from amaranth.build import Clock
from amaranth.hdl import Cat, ClockDomain, Module, Signal
from amaranth.lib import wiring
from amaranth_boards.icebreaker import ICEBreakerPlatform

unit_dir, build_dir, mhz, seed = Path(sys.argv[1]).resolve(), sys.argv[2], sys.argv[3], sys.argv[4]
top_name = json.loads(next(unit_dir.glob("*.json")).read_text())["top"]
spec = importlib.util.spec_from_file_location("unit_wrapper", unit_dir / f"{top_name}_amaranth.py")
wrapper = importlib.util.module_from_spec(spec)
spec.loader.exec_module(wrapper)
unit_class = next(v for v in vars(wrapper).values() if isinstance(v, type) and v.__module__ == wrapper.__name__)


class Top(wiring.Component):
    def __init__(self):
        super().__init__({})

    def elaborate(self, platform):
        m = Module()
        # the sync domain on the oscillator pin, its reset two registers long from power-up
        # (the platform's default domain counts ~10 µs in a 16-bit timer first: its carry
        # chain, not the unit, would set the clock)
        m.domains.sync = sync = ClockDomain("sync")
        m.d.comb += sync.clk.eq(platform.request("clk12", 0).i)
        boot = Signal(2, init=0b11, reset_less=True)
        m.d.sync += boot.eq(boot >> 1)
        m.d.comb += sync.rst.eq(boot[0])
        m.submodules.unit = unit = unit_class()
        lfsr = Signal(32, init=0xACE1_2345)
        m.d.sync += lfsr.eq(Cat(lfsr[1:], lfsr[0] ^ lfsr[10] ^ lfsr[30] ^ lfsr[31]))
        m.d.comb += unit.sink.valid.eq(lfsr[0])
        m.d.comb += unit.sink.payload.as_value().eq(Cat(lfsr, lfsr[::-1]))
        if not unit.source.signature.always_ready:
            m.d.comb += unit.source.ready.eq(lfsr[5])
        # the results folded in registered steps (4 bits a LUT), so the fold is never the
        # critical path: a register of what came out, its 4-bit groups' parities, their parity
        out = unit.source.payload.as_value()
        taken = Signal(len(out))
        m.d.sync += taken.eq(out & unit.source.valid.replicate(len(out)))
        groups = Signal((len(out) + 3) // 4)
        m.d.sync += groups.eq(Cat(taken[i : i + 4].xor() for i in range(0, len(out), 4)))
        parts = Signal((len(groups) + 3) // 4)
        m.d.sync += parts.eq(Cat(groups[i : i + 4].xor() for i in range(0, len(groups), 4)))
        fold = Signal()
        m.d.sync += fold.eq(fold ^ parts.xor())
        m.d.comb += platform.request("led_r", 0).o.eq(fold)
        return m


class Platform(ICEBreakerPlatform):
    """The iCEBreaker with its clock timed at MHZ (where a user's PLL would take it): nextpnr
    places for that clock as `specgen synth` does, not for the oscillator's 12 MHz."""

    resources = [copy.copy(r) for r in ICEBreakerPlatform.resources]
    for r in resources:
        if r.name == "clk12":
            r.clock = Clock(float(mhz) * 1e6)


Platform().build(
    Top(),
    name="top",
    build_dir=build_dir,
    synth_opts="-dsp",
    nextpnr_opts=f"--seed {seed} --timing-allow-fail",
)
print(Path(build_dir) / "top.tim")
