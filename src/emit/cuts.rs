//! The registered cuts: which signals each holds, and the delay lines of those that only wait.

use super::*;

/// Whether every read of table `t` is a block RAM with its registers (no `$readmemh` memory then).
pub(super) fn block_table(dp: &datapath::Datapath, t: usize) -> bool {
    let mut reads = dp.reads.iter().filter(|r| r.table == t).peekable();
    reads.peek().is_some() && reads.all(|r| r.block)
}

/// Where a signal's chain of registers (its `read` masks per cut) is cut in two for block RAM:
/// each index `k` of a read word, not the last, that ends a stretch of unread words and itself
/// as long as [`DelayLine::memory_tail`] takes into block RAM.
pub(super) fn unread_stretches(read: &[u128], width: u32, memory: bool) -> Vec<usize> {
    let mut out = Vec::new();
    if !memory {
        return out;
    }
    let mut gap_from = 0;
    for (k, &r) in read.iter().enumerate() {
        if r == 0 {
            continue;
        }
        let words = k + 1 - gap_from; // the stretch and the word read at its end
        if k + 1 < read.len()
            && words >= datapath::MEMORY_TAIL_MIN_CUTS
            && width * words as u32 >= datapath::MEMORY_TAIL_MIN_BITS
        {
            out.push(k);
        }
        gap_from = k + 1;
    }
    out
}

/// Adds the chain of `name` through the cuts `at` to the delay line through the same cuts, or
/// as a line of its own, `line`.
#[allow(clippy::too_many_arguments)]
pub(super) fn lines_add(
    lines: &mut Vec<DelayLine>,
    line: &str,
    name: &str,
    width: u32,
    source: &str,
    at: &[usize],
    read: &[u128],
    target: Target,
) {
    let member = Waiting {
        name: name.to_string(),
        width,
        source: source.to_string(),
        read: read.to_vec(),
    };
    match lines.iter_mut().find(|l| l.cuts == at) {
        Some(l) => {
            l.members.push(member);
            l.name = format!("waiting_c{}_c{}", at[0], at[at.len() - 1]);
        }
        None => lines.push(DelayLine {
            name: line.to_string(),
            cuts: at.to_vec(),
            members: vec![member],
            memory: crate::family::of(target).has_block_ram(),
            distributed: crate::family::of(target).distributed_ram(),
        }),
    }
}

/// The registered cuts of a datapath, each with the signals it holds and where from: a signal
/// that only waits (registered at several cuts, each taking the one before) is one
/// [`DelayLine`] at the first of them.
pub(super) fn cut_list(dp: &datapath::Datapath, target: Target) -> Vec<Cut> {
    let mut cuts: Vec<Cut> = (1..=dp.live.len())
        .map(|index| Cut {
            index,
            registered: dp.registered.contains(&(index as u32)),
            signals: Vec::new(),
            lines: Vec::new(),
        })
        .collect();
    // each signal's chain of registers: the cuts holding it, in order, and the first source
    let mut chains: Vec<(String, u32, String, Vec<usize>)> = Vec::new();
    for (k, live) in dp.live.iter().enumerate() {
        let index = k + 1;
        if !cuts[k].registered {
            continue;
        }
        for l in live {
            let continues = chains.iter_mut().rev().find(|c| {
                c.0 == l.name && l.source == format!("{}_c{}", c.0, c.3.last().expect("a cut"))
            });
            match continues {
                Some(c) => c.3.push(index),
                None => chains.push((l.name.clone(), l.width, l.source.clone(), vec![index])),
            }
        }
    }
    // the chains through the same cuts share one delay line (at their first cut)
    let mut lines: Vec<DelayLine> = Vec::new();
    for (name, width, mut source, mut at) in chains {
        // a product's first register is its own (the DSP block's output register), the rest
        // of its wait a delay line (never a same-name copy); kept as a register of its own:
        // yosys 0.23's ice40_dsp, given the product's register with a shift register after
        // it, changes the function (found by `synth --verify` on blinn's x*g_lo), and given a
        // plain second register that only the first feeds, crashes (a segmentation fault)
        let product = at.len() > 1 && dp.products.contains(&name);
        // a multiplier reads the first register: it stays a register of its own, kept out of
        // the DSP block (yosys 0.70's ice40_dsp takes the first flip-flop of a delay line
        // into the block as its input register, and the logic before it becomes the path)
        let operand = at.len() > 1 && dp.read_by_block(&name, at[0]);
        // a copy of a register: its flip-flop kept too ([`datapath::Datapath::copies`])
        let copy = dp.copies.contains(&name);
        if copy {
            // each of its registers a kept flip-flop of its own (a line would hold the three
            // copies' words side by side, where yosys merges them, and its last flip-flop could
            // become the block's input register, far from the first)
            for k in at {
                cuts[k - 1].signals.push(CutSignal {
                    name: name.clone(),
                    width,
                    source,
                    keep: true,
                    copy,
                });
                source = format!("{name}_c{k}");
            }
            continue;
        }
        if product || operand {
            cuts[at[0] - 1].signals.push(CutSignal {
                name: name.clone(),
                width,
                source,
                keep: true,
                copy: false,
            });
            source = format!("{name}_c{}", at[0]);
            at.remove(0);
        }
        if at.len() == 1 && !product && !operand {
            let keep = dp.read_by_block(&name, at[0]);
            cuts[at[0] - 1].signals.push(CutSignal {
                name,
                width,
                source,
                keep,
                copy: false,
            });
            continue;
        }
        let read: Vec<u128> = at
            .iter()
            .map(|k| dp.read.get(&format!("{name}_c{k}")).copied().unwrap_or(0))
            .collect();
        // a long unread stretch before a read that is not the last: the line ends at that read
        // (the stretch its tail, in block RAM where [`DelayLine::memory_tail`] takes it) and the
        // rest is a line of its own, from the word read there
        let (mut from, mut line) = (0, name.clone());
        for k in unread_stretches(&read, width, crate::family::of(target).has_block_ram()) {
            lines_add(
                &mut lines,
                &line,
                &name,
                width,
                &source,
                &at[from..=k],
                &read[from..=k],
                target,
            );
            source = format!("{name}_c{}", at[k]);
            from = k + 1;
            line = format!("{name}_from_c{}", at[from]);
        }
        lines_add(
            &mut lines,
            &line,
            &name,
            width,
            &source,
            &at[from..],
            &read[from..],
            target,
        );
    }
    for l in lines {
        let first = l.cuts[0];
        cuts[first - 1].lines.push(l);
    }
    cuts
}

