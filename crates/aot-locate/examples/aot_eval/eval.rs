//! Evaluates Arrival-of-Time on the simulated fingertip taps (`fixtures/datasets/fingertip/`).
//!
//! Shared by the `aot_eval` example (which writes `docs/contact-location.md`) and the drift
//! test (which re-runs one OSR and compares with the doc).

use aot_locate::{ArrivalDetector, ArrivalEvent, DetectorConfig, Geometry, Scores, eq3};
use std::collections::BTreeMap;
use std::path::Path;

/// One row of `taps.csv`.
#[derive(Debug, Clone)]
pub(crate) struct Tap {
    pub(crate) id: u32,
    pub(crate) osr: u16,
    pub(crate) shape: String,
    pub(crate) mask: u32,
    pub(crate) force_kgf: u32,
    pub(crate) repeat: u32,
    pub(crate) aot_region: usize,
    pub(crate) held_pa: [f32; 3],
}

/// One frame of `series.csv`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Frame {
    pub(crate) t_us: i64,
    pub(crate) p_pa: [f32; 3],
}

/// The tap table and each tap's frames.
pub(crate) struct Dataset {
    pub(crate) taps: Vec<Tap>,
    pub(crate) series: BTreeMap<u32, Vec<Frame>>,
}

fn rows(text: &str) -> impl Iterator<Item = Vec<&str>> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .skip(1) // header
        .map(|l| l.split(',').collect())
}

fn field<T: std::str::FromStr>(row: &[&str], i: usize) -> Result<T, String> {
    row.get(i)
        .ok_or_else(|| format!("missing column {i} in {row:?}"))?
        .trim()
        .parse()
        .map_err(|_| format!("bad column {i} in {row:?}"))
}

impl Dataset {
    /// Reads `taps.csv` and `series.csv` from `dir`, keeping the taps `keep` accepts.
    pub(crate) fn load(dir: &Path, keep: impl Fn(&Tap) -> bool) -> Result<Dataset, String> {
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).map_err(|e| format!("{f}: {e}"));
        let mut taps = Vec::new();
        for r in rows(&read("taps.csv")?) {
            let tap = Tap {
                id: field(&r, 0)?,
                osr: field(&r, 1)?,
                shape: field(&r, 2)?,
                mask: field(&r, 4)?,
                aot_region: field(&r, 6)?,
                force_kgf: field(&r, 7)?,
                repeat: field(&r, 8)?,
                held_pa: [field(&r, 9)?, field(&r, 10)?, field(&r, 11)?],
            };
            if keep(&tap) {
                taps.push(tap);
            }
        }
        let wanted: std::collections::BTreeSet<u32> = taps.iter().map(|t| t.id).collect();
        let mut series: BTreeMap<u32, Vec<Frame>> = BTreeMap::new();
        for r in rows(&read("series.csv")?) {
            let id: u32 = field(&r, 0)?;
            if wanted.contains(&id) {
                series.entry(id).or_default().push(Frame {
                    t_us: field(&r, 1)?,
                    p_pa: [field(&r, 2)?, field(&r, 3)?, field(&r, 4)?],
                });
            }
        }
        Ok(Dataset { taps, series })
    }
}

/// What one tap gives eq. 3: arrival times from the series (detected sample by sample, onset
/// at t = 0 as the dataset defines it) and the held pressures read against the baseline the
/// detector tracked before arrival (the steady rise, as Table 2 reports pressures while held).
pub(crate) fn tap_event(tap: &Tap, frames: &[Frame], config: DetectorConfig) -> ArrivalEvent {
    let mut d = ArrivalDetector::new(config);
    for f in frames {
        d.push(f.t_us, f.p_pa);
    }
    d.event(0, tap.held_pa)
}

/// The scoring rules compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Rule {
    /// Eq. 3 as written, `P_k` = held rise above the tracked baseline.
    Eq3Rise,
    /// Eq. 3 as written, `P_k` = absolute held pressure (Table 2's columns are absolute hPa).
    Eq3Absolute,
    /// Not the paper's: time of flight. Arrival times are modelled as `t_k = a + b·r` and the
    /// area whose `r_{n,k}` fit the arrived sensors' times best (least squares) wins; `a`, `b`
    /// fitted per OSR on the training repeat.
    TimeOfFlight,
}

impl Rule {
    pub(crate) const ALL: [Rule; 3] = [Rule::Eq3Rise, Rule::Eq3Absolute, Rule::TimeOfFlight];

