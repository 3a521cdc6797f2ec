//! `fixtures/scenes/softness.toml` run as written: the selected LM model's accuracies and
//! confusion counts are its committed metrics row (issue 8), and the paper's figures stand
//! beside them from the seed 001 fixture.

mod common;

use common::{committed, metrics, run_scene, value};
use handstack::Plot;

#[test]
fn softness_scene_reproduces_the_committed_softness_metrics() {
    let o = run_scene("softness");
    let m = metrics("softness");
    let seed = committed(&m, "selected", "lm_seed");
    assert_eq!(value(&o, "softness_seed"), seed);
    let row = format!("lm/seed{seed}");
    let published = paper_fixtures::seed001::softness_accuracy().expect("fixture");
    for set in ["regular", "irregular"] {
        let fig = o.figure(&format!("{set}_accuracy_pct")).expect("figure");
        let theirs = 100.0 * committed(&m, &row, &format!("{set}_accuracy"));
        assert!(
            (fig.value - theirs).abs() < 1e-9,
            "{set}: {} vs {theirs}",
            fig.value
        );
        let paper = published
            .iter()
            .find(|r| r.test_set == set)
            .expect("paper row");
        assert_eq!(fig.paper, Some(paper.accuracy_pct));
        assert_eq!(fig.met, Some(fig.value >= paper.accuracy_pct));
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
            let set = if title.contains("irregular") {
                "irregular"
            } else {
                "regular"
            };
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
    assert_eq!(seen, 2);
}
