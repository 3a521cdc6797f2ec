//! The speed/accuracy trade points the report draws: `docs/trade/points.csv`, written by
//! `papers trade`, one row per knob setting (read through the trade module's schema,
//! [`CsvRow`], so the writer and every reader agree on one format).

use super::ReportError;
use handstack::{Line, Plot};
use paper_experiments::trade::{CsvRow, parse_csv};
use std::path::{Path, PathBuf};

/// One measured knob setting: a row of `points.csv`.
pub type TradePoint = CsvRow;

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
/// let points = paper_scenes::report::trade_points::parse(csv, "points.csv".as_ref())?;
/// assert_eq!(points[0].cost_us, 9.04);
/// assert!(points[0].pareto);
/// # Ok::<(), paper_scenes::report::ReportError>(())
/// ```
pub fn parse(text: &str, path: &Path) -> Result<Vec<TradePoint>, ReportError> {
    Ok(parse_csv(path, text)?)
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
    fn malformed_rows_name_their_line_and_problem() {
        let cases = [
            (
                format!("{HEADER}\nforce,osr,256,fast,80,%,true\n"),
                2,
                "column `cost_us`: `fast`",
            ),
            (format!("{HEADER}\nforce,osr,256,1.0,80,%\n"), 2, "6 fields"),
            (
                format!("{HEADER}\n\nforce,osr,256,1.0,80,%,maybe\n"),
                3,
                "pareto",
            ),
            (
                "task,knob,setting\n".to_owned(),
                1,
                "missing column `cost_us`",
            ),
            (String::new(), 1, "missing column `task`"),
        ];
        for (csv, line, word) in cases {
            match parse(&csv, Path::new("p.csv")) {
                Err(ReportError::TradeCsv(e)) => {
                    assert_eq!(e.line, Some(line), "{csv:?}");
                    let problem = e.to_string();
                    assert!(problem.starts_with(&format!("p.csv:{line}: ")), "{problem}");
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
