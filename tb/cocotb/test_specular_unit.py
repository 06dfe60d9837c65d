"""cocotb test: the unit against golden vectors from `specgen vectors` (CSV).

Every row's inputs are applied with in_valid = 1, one per clock for a pipelined unit, and
every output is compared with the row's expected value at the time the vectors' header
states: for latency L, after the L-th rising edge counted from the one that samples the row.
out_valid is checked too (0 while the pipeline fills after reset, 1 for every row).
A `ready` or `axis` unit (manifest `interface`) is driven as a stream instead: rows offered in
order with random gaps (in_valid never drops before its transfer), out_ready stalled at random
(full rate, every other cycle, long stalls), and every result checked once, in order, with its
tag (the row's index), and unchanged while stalled. `axis` fields are packed and unpacked at
the manifest's `tdata` offsets. A static colour is loaded through ks_load while idle.
Environment: SPECGEN_RTL_DIR (the unit's directory), SPECGEN_VECTORS_FILE (the CSV), and
optionally SPECGEN_MAX_ROWS (check only the first rows).
"""
import csv
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from specgen_manifest import check

INPUTS = ["cos_g", "n", "ks_r", "ks_g", "ks_b"]
OUTPUTS = ["intensity", "spec_r", "spec_g", "spec_b", "done"]


def load_vectors(path):
    with open(path) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    reader = csv.reader(lines)
    header = next(reader)
    missing = [p for p in INPUTS + OUTPUTS if p not in header]
    assert not missing, f"{path}: no column for {missing} (header {header})"
    return [dict(zip(header, map(int, row))) for row in reader]


def value(signal):
    v = signal.value
    return int(v) if v.is_resolvable else None


def rows_and_manifest():
    # the files, the unit's header and the vectors must all be of the manifest's configuration
    info = check(os.environ["SPECGEN_RTL_DIR"], os.environ["SPECGEN_VECTORS_FILE"])
    rows = load_vectors(os.environ["SPECGEN_VECTORS_FILE"])
    limit = int(os.environ.get("SPECGEN_MAX_ROWS", "0") or 0)
    if limit:
        rows = rows[:limit]
    assert rows, "no vectors"
    return info, rows


class Ports:
    """The unit's ports under the names of its interface, fields packed per the manifest."""

    def __init__(self, dut, info):
        self.dut = dut
        self.axis = info.get("interface") == "axis"
        self.tag_bits = info.get("tag_bits", 0)
        self.static = info.get("colour") == "static"
        self.s_fields = info["tdata"]["s_axis"] if self.axis else None
        self.m_fields = info["tdata"]["m_axis"] if self.axis else None
        n = (lambda a, b: a if self.axis else b)
        self.clk = getattr(dut, n("aclk", "clk"))
        self.in_valid = getattr(dut, n("s_axis_tvalid", "in_valid"))
        handshake = info.get("interface", "valid") != "valid"
        # a valid unit has no ready ports: the producer is always taken, the consumer always ready
        self.in_ready = getattr(dut, n("s_axis_tready", "in_ready")) if handshake else None
        self.out_valid = getattr(dut, n("m_axis_tvalid", "out_valid"))
        self.out_ready = getattr(dut, n("m_axis_tready", "out_ready")) if handshake else None
        self.in_tag = getattr(dut, n("s_axis_tuser", "in_tag")) if self.tag_bits else None
        self.out_tag = getattr(dut, n("m_axis_tuser", "out_tag")) if self.tag_bits else None
        if info.get("clock_enable"):
            # the clock enable stays high: every edge is one the stream moves on
            getattr(dut, n("aclken", "clk_en")).value = 1

    def reset(self, on):
        if self.axis:
            self.dut.aresetn.value = 0 if on else 1
        else:
            self.dut.rst.value = 1 if on else 0

    def offer(self, row, tag):
        names = ["cos_g", "n"] + ([] if self.static else ["ks_r", "ks_g", "ks_b"])
        if self.axis:
            word = 0
            for f in self.s_fields:
                word |= row[f["name"]] << f["lo"]
            self.dut.s_axis_tdata.value = word
        else:
            for p in names:
                getattr(self.dut, p).value = row[p]
        if self.in_tag is not None:
            self.in_tag.value = tag & ((1 << self.tag_bits) - 1)

    def result(self):
        """The outputs now, by port name (None where unresolvable), and the tag."""
        if self.axis:
            word = value(self.dut.m_axis_tdata)
            out = {f["name"]: None if word is None else (word >> f["lo"]) & ((1 << f["width"]) - 1) for f in self.m_fields}
        else:
            out = {p: value(getattr(self.dut, p)) for p in OUTPUTS}
        tag = value(self.out_tag) if self.out_tag is not None else 0
        return out, tag


