//! How a line reads a depth: the fitted line and its ceiling, the floors of today's RTL at the
//! configuration's widths, the corners around widths never measured, and the rule that gave the
//! figure.

use super::*;

impl Line {
    /// The Fmax the model predicts for the slowest stretch `e` and the mean stretch `m`.
    pub fn fmax(&self, e: f64, m: f64) -> f64 {
        if e <= self.cap_up_to {
            return self.cap_mhz;
        }
        let line = self.cap_mhz.min(
            1000.0 / (self.offset_ns + self.ns_per_unit * e + self.ns_per_mean_unit * m).max(1e-6),
        );
        line.max(self.measured_floor(e, m))
    }

    /// The Fmax measured (`fit::row_figure`) on the nearest calibration unit whose slowest and mean
    /// stretches are both at least `e` and `m` (nearest: the least sum of the two differences;
    /// of equals, the slower; 0: none). Not the best of them: the data is not monotone to a
    /// seed's scatter (lean on the iCE40: 70.2 MHz at 5 stages, 64.3 at 6 with stretches no
    /// longer), and a unit measured itself is assured its own figure. The manifest, and so the
    /// calibration data, states the stretches to 0.01.
    pub fn measured_floor(&self, e: f64, m: f64) -> f64 {
        let distance = |p: &[f64; 3]| (p[0] - e) + (p[1] - m);
        self.measured
            .iter()
            .filter(|p| p[0] >= e - 0.005 && p[1] >= m - 0.005)
            .min_by(|a, b| {
                distance(a)
                    .total_cmp(&distance(b))
                    .then(a[2].total_cmp(&b[2]))
            })
            .map_or(0.0, |p| p[2])
    }

    /// Whether a unit with stretches `e`, `m` lies between calibration units: one no shorter
    /// (its floor) and one no longer. The line is not asked there: between two depths the
    /// clock jumps where the last long stretch goes, and no line knows which depth that is
    /// (fitted on the ECP5: 130 MHz at 38 stages, 206 at 48, and the line said 177 at 44,
    /// which measured 134).
    pub fn bracketed(&self, e: f64, m: f64) -> bool {
        self.measured_floor(e, m) > 0.0
            && self
                .measured
                .iter()
                .any(|p| p[0] <= e + 0.005 && p[1] <= m + 0.005)
    }

    /// The line with only the measured units whose widths `plan` has: a unit measured at other
    /// widths is no floor for it (routes differ with the widths: a narrow schlick with stretches
    /// shorter than a default-width unit's measured 49.2 MHz where that one had 55), and at
    /// widths never measured no stretch is assured the cap. The line and its margin stay those
    /// fitted over every width of the grid.
    pub(crate) fn at_widths_of(self, plan: &Plan) -> Line {
        let mut line = self.of_todays_rtl();
        line.cap_up_to = line.cap_up_to.min(
            line.measured
                .iter()
                .filter(|p| p[2] >= line.cap_mhz - 0.05)
                .map(|p| p[0])
                .fold(-1.0, f64::max),
        );
        line.widths_of(plan)
    }

    /// The line with only the measured units whose rows name the RTL they were measured on (a
    /// row that names none is the fit's data, no floor and no corner). That each named RTL is
    /// the one specgen writes today is held by `specgen stale` and the suite
    /// (`explore::calibration_evidence`): a row of another RTL fails them.
    pub(crate) fn of_todays_rtl(self) -> Line {
        let keep: Vec<bool> = (0..self.measured.len())
            .map(|i| self.measured_digest.get(i).is_some_and(|d| !d.is_empty()))
            .collect();
        self.keeping(&keep)
    }

    /// The line with only the measured units whose flag in `keep` is set (each unit's figures,
    /// flags, depth and digest together).
    pub(crate) fn keeping(mut self, keep: &[bool]) -> Line {
        retain_flagged(&mut self.measured, keep);
        retain_flagged(&mut self.measured_args, keep);
        retain_flagged(&mut self.measured_digest, keep);
        retain_flagged(&mut self.measured_stages, keep);
        self
    }

