//! `papers docs contact-mlp`: from the contact-area MLP's committed `metrics.json`
//! (`crates/tactile-nets/models/contact_mlp/`, written by `papers train contact-mlp`), draws
//! `docs/contact-location/contact-mlp-osr.svg` and prints the markdown tables of
//! `docs/contact-location.md`: the held-out metrics, and the centroid model's validation search
//! (`offlattice_centroid_selection.json`).

use super::plot::{draw_legend, legend_mark, plot_err};
use anyhow::{Context, Result};
use paper_experiments::contact_eval::{
    METRICS_FILE, MODEL_DIR, Mlp, OFF_LATTICE_CENTROID_SELECTION_FILE,
};
use plotters::prelude::*;
use std::path::Path;
use tactile_nets::metrics::MetricsFile;

/// The plot written next to `docs/contact-location.md`.
pub(crate) const PLOT: &str = "docs/contact-location/contact-mlp-osr.svg";

/// Draws the plot and prints the tables from the committed metrics and search.
pub(crate) fn write(root: &Path) -> Result<()> {
    let metrics = read(root, METRICS_FILE)?;
    plot(&metrics, &root.join(PLOT))?;
    let search = read(root, OFF_LATTICE_CENTROID_SELECTION_FILE)?;
    println!(
        "wrote {PLOT}\n\n{}\n{}",
        table(&metrics),
        search_table(&search)?
    );
    Ok(())
}

/// The committed metrics file `file` of [`MODEL_DIR`].
fn read(root: &Path, file: &str) -> Result<MetricsFile> {
    let path = root.join(MODEL_DIR).join(file);
    Ok(MetricsFile::from_json(
        &std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?,
    )?)
}

/// The centroid model's search as a markdown table, one row per candidate in search order,
/// the chosen one (which the file's description names) in bold.
pub(crate) fn search_table(search: &MetricsFile) -> Result<String> {
    let chosen = search
        .description
        .split_once("chosen ")
        .and_then(|(_, rest)| rest.split(';').next())
        .context("the search file's description names no chosen candidate")?;
    let first = search.rows.first().context("an empty search")?;
    let taps = first
        .values
        .get("single_cell_taps")
        .copied()
        .unwrap_or(f64::NAN);
    // Only the single-cell figure: the file's centroid error is measured to the unshifted
    // cells' centroid, which off the lattice is not where the tap was.
    let mut s = format!(
        "| candidate (validation draws, OSR 256) | single-cell taps placed (of {taps}) |\n\
         |---|---:|\n"
    );
    for row in &search.rows {
        let accuracy = 100.0 * row.values.get("area_accuracy").copied().unwrap_or(f64::NAN);
        if row.label == chosen {
            s += &format!("| **{} (chosen)** | **{accuracy:.2} %** |\n", row.label);
        } else {
            s += &format!("| {} | {accuracy:.2} % |\n", row.label);
        }
    }
    Ok(s)
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

/// The models the plot draws (the off-lattice ones decode to one cell, so their cell errors
/// measure their label, not their aim: they are in the table only).
const PLOTTED: [Mlp; 3] = [Mlp::AverageArea, Mlp::CellSet, Mlp::Chosen];
/// The table's models, in order.
const TABLED: [Mlp; 5] = [
    Mlp::AverageArea,
    Mlp::CellSet,
    Mlp::Chosen,
    Mlp::OffLattice,
    Mlp::OffLatticeCentroid,
];

fn value(metrics: &MetricsFile, osr: u16, model: Mlp, key: &str) -> f64 {
    metrics
        .row(&model.file_and_label(osr).1)
        .and_then(|r| r.values.get(key).copied())
        .unwrap_or(f64::NAN)
}

/// The markdown table: one row per OSR and model.
pub(crate) fn table(metrics: &MetricsFile) -> String {
    let mut s = String::from(
        "| OSR | model | 24-area acc. (single-cell taps) | exact set | mean cell error | mean centroid error, cells |\n\
         |---:|---|---:|---:|---:|---:|\n",
    );
    for osr in osrs(metrics) {
        for m in TABLED {
            let v = |k| value(metrics, osr, m, k);
            if v("taps").is_nan() {
                continue;
            }
            s += &format!(
                "| {osr} | {} | {:.1} % | {:.1} % | {:.2} | {:.2} |\n",
                m.name(),
                100.0 * v("area_accuracy"),
                100.0 * v("exact_accuracy"),
                v("mean_cell_error"),
                v("mean_centroid_error"),
            );
        }
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
            Mlp::AverageArea,
            "area_accuracy",
            "24-area, paper recipe, eq. 4 regression",
            RED,
        ),
        (
            Mlp::CellSet,
            "area_accuracy",
            "24-area, paper recipe, cell-set head",
            BLUE,
        ),
        (
            Mlp::Chosen,
            "area_accuracy",
            "24-area, validation-chosen",
            GREEN,
        ),
        (
            Mlp::Chosen,
            "exact_accuracy",
            "exact set, validation-chosen",
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
    for (model, key, name, color) in series {
        let pts: Vec<(f64, f64)> = osrs
            .iter()
            .enumerate()
            .map(|(i, &o)| (i as f64, 100.0 * value(metrics, o, model, key)))
            .collect();
        chart
            .draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
            .map_err(plot_err)?
            .label(name)
            .legend(legend_mark(color));
        chart
            .draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
            .map_err(plot_err)?;
    }
    draw_legend(&mut chart, SeriesLabelPosition::LowerRight)?;
    let max_err = osrs
        .iter()
        .flat_map(|&o| PLOTTED.map(|m| value(metrics, o, m, "mean_cell_error")))
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
    for (model, color) in PLOTTED.into_iter().zip([RED, BLUE, GREEN]) {
        let name = model.name();
        let pts: Vec<(f64, f64)> = osrs
            .iter()
            .enumerate()
            .map(|(i, &o)| (i as f64, value(metrics, o, model, "mean_cell_error")))
            .collect();
        chart
            .draw_series(LineSeries::new(pts, color.stroke_width(2)))
            .map_err(plot_err)?
            .label(name)
            .legend(legend_mark(color));
    }
    draw_legend(&mut chart, SeriesLabelPosition::MiddleRight)?;
    root.present().map_err(plot_err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/contact-location.md quotes the table this job prints (it is pasted, not written
    /// into a section: prose surrounds it), so a retrained model cannot leave it stale.
    #[test]
    fn the_doc_quotes_the_printed_table() -> Result<()> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let metrics = MetricsFile::from_json(&std::fs::read_to_string(
            root.join(MODEL_DIR).join(METRICS_FILE),
        )?)?;
        let doc = std::fs::read_to_string(root.join("docs/contact-location.md"))?;
        let table = table(&metrics);
        assert_eq!(table.lines().count(), 2 + 5 * TABLED.len(), "{table}");
        assert!(
            doc.contains(&table),
            "docs/contact-location.md does not quote `papers docs contact-mlp`'s table:\n{table}"
        );
        // And the centroid model's search, every candidate, one of them chosen.
        let search = search_table(&read(&root, OFF_LATTICE_CENTROID_SELECTION_FILE)?)?;
        let grid = paper_experiments::contact_eval::off_lattice_centroid_grid();
        assert_eq!(search.lines().count(), 2 + grid.len(), "{search}");
        assert_eq!(search.matches("(chosen)").count(), 1, "{search}");
        assert!(
            doc.contains(&search),
            "docs/contact-location.md does not quote the centroid search's table:\n{search}"
        );
        Ok(())
    }
}