/// The hard products whose block has no register of its own on the netlist, each with why;
/// empty: the unit promises every block its register (SPEC §7), which `synth` checks. A block
/// the unit instantiates (an ECP5 MULT18X18D) has its registers by construction. An inferred
/// product has one where the family's synthesis takes it into the block
/// ([`crate::family::Family::registers_inferred_blocks`]: yosys's ice40_dsp takes the
/// register after a product, or after its add, when nothing else reads what it holds): the
/// product is one block, no wider than the block's output, registered whole at the cut after
/// its step, read by nothing else in that step, and no operand has constant zero low bits
/// (yosys takes that shift, and the add and the register behind it, out of the block). A
/// register kept in the fabric (`(* keep *)`) is taken all the same.
pub(crate) fn unregistered_products(
    dp: &datapath::Datapath,
    cuts: &[Cut],
    target: Target,
) -> Vec<(String, String)> {
    let family = crate::family::of(target);
    let mut out = Vec::new();
    for s in &dp.steps {
        for w in s.wires.iter().filter(|w| w.product().is_some()) {
            let blocks = dp.product_blocks(&w.name);
            if blocks == 0 {
                continue; // LUTs: no block
            }
            let wire = format!("{}_s{}", w.name, s.index);
            let cut = cuts.get(s.index - 1).filter(|c| c.registered);
            let whole = cut.is_some_and(|c| {
                c.signals
                    .iter()
                    .any(|r| r.name == w.name && r.source == wire)
            });
            let why = if !family.registers_inferred_blocks() {
                format!(
                    "an inferred product: {} maps it without registers",
                    family.name()
                )
            } else if blocks > 1 {
                format!("the synthesis tool splits it over {blocks} blocks, summed in the fabric")
            } else if w.width as u64 > 2 * family.multiplier_bits() as u64 {
                format!("its {} bits run past the block's {}-bit output: the add above them is in the fabric", w.width, 2 * family.multiplier_bits())
            } else if dp.shifted_products.contains(&w.name) {
                "an operand's low bits are constant zeros: the tool shifts outside the block, and adds and registers there".to_string()
            } else if s.wires.iter().any(|o| o.expr.reads.contains(&wire)) {
                format!("logic reads it in its own step ({})", s.index)
            } else if cut.is_none() {
                format!("no register at the cut after its step ({})", s.index)
            } else if !whole {
                "no register of its own holds it whole".to_string()
            } else {
                continue;
            };
            out.push((w.name.clone(), why));
        }
    }
    out
}