    pub(super) fn widths_of(mut self, plan: &Plan) -> Line {
        let own = Shape::of_plan(plan);
        let keep: Vec<bool> = (0..self.measured.len())
            .map(|i| {
                Shape::of_args(
                    self.measured_args.get(i).map_or("", String::as_str),
                    &plan.cfg.params,
                )
                .is_some_and(|sh| sh == own)
            })
            .collect();
        if !keep.iter().any(|&k| k) {
            // widths never measured: each calibrated width's units by depth
            let mut corners: Vec<Corner> = Vec::new();
            for (i, p) in self.measured.iter().enumerate() {
                let (args, stages) = (
                    self.measured_args.get(i).cloned().unwrap_or_default(),
                    self.measured_stages.get(i).copied().unwrap_or(0),
                );
                match corners.iter_mut().find(|c| c.args == args) {
                    Some(c) => c.units.push((stages, p[0], p[2])),
                    None => {
                        let Some(shape) = Shape::of_args(&args, &plan.cfg.params) else {
                            continue;
                        };
                        corners.push(Corner {
                            args,
                            deepest: 0,
                            units: vec![(stages, p[0], p[2])],
                            shape,
                        })
                    }
                }
            }
            // a reading only from widths of the same rounding, ROM style and registers, with a
            // product in LUTs for its size where the configuration has one (a table in LUTs
            // says nothing of one in block RAM, a LUT multiplier nothing of an SB_MAC16)
            corners.retain(|c| c.shape.alike(&own));
            // whether some calibrated widths lie on either side of the configuration's: no wider
            // in every width, and no narrower (at each depth, [`Line::corner`] takes the nearest
            // of those measured there)
            let (below, above) = nearest_around(&own, corners.iter().map(|c| &c.shape));
            if !below.is_empty() && !above.is_empty() {
                self.around = below.into_iter().chain(above).cloned().collect();
                self.surrounded = true;
            }
            self.own = Some(own.clone());
            let mut longest_step = f64::NEG_INFINITY;
            for c in &mut corners {
                let deepest = c.units.iter().map(|u| u.0).max().unwrap_or(0);
                let (d, step) = params_with_args(&plan.cfg.params, &c.args)
                    .and_then(|p| deepest_of(&p))
                    .unwrap_or((deepest, f64::INFINITY));
                c.deepest = d.max(deepest);
                longest_step = longest_step.max(step);
            }
            // a step longer than every corner's longest by a LUT level or more (a product left
            // in LUTs that none of them has: a LUT tree and a carry chain, 8 or more) is not
            // between them
            let own_step = plan.longest_step();
            self.surrounded &= own_step < longest_step + crate::datapath::LUT_DELAY.ns;
            self.corners = corners;
            self.deepest = plan.cut_points;
            // the cap where a calibration unit as short reached it: only at widths measured
            self.cap_up_to = -1.0;
        }
        retain_flagged(&mut self.measured, &keep);
        self.measured_args.clear();
        self.measured_stages.clear();
        self
    }

    /// At widths never measured, what the corners measured near `stages`, and whether that
    /// figure is assured or only a ceiling. Without corners: unbounded, nothing assured.
    ///
    /// *A floor where surrounded*: at this depth, the calibrated widths with a unit at as many
    /// cuts from their own deepest as `stages` is from the configuration's, or a little
    /// shallower ([`Corner::unit_at`]); the nearest of them on either side of the
    /// configuration's widths, and every one in the box they span; the least of their figures
    /// is assured where the slowest stretch `e` is no longer than the longest of theirs. A unit
    /// between two measured widths at the same distance from its deepest has products, tables
    /// and carries between theirs, and the cuts that bring the jump of the last long stretch are
    /// counted from the deepest (blinn on the ECP5: 149 MHz at 7 cuts from the deepest at narrow
    /// widths, 167 at the default ones).
    ///
    /// *Else a ceiling*: the least, over the corners no harder to clock ([`Line::caps`]), of
    /// each one's shallowest unit at as many cuts from its deepest or fewer (a deeper unit of a width runs as fast as a shallower one
    /// or faster, so a shallower unit is no ceiling). Between calibrated widths the line alone
    /// over-promised (a lean at 10/6/8/12 bits, 11 stages, predicted 124.9 MHz, measured 83.2,
    /// where the narrow unit had 52.2 at that depth).
    pub fn corner(&self, stages: u32, e: f64) -> (f64, bool) {
        if self.corners.is_empty() {
            return (f64::INFINITY, false);
        }
        let from_deepest = self.deepest.saturating_sub(stages);
        if let (true, Some(own)) = (self.surrounded, &self.own) {
            // the widths measured at this depth, the nearest of them on either side, and every
            // one in the box they span: between two widths a unit may be slower than both
            // (schlick on the ECP5 at 9 stages: 118 MHz at 8/6/5/8, 115 at the defaults, 69-70
            // at four widths between them)
            let here: Vec<(&Corner, &(u32, f64, f64))> = self
                .corners
                .iter()
                .filter_map(|c| c.unit_at(from_deepest).map(|u| (c, u)))
                .collect();
            let (below, above) = nearest_around(own, here.iter().map(|(c, _)| &c.shape));
            if !below.is_empty() && !above.is_empty() {
                let inside = |sh: &Shape| {
                    below.iter().any(|b| b.no_wider(sh)) && above.iter().any(|a| sh.no_wider(a))
                };
                let (mut value, mut longest) = (f64::INFINITY, f64::NEG_INFINITY);
                for (_, &(_, ce, f)) in here.iter().filter(|(c, _)| inside(&c.shape)) {
                    value = value.min(f);
                    longest = longest.max(ce);
                }
                if e <= longest + 0.005 {
                    return (value, true);
                }
            }
        }
        let ceiling = self
            .corners
            .iter()
            .filter(|c| self.caps(c))
            .filter_map(|c| c.unit_at_or_deeper(from_deepest))
            .map(|u| u.2)
            .fold(f64::INFINITY, f64::min);
        (ceiling, false)
    }

