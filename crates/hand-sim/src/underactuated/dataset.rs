//! The seeded softness grasps the softness net trains and tests on, following seed 001's protocol
//! (§3.1, §3.3, §4): training = the 27 model objects × [`REPEATS`] poses, 18 household objects
//! and 6 empty grasps; tests = 24 regular-shape objects (new instances of the model shapes, new
//! poses) and 30 irregular household objects; and, beyond the paper, a fresh draw of
//! [`LARGE_IRREGULAR_TESTS`] household test objects from the same generator (at 30 objects one
//! object is worth 3.3 points).
//!
//! Household objects have one overall modulus (their label's class) but each finger meets a
//! different local stiffness (log-normal spread, and with probability [`FEATURE_PROBABILITY`]
//! a feature — a cap, a rib, a hollow — of the adjacent class) and a different local width:
//! the paper's explanation of its irregular-set errors, "lack of similarity softness between
//! certain sides" (§4).
//!
//! A household object is labelled by what its fingers measure ([`sensor_class`]: the class
//! band holding the median of its four local moduli), as the paper labels its test objects
//! "related to the softness of objects measured by sensors" (§4); its hidden overall class
//! stays beside it ([`GraspSpec::overall`]). Model and regular objects meet one material on
//! every finger, and carry that material's class as both.
//!
//! The files' rows are [`GraspRow`] (`grasps.csv`) and [`SampleRow`] (`train.csv`,
//! `test_regular.csv`, `test_irregular.csv`), [`Schema`] records paper-experiments reads back.

use super::UnderactuatedConfig;
use super::grasp::{GraspSeries, record_grasp};
use super::object::{MODEL_SIZES_MM, Material, ObjectConfig, Shape};
use crate::SimError;
use crate::records::{self, Exp, Fixed, Schema};
use hand_traits::Softness;
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use serde::{Deserialize, Serialize};

/// Poses per model object in the training set.
pub const REPEATS: usize = 5;
/// Household objects in the training set (seed 001 §3.3: 18).
pub const HOUSEHOLD_TRAINING: usize = 18;
/// Empty grasps in the training set (seed 001 §3.1: six).
pub const EMPTY_GRASPS: usize = 6;
/// Regular-shape test objects (seed 001 §4: 24).
pub const REGULAR_TESTS: usize = 24;
/// Irregular-shape test objects (seed 001 §4: 30).
pub const IRREGULAR_TESTS: usize = 30;
/// Household test objects of the large fresh draw (not in the paper).
pub const LARGE_IRREGULAR_TESTS: usize = 1000;
/// Sampling rate of the series, Hz.
pub const SAMPLE_HZ: f64 = 10.0;
/// Chance that a finger of a household object meets a feature of the adjacent class.
pub const FEATURE_PROBABILITY: f64 = 0.3;
/// Spread (σ of the natural log) of a household finger's local modulus around the object's
/// overall one, away from a feature.
pub const LOCAL_MODULUS_SD: f64 = 0.5;

/// Which part of the protocol a grasp belongs to (the `set` column: [`Set::name`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Set {
    /// Model objects, household objects and empty grasps.
    Train,
    /// New instances of the model shapes.
    TestRegular,
    /// Irregular household objects.
    TestIrregular,
    /// The fresh draw of [`LARGE_IRREGULAR_TESTS`] household objects (same generator and law
    /// as [`Set::TestIrregular`], its own seeded stream).
    TestIrregular1000,
}

impl Set {
    /// Every set, in file order.
    pub const ALL: [Set; 4] = [
        Set::Train,
        Set::TestRegular,
        Set::TestIrregular,
        Set::TestIrregular1000,
    ];

