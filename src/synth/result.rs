//! What a synthesis found, told: the result's table, the seeds capped at the blocks' limits,
//! and a log that says the design does not fit.

use super::*;

/// Every seed's figure capped as the median is: none above a limit of a block the unit uses.
pub(crate) fn capped_seeds(seeds: &[f64], limits: &[crate::family::BlockLimit]) -> Vec<f64> {
    seeds
        .iter()
        .map(|&f| crate::family::blocks::limited(f, limits).0)
        .collect()
}

impl SynthResult {
    /// Fmax in words: the median and every seed's range, each capped by the blocks' limits;
    /// where a limit caps any seed, the block and nextpnr's own median and range follow. None
    /// without place-and-route.
    pub fn fmax_text(&self) -> Option<String> {
        let m = self.fmax_mhz?;
        let capped = if self.fmax_seeds_capped.len() == self.fmax_seeds.len() {
            &self.fmax_seeds_capped
        } else {
            &self.fmax_seeds
        };
        let lo = capped.iter().copied().reduce(f64::min)?;
        let hi = capped.iter().copied().reduce(f64::max)?;
        let (raw_lo, raw_hi) = (
            self.fmax_seeds
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min),
            self.fmax_seeds.iter().copied().fold(0.0, f64::max),
        );
        let seeds = self.fmax_seeds.len();
        let route = self.fmax_route_mhz.unwrap_or(m);
        Some(if raw_hi > hi {
            let block = self
                .block_limits
                .iter()
                .filter(|(_, mhz, _)| *mhz <= raw_hi)
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map_or("a block's", |(b, _, _)| b.as_str())
                .to_string();
            format!("{m:.1} median of {seeds} seeds ({lo:.1}–{hi:.1}), each capped by the {block} limit (nextpnr: {route:.1}, {raw_lo:.1}–{raw_hi:.1})")
        } else {
            format!("{m:.1} median of {seeds} seeds ({lo:.1}–{hi:.1})")
        })
    }

    /// Fmax, capped by the blocks' limits (None: no place-and-route, or it failed).
    pub fn fmax(&self) -> Option<f64> {
        self.fmax_mhz
    }
    /// Logic cells after packing (None without place-and-route).
    pub fn cells(&self) -> Option<u64> {
        self.logic_cells
    }
    /// Reads a `specgen synth --json` result: a regular file of at most 1 MiB (never a FIFO or a
    /// device), a JSON object naming a known model and a target, with its LUT count. A manifest,
    /// `{}` or another tool's JSON is refused with the reason.
    pub fn from_file(path: &Path) -> Result<SynthResult, Failure> {
        let text =
            crate::small_file::read(path, 1 << 20).map_err(
                |e| match crate::small_file::refused(&e) {
                    false => input(format!("{} {e}", path.display())),
                    true => input(format!(
                        "{} {e}; allowed a regular file of at most 1 MiB",
                        path.display()
                    )),
                },
            )?;
        let value: serde_json::Value = serde_json::from_str(&text)
            .map_err(|e| input(format!("{} is not JSON: {e}", path.display())))?;
        let not = |why: &str| {
            input(format!(
                "{} is not a `specgen synth --json` result: {why}",
                path.display()
            ))
        };
        let obj = value.as_object().ok_or_else(|| not("not a JSON object"))?;
        if obj.contains_key("generator") || obj.contains_key("ports") {
            return Err(not("it is a unit's manifest"));
        }
        for key in ["model", "target", "luts", "dsp_blocks"] {
            if !obj.contains_key(key) {
                return Err(not(&format!("no \"{key}\"")));
            }
        }
        let r: SynthResult = serde_json::from_value(value).map_err(|e| not(&e.to_string()))?;
        if !crate::config::SpecularModel::ALL
            .iter()
            .any(|m| m.name() == r.model)
        {
            let allowed: Vec<&str> = crate::config::SpecularModel::ALL
                .iter()
                .map(|m| m.name())
                .collect();
            return Err(not(&format!(
                "unknown model {:?}; allowed {}",
                r.model,
                allowed.join(", ")
            )));
        }
        // figures a place-and-route can give: a clock in (0, 1000] MHz, an Fmax in (0, 2000]
        let mhz_ok = |f: f64, max: f64| f.is_finite() && f > 0.0 && f <= max;
        for (key, f, max) in r
            .fmax_mhz
            .iter()
            .chain(&r.fmax_seeds)
            .map(|&f| ("fmax_mhz", f, 2000.0))
            .chain(r.clock_mhz.map(|f| ("clock_mhz", f, 1000.0)))
        {
            if !mhz_ok(f, max) {
                return Err(not(&format!(
                    "{key} {f} is not a clock; allowed (0, {max}] MHz"
                )));
            }
        }
        Ok(r)
    }
}

