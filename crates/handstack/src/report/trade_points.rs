//! The speed/accuracy trade points the report draws: `docs/trade/points.csv`, written by
//! `handstack trade`, one row per knob setting with the columns
//! `task,knob,setting,cost_us,accuracy,accuracy_unit,pareto` (any order, `#` lines ignored).

use super::ReportError;
use crate::{Line, Plot};
use std::path::{Path, PathBuf};

/// One measured knob setting.
#[derive(Debug, Clone, PartialEq)]
pub struct TradePoint {
    /// The task the accuracy is measured on (e.g. `force`, `location`).
    pub task: String,
    /// The knob turned (e.g. `ms5611_osr`).
    pub knob: String,
    /// Its setting (e.g. `4096`).
    pub setting: String,
    /// Cost per control cycle, µs.
    pub cost_us: f64,
    /// The task's quality figure (an accuracy, or an error / noise where lower is better),
    /// in `unit`.
    pub accuracy: f64,
    /// Unit of `accuracy` (`%`, `gf`, …): the CSV's `accuracy_unit`.
    pub unit: String,
    /// Whether the point is on its task's Pareto front.
    pub pareto: bool,
}

/// What the report's trade section shows.
#[derive(Debug, Clone, PartialEq)]
pub enum TradeSection {
    /// No trade points were asked for.
    NotRequested,
    /// The points file was asked for but does not exist.
    Absent(PathBuf),
    /// The points read from `path`.
    Points {
        /// Where they were read from.
        path: PathBuf,
        /// The rows, in file order.
        points: Vec<TradePoint>,
    },
}

const COLUMNS: [&str; 7] = [
    "task",
    "knob",
    "setting",
    "cost_us",
    "accuracy",
    "accuracy_unit",
    "pareto",
];

impl TradeSection {
    /// Reads `path`: [`TradeSection::Absent`] when it does not exist, an error naming the
    /// line when a row is malformed.
    pub fn load(path: &Path) -> Result<Self, ReportError> {
        match std::fs::read_to_string(path) {
            Ok(text) => Ok(Self::Points {
                path: path.to_path_buf(),
                points: parse(&text, path)?,
            }),
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                Ok(Self::Absent(path.to_path_buf()))
            }
            Err(source) => Err(ReportError::Io {
                path: path.to_path_buf(),
                source,
            }),
        }
    }
}

/// Parses the CSV text of `path` (named in errors).
///
/// ```
/// let csv = "task,knob,setting,cost_us,accuracy,accuracy_unit,pareto\n\
///            force,osr,4096,9.04,97.5,%,true\n";
/// let points = handstack::report::trade_points::parse(csv, "points.csv".as_ref())?;
/// assert_eq!(points[0].cost_us, 9.04);
/// assert!(points[0].pareto);
/// # Ok::<(), handstack::report::ReportError>(())
/// ```
pub fn parse(text: &str, path: &Path) -> Result<Vec<TradePoint>, ReportError> {
    let err = |line: usize, problem: String| ReportError::TradeCsv {
        path: path.to_path_buf(),
        line,
        problem,
    };
    let mut rows = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'));
    let (header_line, header) = rows
        .next()
        .ok_or_else(|| err(1, "empty file: no header".into()))?;
    let names: Vec<&str> = header.split(',').map(str::trim).collect();
    let mut index = [0usize; COLUMNS.len()];
    for (slot, col) in index.iter_mut().zip(COLUMNS) {
        *slot = names.iter().position(|n| *n == col).ok_or_else(|| {
            err(
                header_line,
                format!("header lacks column `{col}` (wanted {})", COLUMNS.join(",")),
            )
        })?;
    }
    rows.map(|(line, row)| {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != names.len() {
            return Err(err(
                line,
                format!("{} fields, the header has {}", cells.len(), names.len()),
            ));
        }
        let num = |k: usize| {
            cells[index[k]].parse::<f64>().map_err(|_| {
                err(
                    line,
                    format!("`{}` is not a number: {:?}", COLUMNS[k], cells[index[k]]),
                )
            })
        };
        let pareto = match cells[index[6]] {
            "true" | "1" | "yes" => true,
            "false" | "0" | "no" | "" => false,
            other => {
                return Err(err(
                    line,
                    format!("`pareto` must be true or false, not {other:?}"),
                ));
            }
        };
        Ok(TradePoint {
            task: cells[index[0]].to_owned(),
            knob: cells[index[1]].to_owned(),
            setting: cells[index[2]].to_owned(),
            cost_us: num(3)?,
            accuracy: num(4)?,
            unit: cells[index[5]].to_owned(),
            pareto,
        })
    })
    .collect()
}

