//! Trade points and tasks, and `points.csv` (columns
//! `task,knob,setting,cost_us,accuracy,accuracy_unit,pareto`).

use super::error::TradeError;
use super::pareto::{Better, pareto_front};
use hand_sim::records::{self, DatasetError, Schema};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// What a cost figure is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CostKind {
    /// CPU time per call, measured in this run (median of repeats).
    Cpu,
    /// Time on the wire / in the sensor's conversion, from the datasheet: no CPU involved.
    Wire,
}

/// One task: points that answer the same question and may be compared.
#[derive(Debug, Clone, PartialEq)]
pub struct Task {
    /// Stable identifier (CSV `task` column, plot file stem).
    pub id: &'static str,
    /// Heading in `docs/trade.md`.
    pub title: &'static str,
    /// What the cost is.
    pub cost: CostKind,
    /// What the cost axis measures, for the table and the plot.
    pub cost_label: &'static str,
    /// Which way the quality figure improves.
    pub better: Better,
    /// The quality figure's unit (CSV `accuracy_unit`).
    pub unit: &'static str,
    /// How the points were obtained and what they can and cannot be compared with.
    pub note: String,
}

/// One measured setting.
#[derive(Debug, Clone, PartialEq)]
pub struct Point {
    /// The [`Task::id`] it belongs to.
    pub task: &'static str,
    /// The knob turned.
    pub knob: String,
    /// The knob's setting.
    pub setting: String,
    /// Cost per control cycle (see the task's [`CostKind`]), µs.
    pub cost_us: f64,
    /// Quality (accuracy, error or noise: see the task's unit and [`Better`]).
    pub accuracy: f64,
    /// Whether it is on its task's Pareto front (set by [`mark_fronts`]).
    pub pareto: bool,
}

/// Sets [`Point::pareto`] task by task, on the values as [`to_csv`] writes them.
///
/// Errors: [`TradeError::NotFinite`] for a NaN / infinite point (its index in `points`), or
/// [`TradeError::Input`] for a point whose task is not in `tasks`.
pub fn mark_fronts(tasks: &[Task], points: &mut [Point]) -> Result<(), TradeError> {
    if let Some(p) = points
        .iter()
        .find(|p| !tasks.iter().any(|t| t.id == p.task))
    {
        return Err(TradeError::input(
            "trade points",
            format!("unknown task {}", p.task),
        ));
    }
    for task in tasks {
        let idx: Vec<usize> = (0..points.len())
            .filter(|&i| points[i].task == task.id)
            .collect();
        // As `points.csv` writes them (4 and 6 decimals): two costs that round alike are a
        // tie there, and the committed flags must be the fronts of the committed points.
        let rounded = |x: f64, decimals: i32| {
            let f = 10f64.powi(decimals);
            (x * f).round() / f
        };
        let xy: Vec<(f64, f64)> = idx
            .iter()
            .map(|&i| {
                (
                    rounded(points[i].cost_us, 4),
                    rounded(points[i].accuracy, 6),
                )
            })
            .collect();
        let front = pareto_front(&xy, task.better).map_err(|e| match e {
            TradeError::NotFinite { index } => TradeError::NotFinite { index: idx[index] },
            e => e,
        })?;
        for (&i, on) in idx.iter().zip(front) {
            points[i].pareto = on;
        }
    }
    Ok(())
}

/// `points.csv`: one row per point (fields never contain commas: settings use `;`).
pub fn to_csv(tasks: &[Task], points: &[Point]) -> String {
    let rows = points.iter().map(|p| CsvRow {
        task: p.task.to_owned(),
        knob: p.knob.replace(',', ";"),
        setting: p.setting.replace(',', ";"),
        cost_us: p.cost_us,
        accuracy: p.accuracy,
        unit: tasks
            .iter()
            .find(|t| t.id == p.task)
            .map_or("", |t| t.unit)
            .to_owned(),
        pareto: p.pareto,
    });
    records::render("", rows)
}