    /// Whether a calibrated width caps the configuration's clock: its units are no harder to
    /// clock ([`Shape::easier_than`]: no wider, as many blocks or more), so one as deep or
    /// deeper runs at least as fast as this one would. A wider width, or one with products in
    /// the fabric, is slower and caps nothing (a lean at 14/9/6/14 was held at the 59.1 MHz of
    /// 18-bit cosines; a budget of 5 blocks capped a fitted unit whose products are all blocks).
    fn caps(&self, c: &Corner) -> bool {
        self.own.as_ref().is_none_or(|own| c.shape.easier_than(own))
    }

    /// At widths never measured, the corners' unit that sets [`Line::corner`]'s figure at
    /// `stages` for a slowest stretch `e`: its widths (generate flags beyond the defaults), depth
    /// and median Fmax, and whether the figure is a floor (else a ceiling).
    pub fn nearest_unit(&self, stages: u32, e: f64) -> Option<(&str, u32, f64, bool)> {
        let (value, floor) = self.corner(stages, e);
        let from_deepest = self.deepest.saturating_sub(stages);
        self.corners
            .iter()
            .filter(|c| floor || self.caps(c))
            .filter_map(|c| {
                if floor {
                    c.unit_at(from_deepest)
                } else {
                    c.unit_at_or_deeper(from_deepest)
                }
                .map(|u| (c.args.as_str(), u.0, u.2, floor))
            })
            .find(|u| u.2 == value)
    }

    /// The model's Fmax for `plan`.
    pub fn fmax_of(&self, plan: &Plan) -> f64 {
        let (e, m) = stretches(plan);
        let f = self.fmax(e, m);
        match self.corner(plan.cfg.stages(), e) {
            (v, true) => f.max(v),
            _ => f,
        }
    }

    /// What `--target-mhz` compares with its target: the cap where a calibration unit as short
    /// reached it; between calibration units, what the longer one measured (`bracketed`);
    /// else the line's prediction times the fit's margin, or a measured floor if higher. At
    /// widths never measured, no more than the corners measured at its depth, and that with
    /// [`corner_margin`] where they surround its widths ([`Line::corner`]).
    pub fn assured_of(&self, plan: &Plan) -> f64 {
        self.assured_by_rule(plan).0
    }

    /// [`Line::assured_of`], and the rule of the module doc that gave it.
    pub fn assured_by_rule(&self, plan: &Plan) -> (f64, Rule) {
        let (e, m) = stretches(plan);
        let inferred = inferred_blocks(plan);
        match self.corner(plan.cfg.stages(), e) {
            (v, true) if !inferred => (v * corner_margin(), Rule::Between),
            (v, _) => {
                let (a, rule) = self.assured_with_rule(e, m);
                match rule {
                    // the line was fitted to units whose blocks have their registers
                    Rule::Line if inferred => (0.0, Rule::Line),
                    _ => (a.min(v), rule),
                }
            }
        }
    }

    /// [`Line::assured_of`] for the stretches `e`, `m`.
    pub fn assured(&self, e: f64, m: f64) -> f64 {
        self.assured_with_rule(e, m).0
    }

    pub(super) fn assured_with_rule(&self, e: f64, m: f64) -> (f64, Rule) {
        let floor = self.measured_floor(e, m);
        if e <= self.cap_up_to {
            (self.cap_mhz, Rule::Floor)
        } else if self.bracketed(e, m) {
            (floor, Rule::Floor)
        } else {
            let line = self.fmax(e, m) * self.margin;
            if floor > 0.0 && floor >= line {
                (floor, Rule::Floor)
            } else {
                (line, Rule::Line)
            }
        }
    }
}

/// Whether `plan` leaves a product to the synthesis tool on a family whose unit instantiates
/// its blocks with their registers (the ECP5, the GW1NR-9): at such a depth the tool maps it
/// into a block without registers, behind a table read without its output register, paths no
/// calibrated width around it measured. Such a depth is assured only by units of its own widths
/// measured on today's RTL, never by the widths around it or the line (schlick on the ECP5 at 10 stages, at 11/9/7/11, 14/10/7/12 and 10/7/8/13 bits:
/// 69-70 MHz, where the widths around them had 111).
pub(crate) fn inferred_blocks(plan: &Plan) -> bool {
    let dp = &plan.datapath;
    crate::family::of(plan.cfg.target()).instantiated_blocks()
        && dp.steps.iter().any(|s| {
            s.dsps.is_empty()
                && s.wires
                    .iter()
                    .any(|w| w.product().is_some() && dp.product_blocks(&w.name) > 0)
        })
}
