//! Training the softness network ([`crate::softness`]) by least squares on one-hot targets —
//! by Levenberg–Marquardt (the paper's `trainlm`, through the `levenberg-marquardt` crate) or,
//! for comparison, by full-batch Adam on the same network and the same analytic derivative.
//!
//! One code path: both optimisers see the residuals `r = y − t` of every (sample, class) and
//! the Jacobian rows `∂y/∂p` of [`Layers::jacobian`]. LM takes the stacked Jacobian `J`; Adam
//! takes the gradient of `½·mean(r²)`, which is `Jᵀr / m`, accumulated row by row.
//!
//! Training rows: every `stride`-th sample of each training series (from its first), with its
//! grasp's one-hot label. Initial weights: uniform in `±√(6 / (fan_in + fan_out))` (Glorot),
//! biases 0, drawn from a ChaCha8 stream seeded by [`SoftnessTrainConfig::seed`]; computation in
//! f64, the result rounded to f32.
//!
//! # How LM stops ([`Stop`])
//! The crate's [`TerminationReason`]s become either a [`Stop`] (weights usable: converged on
//! `ftol` / `xtol`, gradient orthogonal to the residuals, zero residuals, no further improvement
//! possible at machine precision, or the evaluation budget spent — Matlab's "max epochs") or a
//! [`NetError::Training`] (non-finite residuals or Jacobian, or a usage error). A singular or
//! rank-deficient Jacobian (e.g. a variable that never varies, or saturated neurons) is no
//! error: the crate's pivoted QR solves the damped step whatever the rank.

use crate::error::NetError;
use crate::softness::N_VARIABLES;
use crate::softness::{CLASSES, HIDDEN, InputScale, N_PARAMS, SoftnessNet};
pub use crate::softness_layers::{Layers, Pass};
use hand_traits::Softness;
use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt, TerminationReason};
use nalgebra::storage::Owned;
use nalgebra::{DMatrix, DVector, Dyn, SVector, U1};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Levenberg–Marquardt settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LmConfig {
    /// The crate's patience: at most `patience · (N_PARAMS + 1)` residual evaluations.
    pub patience: usize,
    /// `ftol` = `xtol` = `gtol`: relative reduction, step and gradient-angle tolerances.
    pub tol: f64,
}

impl Default for LmConfig {
    /// Patience 3 (216 evaluations), tolerances 1e-10.
    fn default() -> Self {
        LmConfig {
            patience: 3,
            tol: 1e-10,
        }
    }
}

/// Full-batch Adam settings (β₁ 0.9, β₂ 0.999, ε 1e-8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdamConfig {
    /// Passes over the training rows, one step each.
    pub epochs: usize,
    /// Step size.
    pub learning_rate: f64,
}

impl Default for AdamConfig {
    /// 2000 epochs at 0.01.
    fn default() -> Self {
        AdamConfig {
            epochs: 2000,
            learning_rate: 0.01,
        }
    }
}

/// Which optimiser fits the weights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Optimiser {
    /// Levenberg–Marquardt, as in the underactuated-hand softness paper ("Distinguish the
    /// Textures of Grasped Objects…"), §3.3.
    Lm(LmConfig),
    /// Adam, for comparison.
    Adam(AdamConfig),
}

impl Optimiser {
    /// LM with [`LmConfig::default`].
    pub fn lm() -> Optimiser {
        Optimiser::Lm(LmConfig::default())
    }

    /// Adam with [`AdamConfig::default`].
    pub fn adam() -> Optimiser {
        Optimiser::Adam(AdamConfig::default())
    }

    /// `lm` or `adam`.
    pub fn name(&self) -> &'static str {
        match self {
            Optimiser::Lm(_) => "lm",
            Optimiser::Adam(_) => "adam",
        }
    }
}

/// How to train.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftnessTrainConfig {
    /// The optimiser and its settings.
    pub optimiser: Optimiser,
    /// Seed of the initial weights.
    pub seed: u64,
    /// Use every `stride`-th sample of each series (1: all).
    pub stride: usize,
}

/// Why training stopped with usable weights.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// LM: `ftol` and / or `xtol` met.
    Converged,
    /// LM: the residuals are orthogonal to every Jacobian column (`gtol`).
    Orthogonal,
    /// LM: the residuals are exactly zero.
    ResidualsZero,
    /// LM: the tolerances are below what machine precision can show; the weights are the best
    /// found.
    MachinePrecision,
    /// LM: the evaluation budget ([`LmConfig::patience`]) was spent.
    BudgetSpent,
    /// Adam: all epochs ran.
    Epochs,
}

impl Stop {
    /// A short name for reports.
    pub fn name(self) -> &'static str {
        match self {
            Stop::Converged => "converged",
            Stop::Orthogonal => "orthogonal",
            Stop::ResidualsZero => "residuals zero",
            Stop::MachinePrecision => "machine precision",
            Stop::BudgetSpent => "budget spent",
            Stop::Epochs => "epochs",
        }
    }
}

