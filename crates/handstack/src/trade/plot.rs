//! One SVG per task: every point, the Pareto front marked and joined in cost order.

use super::error::TradeError;
use super::pareto::Better;
use super::point::{Point, Task};
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

/// A cost tick without trailing `.0` noise: 12000, 2.5, 0.15.
fn tick(x: f64) -> String {
    match x.abs() {
        a if a >= 100.0 || a == 0.0 => format!("{x:.0}"),
        a if a >= 1.0 => format!("{x:.1}"),
        _ => format!("{x:.2}"),
    }
}

/// `(lo, hi)` padded so single values and flat sets still get an axis.
fn span(values: impl Iterator<Item = f64>, log: bool) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
        (l.min(v), h.max(v))
    });
    if log {
        (lo / 1.6, hi * 1.6)
    } else {
        let pad = ((hi - lo) * 0.12).max(hi.abs() * 0.05).max(1e-3);
        (lo - pad, hi + pad)
    }
}

fn chart(
    task: &Task,
    points: &[&Point],
    area: &DrawingArea<SVGBackend, Shift>,
) -> Result<(), String> {
    let (cmin, cmax) = points.iter().fold((f64::INFINITY, 0.0f64), |(l, h), p| {
        (l.min(p.cost_us), h.max(p.cost_us))
    });
    // A wide cost spread (ns to ms) reads only on a log axis.
    let log_x = cmin > 0.0 && cmax > 10.0 * cmin;
    let (_, chi) = span(points.iter().map(|p| p.cost_us), false);
    let (ylo, yhi) = span(points.iter().map(|p| p.accuracy), false);
    let ylo = if ylo < 0.0 && points.iter().all(|p| p.accuracy >= 0.0) {
        0.0
    } else {
        ylo
    };
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
                .x_label_formatter(&|x: &f64| tick(*x))
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
        let (lo, hi) = span(points.iter().map(|p| p.cost_us), true);
        body!(
            builder(area)
                .build_cartesian_2d((lo..hi).log_scale(), ylo..yhi)
                .map_err(|x| x.to_string())?
        );
    } else {
        body!(
            builder(area)
                .build_cartesian_2d(0.0..chi, ylo..yhi)
                .map_err(|x| x.to_string())?
        );
    }
    Ok(())
}
