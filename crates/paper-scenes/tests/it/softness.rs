//! `fixtures/scenes/softness.toml` run as written: the selected model of our variant
//! (`model = "ours"`) — its accuracies and confusion counts are its committed metrics row (the 24
//! regular, the 30 irregular and the 1000 fresh irregular objects), the paper's figures stand
//! beside them from the seed 001 fixture, and the hidden-class figures carry no target.

use crate::common;

use common::{committed, metrics_in, run_scene, value};
use handstack::Plot;

#[test]
fn softness_scene_reproduces_the_committed_softness_metrics() {
    let o = run_scene("softness");
    let m = metrics_in("softness", "ours_metrics.json");
    let seed = committed(&m, "ours/selected", "lm_seed");
    assert_eq!(value(&o, "softness_seed"), seed);
    // Rows `ours/<features>/lm/seed<N>`: the selected seed's.
    let row = m
        .rows
        .iter()
        .map(|r| r.label.clone())
        .find(|l| l.starts_with("ours/") && l.ends_with(&format!("/lm/seed{seed}")))
        .expect("the selected seed's row");
    let published = paper_fixtures::seed001::softness_accuracy().expect("fixture");
    for (set, paper_row) in [
        ("regular", "regular"),
        ("irregular", "irregular"),
        ("irregular_1000", "irregular"),
    ] {
        let fig = o.figure(&format!("{set}_accuracy_pct")).expect("figure");
        let theirs = 100.0 * committed(&m, &row, &format!("{set}_accuracy"));
        assert!(
            (fig.value - theirs).abs() < 1e-9,
            "{set}: {} vs {theirs}",
            fig.value
        );
        let paper = published
            .iter()
            .find(|r| r.test_set == paper_row)
            .expect("paper row");
        assert_eq!(fig.paper, Some(paper.accuracy_pct));
        assert_eq!(fig.met, Some(fig.value >= paper.accuracy_pct));
    }
    for set in ["irregular", "irregular_1000"] {
        let fig = o
            .figure(&format!("{set}_overall_accuracy_pct"))
            .expect("hidden-class figure");
        let theirs = 100.0 * committed(&m, &row, &format!("{set}_overall_accuracy"));
        assert!((fig.value - theirs).abs() < 1e-9, "{set}: {}", fig.value);
        assert_eq!((fig.paper, fig.met), (None, None), "no target");
        let ceiling = o
            .figure(&format!("{set}_overall_bayes_ceiling_pct"))
            .expect("Bayes ceiling");
        assert!(ceiling.value > 80.0 && ceiling.value <= 100.0);
        assert_eq!(ceiling.met, None);
    }
    // Confusion matrices: the committed counts, cell by cell (soft, moderate, hard).
    let names = ["soft", "moderate", "hard"];
    let mut seen = 0;
    for p in &o.plots {
        if let Plot::Confusion {
            title,
            labels,
            counts,
        } = p
        {
            let set = title
                .strip_prefix("Softness, ")
                .and_then(|t| t.split(' ').next())
                .expect("a softness confusion title");
            assert_eq!(labels, &names);
            for (t, row_counts) in counts.iter().enumerate() {
                for (q, c) in row_counts.iter().enumerate() {
                    let key = format!("{set}_cm_{}_{}", names[t], names[q]);
                    assert_eq!(f64::from(*c), committed(&m, &row, &key), "{key}");
                }
            }
            seen += 1;
        }
    }
    assert_eq!(seen, 3);
}
