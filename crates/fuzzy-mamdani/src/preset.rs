//! The grasp controller of the barometric-fingertip paper (seed `000`, §5), as a preset.
//!
//! The paper fixes the structure: a Mamdani controller whose inputs are the contact-pressure
//! error and its derivative, 9 terms each (NH NB NM NS ZO PS PM PB PH), Gaussian (eq. 5) for NH
//! and PH and triangles (eq. 6) between, Gaussian output terms, center-average defuzzification,
//! and a torque limit on the MX-28's 0…1023 scale. Its MF plots and rule table (Figures 15–17)
//! are lost, so the numbers below are chosen, and why:
//!
//! * **Universes.** Both inputs are normalised to `[-1, 1]` (the paper normalises crisp inputs
//!   before fuzzification): error `e = (target − measured pressure) / error_scale`, rate
//!   `de = (d measured / dt) / rate_scale`, clamped at the ends. The scales default to
//!   2 kPa and 10 kPa/s ([`GraspScales`]), the order of a fingertip's contact-pressure rise
//!   under silicone; tune them per hand.
//! * **Input terms.** Centres evenly spaced at −1, −0.75 … 1. The seven inner triangles have
//!   their feet on the neighbouring centres (a Ruspini partition: memberships sum to 1, so no
//!   input is "unknown" and the surface has no flat holes). NH / PH are Gaussians at ±1 with
//!   σ = 0.125 / √(2 ln 2) ≈ 0.1062, so that they cross NB / PB at 0.5 halfway between centres
//!   exactly like neighbouring triangles do.
//! * **Output terms.** Gaussians centred evenly over the torque scale, `k · 1023 / 8`
//!   (NH = 0 … ZO = 511.5 … PH = 1023), σ = 54.3 so neighbours cross at 0.5. Center average only
//!   uses the centres; σ matters if the defuzzifier is switched to an integral one.
//! * **Rules** (9 × 9): `tau = T[clamp(i − j + 4)]` for `e is T[i]` and `de is T[j]`. The error
//!   term pushes torque up when pressure is below target (PD's proportional part); a rising
//!   pressure (positive `de`) means the contact is already closing, so it pulls torque down (the
//!   derivative part damps overshoot that would crush a paper cup). Every anti-diagonal has one
//!   output, so the table is monotone: more error never lowers torque, a faster rise never raises
//!   it. With the partition above, center-average interpolates the table bilinearly-like between
//!   centres: the surface is smooth and monotone, like the paper's Figure 18
//!   (`tests/it/preset.rs` checks both on a grid).
//! * **Operators.** Product AND, max aggregation, min implication, center average. With center
//!   average the AND decides monotonicity: under min, a rule cell already clamped to NH keeps
//!   gaining weight as `e` grows and the torque can *fall* (0.8 units at e = −0.975,
//!   de = 0.225). Product makes the weights separable, μᵢ(e)·νⱼ(de), so the output is a weighted
//!   mean of row averages that grow with `i`, with weights shifting right as `e` grows.
//!
//! [`GraspController`] maps the torque to an [`Effort`], optionally inside an object's Table 5
//! torque band (e.g. paper cup 50…1023, cube 80…400). It evaluates the preset from fixed-size
//! tables (18 input memberships, 81 rules, 9 centres) with the general engine's arithmetic, in
//! the same order: the same values as [`grasp_engine`] (`tests/it/preset.rs` compares them on a
//! grid), with no heap at all, so a fingertip's firmware needs no allocator.

use alloc::format;

use hand_traits::{Effort, GraspObservation, GraspPolicy};

use crate::engine::{admit_to, weighted_mean};
use crate::{Defuzzifier, Engine, EngineBuilder, EvalError, Mf, OutOfRange, Real, TNorm};

/// The paper's term names, most negative first (Table 3).
pub const TERM_NAMES: [&str; 9] = ["NH", "NB", "NM", "NS", "ZO", "PS", "PM", "PB", "PH"];

/// The top of the MX-28 torque-limit scale ([`Effort::TORQUE_LIMIT_RAW_MAX`]).
pub const TORQUE_RAW_MAX: f64 = Effort::TORQUE_LIMIT_RAW_MAX as f64;

