//! The harness's binary records (a cycle's inputs in, its sampled outputs back, in chunks) and
//! a mismatch's trace.

use super::*;

pub(super) const IN_RECORD: usize = 24;

/// An output record: 24 bytes with `out_tag`, 12 without (`-DTAGGED`).
pub(super) fn out_record(tagged: bool) -> usize {
    if tagged {
        24
    } else {
        12
    }
}

/// Cycles a batch: the harness's `BATCH`.
pub(super) const CHUNK: u64 = 1 << 14;

/// The input record's flags byte.
pub(super) fn flags(c: &Cycle) -> u8 {
    c.valid as u8
        | (c.rst as u8) << 1
        | (!c.stall as u8) << 2
        | (c.load as u8) << 3
        | (c.disabled as u8) << 4
}

pub(super) fn encode(c: &Cycle, buf: &mut Vec<u8>) {
    buf.extend_from_slice(&c.inputs.cos_g.to_le_bytes());
    buf.extend_from_slice(&(c.inputs.n as u16).to_le_bytes());
    for k in c.inputs.ks {
        buf.extend_from_slice(&(k as u16).to_le_bytes());
    }
    buf.push(flags(c));
    buf.extend_from_slice(&[0, 0, 0]);
    buf.extend_from_slice(&c.tag.to_le_bytes());
}

/// One cycle folded into a batch's digest of the inputs applied, as the harness folds the cycle
/// it applied (its `applied`, over the input record's fields).
pub(super) fn applied(h: u64, c: &Cycle) -> u64 {
    let [r, g, b] = c.inputs.ks.map(|k| k as u16 as u64);
    let a = c.inputs.cos_g as u64 | (c.inputs.n as u16 as u64) << 32 | (flags(c) as u64) << 48;
    (h.rotate_left(7) ^ a).wrapping_add((r | g << 16 | b << 32) ^ c.tag)
}

pub(super) fn decode(rec: &[u8]) -> Sampled {
    let u16at = |i: usize| u16::from_le_bytes([rec[i], rec[i + 1]]) as u32;
    Sampled {
        outputs: Outputs {
            intensity: u32::from_le_bytes([rec[0], rec[1], rec[2], rec[3]]),
            spec: [u16at(4), u16at(6), u16at(8)],
            done: rec[10] & 2 != 0,
        },
        valid: rec[10] & 1 != 0,
        in_ready: rec[10] & 4 != 0,
        idle: rec[10] & 8 != 0,
        tag: rec
            .get(16..24)
            .map_or(0, |t| u64::from_le_bytes(t.try_into().expect("8 bytes"))),
    }
}

/// Replays a short window around a failure with a tracing build and writes its VCD.
pub fn write_trace(
    design: &Design,
    tools: &SimTools,
    model: &Model,
    stims: &[Box<dyn Stimulus>],
    m: &Mismatch,
    path: &Path,
) -> Result<(), Failure> {
    // a short window: a quick build
    let built = build(design, Simulator::Verilator, tools, true, 0)?;
    let stim = stims[m.run].as_ref();
    let s = design.cfg.latency() as u64;
    let from = m.cycle.saturating_sub(16 + s);
    let to = (m.cycle + 4).min(stim.len() - 1);
    let mut cycles = Vec::new();
    if design.cfg.clocked() {
        cycles.push(Cycle {
            rst: true,
            valid: false,
            ..stim.cycle(from)
        });
    }
    cycles.extend((from..=to).map(|i| stim.cycle(i)));
    // the harness writes into a directory of ours; the trace reaches `path` only when it exists
    let work = crate::process::temp_dir().map_err(|e| error::tool("simulator", e.to_string()))?;
    let vcd = work.path().join("trace.vcd");
    run_one(
        &built,
        design,
        model,
        &Recorded(cycles),
        0,
        &AtomicU64::new(0),
        &[("SPECGEN_VCD", &vcd)],
    )?;
    let bytes = match std::fs::read(&vcd) {
        Ok(b) if !b.is_empty() => b,
        _ => return Err(error::tool("verilator", "the simulator wrote no trace")),
    };
    crate::output::write_file(path, &bytes).map_err(|e| Failure::io("write", path, e))
}
