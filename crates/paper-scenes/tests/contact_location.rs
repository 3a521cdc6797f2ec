//! `fixtures/scenes/contact-location.toml` run as written: the MLP reproduces its committed
//! metrics row at the scene's OSR, and eq. 3 / ranging reproduce the hits the AoT table of
//! docs/contact-location.md states for that OSR (the table `cargo run -p paper-experiments --example
//! aot_eval -- --write` writes and aot-locate's drift test checks).

mod common;

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

#[test]
fn contact_scene_reproduces_the_committed_contact_figures() {
    let o = run_scene("contact-location");
    let osr = 512;
    let row = doc_row(osr);
    assert_eq!(
        (value(&o, "aot_eq3_hits"), value(&o, "aot_eq3_taps")),
        row[0]
    );
    assert_eq!(
        (value(&o, "aot_ranging_hits"), value(&o, "aot_ranging_taps")),
        row[2]
    );
    // Ranging on taps centred inside one area: the 90 % met (docs: 100 % at OSR 512).
    let inside = o
        .figure("aot_ranging_interior_accuracy_pct")
        .expect("figure");
    assert_eq!(inside.met, Some(true), "{inside:?}");
    // The MLP: the committed model of this OSR on the held-out taps, as its metrics row says.
    let m = metrics("contact_mlp");
    let label = format!("osr{osr}/chosen");
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