/// The paper's controller as an engine: inputs `e`, `de` on `[-1, 1]`, output `torque` on
/// `[0, 1023]`, center-average defuzzification (see the module documentation for the numbers).
///
/// ```
/// let engine = fuzzy_mamdani::grasp_engine::<f64>();
/// let mut s = engine.scratch();
/// let hold = engine.evaluate(&mut s, &[0.0, 0.0])?[0];
/// let squeeze = engine.evaluate(&mut s, &[0.8, 0.0])?[0];
/// assert!((hold - 511.5).abs() < 1e-9 && squeeze > hold);
/// # Ok::<(), fuzzy_mamdani::EvalError>(())
/// ```
pub fn grasp_engine<T: Real>() -> Engine<T> {
    let input_terms = || (0..9).map(|i| (TERM_NAMES[i], input_term(i)));
    let output_terms = (0..9).map(|k| (TERM_NAMES[k], output_term(k)));
    let mut b = EngineBuilder::new("grasp")
        .out_of_range(OUT_OF_RANGE)
        .input("e", -T::one(), T::one(), input_terms())
        .input("de", -T::one(), T::one(), input_terms())
        .conjunction(TNorm::AlgebraicProduct)
        .defuzzifier(Defuzzifier::CenterAverage)
        .output("torque", T::zero(), T::of(TORQUE_RAW_MAX), output_terms);
    for (i, ei) in TERM_NAMES.iter().enumerate() {
        for (j, dej) in TERM_NAMES.iter().enumerate() {
            b = b.rule(format!(
                "if e is {ei} and de is {dej} then torque is {}",
                TERM_NAMES[consequent(i, j)]
            ));
        }
    }
    // The preset is fixed data, tested to build; an error here is a bug caught by every test.
    match b.build() {
        Ok(e) => e,
        Err(e) => unreachable!("the grasp preset is valid: {e}"),
    }
}

/// Both inputs outside `[-1, 1]` saturate at the ends (and ±∞ with them).
const OUT_OF_RANGE: OutOfRange = OutOfRange::Clamp;

/// Input term `i` (of `e` and of `de`, the same partition): Gaussians at the ends, triangles
/// between, centres every 0.25 from −1.
fn input_term<T: Real>(i: usize) -> Mf<T> {
    let centre = |i: usize| T::of(-1.0 + 0.25 * i as f64);
    match i {
        0 | 8 => Mf::Gaussian {
            sigma: T::of(0.125 / num_traits::Float::sqrt(2.0 * core::f64::consts::LN_2)),
            mean: centre(i),
        },
        _ => Mf::Triangle {
            a: centre(i - 1),
            b: centre(i),
            c: centre(i + 1),
        },
    }
}

/// Output term `k`: a Gaussian at `k · 1023 / 8`, crossing its neighbours at 0.5.
fn output_term<T: Real>(k: usize) -> Mf<T> {
    let step = TORQUE_RAW_MAX / 8.0;
    Mf::Gaussian {
        sigma: T::of(step / 2.0 / num_traits::Float::sqrt(2.0 * core::f64::consts::LN_2)),
        mean: T::of(step * k as f64),
    }
}

/// The rule table: the output term of `e is T[i] and de is T[j]`.
fn consequent(i: usize, j: usize) -> usize {
    (i + 4).saturating_sub(j).min(8)
}

/// Physical full-scale values that map onto the normalised universes' ends.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GraspScales {
    /// Pressure error (target − measured), in pascal, that counts as "huge" (`e = ±1`).
    pub error_pa: f32,
    /// Pressure rate, in pascal per second, that counts as "huge" (`de = ±1`).
    pub rate_pa_per_s: f32,
}

impl Default for GraspScales {
    fn default() -> Self {
        GraspScales {
            error_pa: 2_000.0,
            rate_pa_per_s: 10_000.0,
        }
    }
}

/// The paper's grasp controller as a [`GraspPolicy`]: the preset's tables in fixed-size arrays
/// (no heap), evaluated as [`grasp_engine`] evaluates them.
#[derive(Debug, Clone)]
pub struct GraspController {
    /// The terms of `e` and of `de` (the same partition).
    terms: [Mf<f32>; 9],
    /// The output terms' centres (center average uses nothing else of them).
    centres: [f32; 9],
    scales: GraspScales,
    torque_band: (u16, u16),
}