    /// The name used in the CSV files (also the series file's stem).
    pub fn name(self) -> &'static str {
        match self {
            Set::Train => "train",
            Set::TestRegular => "test_regular",
            Set::TestIrregular => "test_irregular",
            Set::TestIrregular1000 => "test_irregular_1000",
        }
    }

    /// Whether the set's series file is gzip-compressed (`<name>.csv.gz`, the same CSV inside):
    /// the large draw's 141 000 rows are ≈ 8 MB as text, ≈ 2 MB compressed.
    pub fn compressed(self) -> bool {
        self == Set::TestIrregular1000
    }

    /// The series file's name: `<name>.csv`, or `<name>.csv.gz` when [`compressed`](Self::compressed).
    pub fn series_file(self) -> String {
        let gz = if self.compressed() { ".gz" } else { "" };
        format!("{}.csv{gz}", self.name())
    }
}

/// One grasp to run: what is grasped, its label and its seed.
#[derive(Debug, Clone, PartialEq)]
pub struct GraspSpec {
    /// Index over the whole dataset.
    pub id: usize,
    /// Protocol set.
    pub set: Set,
    /// The object's name; repeats of one model object share it.
    pub object_id: String,
    /// `model`, `regular`, `household` or `empty`.
    pub kind: &'static str,
    /// The class label: what the fingers measure ([`sensor_class`] of the local moduli) for a
    /// household object, the material's class otherwise; `None` for an empty grasp.
    pub label: Option<Softness>,
    /// The object's hidden overall class (the band its overall modulus was drawn from); the
    /// material's class for model and regular objects; `None` for an empty grasp.
    pub overall: Option<Softness>,
    /// The object.
    pub object: ObjectConfig,
    /// The grasp's scene seed (pose, sensor spread and noise).
    pub seed: u64,
}

/// A grasp that was run.
#[derive(Debug, Clone, PartialEq)]
pub struct Grasp {
    /// What was run.
    pub spec: GraspSpec,
    /// What the sensors read.
    pub series: GraspSeries,
}

/// Overall moduli, Pa, household objects of each class are drawn from (log-uniform); gaps
/// between the bands keep every overall label unambiguous.
pub fn household_band(class: Softness) -> (f64, f64) {
    match class {
        Softness::Soft => (8e3, 45e3),
        Softness::Moderate => (60e3, 0.5e6),
        Softness::Hard => (20e6, 10e9),
    }
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    rng.sample(StandardNormal)
}

fn log_uniform(rng: &mut ChaCha8Rng, (lo, hi): (f64, f64)) -> f64 {
    (lo.ln() + rng.random::<f64>() * (hi.ln() - lo.ln())).exp()
}

/// A model-like object: a model shape of `size_mm`, the class's material with its modulus
/// spread by `sd` (log) overall and `local_sd` per finger.
fn regular(
    rng: &mut ChaCha8Rng,
    shape: Shape,
    size_mm: f64,
    class: Softness,
    sd: f64,
    local_sd: f64,
) -> ObjectConfig {
    let material = Material::of(class);
    ObjectConfig {
        shape,
        size_mm,
        material,
        modulus_pa: Some(material.nominal_modulus_pa() * (sd * normal(rng)).exp()),
        local_modulus_factor: std::array::from_fn(|_| (local_sd * normal(rng)).exp()),
        local_width_factor: [1.0; 4],
    }
}

/// The classes a household object's feature is drawn from, each with chance ½: the neighbours
/// of `class` on the soft → hard scale.
pub fn adjacent(class: Softness) -> [Softness; 2] {
    match class {
        Softness::Soft => [Softness::Moderate; 2],
        Softness::Moderate => [Softness::Soft, Softness::Hard],
        Softness::Hard => [Softness::Moderate; 2],
    }
}

