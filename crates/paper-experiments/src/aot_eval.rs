//! Evaluates Arrival-of-Time on the simulated fingertip taps (`fixtures/datasets/fingertip/`,
//! read by [`crate::data::fingertip`]).
//!
//! Shared by the `aot_eval` example (which writes `docs/contact-location.md`), the drift test
//! (which re-runs one OSR and compares with the doc) and handstack's contact-location scene.

use crate::data::fingertip::{Dataset, Tap, TapSeries};
use aot_locate::{
    ArrivalDetector, ArrivalEvent, DetectorConfig, Geometry, Ranging, RangingFit, Scores, eq3,
};
use std::collections::BTreeMap;

/// What one tap gives eq. 3: arrival times from the series (detected sample by sample, onset
/// at t = 0 as the dataset defines it) and the held pressures read against the baseline the
/// detector tracked before arrival (the steady rise, as Table 2 reports pressures while held).
pub fn tap_event(tap: &Tap, series: &TapSeries, config: DetectorConfig) -> ArrivalEvent {
    let mut d = ArrivalDetector::new(config);
    for (t_us, p) in series.frames() {
        d.push(t_us, [p[0], p[1], p[2]]);
    }
    d.event(0, tap.held_pa)
}

/// The scoring rules compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Rule {
    /// Eq. 3 as written, `P_k` = held rise above the tracked baseline.
    Eq3Rise,
    /// Eq. 3 as written, `P_k` = absolute held pressure (Table 2's columns are absolute hPa).
    Eq3Absolute,
    /// Not the paper's: eq. 3's ingredients as ranges ([`Ranging`]): `t_k ≈ a + b·r + c·L_k`
    /// gives each arrived sensor a range, the pad point that matches them best picks the area;
    /// `a`, `b`, `c` fitted per OSR on the training repeat.
    Ranging,
}

impl Rule {
    /// Every rule, in report order.
    pub const ALL: [Rule; 3] = [Rule::Eq3Rise, Rule::Eq3Absolute, Rule::Ranging];

    /// Its name in the report.
    pub fn name(self) -> &'static str {
        match self {
            Rule::Eq3Rise => "eq. 3, P = held rise",
            Rule::Eq3Absolute => "eq. 3, P = absolute held",
            Rule::Ranging => "ranging (fitted)",
        }
    }

    /// The area this rule picks, `None` if eq. 3 refuses the input (no sensor arrived).
    pub fn predict(
        self,
        geometry: &Geometry,
        ranging: Option<&Ranging>,
        tap: &Tap,
        event: &ArrivalEvent,
    ) -> Option<usize> {
        let scores: Scores = match self {
            Rule::Ranging => ranging?.scores(geometry, event).ok()?,
            Rule::Eq3Rise => eq3(geometry, event).ok()?,
            Rule::Eq3Absolute => {
                let abs = ArrivalEvent {
                    pressure_pa: tap.held_pa,
                    ..*event
                };
                eq3(geometry, &abs).ok()?
            }
        };
        Some(scores.argmax())
    }
}

/// Hits and trials.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Tally {
    /// Correct answers.
    pub hits: u32,
    /// Trials.
    pub n: u32,
}

impl Tally {
    /// Counts one trial.
    pub fn add(&mut self, hit: bool) {
        self.hits += u32::from(hit);
        self.n += 1;
    }

    /// Accuracy in percent (0 for no trials).
    pub fn percent(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            100.0 * f64::from(self.hits) / f64::from(self.n)
        }
    }

    /// Both tallies' trials together (two held-out sets of the same draw).
    pub fn pooled(self, other: Tally) -> Tally {
        Tally {
            hits: self.hits + other.hits,
            n: self.n + other.n,
        }
    }

    /// The Wilson score interval of the accuracy at 95 % (z = 1.96), percent; `(0, 100)` for
    /// no trials. Unlike the normal approximation it stays inside 0–100 near a perfect score.
    pub fn wilson95(&self) -> (f64, f64) {
        if self.n == 0 {
            return (0.0, 100.0);
        }
        let (z, n) = (1.96f64, f64::from(self.n));
        let p = f64::from(self.hits) / n;
        let centre = (p + z * z / (2.0 * n)) / (1.0 + z * z / n);
        let half = z / (1.0 + z * z / n) * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt();
        // Clamped: at 0 or n hits one bound is 0 or 1 up to rounding.
        (
            (100.0 * (centre - half)).max(0.0),
            (100.0 * (centre + half)).min(100.0),
        )
    }
}