/// What training did.
#[derive(Debug, Clone, PartialEq)]
pub struct TrainReport {
    /// Why it stopped.
    pub stop: Stop,
    /// Training rows (samples).
    pub rows: usize,
    /// Training mean squared error (over rows × classes) at every residual evaluation (LM,
    /// trial steps included) or epoch (Adam), first = the initial weights.
    pub curve: Vec<f64>,
    /// Training mean squared error of the returned (f64) weights.
    pub mse: f64,
}

/// The training rows: normalised inputs and one-hot targets.
struct Rows {
    z: Vec<SVector<f64, N_VARIABLES>>,
    t: Vec<[f64; CLASSES]>,
}

impl Rows {
    /// Residual count `m`.
    fn residuals(&self) -> usize {
        self.z.len() * CLASSES
    }

    /// Calls `f(row, residuals r = y − t, Jacobian rows)` for each row.
    fn each(
        &self,
        l: &Layers<f64>,
        jacobian: bool,
        mut f: impl FnMut(usize, [f64; CLASSES], Option<&nalgebra::SMatrix<f64, CLASSES, N_PARAMS>>),
    ) {
        for (i, (z, t)) in self.z.iter().zip(&self.t).enumerate() {
            let pass = l.forward(z);
            let r = core::array::from_fn(|k| pass.y[k] - t[k]);
            let j = jacobian.then(|| l.jacobian(z, &pass));
            f(i, r, j.as_ref());
        }
    }

    fn mse(&self, l: &Layers<f64>) -> f64 {
        let mut sum = 0.0;
        self.each(l, false, |_, r, _| {
            sum += r.iter().map(|v| v * v).sum::<f64>()
        });
        sum / self.residuals() as f64
    }
}

/// The LM problem: parameters `p`, residuals `y(p) − t` over every row and class.
struct Problem<'a> {
    rows: &'a Rows,
    p: DVector<f64>,
    layers: Layers<f64>,
    curve: Vec<f64>,
}

impl Problem<'_> {
    fn set(&mut self, p: &DVector<f64>) {
        self.p.copy_from(p);
        if let Some(l) = Layers::from_flat(p.as_slice()) {
            self.layers = l;
        }
        self.curve.push(self.rows.mse(&self.layers));
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn, U1>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn, U1>;

    fn set_params(&mut self, p: &DVector<f64>) {
        self.set(p);
    }

    fn params(&self) -> DVector<f64> {
        self.p.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        let mut out = DVector::zeros(self.rows.residuals());
        self.rows.each(&self.layers, false, |i, r, _| {
            for k in 0..CLASSES {
                out[i * CLASSES + k] = r[k];
            }
        });
        Some(out)
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let mut out = DMatrix::zeros(self.rows.residuals(), N_PARAMS);
        self.rows.each(&self.layers, true, |i, _, j| {
            if let Some(j) = j {
                out.view_mut((i * CLASSES, 0), (CLASSES, N_PARAMS))
                    .copy_from(j);
            }
        });
        Some(out)
    }
}

/// Glorot-uniform weights, zero biases, from `seed`.
fn initial(seed: u64) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut p = Vec::with_capacity(N_PARAMS);
    for (fan_in, fan_out) in [(N_VARIABLES, HIDDEN), (HIDDEN, HIDDEN), (HIDDEN, CLASSES)] {
        let a = (6.0 / (fan_in + fan_out) as f64).sqrt();
        p.extend((0..fan_in * fan_out).map(|_| rng.random_range(-a..a)));
        p.extend(std::iter::repeat_n(0.0, fan_out));
    }
    p
}

fn one_hot(s: Softness) -> [f64; CLASSES] {
    core::array::from_fn(|k| if k == s.index() { 1.0 } else { 0.0 })
}

/// Trains a classifier on labelled series (each a slice of samples) with `config`.
///
/// Errors: [`NetError::Training`] for no samples, a zero stride or an LM failure (see the
/// module docs), [`NetError::NonFinite`] for a non-finite reading (index into the flattened
/// training samples).
pub fn train(
    grasps: &[(&[[f32; N_VARIABLES]], Softness)],
    config: &SoftnessTrainConfig,
) -> Result<(SoftnessNet, TrainReport), NetError> {
    if config.stride == 0 {
        return Err(NetError::Training("stride 0".into()));
    }
    let picked: Vec<(&[f32; N_VARIABLES], Softness)> = grasps
        .iter()
        .flat_map(|(series, label)| {
            series
                .iter()
                .step_by(config.stride)
                .map(move |s| (s, *label))
        })
        .collect();
    if picked.is_empty() {
        return Err(NetError::Training("no training samples".into()));
    }
    if let Some(i) = picked
        .iter()
        .flat_map(|(s, _)| s.iter())
        .position(|v| !v.is_finite())
    {
        return Err(NetError::NonFinite { index: i });
    }
    let scale = InputScale::fit(picked.iter().map(|(s, _)| *s));
    let rows = Rows {
        z: picked
            .iter()
            .map(|(s, _)| SVector::from(scale.apply(s).map(f64::from)))
            .collect(),
        t: picked.iter().map(|(_, l)| one_hot(*l)).collect(),
    };
    let p0 = initial(config.seed);
    let (p, stop, curve) = match config.optimiser {
        Optimiser::Lm(lm) => levenberg_marquardt(&rows, p0, lm)?,
        Optimiser::Adam(adam) => self::adam(&rows, p0, adam),
    };
    let layers =
        Layers::from_flat(&p).ok_or_else(|| NetError::Training("parameter count".into()))?;
    let mse = rows.mse(&layers);
    let flat32: Vec<f32> = p.iter().map(|&v| v as f32).collect();
    let net = SoftnessNet::from_flat(&flat32, scale)
        .ok_or_else(|| NetError::Training("parameter count".into()))?;
    let report = TrainReport {
        stop,
        rows: rows.z.len(),
        curve,
        mse,
    };
    Ok((net, report))
}