/// A household object of overall class `class`.
pub(super) fn household(rng: &mut ChaCha8Rng, class: Softness) -> ObjectConfig {
    let shape = Shape::ALL[rng.random_range(0..Shape::ALL.len())];
    let size_mm = rng.random_range(55.0..110.0);
    let overall = log_uniform(rng, household_band(class));
    let local_modulus_factor = std::array::from_fn(|_| {
        if rng.random::<f64>() < FEATURE_PROBABILITY {
            let other = adjacent(class)[rng.random_range(0..2)];
            log_uniform(rng, household_band(other)) / overall
        } else {
            (LOCAL_MODULUS_SD * normal(rng)).exp()
        }
    });
    ObjectConfig {
        shape,
        size_mm,
        material: Material::of(class),
        modulus_pa: Some(overall),
        local_modulus_factor,
        local_width_factor: std::array::from_fn(|_| (0.15 * normal(rng)).exp()),
    }
}

/// The label rule of a household object: the class of the band holding the median
/// of its four local moduli — in ln, the mean of the ln of the second and third smallest (the
/// geometric mean of the middle two). A median in the gap between two bands belongs to the
/// band nearer in ln (the boundary is the gap's geometric midpoint: 51.96 kPa between soft and
/// moderate, 3.162 MPa between moderate and hard), one at a boundary to the harder class; below
/// the soft band is soft, above the hard band hard.
///
/// Errors on a modulus that is not finite and positive.
///
/// ```
/// use hand_sim::underactuated::dataset::sensor_class;
/// use hand_traits::Softness;
/// // Two fingers on a moderate 200 kPa, two on soft 20 kPa: median √(20 k · 200 k) = 63 kPa.
/// assert_eq!(sensor_class([20e3, 200e3, 20e3, 200e3]).unwrap(), Softness::Moderate);
/// // One finger on a hard feature does not move the median of a soft object.
/// assert_eq!(sensor_class([20e3, 30e3, 1e9, 15e3]).unwrap(), Softness::Soft);
/// assert!(sensor_class([20e3, f64::NAN, 20e3, 20e3]).is_err());
/// ```
pub fn sensor_class(local_moduli_pa: [f64; 4]) -> Result<Softness, SimError> {
    check_moduli(&local_moduli_pa)?;
    let mut ln = local_moduli_pa.map(f64::ln);
    ln.sort_by(f64::total_cmp);
    let median = 0.5 * (ln[1] + ln[2]);
    let boundary = |softer: Softness, harder: Softness| {
        0.5 * (household_band(softer).1.ln() + household_band(harder).0.ln())
    };
    Ok(if median < boundary(Softness::Soft, Softness::Moderate) {
        Softness::Soft
    } else if median < boundary(Softness::Moderate, Softness::Hard) {
        Softness::Moderate
    } else {
        Softness::Hard
    })
}

/// Errors unless every one of four local moduli is finite and positive.
pub(super) fn check_moduli(local_moduli_pa: &[f64; 4]) -> Result<(), SimError> {
    match local_moduli_pa
        .iter()
        .find(|m| !(m.is_finite() && **m > 0.0))
    {
        Some(bad) => Err(SimError::config(
            "local_moduli_pa",
            format!("must be finite and > 0, got {bad}"),
        )),
        None => Ok(()),
    }
}