    pub(crate) fn name(self) -> &'static str {
        match self {
            Rule::Eq3Rise => "eq. 3, P = held rise",
            Rule::Eq3Absolute => "eq. 3, P = absolute held",
            Rule::TimeOfFlight => "time of flight (fitted)",
        }
    }

    /// The area this rule picks, `None` if eq. 3 refuses the input (no sensor arrived).
    pub(crate) fn predict(
        self,
        geometry: &Geometry,
        tof: &TofFit,
        tap: &Tap,
        event: &ArrivalEvent,
    ) -> Option<usize> {
        let scores: Scores = match self {
            Rule::TimeOfFlight => tof.scores(geometry, event)?,
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
pub(crate) struct Tally {
    pub(crate) hits: u32,
    pub(crate) n: u32,
}

impl Tally {
    pub(crate) fn add(&mut self, hit: bool) {
        self.hits += u32::from(hit);
        self.n += 1;
    }

    /// Accuracy in percent (0 for no trials).
    pub(crate) fn percent(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            100.0 * f64::from(self.hits) / f64::from(self.n)
        }
    }
}

/// Accuracy of each rule by OSR, by (OSR, shape) and by (OSR, force); plus how often a
/// sensor never arrived.
#[derive(Debug, Default)]
pub(crate) struct Report {
    pub(crate) by_osr: BTreeMap<(Rule, u16), Tally>,
    pub(crate) by_shape: BTreeMap<(Rule, u16, String), Tally>,
    pub(crate) by_force: BTreeMap<(Rule, u16, u32), Tally>,
    pub(crate) missing_sensor: BTreeMap<u16, Tally>,
    pub(crate) no_arrival: BTreeMap<u16, u32>,
    pub(crate) fits: BTreeMap<u16, TofFit>,
    /// How often each rule picked each area (all OSRs): which areas a rule can reach at all.
    pub(crate) picked: BTreeMap<Rule, [u32; 9]>,
}

/// The repeat the time-of-flight variant is fitted on; the other is held out.
pub(crate) const TRAIN_REPEAT: u32 = 0;

/// `t = a + b·d`: arrival time against distance from the patch centroid, by least squares.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct TofFit {
    pub(crate) a_us: f64,
    pub(crate) b_us_per_mm: f64,
}

impl TofFit {
    /// Fits on the arrived sensors of `taps` (true centroid from the mask).
    pub(crate) fn fit<'a>(taps: impl Iterator<Item = (&'a Tap, &'a ArrivalEvent)>) -> TofFit {
        let (mut n, mut sx, mut sy, mut sxx, mut sxy) = (0.0, 0.0, 0.0, 0.0, 0.0);
        let sensors = Geometry::SIMULATED_SENSORS_MM;
        for (tap, e) in taps {
            let Some(c) = centroid_mm(tap.mask) else {
                continue;
            };
            for (k, t) in e.arrival_us.iter().enumerate() {
                if let Some(t) = t {
                    let d = f64::from(
                        ((c[0] - sensors[k][0]).powi(2) + (c[1] - sensors[k][1]).powi(2)).sqrt(),
                    );
                    let t = f64::from(*t);
                    n += 1.0;
                    sx += d;
                    sy += t;
                    sxx += d * d;
                    sxy += d * t;
                }
            }
        }
        let b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        let a = (sy - b * sx) / n;
        if a.is_finite() && b.is_finite() {
            TofFit {
                a_us: a,
                b_us_per_mm: b,
            }
        } else {
            TofFit::default()
        }
    }

    /// Negative squared residual of the arrived sensors' times against each area's `a + b·r`.
    pub(crate) fn scores(&self, geometry: &Geometry, e: &ArrivalEvent) -> Option<Scores> {
        if e.arrival_us.iter().all(Option::is_none) {
            return None;
        }
        let values = std::array::from_fn(|n| {
            -(0..3)
                .filter_map(|k| {
                    let t = f64::from(e.arrival_us[k]?);
                    let r = geometry.distance_mm(n, k)?;
                    Some((t - self.a_us - self.b_us_per_mm * r).powi(2))
                })
                .sum::<f64>()
        });
        Some(Scores::from_values(values))
    }
}

/// Runs every rule on the held-out taps of `data` (repeat 1), after fitting the
/// time-of-flight variant on the training taps (repeat 0).
pub(crate) fn evaluate(data: &Dataset, geometry: &Geometry, config: DetectorConfig) -> Report {
    let mut rep = Report::default();
    let events: Vec<(&Tap, ArrivalEvent)> = data
        .taps
        .iter()
        .map(|tap| {
            let frames = data.series.get(&tap.id).map(Vec::as_slice).unwrap_or(&[]);
            (tap, tap_event(tap, frames, config))
        })
        .collect();
    let mut fits = BTreeMap::new();
    for (tap, _) in &events {
        fits.entry(tap.osr).or_insert_with(|| {
            TofFit::fit(
                events
                    .iter()
                    .filter(|(t, _)| t.osr == tap.osr && t.repeat == TRAIN_REPEAT)
                    .map(|(t, e)| (*t, e)),
            )
        });
    }
    rep.fits = fits.clone();
    for (tap, event) in events.iter().filter(|(t, _)| t.repeat != TRAIN_REPEAT) {
        let (tap, event) = (*tap, *event);
        let missing = event.arrival_us.iter().any(Option::is_none);
        rep.missing_sensor.entry(tap.osr).or_default().add(missing);
        if event.arrival_us.iter().all(Option::is_none) {
            *rep.no_arrival.entry(tap.osr).or_default() += 1;
        }
        for rule in Rule::ALL {
            let pick = rule.predict(geometry, &fits[&tap.osr], tap, &event);
            if let Some(p) = pick {
                rep.picked.entry(rule).or_default()[p] += 1;
            }
            let hit = pick == Some(tap.aot_region);
            rep.by_osr.entry((rule, tap.osr)).or_default().add(hit);
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
pub(crate) fn centroid_mm(mask: u32) -> Option<[f32; 2]> {
    let [r, c] = aot_locate::CellSet::from_bits(mask)?.centroid()?;
    Some([(c - 0.5) * 3.0 - 9.0, 6.0 - (r - 0.5) * 3.0])
}