/// `84.8 % (173/204)`, as every table of the report prints a tally.
impl std::fmt::Display for Tally {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{:.1} % ({}/{})", self.percent(), self.hits, self.n)
    }
}

/// Accuracy of each rule by OSR, by (OSR, shape) and by (OSR, force); plus how often a
/// sensor never arrived.
#[derive(Debug, Default)]
pub struct Report {
    /// Accuracy per (rule, OSR).
    pub by_osr: BTreeMap<(Rule, u16), Tally>,
    /// Accuracy per (rule, OSR, shape).
    pub by_shape: BTreeMap<(Rule, u16, String), Tally>,
    /// Accuracy per (rule, OSR, force kgf).
    pub by_force: BTreeMap<(Rule, u16, u32), Tally>,
    /// Taps with a sensor that never arrived, per OSR.
    pub missing_sensor: BTreeMap<u16, Tally>,
    /// Taps where no sensor arrived, per OSR.
    pub no_arrival: BTreeMap<u16, u32>,
    /// The ranging fit per OSR.
    pub fits: BTreeMap<u16, Ranging>,
    /// How often each rule picked each area (all OSRs): which areas a rule can reach at all.
    pub picked: BTreeMap<Rule, [u32; 9]>,
    /// Taps whose centroid lies inside one area (`true`) or on a border between areas:
    /// hits against the strict label, per rule and OSR.
    pub by_interior: BTreeMap<(Rule, u16, bool), Tally>,
    /// Hits when any area whose closed rectangle holds the centroid counts (a centroid on a
    /// border belongs to both sides), per rule and OSR.
    pub tolerant: BTreeMap<(Rule, u16), Tally>,
    /// Accuracy per (rule, OSR, labelled area 0…8): the per-area map of seed 000 Figure 11.
    pub by_region: BTreeMap<(Rule, u16, usize), Tally>,
    /// What the held-out taps whose centroid lies on a border carry about a side, per OSR.
    pub border: BTreeMap<u16, Border>,
}

/// The held-out taps whose patch centroid lies on a border between two areas: whether the
/// contact itself favours a side, and where the ranging scorer places them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Border {
    /// Border taps.
    pub taps: u32,
    /// Of them, taps whose cells (by cell centre; none lies on a border) split evenly between
    /// the two sides of the border.
    pub even_cells: u32,
    /// Of them, taps whose eq. 4 column (or row) mean is a half-integer: rounding the label to a
    /// cell is a tie too.
    pub eq4_tie: u32,
    /// The labelled area's offset from the centroid along the border's normal, by the side of
    /// the pad the border is on (`x < 0` first): `+1` when the label is the area towards +x.
    pub label_side: [Option<i8>; 2],
    /// The ranging position's offset from the border towards the labelled area, mm, per tap.
    pub offsets_mm: Vec<f64>,
}

impl Border {
    /// Mean and sample standard deviation of [`Border::offsets_mm`].
    pub fn offset_stats(&self) -> (f64, f64) {
        let n = self.offsets_mm.len() as f64;
        let mean = self.offsets_mm.iter().sum::<f64>() / n;
        let var = self
            .offsets_mm
            .iter()
            .map(|o| (o - mean).powi(2))
            .sum::<f64>()
            / (n - 1.0);
        (mean, var.sqrt())
    }

    /// Ranging positions on the labelled side of the border.
    pub fn on_label_side(&self) -> usize {
        self.offsets_mm.iter().filter(|o| **o > 0.0).count()
    }

