//! Drift check: re-runs the evaluator on one OSR's taps and compares with the table that
//! `docs/contact-location.md` states (regenerate it with the `aot_eval` example on change).

use aot_locate::DetectorConfig;
use hand_sim::fingertip::geometry::aot_geometry;
use paper_experiments::aot_eval as eval;
use paper_experiments::data::fingertip;
use std::path::PathBuf;

/// The OSR re-run: 4096 has the shortest series, so the test stays fast.
const OSR: u16 = 4096;

/// The first line after `marker` in `doc` that is the table row for `osr`.
fn osr_row<'a>(doc: &'a str, marker: &str, osr: u16) -> Option<&'a str> {
    doc[doc.find(marker)?..]
        .lines()
        .find(|l| l.starts_with(&format!("| {osr} |")))
}

/// `hits/n` as numbers.
fn fraction(cell: &str) -> Option<(u32, u32)> {
    let (h, n) = cell.trim().split_once('/')?;
    Some((h.parse().ok()?, n.parse().ok()?))
}

/// The doc's AoT row for `osr`: each rule's `hits/n` cells (written `x % (hits/n)`), in
/// column order.
fn doc_row(doc: &str, osr: u16) -> Option<Vec<(u32, u32)>> {
    let line = osr_row(doc, "## Arrival-of-Time (3 × 3)", osr)?;
    Some(
        line.split('|')
            .filter_map(|cell| fraction(cell.trim().split('(').nth(1)?.strip_suffix(')')?))
            .collect(),
    )
}

/// The doc's border-tap row for `osr`: the `a/b` counts (even splits, eq. 4 ties, ranging on
/// the label's side).
fn border_row(doc: &str, osr: u16) -> Option<Vec<(u32, u32)>> {
    let line = osr_row(doc, "**Does a border tap have a side?**", osr)?;
    Some(line.split('|').filter_map(fraction).collect())
}

#[test]
fn doc_table_matches_a_rerun_of_one_osr() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let doc = std::fs::read_to_string(root.join("docs/contact-location.md")).unwrap();
    let stated = doc_row(&doc, OSR).expect("the doc has an AoT row for OSR 4096");
    let mut data = fingertip::load(&root).unwrap();
    data.retain(|t| t.osr == OSR);
    let rep = eval::evaluate(&data, &aot_geometry(), DetectorConfig::DEFAULT);
    let measured: Vec<(u32, u32)> = eval::Rule::ALL
        .iter()
        .map(|r| {
            let t = rep.by_osr[&(*r, OSR)];
            (t.hits, t.n)
        })
        .collect();
    assert_eq!(stated, measured);
    let b = &rep.border[&OSR];
    let n = b.taps;
    assert_eq!(
        border_row(&doc, OSR).expect("the doc has a border row for OSR 4096"),
        vec![
            (b.even_cells, n),
            (b.eq4_tie, n),
            (b.on_label_side() as u32, b.offsets_mm.len() as u32)
        ]
    );
}
