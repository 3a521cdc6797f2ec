//! `fixtures/scenes/contact-location.toml` run as written: the MLP reproduces its committed
//! metrics row at the scene's OSR, eq. 3 / ranging reproduce the hits the AoT table of
//! docs/contact-location.md states for that OSR (the table `cargo run -p paper-experiments
//! --example aot_eval -- --write` writes and its drift test checks), and every estimator's
//! jittered-set (and the MLP's single-cell-set) figure is the one the doc's tables state (`cargo xtask train
//! contact-mlp --docs-only`; `contact_location_drift` checks it).

use crate::common;

use common::{committed, metrics, root, run_scene, value};
use handstack::Plot;

/// The doc's AoT row for `osr`: `(hits, n)` per rule column (eq. 3 rise, eq. 3 absolute,
/// ranging, then the missing-sensor count).
fn doc_row(osr: u16) -> Vec<(f64, f64)> {
    let doc = std::fs::read_to_string(root().join("docs/contact-location.md")).expect("doc");
    let section = &doc[doc.find("## Arrival-of-Time (3 × 3)").expect("AoT section")..];
    let line = section
        .lines()
        .find(|l| l.starts_with(&format!("| {osr} |")))
        .expect("a row for the OSR");
    line.split('|')
        .filter_map(|cell| {
            let inner = cell.trim().split('(').nth(1)?.strip_suffix(')')?;
            let (h, n) = inner.split_once('/')?;
            Some((h.parse().ok()?, n.parse().ok()?))
        })
        .collect()
}

/// The row for `osr` of the first table after `marker` in the doc's jittered-set section:
/// every `(hits/n)` as a percentage, in column order. The jittered table (marker: the
/// heading) holds eq. 3 rise, eq. 3 absolute, ranging, the off-lattice centroid-regression
/// MLP's single-cell and every-tap figures, then the other MLPs'; the single-cell set's table
/// (marker "The single-cell set,") the centroid-regression MLP first.
fn jittered_row(osr: u16, marker: &str) -> Vec<f64> {
    doc_table_row(marker, &format!("| {osr} |"))
}

/// The row starting `row` of the first table after `marker` in the doc's jittered-set
/// section: every `(hits/n)` as a percentage, in column order.
fn doc_table_row(marker: &str, row: &str) -> Vec<f64> {
    let doc = std::fs::read_to_string(root().join("docs/contact-location.md")).expect("doc");
    let section = &doc[doc
        .find("## Off the lattice: the jittered held-out set")
        .expect("jittered section")..];
    let section = &section[section.find(marker).expect("marker")..];
    let line = section
        .lines()
        .find(|l| l.starts_with(row))
        .expect("the row");
    line.split('(')
        .skip(1)
        .filter_map(|c| {
            let (h, n) = c.split(')').next()?.split_once('/')?;
            Some(100.0 * h.parse::<f64>().ok()? / n.parse::<f64>().ok()?)
        })
        .collect()
}

#[test]
fn contact_scene_reproduces_the_committed_contact_figures() {
    let o = run_scene("contact-location");
    // The scene file's OSR, chosen from the trade (its comment says why).
    let osr = 256;
    let row = doc_row(osr);
    assert_eq!(
        (value(&o, "aot_eq3_hits"), value(&o, "aot_eq3_taps")),
        row[0]
    );
    assert_eq!(
        (value(&o, "aot_ranging_hits"), value(&o, "aot_ranging_taps")),
        row[2]
    );
    // The labels: ranging meets 90 % on the lattice (a border tap in either area) and
    // on the jittered set (strict), as the doc states; the strict and interior-only lattice
    // figures carry no target.
    for fig in [
        "aot_ranging_accuracy_pct",
        "aot_ranging_jittered_accuracy_pct",
    ] {
        let f = o.figure(fig).expect("figure");
        assert_eq!(f.met, Some(true), "{f:?}");
    }
    for fig in [
        "aot_ranging_strict_accuracy_pct",
        "aot_ranging_interior_accuracy_pct",
    ] {
        assert_eq!(o.figure(fig).expect("figure").met, None);
    }
    let jittered = jittered_row(osr, "## Off the lattice");
    for (fig, column) in [
        ("aot_eq3_jittered_accuracy_pct", 0),
        ("aot_ranging_jittered_accuracy_pct", 2),
        ("mlp_jittered_area_accuracy_pct", 3),
        ("mlp_jittered_centroid_cell_pct", 4),
    ] {
        let (ours, doc) = (value(&o, fig), jittered[column]);
        assert!(
            (ours - doc).abs() < 1e-9,
            "{fig}: {ours} vs the doc's {doc}"
        );
    }
    let single_cell = jittered_row(osr, "The single-cell set,")[0];
    let ours = value(&o, "mlp_single_cell_area_accuracy_pct");
    assert!((ours - single_cell).abs() < 1e-9, "{ours} vs {single_cell}");
    // The pooled figure is the doc's pooled column (its first tally).
    let pooled = jittered_row(osr, "The single-cell set,")[5];
    let ours = value(&o, "mlp_off_lattice_pooled_area_accuracy_pct");
    assert!((ours - pooled).abs() < 1e-9, "{ours} vs {pooled}");
    // At OSR 256 the OSR-256 set too: the doc's row of the scene's model, and the same pool.
    let row = doc_table_row(
        "The OSR-256 single-cell set,",
        "| trained off the lattice, centroid regression |",
    );
    let ours = value(&o, "mlp_single_cell_osr256_area_accuracy_pct");
    assert!((ours - row[0]).abs() < 1e-9, "{ours} vs {}", row[0]);
    assert!((pooled - row[1]).abs() < 1e-9, "{pooled} vs {}", row[1]);
    // The MLP: the committed model the scene names (`off_lattice_centroid`) of this OSR on the
    // held-out taps, as its metrics row says.
    let m = metrics("contact_mlp");
    let (_, label) = paper_experiments::contact_eval::Mlp::OffLatticeCentroid.file_and_label(osr);
    for (fig, key, scale) in [
        ("mlp_area_accuracy_pct", "area_accuracy", 100.0),
        ("mlp_exact_accuracy_pct", "exact_accuracy", 100.0),
        ("mlp_mean_cell_error", "mean_cell_error", 1.0),
    ] {
        let (ours, theirs) = (value(&o, fig), scale * committed(&m, &label, key));
        assert!((ours - theirs).abs() < 1e-9, "{fig}: {ours} vs {theirs}");
    }
    // Figure 11-style maps: 3 × 3 per AoT rule, 4 × 6 for the MLP, each a percentage per area
    // whose taps-weighted mean is the overall accuracy.
    let grids: Vec<(usize, usize)> = o
        .plots
        .iter()
        .filter_map(|p| match p {
            Plot::Grid {
                rows, cols, values, ..
            } => {
                assert_eq!(values.len(), rows * cols);
                assert!(
                    values
                        .iter()
                        .all(|v| v.is_nan() || (0.0..=100.0).contains(v))
                );
                Some((*rows, *cols))
            }
            _ => None,
        })
        .collect();
    assert_eq!(grids, vec![(3, 3), (3, 3), (4, 6)]);
}
