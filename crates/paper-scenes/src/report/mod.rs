//! The demo report: one self-contained HTML file (inline CSS and SVG, no network, no script)
//! of a list of [`Outcome`]s and the speed/accuracy trade points.
//!
//! First what the stack achieves over every scene (targets met, findings, this software's own
//! misses by name). Per scene: its title, a figures table (value, paper, target, met — an unmet
//! target shows as unmet, a finding with its reason) and one inline SVG per
//! [`Plot`](handstack::Plot). Then the trade curves read from
//! `docs/trade/points.csv` (see [`trade_points`]), or a note saying why they are missing.
//! The header names the git commit, the date and the machine the runs were made on.
//!
//! ```
//! use paper_scenes::report::{Provenance, TradeSection, render};
//! use handstack::{Figure, Outcome};
//!
//! let outcome = Outcome {
//!     scene: "weight-estimation".into(),
//!     title: "Seed 000 Table 1 <weights>".into(),
//!     figures: vec![Figure {
//!         name: "mae_gf".into(),
//!         label: "mean absolute error".into(),
//!         value: 4.2,
//!         unit: "gf".into(),
//!         paper: Some(3.9),
//!         source: Some("seed 000 Table 1".into()),
//!         target: Some("≤ 5".into()),
//!         met: Some(true),
//!         finding: None,
//!     }],
//!     plots: vec![],
//!     notes: vec![],
//!     wall_s: 1.5,
//! };
//! let trade = TradeSection::NotRequested;
//! let html = render(&[outcome], &[], &trade, &Provenance::fixed("abc123"))?;
//! assert!(html.contains("Seed 000 Table 1 &lt;weights&gt;")); // text is escaped
//! assert!(html.contains(r#"data-figure="mae_gf""#));
//! # Ok::<(), paper_scenes::report::ReportError>(())
//! ```

pub mod browser;
mod html;
mod plot_svg;
mod provenance;
pub mod trade_points;

pub use html::render;
pub use provenance::Provenance;
pub use trade_points::{TradePoint, TradeSection};

use handstack::Outcome;
// Figures as handstack's summary shows them: one number format in every output of a run.
use handstack::summary::number as fmt_num;
use std::path::{Path, PathBuf};

/// Where `papers trade` writes the trade points, relative to the workspace root.
pub use paper_experiments::trade::POINTS as TRADE_POINTS;

/// What can go wrong while writing a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A plot could not be drawn (plotters' message).
    #[error("plot {title:?}: {message}")]
    Plot {
        /// The plot's title.
        title: String,
        /// What plotters said.
        message: String,
    },
    /// The trade points CSV is malformed (the error names the file, line and column).
    #[error(transparent)]
    TradeCsv(#[from] paper_experiments::data::DatasetError),
    /// Reading or writing a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

/// A scene that did not produce an [`Outcome`]: the report lists it with its error, so a
/// failed run is not silently missing from the page.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failed {
    /// The scene (file name or stem).
    pub scene: String,
    /// The error, as the run reported it.
    pub error: String,
}

/// Renders `outcomes`, the `failed` scenes and the trade points at `trade_points` (when
/// given) with the [`Provenance`] detected from the current directory's git checkout, and
/// writes the page to `out`, creating its directory.
///
/// A missing `trade_points` file is not an error (the page says it is absent); a malformed
/// one is.
pub fn write_html(
    outcomes: &[Outcome],
    failed: &[Failed],
    trade_points: Option<&Path>,
    out: &Path,
) -> Result<(), ReportError> {
    let trade = match trade_points {
        None => TradeSection::NotRequested,
        Some(path) => TradeSection::load(path)?,
    };
    let html = render(outcomes, failed, &trade, &Provenance::detect())?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| ReportError::Io {
            path: dir.to_path_buf(),
            source,
        })?;
    }
    std::fs::write(out, html).map_err(|source| ReportError::Io {
        path: out.to_path_buf(),
        source,
    })
}

/// `text` with the characters HTML gives meaning to escaped (safe in text and attributes).
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{ReportError, escape, write_html};
    use std::path::Path;

    #[test]
    fn write_html_creates_the_directory_and_names_an_unwritable_path() {
        let dir = std::env::temp_dir().join(format!("handstack-report-{}", std::process::id()));
        let out = dir.join("a/b/report.html");
        write_html(&[], &[], Some(Path::new("/nonexistent/points.csv")), &out).unwrap();
        let html = std::fs::read_to_string(&out).unwrap();
        assert!(html.starts_with("<!DOCTYPE html>") && html.contains("is absent"));
        // A file where the directory should be.
        let blocked = dir.join("a/b/report.html/inner.html");
        match write_html(&[], &[], None, &blocked) {
            Err(ReportError::Io { path, .. }) => assert!(path.ends_with("report.html")),
            other => panic!("{other:?}"),
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(
            escape(r#"<b a="1">&'</b>"#),
            "&lt;b a=&quot;1&quot;&gt;&amp;&#39;&lt;/b&gt;"
        );
    }
}
