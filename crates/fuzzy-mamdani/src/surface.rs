//! The control surface of a two-input engine: as CSV, and (feature `plot`) as an image.

use std::io::Write;
use std::vec::Vec;

use crate::{Engine, EvalError, Real};

/// The most steps per axis [`surface`] takes (a grid of 16.8 M points).
pub const MAX_SURFACE_STEPS: usize = 1 << 12;

/// Samples output 0 of a two-input engine on a `steps × steps` grid over the input universes:
/// rows of `(x, y, z)`, x-major.
///
/// ```
/// let engine = fuzzy_mamdani::grasp_engine::<f64>();
/// let grid = fuzzy_mamdani::surface(&engine, 3)?;
/// assert_eq!(grid.len(), 9);
/// assert!((grid[4].2 - 511.5).abs() < 1e-9); // e = 0, de = 0
/// # Ok::<(), fuzzy_mamdani::EvalError>(())
/// ```
pub fn surface<T: Real>(engine: &Engine<T>, steps: usize) -> Result<Vec<(T, T, T)>, EvalError> {
    if steps > MAX_SURFACE_STEPS {
        return Err(EvalError::TooManySteps {
            steps,
            max: MAX_SURFACE_STEPS,
        });
    }
    let inputs = engine.inputs();
    if inputs.len() != 2 {
        return Err(EvalError::InputCount {
            expected: 2,
            got: inputs.len(),
        });
    }
    let steps = steps.max(2);
    let at = |v: &crate::InputVariable<T>, k: usize| {
        crate::mf::lerp(v.min, v.max, T::of(k as f64 / (steps - 1) as f64))
    };
    let mut scratch = engine.scratch();
    let mut out = Vec::with_capacity(steps * steps);
    for i in 0..steps {
        for j in 0..steps {
            let (x, y) = (at(&inputs[0], i), at(&inputs[1], j));
            out.push((x, y, engine.evaluate(&mut scratch, &[x, y])?[0]));
        }
    }
    Ok(out)
}

/// Writes [`surface`] as CSV with a header naming the variables.
pub fn write_surface_csv<T: Real>(
    engine: &Engine<T>,
    steps: usize,
    mut w: impl Write,
) -> std::io::Result<()> {
    let grid = surface(engine, steps).map_err(std::io::Error::other)?;
    let names: Vec<&str> = engine
        .inputs()
        .iter()
        .map(|v| v.name.as_str())
        .chain([engine.outputs()[0].name.as_str()])
        .collect();
    writeln!(w, "{}", names.join(","))?;
    for (x, y, z) in grid {
        writeln!(w, "{x},{y},{z}")?;
    }
    Ok(())
}

/// Draws [`surface`] as a heat map (x: input 0, y: input 1, colour: output) into `path`;
/// `.svg` gives SVG, anything else a bitmap (PNG for `.png`).
#[cfg(feature = "plot")]
pub fn plot_surface<T: Real>(
    engine: &Engine<T>,
    steps: usize,
    path: &std::path::Path,
) -> Result<(), std::boxed::Box<dyn std::error::Error>> {
    use plotters::prelude::*;
    if path.extension().is_some_and(|e| e == "svg") {
        heat_map(
            engine,
            steps,
            SVGBackend::new(path, (640, 560)).into_drawing_area(),
        )
    } else {
        heat_map(
            engine,
            steps,
            BitMapBackend::new(path, (640, 560)).into_drawing_area(),
        )
    }
}

#[cfg(feature = "plot")]
fn heat_map<T: Real, DB: plotters::prelude::DrawingBackend>(
    engine: &Engine<T>,
    steps: usize,
    root: plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
) -> Result<(), std::boxed::Box<dyn std::error::Error>>
where
    DB::ErrorType: 'static,
{
    use plotters::prelude::*;
    let grid = surface(engine, steps)?;
    let f = |v: T| v.to_f64_lossless();
    let (ins, out) = (engine.inputs(), &engine.outputs()[0]);
    let (zlo, zhi) = (f(out.min), f(out.max));
    let cell = |v: &crate::InputVariable<T>| (f(v.max) - f(v.min)) / (steps.max(2) - 1) as f64;
    let (dx, dy) = (cell(&ins[0]), cell(&ins[1]));
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            std::format!("{}: {}", engine.name(), out.name),
            ("sans-serif", 20),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(
            f(ins[0].min) - dx / 2.0..f(ins[0].max) + dx / 2.0,
            f(ins[1].min) - dy / 2.0..f(ins[1].max) + dy / 2.0,
        )?;
    chart
        .configure_mesh()
        .x_desc(ins[0].name.as_str())
        .y_desc(ins[1].name.as_str())
        .draw()?;
    chart.draw_series(grid.iter().map(|&(x, y, z)| {
        // Blue (low output) to red (high output).
        let t = ((f(z) - zlo) / (zhi - zlo)).clamp(0.0, 1.0);
        let (x, y) = (f(x), f(y));
        let corners = [(x - dx / 2.0, y - dy / 2.0), (x + dx / 2.0, y + dy / 2.0)];
        Rectangle::new(corners, HSLColor(0.66 * (1.0 - t), 0.85, 0.5).filled())
    }))?;
    root.present()?;
    Ok(())
}
