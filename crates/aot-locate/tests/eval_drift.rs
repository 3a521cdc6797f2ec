//! Drift check: re-runs the evaluator on one OSR's taps and compares with the table that
//! `docs/contact-location.md` states (regenerate it with the `aot_eval` example on change).

use aot_locate::eval;
use aot_locate::{DetectorConfig, Geometry};
use std::path::PathBuf;

/// The OSR re-run: 4096 has the shortest series, so the test stays fast.
const OSR: u16 = 4096;

/// The doc's row for `osr`: each rule's `hits/n` cells, in column order.
fn doc_row(doc: &str, osr: u16) -> Option<Vec<(u32, u32)>> {
    let section = &doc[doc.find("## Arrival-of-Time (3 × 3)")?..];
    let line = section
        .lines()
        .find(|l| l.starts_with(&format!("| {osr} |")))?;
    Some(
        line.split('|')
            .filter_map(|cell| {
                let inner = cell.trim().split('(').nth(1)?.strip_suffix(')')?;
                let (h, n) = inner.split_once('/')?;
                Some((h.parse().ok()?, n.parse().ok()?))
            })
            .collect(),
    )
}

#[test]
fn doc_table_matches_a_rerun_of_one_osr() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let doc = std::fs::read_to_string(root.join("docs/contact-location.md")).unwrap();
    let stated = doc_row(&doc, OSR).expect("the doc has an AoT row for OSR 4096");
    let data =
        eval::Dataset::load(&root.join("fixtures/datasets/fingertip"), |t| t.osr == OSR).unwrap();
    let rep = eval::evaluate(&data, &Geometry::simulated_pad(), DetectorConfig::DEFAULT);
    let measured: Vec<(u32, u32)> = eval::Rule::ALL
        .iter()
        .map(|r| {
            let t = rep.by_osr[&(*r, OSR)];
            (t.hits, t.n)
        })
        .collect();
    assert_eq!(stated, measured);
}