/// The paper's grasp controller with the default scales and the full 0…1023 torque band.
///
/// ```
/// use hand_traits::{GraspObservation, GraspPolicy};
/// let mut c = fuzzy_mamdani::grasp_controller();
/// let far_below = c.effort(&GraspObservation { pressure_error_pa: 5_000.0, pressure_rate_pa_per_s: 0.0 })?;
/// let at_target = c.effort(&GraspObservation { pressure_error_pa: 0.0, pressure_rate_pa_per_s: 0.0 })?;
/// assert_eq!(far_below.to_torque_limit_raw(), 1023);
/// assert!(at_target < far_below);
/// # Ok::<(), fuzzy_mamdani::EvalError>(())
/// ```
pub fn grasp_controller() -> GraspController {
    GraspController::new(GraspScales::default())
}

impl GraspController {
    /// A controller with the given scales and the full torque band. Allocates nothing.
    pub fn new(scales: GraspScales) -> Self {
        GraspController {
            terms: core::array::from_fn(input_term),
            // Every output term is a Gaussian: its centre is its mean.
            centres: core::array::from_fn(|k| output_term(k).center().unwrap_or(0.0)),
            scales,
            torque_band: (0, 1023),
        }
    }

    /// Maps the engine's 0…1023 output into `min_raw..=max_raw`, an object's band from the
    /// paper's Table 5 (e.g. `(50, 1023)` for a paper cup, `(160, 370)` for a scroll tissue).
    /// Values above 1023 saturate; a reversed band is put in order.
    pub fn with_torque_band(mut self, min_raw: u16, max_raw: u16) -> Self {
        let (lo, hi) = (min_raw.min(1023), max_raw.min(1023));
        self.torque_band = (lo.min(hi), lo.max(hi));
        self
    }

    /// The same controller as a general engine, built on each call (it allocates), for
    /// surfaces, export and inspection: [`grasp_engine`].
    pub fn engine(&self) -> Engine<f32> {
        grasp_engine()
    }

    /// The torque (0…1023) for one observation, before the torque band: what [`grasp_engine`]
    /// gives for the normalised inputs. Allocates nothing.
    ///
    /// Errors: [`EvalError::NonFiniteInput`] for a NaN input (a scale of 0 makes one).
    pub fn torque_raw(&mut self, obs: &GraspObservation) -> Result<f32, EvalError> {
        let (lo, hi) = (-1.0, 1.0);
        let e = admit_to(
            lo,
            hi,
            OUT_OF_RANGE,
            obs.pressure_error_pa / self.scales.error_pa,
            0,
        )?;
        let de_raw = obs.pressure_rate_pa_per_s / self.scales.rate_pa_per_s;
        let de = admit_to(lo, hi, OUT_OF_RANGE, de_raw, 1)?;
        let mu_e: [f32; 9] = core::array::from_fn(|i| self.terms[i].membership(e));
        let mu_de: [f32; 9] = core::array::from_fn(|j| self.terms[j].membership(de));
        let fired = self.fired(&mu_e, &mu_de);
        let (num, den) = fired
            .clone()
            .fold((0.0, 0.0), |(n, d), (w, c)| (n + w * c, d + w));
        let halved = || fired.fold(0.0, |n, (w, c)| n + w / den * (c * 0.5));
        weighted_mean(num, den, halved).ok_or(EvalError::NoRuleFired { output: 0 })
    }
}

impl GraspController {
    /// Each fired rule's weight (its product strength; every rule weighs 1) and its conclusion's
    /// centre, in the engine's order: rules `e is T[i] and de is T[j]` i major, those with a zero
    /// membership or weight left out (they add nothing).
    fn fired<'a>(
        &'a self,
        mu_e: &'a [f32; 9],
        mu_de: &'a [f32; 9],
    ) -> impl Iterator<Item = (f32, f32)> + Clone + 'a {
        let nonzero = |mu: &'a [f32; 9]| mu.iter().copied().enumerate().filter(|(_, m)| *m != 0.0);
        nonzero(mu_e)
            .flat_map(move |(i, a)| {
                nonzero(mu_de).map(move |(j, b)| (a * b, self.centres[consequent(i, j)]))
            })
            .filter(|(w, _)| *w > 0.0)
    }
}

impl GraspPolicy for GraspController {
    type Error = EvalError;

    fn effort(&mut self, obs: &GraspObservation) -> Result<Effort, EvalError> {
        let raw = self.torque_raw(obs)?;
        let (lo, hi) = (f32::from(self.torque_band.0), f32::from(self.torque_band.1));
        let banded = lo + raw / TORQUE_RAW_MAX as f32 * (hi - lo);
        Ok(Effort::saturating(banded / TORQUE_RAW_MAX as f32))
    }
}