/// The tasks in first-seen order.
pub(super) fn tasks(points: &[TradePoint]) -> Vec<&str> {
    let mut tasks: Vec<&str> = Vec::new();
    for p in points {
        if !tasks.contains(&p.task.as_str()) {
            tasks.push(&p.task);
        }
    }
    tasks
}

/// One task's curves as a [`Plot::Lines`] (a line per knob through its settings by cost)
/// and its Pareto front, by cost.
pub(super) fn task_plot(points: &[TradePoint], task: &str) -> (Plot, Line) {
    let of_task: Vec<&TradePoint> = points.iter().filter(|p| p.task == task).collect();
    let by_cost = |pred: &dyn Fn(&TradePoint) -> bool| {
        let mut pts: Vec<(f64, f64)> = of_task
            .iter()
            .filter(|p| pred(p))
            .map(|p| (p.cost_us, p.accuracy))
            .collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts
    };
    let mut knobs: Vec<&str> = Vec::new();
    for p in &of_task {
        if !knobs.contains(&p.knob.as_str()) {
            knobs.push(&p.knob);
        }
    }
    let lines = knobs
        .iter()
        .map(|k| Line {
            label: (*k).to_owned(),
            points: by_cost(&|p| p.knob == *k),
        })
        .collect();
    let front = Line {
        label: "Pareto front".into(),
        points: by_cost(&|p| p.pareto),
    };
    let unit = of_task.first().map_or("", |p| p.unit.as_str());
    let plot = Plot::Lines {
        title: format!("{task}: quality figure vs cost per cycle"),
        x_label: "cost per cycle, µs".into(),
        // The unit names the figure (`% correct (24 areas)`, `pressure rms error (Pa)`).
        y_label: unit.to_owned(),
        lines,
    };
    (plot, front)
}

#[cfg(test)]
mod tests {
    use super::*;

    const HEADER: &str = "task,knob,setting,cost_us,accuracy,accuracy_unit,pareto";

    #[test]
    fn columns_in_any_order_and_comments() {
        let csv = "# from handstack trade\npareto,task,knob,setting,cost_us,accuracy,accuracy_unit\n\
                   false,force,osr,256,1.2,80.5,%\n";
        let p = parse(csv, Path::new("p.csv")).unwrap();
        assert_eq!(p.len(), 1);
        assert_eq!(
            (p[0].task.as_str(), p[0].setting.as_str()),
            ("force", "256")
        );
        assert_eq!((p[0].cost_us, p[0].accuracy), (1.2, 80.5));
        assert!(!p[0].pareto);
    }

    #[test]
    fn malformed_rows_name_their_line_and_problem() {
        let cases = [
            (
                format!("{HEADER}\nforce,osr,256,fast,80,%,true\n"),
                2,
                "cost_us",
            ),
            (format!("{HEADER}\nforce,osr,256,1.0,80,%\n"), 2, "6 fields"),
            (
                format!("{HEADER}\n\nforce,osr,256,1.0,80,%,maybe\n"),
                3,
                "pareto",
            ),
            ("task,knob,setting\n".to_owned(), 1, "cost_us"),
            (String::new(), 1, "empty"),
        ];
        for (csv, line, word) in cases {
            match parse(&csv, Path::new("p.csv")) {
                Err(ReportError::TradeCsv {
                    line: l, problem, ..
                }) => {
                    assert_eq!(l, line, "{csv:?}");
                    assert!(problem.contains(word), "{problem} lacks {word}");
                }
                other => panic!("{csv:?} gave {other:?}"),
            }
        }
    }

    #[test]
    fn missing_file_is_absent_not_an_error() {
        let path = Path::new("/nonexistent/handstack/points.csv");
        assert_eq!(
            TradeSection::load(path).unwrap(),
            TradeSection::Absent(path.to_path_buf())
        );
    }

    #[test]
    fn task_plot_has_a_line_per_knob_and_the_front_apart() {
        let csv = format!(
            "{HEADER}\nforce,osr,4096,9,97,%,true\nforce,osr,256,1,80,%,true\n\
             force,width,8,5,85,%,false\nloc,osr,256,1,50,%,true\n"
        );
        let p = parse(&csv, Path::new("p.csv")).unwrap();
        assert_eq!(tasks(&p), ["force", "loc"]);
        let (Plot::Lines { lines, y_label, .. }, front) = task_plot(&p, "force") else {
            panic!("not lines")
        };
        assert_eq!(y_label, "%");
        let labels: Vec<&str> = lines.iter().map(|l| l.label.as_str()).collect();
        assert_eq!(labels, ["osr", "width"]);
        // Sorted by cost.
        assert_eq!(lines[0].points, [(1.0, 80.0), (9.0, 97.0)]);
        assert_eq!(front.points, [(1.0, 80.0), (9.0, 97.0)]);
    }
}
