"""cocotb test: the unit against golden vectors from `specgen vectors` (CSV).

Every row's inputs are applied with in_valid = 1, one per clock for a pipelined unit, and
every output is compared with the row's expected value at the time the vectors' header
states: for latency L, after the L-th rising edge counted from the one that samples the row.
out_valid is checked too (0 while the pipeline fills after reset, 1 for every row).
Environment: SPECGEN_RTL_DIR (the unit's directory), SPECGEN_VECTORS_FILE (the CSV), and
optionally SPECGEN_MAX_ROWS (check only the first rows).
"""
import csv
import os

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge, Timer

from specgen_manifest import manifest

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


@cocotb.test()
async def golden_vectors(dut):
    info = manifest(os.environ["SPECGEN_RTL_DIR"])
    latency = info["latency"]
    rows = load_vectors(os.environ["SPECGEN_VECTORS_FILE"])
    limit = int(os.environ.get("SPECGEN_MAX_ROWS", "0") or 0)
    if limit:
        rows = rows[:limit]
    assert rows, "no vectors"
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