async def stream(dut, info, rows):
    """A ready/axis unit under random backpressure: every result once, in order, stable."""
    io = Ports(dut, info)
    rng = random.Random(1)
    mask = (1 << io.tag_bits) - 1
    cocotb.start_soon(Clock(io.clk, 10, units="ns").start())
    io.in_valid.value = 0
    if io.out_ready is not None:
        io.out_ready.value = 0
    if io.static:
        dut.ks_load.value = 0
    io.reset(True)
    for _ in range(2):
        await RisingEdge(io.clk)
    await FallingEdge(io.clk)
    io.reset(False)
    sent = got = cycle = 0
    material = None
    before = None  # (out_valid, out_ready, outputs, tag) of the last cycle
    offered = False  # in_valid as driven in the last cycle
    in_ready_before = 0  # in_ready in the last cycle (a register: it changes only at edges)
    mismatches = []
    # each iteration runs at a falling edge: the rising edge just passed sampled what was
    # driven in the last iteration, and what is set now is sampled at the next rising edge
    while got < len(rows):
        cycle += 1
        assert cycle < 50 * len(rows) + 1000, f"{got} of {len(rows)} results after {cycle} cycles"
        taken = offered and (io.in_ready is None or in_ready_before == 1)
        sent += taken
        in_ready_before = value(io.in_ready) if io.in_ready is not None else 1
        # the consumer: the result on the ports now, and whether it is taken at the next edge
        out, tag = io.result()
        valid = value(io.out_valid)
        phase = (cycle // 500) % 3
        ready = 1 if io.out_ready is None or phase == 0 else int(rng.random() < (0.5 if phase == 1 else 0.35))
        if io.out_ready is not None:
            io.out_ready.value = ready
        if before and before[0] == 1 and before[1] == 0 and (valid != 1 or (out, tag) != before[2:]):
            mismatches.append(f"cycle {cycle}: the result changed while out_ready was low")
        if valid == 1 and ready == 1:
            want = rows[got]
            bad = [p for p in OUTPUTS if out[p] != want[p]]
            if bad or (io.tag_bits and tag != got & mask):
                mismatches.append(f"result {got}: {out} tag {tag}; expected {[want[p] for p in OUTPUTS]} tag {got & mask}")
            got += 1
        before = (valid, ready, out, tag)
        # the producer: a new offer once the last was taken, after a random gap
        if io.static:
            dut.ks_load.value = 0
        if not offered or taken:
            offered = False
            io.in_valid.value = 0
            if sent < len(rows) and rng.random() < 0.85:
                row = rows[sent]
                colour = (row["ks_r"], row["ks_g"], row["ks_b"])
                if io.static and colour != material:
                    # a new colour: only while idle, with nothing taken at the next edge
                    if value(dut.idle) == 1 and not taken:
                        dut.ks_r.value, dut.ks_g.value, dut.ks_b.value = colour
                        dut.ks_load.value = 1
                        material = colour
                else:
                    io.offer(row, sent)
                    io.in_valid.value = 1
                    offered = True
        await FallingEdge(io.clk)
    dut._log.info(f"{len(rows)} results in {cycle} cycles under backpressure: {len(mismatches)} mismatches")
    assert not mismatches, f"{len(mismatches)} mismatches; first: " + "; ".join(mismatches[:5])


@cocotb.test()
async def golden_vectors(dut):
    info, rows = rows_and_manifest()
    if info.get("interface", "valid") != "valid" or info.get("colour") == "static":
        await stream(dut, info, rows)
        return
    latency = info["latency"]
    mismatches = []

    def check(i, row):
        if value(dut.out_valid) != 1:
            mismatches.append(f"row {i}: out_valid is {dut.out_valid.value}, expected 1")
        for port in OUTPUTS:
            got = value(getattr(dut, port))
            if got != row[port]:
                inputs = ", ".join(f"{p}={row[p]}" for p in INPUTS)
                mismatches.append(f"row {i} ({inputs}): {port} = {got}, expected {row[port]}")

    def apply(row):
        for port in INPUTS:
            getattr(dut, port).value = row[port]
        dut.in_valid.value = 1

    if latency == 0:
        for i, row in enumerate(rows):
            apply(row)
            await Timer(1, units="ns")
            check(i, row)
    else:
        cocotb.start_soon(Clock(dut.clk, 10, units="ns").start())
        apply(rows[0])
        dut.in_valid.value = 0
        dut.rst.value = 1
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        dut.rst.value = 0
        # iteration t runs after t rising edges since reset; row t is sampled by the next one
        for t in range(len(rows) + latency):
            if t >= latency:
                check(t - latency, rows[t - latency])
            elif value(dut.out_valid) != 0:
                mismatches.append(f"cycle {t} after reset: out_valid is {dut.out_valid.value}, expected 0")
            if t < len(rows):
                apply(rows[t])
            else:
                dut.in_valid.value = 0
            await FallingEdge(dut.clk)
    dut._log.info(f"{len(rows)} vectors, latency {latency}: {len(mismatches)} mismatches")
    assert not mismatches, f"{len(mismatches)} mismatches; first: " + "; ".join(mismatches[:5])
