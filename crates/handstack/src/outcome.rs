//! What a scene run measured: figures (with the paper's value and the target beside them) and
//! the data a report draws. Serialised as-is by `handstack run --json`.

use serde::Serialize;

/// The result of one scene run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Outcome {
    /// The scene's name (its file stem, e.g. `weight-estimation`).
    pub scene: String,
    /// One line saying what the scene reproduces (paper, table or figure).
    pub title: String,
    /// The measured figures, in report order.
    pub figures: Vec<Figure>,
    /// The data for the report's plots, in report order.
    pub plots: Vec<Plot>,
    /// What the run left its devices doing, one line each (`hand released (opened to 3.14
    /// rad), then torque off`).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
    /// Wall time of the run, seconds (not part of any assertion).
    pub wall_s: f64,
}

impl Outcome {
    /// The figure named `name`, if the run measured it.
    pub fn figure(&self, name: &str) -> Option<&Figure> {
        self.figures.iter().find(|f| f.name == name)
    }
}

/// One measured number.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Figure {
    /// Stable identifier, `snake_case` (tests and `--json` consumers key on it).
    pub name: String,
    /// What it is, for people.
    pub label: String,
    /// The measured value.
    pub value: f64,
    /// Its unit (`%`, `gf`, `µs`, `raw`, …; empty when dimensionless).
    pub unit: String,
    /// The paper's published value for the same figure, if it publishes one.
    pub paper: Option<f64>,
    /// Where the paper's value comes from (seed, table, page), when `paper` is set.
    pub source: Option<String>,
    /// The target, e.g. `≥ 90` or `≤ 0.5`, if one is set.
    pub target: Option<String>,
    /// Whether `value` meets `target` (`None` without a target).
    pub met: Option<bool>,
    /// Why a missed target is a finding about the method rather than a fault of this
    /// software (a paper's formula as written, say), in plain words; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub finding: Option<String>,
}

/// Data for one plot of the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Plot {
    /// Lines over a shared x axis (grasp traces, training curves, trade curves).
    Lines {
        /// Plot title.
        title: String,
        /// x-axis label with unit.
        x_label: String,
        /// y-axis label with unit.
        y_label: String,
        /// The lines.
        lines: Vec<Line>,
    },
    /// A confusion matrix: `counts[true][predicted]`.
    Confusion {
        /// Plot title.
        title: String,
        /// Class names, in index order.
        labels: Vec<String>,
        /// Counts, row = true class, column = predicted class.
        counts: Vec<Vec<u32>>,
    },
    /// A value per cell of a rows × cols grid, row-major (contact maps as in Kim et al. 2020,
    /// Figure 11).
    Grid {
        /// Plot title.
        title: String,
        /// Grid rows.
        rows: usize,
        /// Grid columns.
        cols: usize,
        /// `rows * cols` values, row-major.
        values: Vec<f64>,
        /// Unit of the values.
        unit: String,
    },
    /// z over an x × y grid (the fuzzy controller's control surface).
    Surface {
        /// Plot title.
        title: String,
        /// x-axis label with unit.
        x_label: String,
        /// y-axis label with unit.
        y_label: String,
        /// z label with unit.
        z_label: String,
        /// x sample points.
        xs: Vec<f64>,
        /// y sample points.
        ys: Vec<f64>,
        /// `z[iy][ix]`.
        z: Vec<Vec<f64>>,
    },
}

/// One line of a [`Plot::Lines`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Line {
    /// Legend entry.
    pub label: String,
    /// `(x, y)` points in order.
    pub points: Vec<(f64, f64)>,
}