    fn add(&mut self, tap: &Tap, centroid: [f32; 2], holding: &[usize], ranging: Option<[f64; 2]>) {
        let grid = hand_sim::fingertip::geometry::PAD;
        let centres = grid.centres_mm();
        let (a, b) = (holding[0], holding[1]);
        self.taps += 1;
        // The border's normal: the axis along which the two areas' centres differ.
        let axis = usize::from(centres[a][0] == centres[b][0]);
        let line = (centres[a][axis] + centres[b][axis]) / 2.0;
        let cells = aot_locate::CellSet::from_bits(tap.mask).unwrap_or_default();
        let mut sides = [0u32; 2];
        for cell in cells.iter() {
            sides[usize::from(grid.cell_centre_mm(cell)[axis] > line)] += 1;
        }
        self.even_cells += u32::from(sides[0] == sides[1]);
        let [r, c] = cells.centroid().unwrap_or([0.0, 0.0]);
        let half = |v: f32| (v - v.floor() - 0.5).abs() < 1e-4;
        self.eq4_tie += u32::from(half(r) || half(c));
        let label = centres[usize::from(tap.aot_region)][axis] - centroid[axis];
        let side = if label > 0.0 { 1 } else { -1 };
        self.label_side[usize::from(centroid[axis] > 0.0)] = Some(side);
        if let Some(p) = ranging {
            self.offsets_mm
                .push((p[axis] - f64::from(centroid[axis])) * f64::from(side));
        }
    }
}

/// The areas (0…8) whose closed rectangle on the simulated pad holds the point `c` (mm).
pub fn areas_holding(c: [f32; 2]) -> Vec<usize> {
    let g = hand_sim::fingertip::geometry::PAD;
    let (hw, hh) = (g.width_mm / 6.0, g.height_mm / 6.0);
    g.centres_mm()
        .iter()
        .enumerate()
        .filter(|(_, a)| (c[0] - a[0]).abs() <= hw + 1e-4 && (c[1] - a[1]).abs() <= hh + 1e-4)
        .map(|(n, _)| n)
        .collect()
}

/// The repeat the time-of-flight variant is fitted on; the other is held out.
pub const TRAIN_REPEAT: u32 = 0;

/// Each sensor's distance to the patch centroid of `mask`, mm (`None` for an empty mask).
pub fn distances_mm(mask: u32) -> Option<[f32; 3]> {
    let c = centroid_mm(mask)?;
    let s = hand_sim::fingertip::geometry::AOT_SENSORS_MM;
    Some(std::array::from_fn(|k| {
        ((c[0] - s[k][0]).powi(2) + (c[1] - s[k][1]).powi(2)).sqrt()
    }))
}

/// Runs every rule on the held-out taps of `data` (repeat 1), after fitting the ranging
/// model on the training taps (repeat 0) only.
pub fn evaluate(data: &Dataset, geometry: &Geometry, config: DetectorConfig) -> Report {
    let events = events(data, config);
    let (train, test): (Vec<_>, Vec<_>) = events
        .into_iter()
        .partition(|(t, _)| t.repeat == TRAIN_REPEAT);
    score(&train, &test, geometry, config)
}

/// Runs every rule on every tap of `held_out` (the jittered set: strict labels, no border),
/// after fitting the ranging model on the training taps (repeat 0) of `lattice` only.
pub fn evaluate_held_out(
    lattice: &Dataset,
    held_out: &Dataset,
    geometry: &Geometry,
    config: DetectorConfig,
) -> Report {
    let train: Vec<_> = events(lattice, config)
        .into_iter()
        .filter(|(t, _)| t.repeat == TRAIN_REPEAT)
        .collect();
    score(&train, &events(held_out, config), geometry, config)
}

/// Each tap with its arrival event.
fn events(data: &Dataset, config: DetectorConfig) -> Vec<(&Tap, ArrivalEvent)> {
    data.iter()
        .map(|(tap, series)| (tap, tap_event(tap, series, config)))
        .collect()
}

