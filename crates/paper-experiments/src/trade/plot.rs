//! One SVG per task: every point, the Pareto front marked and joined in cost order.

use super::error::TradeError;
use super::pareto::Better;
use super::point::{Point, Task};
use crate::axis::{fmt_tick, padded, span, wants_log};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

fn err(path: &Path) -> impl Fn(String) -> TradeError + '_ {
    move |detail| TradeError::Write {
        path: path.display().to_string(),
        detail,
    }
}

/// Draws `task`'s points into `path` (SVG), each labelled with its number in `points` (from 1,
/// the `#` column of the report's table).
pub(crate) fn draw(task: &Task, points: &[&Point], path: &Path) -> Result<(), TradeError> {
    let e = err(path);
    let root = SVGBackend::new(path, (900, 520)).into_drawing_area();
    root.fill(&WHITE).map_err(|x| e(x.to_string()))?;
    chart(task, points, &root).map_err(e)?;
    root.present().map_err(|x| err(path)(x.to_string()))
}

fn chart(
    task: &Task,
    points: &[&Point],
    area: &DrawingArea<SVGBackend, Shift>,
) -> Result<(), String> {
    let costs = span(points.iter().map(|p| p.cost_us));
    // A wide cost spread (ns to ms) reads only on a log axis.
    let log_x = wants_log(costs);
    let x_lin = 0.0..padded(costs).end;
    let x_log = {
        let r = padded(span(points.iter().map(|p| p.cost_us.log10())));
        10f64.powf(r.start)..10f64.powf(r.end)
    };
    let y = padded(span(points.iter().map(|p| p.accuracy)));
    // Accuracies and errors are never negative: do not pad the axis below zero.
    let y = if y.start < 0.0 && points.iter().all(|p| p.accuracy >= 0.0) {
        0.0..y.end
    } else {
        y
    };
    let x_tick = if log_x { x_log.clone() } else { x_lin.clone() };
    let y_tick = y.clone();
    let direction = match task.better {
        Better::Higher => "higher is better",
        Better::Lower => "lower is better",
    };
    let front_style = RED.filled();
    let other_style = BLUE.mix(0.7).filled();
    let mut front: Vec<&&Point> = points.iter().filter(|p| p.pareto).collect();
    front.sort_by(|a, b| a.cost_us.total_cmp(&b.cost_us));
    let label_font = ("sans-serif", 12).into_font();
    macro_rules! body {
        ($chart:expr) => {{
            let mut chart = $chart;
            chart
                .configure_mesh()
                .x_desc(task.cost_label)
                .x_labels(8)
                .x_label_formatter(&|x: &f64| fmt_tick(*x, &x_tick))
                .y_label_formatter(&|v: &f64| fmt_tick(*v, &y_tick))
                .y_desc(format!("{} — {direction}", task.unit))
                .axis_desc_style(("sans-serif", 14))
                .draw()
                .map_err(|x| x.to_string())?;
            chart
                .draw_series(LineSeries::new(
                    front.iter().map(|p| (p.cost_us, p.accuracy)),
                    RED.stroke_width(1),
                ))
                .map_err(|x| x.to_string())?;
            chart
                .draw_series(
                    points
                        .iter()
                        .filter(|p| !p.pareto)
                        .map(|p| Circle::new((p.cost_us, p.accuracy), 4, other_style)),
                )
                .map_err(|x| x.to_string())?;
            chart
                .draw_series(
                    front
                        .iter()
                        .map(|p| Circle::new((p.cost_us, p.accuracy), 6, front_style)),
                )
                .map_err(|x| x.to_string())?;
            chart
                .draw_series(points.iter().enumerate().map(|(i, p)| {
                    EmptyElement::at((p.cost_us, p.accuracy))
                        + Text::new(format!("{}", i + 1), (6, -14), label_font.clone())
                }))
                .map_err(|x| x.to_string())?;
        }};
    }
    let builder = |area| {
        let mut b = ChartBuilder::on(area);
        b.caption(
            format!("{} (red: Pareto front)", task.title),
            ("sans-serif", 18),
        )
        .margin(18)
        .margin_right(30)
        .x_label_area_size(45)
        .y_label_area_size(70);
        b
    };
    if log_x {
        body!(
            builder(area)
                .build_cartesian_2d(x_log.log_scale(), y)
                .map_err(|x| x.to_string())?
        );
    } else {
        body!(
            builder(area)
                .build_cartesian_2d(x_lin, y)
                .map_err(|x| x.to_string())?
        );
    }
    Ok(())
}
