//! `papers trade`: per-cycle cost against accuracy for each speed / accuracy knob of the
//! stack, measured in one run, with the Pareto front per task; writes `docs/trade.md`, one SVG
//! per task and the raw points (`docs/trade/points.csv`).
//!
//! Accuracies are deterministic (committed models and datasets, seeded simulators); CPU costs
//! are one-run wall-clock medians on whatever machine runs it (the criterion benches, `cargo
//! xtask bench`, are the reference); wire / conversion costs come from the datasheets.

pub mod defuzz;
mod error;
pub mod fixed_point;
pub mod force_width;
pub mod icm_mode;
pub mod location;
mod pareto;
mod plot;
mod point;
mod report;
pub mod timing;

pub use error::TradeError;
pub use pareto::{Better, pareto_front};
pub use point::{CostKind, CsvRow, Point, Task, mark_fronts, parse_csv, to_csv};
pub use report::markdown;

use std::path::Path;
use std::time::Instant;

/// Where the report goes, relative to the workspace root.
pub const DOC: &str = "docs/trade.md";
/// The directory of the plots and the points.
pub const DIR: &str = "docs/trade";
/// The raw points, relative to the workspace root.
pub const POINTS: &str = "docs/trade/points.csv";

/// A finished trade run.
#[derive(Debug, Clone)]
pub struct Trade {
    /// Every task, report order.
    pub tasks: Vec<Task>,
    /// Every point, Pareto flags set.
    pub points: Vec<Point>,
    /// The machine the CPU costs were measured on.
    pub machine: String,
    /// Wall time of the whole run, s.
    pub wall_s: f64,
    /// Findings printed under a task's table: `(task id, markdown)`.
    pub notes: Vec<(&'static str, String)>,
}

/// Every task, report order.
pub fn tasks() -> Vec<Task> {
    let mut t = location::tasks();
    t.push(force_width::task());
    t.extend(fixed_point::tasks());
    t.push(icm_mode::task());
    t.push(defuzz::task());
    t
}

/// Runs every knob against the workspace at `root`; `progress(step)` is called as each group
/// starts.
///
/// Errors: whatever a committed model, dataset or simulator reports, as [`TradeError`].
pub fn run(root: &Path, mut progress: impl FnMut(&str)) -> Result<Trade, TradeError> {
    let start = Instant::now();
    let machine = timing::machine();
    let tasks = tasks();
    let mut points = Vec::new();
    progress("contact location: AoT and MLP per OSR, CNN variants");
    points.extend(location::points(root)?);
    progress("force DNN widths: 13 leave-one-out models per width");
    let (force, force_note) = force_width::points(root)?;
    points.extend(force);
    progress(
        "fixed point vs f32: contact MLPs, force DNNs, contact CNNs and the softness net on \
         their held-out sets",
    );
    points.extend(fixed_point::mlp_points(root, true)?);
    points.extend(fixed_point::force_points(root, true)?);
    points.extend(fixed_point::cnn_points(root, true)?);
    points.extend(fixed_point::softness_points(root, true)?);
    progress("ICM-20789 pressure modes");
    points.extend(icm_mode::points()?);
    progress("grasp controller defuzzifiers, f32 and f64");
    points.extend(defuzz::points()?);
    let notes = vec![
        (force_width::TASK, force_note),
        (defuzz::TASK, defuzz::precision_note()?),
    ];
    mark_fronts(&tasks, &mut points)?;
    Ok(Trade {
        tasks,
        points,
        machine,
        wall_s: start.elapsed().as_secs_f64(),
        notes,
    })
}

/// Writes [`DOC`], [`POINTS`] and one SVG per task below `root`; returns the files written.
///
/// Errors: [`TradeError::Write`] naming the file.
pub fn write(root: &Path, trade: &Trade) -> Result<Vec<String>, TradeError> {
    let werr = |path: &str| {
        let path = path.to_owned();
        move |e: std::io::Error| TradeError::Write {
            path,
            detail: e.to_string(),
        }
    };
    std::fs::create_dir_all(root.join(DIR)).map_err(werr(DIR))?;
    let mut written = Vec::new();
    for task in &trade.tasks {
        let pts = task_points(trade, task);
        let file = plot_file(task);
        plot::draw(task, &pts, &root.join(&file))?;
        written.push(file);
    }
    std::fs::write(root.join(POINTS), to_csv(&trade.tasks, &trade.points)).map_err(werr(POINTS))?;
    written.push(POINTS.into());
    std::fs::write(root.join(DOC), markdown(trade)).map_err(werr(DOC))?;
    written.push(DOC.into());
    Ok(written)
}

/// `task`'s points, cheapest first (ties in run order): the numbering of its table and plot.
pub fn task_points<'a>(trade: &'a Trade, task: &Task) -> Vec<&'a Point> {
    let mut pts: Vec<&Point> = trade.points.iter().filter(|p| p.task == task.id).collect();
    pts.sort_by(|a, b| a.cost_us.total_cmp(&b.cost_us));
    pts
}

/// A task's plot, relative to the workspace root.
pub fn plot_file(task: &Task) -> String {
    format!("{DIR}/{}.svg", task.id)
}