/// Fits the ranging model per OSR on `train` (with the detector's threshold), then scores
/// every rule on `test`.
fn score(
    train: &[(&Tap, ArrivalEvent)],
    test: &[(&Tap, ArrivalEvent)],
    geometry: &Geometry,
    config: DetectorConfig,
) -> Report {
    let mut rep = Report::default();
    let mut fits = BTreeMap::new();
    for (tap, _) in train {
        if fits.contains_key(&tap.osr) {
            continue;
        }
        let mut fit = RangingFit::new(config.threshold_pa);
        for (t, e) in train.iter().filter(|(t, _)| t.osr == tap.osr) {
            if let Some(d) = distances_mm(t.mask) {
                fit.push(e, d);
            }
        }
        if let Some(model) = fit.finish() {
            fits.insert(tap.osr, model);
        }
    }
    rep.fits = fits.clone();
    for &(tap, event) in test {
        let missing = event.arrival_us.iter().any(Option::is_none);
        rep.missing_sensor.entry(tap.osr).or_default().add(missing);
        if event.arrival_us.iter().all(Option::is_none) {
            *rep.no_arrival.entry(tap.osr).or_default() += 1;
        }
        let centroid = tap.centroid_mm();
        let holding = centroid.map(areas_holding).unwrap_or_default();
        if let (Some(c), 2) = (centroid, holding.len()) {
            let p = fits
                .get(&tap.osr)
                .and_then(|m| m.position_mm(geometry, &event).ok());
            rep.border
                .entry(tap.osr)
                .or_default()
                .add(tap, c, &holding, p);
        }
        for rule in Rule::ALL {
            let pick = rule.predict(geometry, fits.get(&tap.osr), tap, &event);
            rep.tolerant
                .entry((rule, tap.osr))
                .or_default()
                .add(pick.is_some_and(|p| holding.contains(&p)));
            if let Some(p) = pick {
                rep.picked.entry(rule).or_default()[p] += 1;
            }
            let hit = pick == Some(usize::from(tap.aot_region));
            rep.by_interior
                .entry((rule, tap.osr, holding.len() == 1))
                .or_default()
                .add(hit);
            rep.by_osr.entry((rule, tap.osr)).or_default().add(hit);
            rep.by_region
                .entry((rule, tap.osr, usize::from(tap.aot_region)))
                .or_default()
                .add(hit);
            rep.by_shape
                .entry((rule, tap.osr, tap.shape.clone()))
                .or_default()
                .add(hit);
            rep.by_force
                .entry((rule, tap.osr, tap.force_kgf))
                .or_default()
                .add(hit);
        }
    }
    rep
}

/// The patch centroid in pad millimetres (x right, y up, origin at the centre; 3 mm cells).
pub fn centroid_mm(mask: u32) -> Option<[f32; 2]> {
    let centroid = aot_locate::CellSet::from_bits(mask)?.centroid()?;
    Some(hand_sim::fingertip::geometry::PAD.grid_point_mm(centroid))
}

#[cfg(test)]
mod tests {
    use super::Tally;

    /// Newcombe (1998), "Two-sided confidence intervals for the single proportion", Stat. Med.
    /// 17:857–872, Table II, method 3 (score interval without continuity correction).
    #[test]
    fn wilson_interval_matches_newcombe_table_ii() {
        for (hits, n, lo, hi) in [
            (81, 263, 25.53, 36.62),
            (15, 148, 6.24, 16.05),
            (0, 20, 0.0, 16.11),
            (1, 29, 0.61, 17.18),
        ] {
            let (l, h) = Tally { hits, n }.wilson95();
            assert!(
                (l - lo).abs() < 0.006 && (h - hi).abs() < 0.006,
                "{hits}/{n}: {l} {h}"
            );
        }
        assert_eq!(Tally::default().wilson95(), (0.0, 100.0));
        let (l, h) = Tally { hits: 20, n: 20 }.wilson95();
        assert!(h == 100.0 && (l - 83.89).abs() < 0.006, "{l}");
        let pooled = Tally { hits: 1, n: 2 }.pooled(Tally { hits: 3, n: 4 });
        assert_eq!(pooled, Tally { hits: 4, n: 6 });
    }
}