/// Every grasp of the dataset seeded with `seed`, in file order: the paper's protocol, then
/// the large household test draw ([`Set::TestIrregular1000`], its own stream, so the paper's
/// objects do not depend on it).
pub fn specs(seed: u64) -> Result<Vec<GraspSpec>, SimError> {
    let mut rng = crate::seed::stream(seed, "underactuated/dataset");
    let mut out: Vec<GraspSpec> = Vec::new();
    let mut push = |set, object_id: String, kind, class: Option<Softness>, object: ObjectConfig| {
        let id = out.len();
        let seed = crate::seed::derive(seed, &format!("underactuated/grasp/{id}"));
        let label = match (kind, class) {
            ("household", Some(_)) => Some(sensor_class(object.local_moduli())?),
            _ => class,
        };
        out.push(GraspSpec {
            id,
            set,
            object_id,
            kind,
            label,
            overall: class,
            object,
            seed,
        });
        Ok::<(), SimError>(())
    };
    for shape in Shape::ALL {
        for (size_name, size_mm) in ["small", "medium", "big"].into_iter().zip(MODEL_SIZES_MM) {
            for material in Material::ALL {
                let class = material.softness();
                // One physical object per cell, its batch modulus within ±10 % (log σ 0.1).
                let object = regular(&mut rng, shape, size_mm, class, 0.1, 0.0);
                let name = format!(
                    "model-{}-{size_name}-{}",
                    shape.name(),
                    class_name(Some(class))
                );
                for _ in 0..REPEATS {
                    push(Set::Train, name.clone(), "model", Some(class), object)?;
                }
            }
        }
    }
    let rest = [
        (
            Set::Train,
            HOUSEHOLD_TRAINING,
            "household-train",
            "household",
        ),
        (Set::Train, EMPTY_GRASPS, "empty", "empty"),
        (Set::TestRegular, REGULAR_TESTS, "regular", "regular"),
        (
            Set::TestIrregular,
            IRREGULAR_TESTS,
            "irregular",
            "household",
        ),
    ];
    for (set, count, prefix, kind) in rest {
        for i in 0..count {
            let class = Softness::ALL[i % 3];
            let object = match kind {
                "household" => household(&mut rng, class),
                "regular" => {
                    let shape = Shape::ALL[(i / 3) % 3];
                    let size_mm = rng.random_range(60.0..95.0);
                    regular(&mut rng, shape, size_mm, class, 0.3, 0.1)
                }
                _ => ObjectConfig {
                    size_mm: 0.0,
                    ..ObjectConfig::default()
                },
            };
            let label = (kind != "empty").then_some(class);
            push(set, format!("{prefix}-{i:02}"), kind, label, object)?;
        }
    }
    let mut fresh = crate::seed::stream(seed, "underactuated/irregular-1000");
    for i in 0..LARGE_IRREGULAR_TESTS {
        let class = Softness::ALL[i % 3];
        let object = household(&mut fresh, class);
        push(
            Set::TestIrregular1000,
            format!("irregular-1000-{i:04}"),
            "household",
            Some(class),
            object,
        )?;
    }
    Ok(out)
}

/// Runs one spec with the default hand.
pub fn run(spec: &GraspSpec) -> Result<Grasp, SimError> {
    let config = UnderactuatedConfig {
        object: spec.object,
        ..UnderactuatedConfig::default()
    };
    Ok(Grasp {
        spec: spec.clone(),
        series: record_grasp(&config, spec.seed, SAMPLE_HZ)?,
    })
}

/// `n` household objects drawn as the test draws are (overall classes in turn, labelled by
/// [`sensor_class`]) from the stream `name` of `seed`, as training grasps numbered 0, 1, 2…:
/// more household training objects than the paper's 18, for a model that needs them (the
/// softness variant). Each grasp's seed is derived from `name` too, so a draw shares
/// neither objects nor poses with the dataset's streams, or with a draw of another name.
pub fn household_draw(seed: u64, name: &str, n: usize) -> Result<Vec<GraspSpec>, SimError> {
    let mut rng = crate::seed::stream(seed, name);
    (0..n)
        .map(|i| {
            let class = Softness::ALL[i % 3];
            let object = household(&mut rng, class);
            Ok(GraspSpec {
                id: i,
                set: Set::Train,
                object_id: format!("{name}-{i:04}"),
                kind: "household",
                label: Some(sensor_class(object.local_moduli())?),
                overall: Some(class),
                object,
                seed: crate::seed::derive(seed, &format!("{name}/grasp/{i}")),
            })
        })
        .collect()
}

/// Runs every grasp of the dataset seeded with `seed` ([`run_all`]).
pub fn generate(seed: u64) -> Result<Vec<Grasp>, SimError> {
    run_all(&specs(seed)?)
}