fn levenberg_marquardt(
    rows: &Rows,
    p0: Vec<f64>,
    config: LmConfig,
) -> Result<(Vec<f64>, Stop, Vec<f64>), NetError> {
    let mut problem = Problem {
        rows,
        p: DVector::zeros(N_PARAMS),
        layers: Layers::from_flat(&p0)
            .ok_or_else(|| NetError::Training("parameter count".into()))?,
        curve: Vec::new(),
    };
    problem.set(&DVector::from_vec(p0));
    let (problem, report) = LevenbergMarquardt::new()
        .with_patience(config.patience.max(1))
        .with_ftol(config.tol)
        .with_xtol(config.tol)
        .with_gtol(config.tol)
        .minimize(problem);
    let stop = stop_of(report.termination)?;
    // The crate leaves the problem at the best parameters it accepted.
    Ok((problem.p.as_slice().to_vec(), stop, problem.curve))
}

/// The crate's termination reason as a [`Stop`] (usable weights) or a typed error.
fn stop_of(reason: TerminationReason) -> Result<Stop, NetError> {
    match reason {
        TerminationReason::Converged { .. } => Ok(Stop::Converged),
        TerminationReason::Orthogonal => Ok(Stop::Orthogonal),
        TerminationReason::ResidualsZero => Ok(Stop::ResidualsZero),
        TerminationReason::NoImprovementPossible(_) => Ok(Stop::MachinePrecision),
        TerminationReason::LostPatience => Ok(Stop::BudgetSpent),
        other => Err(NetError::Training(format!(
            "Levenberg–Marquardt stopped: {other:?}"
        ))),
    }
}

fn adam(rows: &Rows, mut p: Vec<f64>, config: AdamConfig) -> (Vec<f64>, Stop, Vec<f64>) {
    let (b1, b2, eps) = (0.9f64, 0.999f64, 1e-8);
    let mut m = vec![0.0; N_PARAMS];
    let mut v = vec![0.0; N_PARAMS];
    let mut curve = Vec::with_capacity(config.epochs + 1);
    let scale = 1.0 / rows.residuals() as f64;
    for epoch in 1..=config.epochs {
        let Some(l) = Layers::from_flat(&p) else {
            break;
        };
        let mut grad = [0.0f64; N_PARAMS];
        let mut sq = 0.0;
        rows.each(&l, true, |_, r, j| {
            if let Some(j) = j {
                for k in 0..CLASSES {
                    sq += r[k] * r[k];
                    for (q, g) in grad.iter_mut().enumerate() {
                        *g += j[(k, q)] * r[k];
                    }
                }
            }
        });
        curve.push(sq * scale);
        let (c1, c2) = (1.0 - b1.powi(epoch as i32), 1.0 - b2.powi(epoch as i32));
        for q in 0..N_PARAMS {
            let g = grad[q] * scale;
            m[q] = b1 * m[q] + (1.0 - b1) * g;
            v[q] = b2 * v[q] + (1.0 - b2) * g * g;
            p[q] -= config.learning_rate * (m[q] / c1) / ((v[q] / c2).sqrt() + eps);
        }
    }
    (p, Stop::Epochs, curve)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_termination_reason_is_a_stop_or_a_typed_error() {
        let ok = [
            (
                TerminationReason::Converged {
                    ftol: true,
                    xtol: false,
                },
                Stop::Converged,
            ),
            (TerminationReason::Orthogonal, Stop::Orthogonal),
            (TerminationReason::ResidualsZero, Stop::ResidualsZero),
            (
                TerminationReason::NoImprovementPossible("gtol"),
                Stop::MachinePrecision,
            ),
            (TerminationReason::LostPatience, Stop::BudgetSpent),
        ];
        for (reason, stop) in ok {
            assert_eq!(stop_of(reason).ok(), Some(stop));
        }
        for reason in [
            TerminationReason::Numerical("jacobian"),
            TerminationReason::User("residuals"),
            TerminationReason::NoParameters,
            TerminationReason::NoResiduals,
            TerminationReason::WrongDimensions("residuals"),
        ] {
            assert!(
                matches!(stop_of(reason), Err(NetError::Training(m)) if m.contains("Levenberg"))
            );
        }
    }
}
