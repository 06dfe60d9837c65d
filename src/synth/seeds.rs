//! One unit's place-and-routes of one seed each (a sweep's jobs) as the one result `synth
//! --seeds K` writes for them: what `report --hw` and the benches read.

use super::{median, seed_list, SynthResult};

impl SynthResult {
    /// The results of one unit synthesized alike and placed with one seed each, in seed order,
    /// as one over all the seeds: every seed's figure (nextpnr's and capped), their medians,
    /// what limits the clock, icetime's figures, and the note's seed list. The area figures
    /// are the first's (one netlist). A failed place-and-route makes the whole one failed, its
    /// note said. None for no results.
    pub fn over_seeds(results: &[SynthResult]) -> Option<SynthResult> {
        let first = results.first()?;
        let mut r = first.clone();
        if let Some(failed) = results.iter().find(|x| x.fmax_mhz.is_none()) {
            r.fmax_mhz = None;
            r.fmax_route_mhz = None;
            r.fmax_note = failed.fmax_note.clone();
            return Some(r);
        }
        r.seeds = results
            .iter()
            .flat_map(|x| x.seeds.iter().copied())
            .collect();
        r.fmax_seeds = results
            .iter()
            .flat_map(|x| x.fmax_seeds.iter().copied())
            .collect();
        r.fmax_seeds_capped = results
            .iter()
            .flat_map(|x| x.fmax_seeds_capped.iter().copied())
            .collect();
        r.icetime_seeds = results
            .iter()
            .flat_map(|x| x.icetime_seeds.iter().copied())
            .collect();
        r.icetime_mhz = median(&r.icetime_seeds);
        r.fmax_route_mhz = median(&r.fmax_seeds);
        // each seed is capped by the same limits, and capping keeps the order: the capped
        // median is the median's cap
        r.fmax_mhz = median(&r.fmax_seeds_capped);
        let capped = matches!((r.fmax_mhz, r.fmax_route_mhz), (Some(f), Some(route)) if f < route);
        r.fmax_limited_by = match capped {
            true => results
                .iter()
                .map(|x| &x.fmax_limited_by)
                .find(|w| !w.starts_with("routing"))
                .cloned()
                .unwrap_or_default(),
            false => "routing (nextpnr)".into(),
        };
        // "…, median of seeds S (F), unit between…": every seed's
        if let (Some(at), Some(end)) = (
            r.fmax_note.find("median of seeds "),
            r.fmax_note.find("), unit between"),
        ) {
            let figures = r
                .fmax_seeds
                .iter()
                .map(|f| format!("{f:.1}"))
                .collect::<Vec<_>>()
                .join(", ");
            r.fmax_note.replace_range(
                at..end,
                &format!("median of seeds {} ({figures}", seed_list(&r.seeds)),
            );
        }
        Some(r)
    }
}