/// Runs `specs` on up to two threads (grasps are independent, so the result does not depend on
/// the scheduling), in order.
pub fn run_all(specs: &[GraspSpec]) -> Result<Vec<Grasp>, SimError> {
    let (first, second) = specs.split_at(specs.len() / 2);
    let (a, b) = std::thread::scope(|s| {
        let other = s.spawn(|| second.iter().map(run).collect::<Result<Vec<_>, _>>());
        let mine = first.iter().map(run).collect::<Result<Vec<_>, _>>();
        (mine, other.join())
    });
    let mut grasps = a?;
    match b {
        Ok(rest) => grasps.extend(rest?),
        Err(_) => return Err(SimError::config("dataset", "a grasp thread panicked")),
    }
    Ok(grasps)
}

/// A label's name in the CSV files: `soft`, `moderate`, `hard`, or `none` (empty grasp).
pub fn class_name(label: Option<Softness>) -> &'static str {
    match label {
        Some(Softness::Soft) => "soft",
        Some(Softness::Moderate) => "moderate",
        Some(Softness::Hard) => "hard",
        None => "none",
    }
}

/// The label named `name` ([`class_name`]'s inverse); `None` for a name it does not give.
pub fn class_from_name(name: &str) -> Option<Option<Softness>> {
    [
        Some(Softness::Soft),
        Some(Softness::Moderate),
        Some(Softness::Hard),
        None,
    ]
    .into_iter()
    .find(|&l| class_name(l) == name)
}

/// The `label` column as [`class_name`] writes it.
mod label {
    use super::{Softness, class_from_name, class_name};
    use serde::{Deserialize, Deserializer, Serializer, de};

    pub(super) fn serialize<S: Serializer>(
        label: &Option<Softness>,
        s: S,
    ) -> Result<S::Ok, S::Error> {
        s.serialize_str(class_name(*label))
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(
        d: D,
    ) -> Result<Option<Softness>, D::Error> {
        let name = <&str>::deserialize(d)?;
        class_from_name(name).ok_or_else(|| {
            de::Error::custom(format!(
                "unknown label `{name}`, expected `soft`, `moderate`, `hard` or `none`"
            ))
        })
    }
}

/// The sanity features of a grasp: the 8 readings at the end of the series (4 forces in N, 4
/// distal angles in degrees) — the paper's 8 variables at t₂.
pub fn end_features(grasp: &Grasp) -> [f64; 8] {
    let last = grasp.series.frames.last();
    std::array::from_fn(|j| match last {
        Some(f) if j < 4 => f64::from(f.force_n[j]),
        Some(f) => f64::from(f.distal_angle_rad[j - 4]).to_degrees(),
        None => 0.0,
    })
}

/// One row of `grasps.csv`: one grasp.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GraspRow {
    /// Grasp id: 0, 1, 2… in file order, over all sets.
    pub grasp: usize,
    /// Protocol set (also the stem of the file holding the grasp's series).
    pub set: Set,
    /// Object name; repeats of a model object share it.
    pub object: String,
    /// `model`, `regular`, `household` or `empty`.
    pub kind: String,
    /// The object's shape, `none` for an empty grasp.
    pub shape: String,
    /// Side or diameter, mm.
    pub size_mm: Fixed<f64, 1>,
    /// Overall effective modulus, Pa.
    pub modulus_pa: Exp<f64, 4>,
    /// The class label ([`class_name`]): what the fingers measure ([`sensor_class`]) for a
    /// household object, the material's class otherwise; `None` for an empty grasp.
    #[serde(with = "label")]
    pub label: Option<Softness>,
    /// The hidden overall class ([`GraspSpec::overall`]); `None` for an empty grasp.
    #[serde(with = "label")]
    pub overall: Option<Softness>,
    /// Local modulus finger 1 meets, Pa (household objects differ per finger).
    pub e1_pa: Exp<f64, 4>,
    /// Local modulus finger 2 meets, Pa.
    pub e2_pa: Exp<f64, 4>,
    /// Local modulus finger 3 meets, Pa.
    pub e3_pa: Exp<f64, 4>,
    /// Local modulus finger 4 meets, Pa.
    pub e4_pa: Exp<f64, 4>,
    /// First contact, s after the actuator started; empty for an empty grasp.
    pub t1_s: Option<Fixed<f64, 3>>,
    /// Rows of the grasp in its series file.
    pub samples: usize,
}

