//! The softness classifier against the papers' data (seed 001): the committed models against
//! their metrics and the paper's regular-shape figure, the committed dataset's labels and
//! Bayes ceiling, and our variant's committed metrics and finger-order invariance. (The net's
//! own behaviour is tested in tactile-nets.)

use crate::common::root;
use paper_experiments::data::underactuated::{self, Grasp, GraspSet, N_VARIABLES};
use paper_experiments::softness_eval::{self, METRICS_FILE, MODEL_DIR, labelled, selected};
use tactile_nets::NetError;
use tactile_nets::SoftnessClassifier;
use tactile_nets::metrics::MetricsFile;

fn grasps() -> Vec<Grasp> {
    underactuated::load(&root()).expect("the committed underactuated dataset parses")
}

#[test]
fn committed_models_match_their_metrics_and_beat_the_papers_regular_figure() -> Result<(), NetError>
{
    let grasps = grasps();
    let runs = softness_eval::load_committed(&root(), &grasps)?;
    let fresh = softness_eval::metrics_file(&runs);
    let path = root().join(MODEL_DIR).join(METRICS_FILE);
    let committed = MetricsFile::from_json(&std::fs::read_to_string(&path)?)?;
    let drift = committed.drift(&fresh, 1e-9);
    assert!(
        drift.is_empty(),
        "committed softness metrics drifted:\n{}",
        drift.join("\n")
    );
    // Seed 001 §4: 95.83 % on the 24 regular-shape objects.
    let paper = paper_fixtures::seed001::softness_accuracy().expect("seed 001 accuracy fixture");
    let regular = paper
        .iter()
        .find(|r| r.test_set == "regular")
        .expect("regular row");
    let lm = selected(&runs, "lm").expect("an LM model");
    assert_eq!(lm.evaluation.regular.total(), regular.objects);
    assert!(100.0 * lm.evaluation.regular.accuracy() > regular.accuracy_pct);
    // The 30 and the 1000 irregular objects, each scored under both classes.
    let e = &lm.evaluation;
    assert_eq!(
        [
            e.irregular.total(),
            e.irregular_overall.total(),
            e.irregular_1000.total(),
            e.irregular_1000_overall.total()
        ],
        [30, 30, 1000, 1000]
    );
    Ok(())
}

/// The labels on the committed dataset: every household object's `label` is the class
/// band of the median of its committed local moduli, and the Bayes ceiling of the hidden class
/// computed from the committed grasps is the one `ceiling.csv` states (two paths, one figure).
#[test]
fn committed_labels_are_what_the_fingers_measure_and_the_ceiling_matches() {
    let grasps = grasps();
    let mut household = 0;
    for g in grasps.iter().filter(|g| g.kind == "household") {
        household += 1;
        let measured = hand_sim::underactuated::dataset::sensor_class(g.local_moduli_pa)
            .expect("committed moduli are finite and positive");
        assert_eq!(g.label, Some(measured), "grasp {}", g.id);
        assert!(g.overall.is_some(), "grasp {}", g.id);
    }
    assert_eq!(household, 18 + 30 + 1000);
    let csv = std::fs::read_to_string(root().join(underactuated::DATASET_DIR).join("ceiling.csv"))
        .expect("ceiling.csv");
    for set in [
        GraspSet::Train,
        GraspSet::TestIrregular,
        GraspSet::TestIrregular1000,
    ] {
        let c = softness_eval::bayes_ceiling(&grasps, set).expect("finite moduli");
        let row = format!("{},{},{},", set.name(), c.total(), c.correct());
        assert!(
            csv.lines().any(|l| l.starts_with(&row)),
            "{row} not in ceiling.csv:\n{csv}"
        );
    }
}

#[test]
fn committed_variant_matches_its_metrics_and_ignores_finger_order() -> Result<(), NetError> {
    let grasps = grasps();
    let runs = softness_eval::load_ours(&root(), &grasps)?;
    let fresh = softness_eval::ours_metrics_file(&runs);
    let path = root()
        .join(MODEL_DIR)
        .join(softness_eval::OURS_METRICS_FILE);
    let committed = MetricsFile::from_json(&std::fs::read_to_string(&path)?)?;
    let drift = committed.drift(&fresh, 1e-9);
    assert!(
        drift.is_empty(),
        "committed variant metrics drifted:\n{}",
        drift.join("\n")
    );
    // Swapping which finger met which side changes nothing the variant reads.
    let mut model = runs[0].model.clone();
    for (series, _) in labelled(&grasps, GraspSet::TestIrregular) {
        let swapped: Vec<[f32; N_VARIABLES]> = series
            .iter()
            .map(|s| [s[2], s[0], s[3], s[1], s[6], s[4], s[7], s[5]])
            .collect();
        assert_eq!(model.predict(&series)?, model.predict(&swapped)?);
    }
    // Bad input: typed errors, as the paper net.
    assert!(matches!(
        model.classify(&[1.0; 12]),
        Err(NetError::Shape {
            expected: 16,
            got: 12
        })
    ));
    let mut series = vec![1.0f32; 3 * N_VARIABLES];
    series[9] = f32::NAN;
    assert!(matches!(
        model.classify(&series),
        Err(NetError::NonFinite { index: 9 })
    ));
    Ok(())
}