/// One row of `points.csv` (its schema: columns
/// `task,knob,setting,cost_us,accuracy,accuracy_unit,pareto`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CsvRow {
    /// Task id.
    pub task: String,
    /// Knob.
    pub knob: String,
    /// Setting.
    pub setting: String,
    /// Cost, µs (written with 4 decimals).
    #[serde(serialize_with = "records::fixed::<_, 4, _>")]
    pub cost_us: f64,
    /// Quality figure (written with 6 decimals).
    #[serde(serialize_with = "records::fixed::<_, 6, _>")]
    pub accuracy: f64,
    /// Its unit.
    #[serde(rename = "accuracy_unit")]
    pub unit: String,
    /// On the Pareto front.
    pub pareto: bool,
}

impl Schema for CsvRow {}

/// Parses `points.csv` text (what the drift test and the report read back); `file` names it in
/// errors.
///
/// Errors: [`DatasetError`] naming the line and column of a wrong header, field count or
/// value.
pub fn parse_csv(file: &Path, text: &str) -> Result<Vec<CsvRow>, DatasetError> {
    Ok(records::parse(file, text)?
        .into_iter()
        .map(|r| r.record)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn task(id: &'static str, better: Better) -> Task {
        Task {
            id,
            title: id,
            cost: CostKind::Cpu,
            cost_label: "µs",
            better,
            unit: "%",
            note: String::new(),
        }
    }

    fn point(task: &'static str, cost_us: f64, accuracy: f64) -> Point {
        Point {
            task,
            knob: "k".into(),
            setting: "a, b".into(),
            cost_us,
            accuracy,
            pareto: false,
        }
    }

    #[test]
    fn fronts_are_per_task_and_round_trip_through_csv() {
        let tasks = [task("a", Better::Higher), task("b", Better::Lower)];
        let mut pts = vec![
            point("a", 1.0, 50.0),
            point("b", 1.0, 50.0),
            point("a", 2.0, 40.0),
            point("b", 2.0, 40.0),
        ];
        mark_fronts(&tasks, &mut pts).unwrap();
        assert_eq!(
            pts.iter().map(|p| p.pareto).collect::<Vec<_>>(),
            [true, true, false, true]
        );
        let csv = to_csv(&tasks, &pts);
        let first = "task,knob,setting,cost_us,accuracy,accuracy_unit,pareto\n\
                     a,k,a; b,1.0000,50.000000,%,true\n";
        assert!(csv.starts_with(first), "{csv}");
        let rows = parse_csv("points.csv".as_ref(), &csv).unwrap();
        assert_eq!(rows.len(), 4);
        assert_eq!(rows[3].setting, "a; b");
        assert_eq!(
            (rows[3].cost_us, rows[3].accuracy, rows[3].pareto),
            (2.0, 40.0, true)
        );
    }

    #[test]
    fn bad_points_and_bad_csv_are_named() {
        let tasks = [task("a", Better::Higher)];
        let mut pts = vec![point("a", 1.0, 1.0), point("a", 1.0, f64::NAN)];
        assert_eq!(
            mark_fronts(&tasks, &mut pts),
            Err(TradeError::NotFinite { index: 1 })
        );
        assert!(mark_fronts(&tasks, &mut [point("zz", 1.0, 1.0)]).is_err());
        let header = "task,knob,setting,cost_us,accuracy,accuracy_unit,pareto";
        let bad = format!("{header}\na,k,s,1.0,x,%,true\n");
        let e = parse_csv("p.csv".as_ref(), &bad).unwrap_err();
        assert_eq!((e.line, e.column.as_deref()), (Some(2), Some("accuracy")));
        let e = parse_csv("p.csv".as_ref(), "nope").unwrap_err();
        assert_eq!((e.line, e.column.as_deref()), (Some(1), Some("task")));
    }
}