impl Schema for GraspRow {}

impl GraspRow {
    /// The row of `g`.
    pub fn new(g: &Grasp) -> Self {
        let s = &g.spec;
        let [e1_pa, e2_pa, e3_pa, e4_pa] = s.object.local_moduli().map(Exp);
        GraspRow {
            grasp: s.id,
            set: s.set,
            object: s.object_id.clone(),
            kind: s.kind.to_owned(),
            shape: if s.kind == "empty" {
                "none"
            } else {
                s.object.shape.name()
            }
            .to_owned(),
            size_mm: Fixed(s.object.size_mm),
            modulus_pa: Exp(s.object.modulus()),
            label: s.label,
            overall: s.overall,
            e1_pa,
            e2_pa,
            e3_pa,
            e4_pa,
            t1_s: g.series.first_contact_s.map(Fixed),
            samples: g.series.frames.len(),
        }
    }
}

/// One row of a series file: one sample of a grasp, [`SAMPLE_HZ`] from first contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SampleRow {
    /// The grasp (`grasp` of `grasps.csv`).
    pub grasp: usize,
    /// Time since first contact, s.
    pub t_s: Fixed<f64, 1>,
    /// Finger 1's FSR force, N.
    pub f1_n: Fixed<f32, 3>,
    /// Finger 2's FSR force, N.
    pub f2_n: Fixed<f32, 3>,
    /// Finger 3's FSR force, N.
    pub f3_n: Fixed<f32, 3>,
    /// Finger 4's FSR force, N.
    pub f4_n: Fixed<f32, 3>,
    /// Finger 1's distal joint angle, degrees.
    pub a1_deg: Fixed<f32, 2>,
    /// Finger 2's distal joint angle, degrees.
    pub a2_deg: Fixed<f32, 2>,
    /// Finger 3's distal joint angle, degrees.
    pub a3_deg: Fixed<f32, 2>,
    /// Finger 4's distal joint angle, degrees.
    pub a4_deg: Fixed<f32, 2>,
}

impl Schema for SampleRow {}

impl SampleRow {
    /// The readings in column order: 4 forces (N), then 4 distal angles (degrees).
    pub fn readings(&self) -> [f32; 8] {
        [
            self.f1_n.0,
            self.f2_n.0,
            self.f3_n.0,
            self.f4_n.0,
            self.a1_deg.0,
            self.a2_deg.0,
            self.a3_deg.0,
            self.a4_deg.0,
        ]
    }
}

/// `grasps.csv`: one row per grasp.
pub fn grasps_csv(grasps: &[Grasp]) -> String {
    records::render("", grasps.iter().map(GraspRow::new))
}

/// `<set>.csv`: every sample of the set's grasps, time since first contact.
pub fn series_csv(grasps: &[Grasp], set: Set) -> String {
    let rows = grasps.iter().filter(|g| g.spec.set == set).flat_map(|g| {
        g.series.frames.iter().enumerate().map(|(k, f)| {
            let [f1_n, f2_n, f3_n, f4_n] = f.force_n.map(Fixed);
            let [a1_deg, a2_deg, a3_deg, a4_deg] =
                f.distal_angle_rad.map(|a| Fixed(a.to_degrees()));
            SampleRow {
                grasp: g.spec.id,
                t_s: Fixed(k as f64 / SAMPLE_HZ),
                f1_n,
                f2_n,
                f3_n,
                f4_n,
                a1_deg,
                a2_deg,
                a3_deg,
                a4_deg,
            }
        })
    });
    records::render("", rows)
}
