//! Defuzzifier knob of the grasp controller (seed 000 §5): center average (the paper's) vs
//! centroid at several sample counts, each in f32 and f64 (fuzzy-mamdani's `Real`). Error:
//! the largest |torque − reference| over a grid of the controller's inputs, the reference being
//! the f64 centroid at [`REFERENCE_SAMPLES`] points; cost: CPU per evaluation, measured.

use super::error::TradeError;
use super::pareto::Better;
use super::point::{CostKind, Point, Task};
use super::timing::median_us;
use fuzzy_mamdani::{Defuzzifier, Engine, EngineBuilder, Real, Resolution, grasp_engine};

/// Task id.
pub const TASK: &str = "grasp-defuzzifier";
/// Grid points per input over the normalised universe [-1, 1] (e, de).
pub const GRID: usize = 41;
/// Samples of the reference centroid.
pub const REFERENCE_SAMPLES: usize = 100_001;
/// Centroid sample counts measured (MATLAB's default is 101).
pub const SAMPLES: [usize; 5] = [11, 21, 51, 101, 1001];

/// The task.
pub fn task() -> Task {
    Task {
        id: TASK,
        title: "Grasp controller: defuzzifier and precision",
        cost: CostKind::Cpu,
        cost_label: "CPU per controller evaluation, µs",
        better: Better::Lower,
        unit: "max |torque error| (raw 0-1023)",
        note: format!(
            "`fuzzy_mamdani::grasp_engine` (seed 000 §5: 9 × 9 rules, product AND, Gaussian \
             output terms) with its defuzzifier swapped. Error: the largest |torque − reference| \
             over a {GRID} × {GRID} grid of (e, de) on [−1, 1]², in MX-28 torque-limit units \
             (0–1023); reference: centroid in f64 at {REFERENCE_SAMPLES} samples. Center average \
             is a different defuzzifier, not a coarser centroid, so its error is how far the \
             paper's choice sits from the centroid surface (not a numerical error); the f32 / \
             f64 rows of one defuzzifier show what single precision costs. Cost: median of \
             repeated passes over the grid, per evaluation."
        ),
    }
}

/// The grasp engine with `defuzzifier` on its output.
pub fn engine<T: Real>(defuzzifier: Defuzzifier) -> Result<Engine<T>, TradeError> {
    let base = grasp_engine::<T>();
    let mut b = EngineBuilder::new(base.name())
        .conjunction(base.conjunction())
        .disjunction(base.disjunction())
        .implication(base.implication());
    for v in base.inputs() {
        b = b.input_variable(v.clone());
    }
    for v in base.outputs() {
        let mut v = v.clone();
        v.defuzzifier = defuzzifier;
        b = b.output_variable(v);
    }
    for r in base.rules() {
        b = b.rule_struct(r.clone());
    }
    b.build().map_err(|e| TradeError::input("grasp engine", e))
}

/// The grid of (e, de) inputs.
pub fn grid() -> Vec<[f64; 2]> {
    let x = |i: usize| -1.0 + 2.0 * i as f64 / (GRID - 1) as f64;
    (0..GRID * GRID)
        .map(|k| [x(k / GRID), x(k % GRID)])
        .collect()
}

/// The engine's torque at every grid point, as f64.
pub fn surface<T: Real>(engine: &Engine<T>, grid: &[[f64; 2]]) -> Result<Vec<f64>, TradeError> {
    let mut s = engine.scratch();
    grid.iter()
        .map(|&[e, de]| {
            let out = engine
                .evaluate(&mut s, &[T::of(e), T::of(de)])
                .map_err(|err| TradeError::input("grasp engine", err))?;
            Ok(out[0].to_f64_lossless())
        })
        .collect()
}

/// The largest |a − b| over two surfaces.
pub fn max_deviation(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The settings: (name, defuzzifier).
pub fn settings() -> Vec<(String, Defuzzifier)> {
    let mut v = vec![("center average".to_owned(), Defuzzifier::CenterAverage)];
    v.extend(SAMPLES.map(|n| {
        (
            format!("centroid {n} samples"),
            Defuzzifier::Centroid(Resolution::Samples(n)),
        )
    }));
    v
}

/// The reference surface.
pub fn reference(grid: &[[f64; 2]]) -> Result<Vec<f64>, TradeError> {
    surface(
        &engine::<f64>(Defuzzifier::Centroid(Resolution::Samples(
            REFERENCE_SAMPLES,
        )))?,
        grid,
    )
}

/// Every setting's error against the reference, without timing: `(setting, precision, error)`.
/// What the drift test recomputes.
pub fn errors() -> Result<Vec<(String, &'static str, f64)>, TradeError> {
    let grid = grid();
    let reference = reference(&grid)?;
    let mut out = Vec::new();
    for (name, d) in settings() {
        out.push((
            name.clone(),
            "f32",
            max_deviation(&surface(&engine::<f32>(d)?, &grid)?, &reference),
        ));
        out.push((
            name,
            "f64",
            max_deviation(&surface(&engine::<f64>(d)?, &grid)?, &reference),
        ));
    }
    Ok(out)
}

/// Knob label.
pub const KNOB: &str = "defuzzifier; precision";

/// Setting label of a defuzzifier at a precision.
pub fn setting(name: &str, precision: &str) -> String {
    format!("{name}; {precision}")
}

/// The largest |f32 − f64| torque per setting over the grid: what single precision changes.
pub fn precision_note() -> Result<String, TradeError> {
    let grid = grid();
    let mut parts = Vec::new();
    for (name, d) in settings() {
        let dev = max_deviation(
            &surface(&engine::<f32>(d)?, &grid)?,
            &surface(&engine::<f64>(d)?, &grid)?,
        );
        parts.push(format!("{name} {dev:.2e}"));
    }
    Ok(format!(
        "**f32 vs f64**: largest |torque(f32) − torque(f64)| over the grid, raw units: {}. \
         Single precision moves the torque by far less than one step of the 0–1023 scale, \
         so the precision choice is a cost choice only.",
        parts.join(", ")
    ))
}

fn cost_us<T: Real>(engine: &Engine<T>, grid: &[[f64; 2]]) -> f64 {
    let inputs: Vec<[T; 2]> = grid.iter().map(|&[a, b]| [T::of(a), T::of(b)]).collect();
    let mut s = engine.scratch();
    median_us(1, || {
        let mut acc = T::zero();
        for x in &inputs {
            if let Ok(out) = engine.evaluate(&mut s, x) {
                acc = acc + out[0];
            }
        }
        acc
    }) / inputs.len() as f64
}

/// Measures every setting: error against the reference and CPU per evaluation.
pub fn points() -> Result<Vec<Point>, TradeError> {
    let grid = grid();
    let errors = errors()?;
    let mut out = Vec::new();
    for (name, d) in settings() {
        let (e32, e64) = (engine::<f32>(d)?, engine::<f64>(d)?);
        for (precision, cost) in [("f32", cost_us(&e32, &grid)), ("f64", cost_us(&e64, &grid))] {
            let err = errors
                .iter()
                .find(|(n, p, _)| *n == name && *p == precision)
                .map_or(f64::NAN, |e| e.2);
            out.push(Point {
                task: TASK,
                knob: KNOB.into(),
                setting: setting(&name, precision),
                cost_us: cost,
                accuracy: err,
                pareto: false,
            });
        }
    }
    Ok(out)
}