pub fn table(r: &SynthResult) -> String {
    let mut s = format!(
        "synthesis of {} for {}{}\n",
        r.top,
        r.target,
        if r.dsp { " with DSPs" } else { "" }
    );
    let rows = [
        ("LUT4 / cells", r.luts.to_string()),
        ("carry cells", r.carry_cells.to_string()),
        ("DSP blocks", r.dsp_blocks.to_string()),
        ("flip-flops", r.flip_flops.to_string()),
        (
            "logic cells",
            r.logic_cells
                .map_or("- (after place-and-route)".into(), |c| c.to_string()),
        ),
        ("block RAMs", r.block_rams.to_string()),
        ("ROM bits", r.rom_bits.to_string()),
        (
            "Fmax (MHz)",
            r.fmax_text()
                .unwrap_or_else(|| format!("- ({})", r.fmax_note)),
        ),
    ];
    for (k, v) in rows {
        s.push_str(&format!("  {k:<14} {v}\n"));
    }
    if let Some(b) = r.dsp_budget {
        let moved = match r.fabric_products.len() {
            0 => "none in the fabric".to_string(),
            n => format!(
                "{n} product(s) in the fabric: {}",
                r.fabric_products.join(", ")
            ),
        };
        s.push_str(&format!("  {:<14} {b} blocks ({moved})\n", "dsp budget"));
    }
    if let Some(m) = r.icetime_mhz {
        s.push_str(&format!(
            "  {:<14} {m:.1} median of {} placed seeds (icetime -d up5k, interior paths)\n",
            "icetime (MHz)",
            r.icetime_seeds.len()
        ));
    } else if !r.icetime_note.is_empty() {
        s.push_str(&format!(
            "  {:<14} - ({})\n",
            "icetime (MHz)", r.icetime_note
        ));
    }
    for (block, mhz, what) in &r.block_limits {
        s.push_str(&format!(
            "  {:<14} {mhz:.1} MHz: {what}\n",
            format!("{block} limit")
        ));
    }
    for b in &r.unregistered_blocks {
        s.push_str(&format!(
            "  {:<14} {b} (nextpnr does not time the multiply inside it: Fmax is an upper bound)\n",
            "unregistered"
        ));
    }
    for b in &r.pipelined_blocks {
        s.push_str(&format!(
            "  {:<14} {b} (nextpnr does not time that add: Fmax is an upper bound)\n",
            "pipelined"
        ));
    }
    s
}

/// nextpnr's own words for a design that does not fit the part (its placer's, its packer's):
/// the only failure stored as a measurement ("does not fit").
pub const DOES_NOT_FIT: [&str; 4] = [
    "no BELs remaining",
    "Unable to place cell",
    "Failed to place",
    "too many",
];

/// Whether a failed nextpnr's log says the design does not fit, on an ERROR line.
pub fn does_not_fit(log: &str) -> bool {
    log.lines()
        .filter(|l| l.starts_with("ERROR"))
        .any(|l| DOES_NOT_FIT.iter().any(|w| l.contains(w)))
}
