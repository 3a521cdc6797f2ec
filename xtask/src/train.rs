//! `cargo xtask train contact-mlp`: trains the contact-area MLP (seeded, one model per OSR and
//! head) and writes `fixtures/models/contact_mlp/` (weights + `metrics.json`), then draws
//! `docs/contact-location/contact-mlp-osr.svg` and prints the markdown table of
//! `docs/contact-location.md`.
//!
//! Training runs as `tactile-nets`'s `train_contact_mlp` example under the optimised `test`
//! profile (dfdx at `opt-level = 0`, the xtask's own profile, is several times slower).

use anyhow::{Context, Result, bail};
use plotters::prelude::*;
use std::path::Path;
use std::process::Command;
use tactile_nets::contact_eval::{METRICS_FILE, MODEL_DIR, row_label};
use tactile_nets::contact_mlp::Head;
use tactile_nets::metrics::MetricsFile;

/// The plot written next to `docs/contact-location.md`.
pub const PLOT: &str = "docs/contact-location/contact-mlp-osr.svg";

/// Runs `cargo xtask train <model>`.
pub fn run(root: &Path, args: &[String]) -> Result<()> {
    match args {
        [model] if model == "contact-mlp" => contact_mlp(root),
        [model] if model == "contact-cnn" => crate::train_cnn::run(root, false),
        [model, flag] if model == "contact-cnn" && flag == "--docs-only" => {
            crate::train_cnn::run(root, true)
        }
        _ => bail!("usage: cargo xtask train contact-mlp | contact-cnn [--docs-only]"),
    }
}

fn contact_mlp(root: &Path) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(["run", "--quiet", "--profile", "test", "-p", "tactile-nets"])
        .args(["--example", "train_contact_mlp", "--"])
        .arg(root)
        .current_dir(root)
        .status()
        .context("running the train_contact_mlp example")?;
    if !status.success() {
        bail!("training failed ({status})");
    }
    let path = root.join(MODEL_DIR).join(METRICS_FILE);
    let metrics = MetricsFile::from_json(
        &std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?,
    )?;
    plot(&metrics, &root.join(PLOT))?;
    println!("wrote {PLOT}\n\n{}", table(&metrics));
    Ok(())
}

/// The OSRs in the metrics rows, ascending.
fn osrs(metrics: &MetricsFile) -> Vec<u16> {
    let mut v: Vec<u16> = metrics
        .rows
        .iter()
        .filter_map(|r| r.label.strip_prefix("osr")?.split('/').next()?.parse().ok())
        .collect();
    v.sort_unstable();
    v.dedup();
    v
}

fn value(metrics: &MetricsFile, osr: u16, head: Head, key: &str) -> f64 {
    metrics
        .row(&row_label(osr, head))
        .and_then(|r| r.values.get(key).copied())
        .unwrap_or(f64::NAN)
}

/// The markdown table: one row per OSR, both heads side by side.
pub fn table(metrics: &MetricsFile) -> String {
    let mut s = String::from(
        "| OSR | 24-area acc. (eq. 4 regression) | 24-area acc. (cell-set) | exact set (regr.) | exact set (cell-set) | mean cell error (regr.) | mean cell error (cell-set) | centroid error, cells (regr. / cell-set) |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for osr in osrs(metrics) {
        let v = |h, k| value(metrics, osr, h, k);
        let (a, c) = (Head::AverageArea, Head::CellSet);
        s += &format!(
            "| {osr} | {:.1} % | {:.1} % | {:.1} % | {:.1} % | {:.2} | {:.2} | {:.2} / {:.2} |\n",
            100.0 * v(a, "area_accuracy"),
            100.0 * v(c, "area_accuracy"),
            100.0 * v(a, "exact_accuracy"),
            100.0 * v(c, "exact_accuracy"),
            v(a, "mean_cell_error"),
            v(c, "mean_cell_error"),
            v(a, "mean_centroid_error"),
            v(c, "mean_centroid_error"),
        );
    }
    s
}

fn plot(metrics: &MetricsFile, path: &Path) -> Result<()> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let osrs = osrs(metrics);
    let n = osrs.len().max(1) as f64;
    let root = SVGBackend::new(path, (960, 400)).into_drawing_area();
    root.fill(&WHITE).map_err(plot_err)?;
    let (left, right) = root.split_horizontally(480);
    let label_osr = |x: &f64| {
        osrs.get(x.round() as usize)
            .filter(|_| (x - x.round()).abs() < 1e-6)
            .map(|o| o.to_string())
            .unwrap_or_default()
    };
    let series = [
        (
            Head::AverageArea,
            "area_accuracy",
            "24-area, eq. 4 regression",
            RED,
        ),
        (
            Head::CellSet,
            "area_accuracy",
            "24-area, cell-set head",
            BLUE,
        ),
        (
            Head::AverageArea,
            "exact_accuracy",
            "exact set, eq. 4 regression",
            MAGENTA,
        ),
        (
            Head::CellSet,
            "exact_accuracy",
            "exact set, cell-set head",
            CYAN,
        ),
    ];
    let mut chart = ChartBuilder::on(&left)
        .caption("Contact-area MLP: held-out accuracy", ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(-0.2..n - 0.8, 0.0..100.0)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .x_desc("MS5611 OSR")
        .y_desc("%")
        .x_labels(osrs.len())
        .x_label_formatter(&label_osr)
        .draw()
        .map_err(plot_err)?;
    for (head, key, name, color) in series {
        let pts: Vec<(f64, f64)> = osrs
            .iter()
            .enumerate()
            .map(|(i, &o)| (i as f64, 100.0 * value(metrics, o, head, key)))
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(plot_err)?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color));
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
            .map_err(plot_err)?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::LowerRight)
        .draw()
        .map_err(plot_err)?;
    let max_err = osrs
        .iter()
        .flat_map(|&o| Head::ALL.map(|h| value(metrics, o, h, "mean_cell_error")))
        .fold(1.0f64, f64::max);
    let mut chart = ChartBuilder::on(&right)
        .caption(
            "Mean cell error (|predicted ∆ touched|)",
            ("sans-serif", 18),
        )
        .margin(10)
        .x_label_area_size(35)
        .y_label_area_size(45)
        .build_cartesian_2d(-0.2..n - 0.8, 0.0..max_err * 1.15)
        .map_err(plot_err)?;
    chart
        .configure_mesh()
        .x_desc("MS5611 OSR")
        .y_desc("cells")
        .x_labels(osrs.len())
        .x_label_formatter(&label_osr)
        .draw()
        .map_err(plot_err)?;
    for (head, name, color) in [
        (Head::AverageArea, "eq. 4 regression", RED),
        (Head::CellSet, "cell-set head", BLUE),
    ] {
        let pts: Vec<(f64, f64)> = osrs
            .iter()
            .enumerate()
            .map(|(i, &o)| (i as f64, value(metrics, o, head, "mean_cell_error")))
            .collect();
        chart
            .draw_series(LineSeries::new(pts, color.stroke_width(2)))
            .map_err(plot_err)?
            .label(name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 16, y)], color));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(plot_err)?;
    root.present().map_err(plot_err)?;
    Ok(())
}

fn plot_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("plot: {e}")
}
