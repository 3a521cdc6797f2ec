//! The softness classifier (seed 001): save → load bit-identical, seeded determinism, typed
//! errors on bad input, rank-deficient Jacobians, finite outputs for huge inputs, the paper's
//! regular-shape figure, and the drift check of the committed metrics.

use hand_traits::{Softness, SoftnessClassifier};
use paper_experiments::data::underactuated::{self, Grasp, GraspSet, N_VARIABLES};
use paper_experiments::softness_eval::{
    self, METRICS_FILE, MODEL_DIR, labelled, model_file, refs, selected,
};
use proptest::prelude::*;
use std::path::{Path, PathBuf};
use tactile_nets::NetError;
use tactile_nets::metrics::MetricsFile;
use tactile_nets::softness::SoftnessNet;
use tactile_nets::softness_train::{
    AdamConfig, LmConfig, Optimiser, SoftnessTrainConfig, Stop, train,
};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn grasps() -> Vec<Grasp> {
    underactuated::load(&root()).expect("the committed underactuated dataset parses")
}

/// A short run: a few evaluations / epochs on every 14th sample.
fn quick(optimiser: &str, seed: u64) -> SoftnessTrainConfig {
    let optimiser = match optimiser {
        "lm" => Optimiser::Lm(LmConfig {
            patience: 1,
            tol: 1e-10,
        }),
        _ => Optimiser::Adam(AdamConfig {
            epochs: 30,
            learning_rate: 0.01,
        }),
    };
    SoftnessTrainConfig {
        optimiser,
        seed,
        stride: 14,
    }
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn committed_lm() -> SoftnessNet {
    SoftnessNet::load(&root().join(MODEL_DIR).join(model_file("lm", 1))).expect("committed model")
}

#[test]
fn training_is_deterministic_and_save_load_is_bit_identical() -> Result<(), NetError> {
    let grasps = grasps();
    let train_set: Vec<_> = labelled(&grasps, GraspSet::Train)
        .into_iter()
        .step_by(6)
        .collect();
    let train_set = refs(&train_set);
    let tests = labelled(&grasps, GraspSet::TestIrregular);
    for opt in ["lm", "adam"] {
        let (a, ra) = train(&train_set, &quick(opt, 3))?;
        let (b, rb) = train(&train_set, &quick(opt, 3))?;
        let (c, _) = train(&train_set, &quick(opt, 4))?;
        assert_eq!(ra, rb, "{opt}: same seed, same run");
        let meta = serde_json::json!({});
        let bytes = a.to_file(meta.clone())?.to_bytes()?;
        assert_eq!(
            bytes,
            b.to_file(meta.clone())?.to_bytes()?,
            "{opt}: same weights"
        );
        assert_ne!(
            bytes,
            c.to_file(meta.clone())?.to_bytes()?,
            "{opt}: other seed"
        );
        let path =
            std::env::temp_dir().join(format!("softness-{opt}-{}.safetensors", std::process::id()));
        a.save(&path, meta)?;
        let loaded = SoftnessNet::load(&path)?;
        std::fs::remove_file(&path)?;
        assert_eq!(loaded, a);
        for (series, _) in &tests {
            let flat = series.as_flattened();
            assert_eq!(bits(&a.scores(flat)?), bits(&loaded.scores(flat)?));
        }
    }
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let mut net = committed_lm();
    assert!(matches!(
        net.sample_outputs(&[0.0; 7]),
        Err(NetError::Shape {
            expected: 8,
            got: 7
        })
    ));
    assert!(matches!(
        net.classify(&[]),
        Err(NetError::Shape {
            expected: 8,
            got: 0
        })
    ));
    assert!(matches!(
        net.classify(&[1.0; 12]),
        Err(NetError::Shape {
            expected: 16,
            got: 12
        })
    ));
    let mut series = vec![1.0f32; 3 * N_VARIABLES];
    series[N_VARIABLES + 5] = f32::NAN;
    assert!(matches!(
        net.classify(&series),
        Err(NetError::NonFinite { index: 13 })
    ));
    series[N_VARIABLES + 5] = f32::INFINITY;
    assert!(matches!(
        net.classify(&series),
        Err(NetError::NonFinite { index: 13 })
    ));
    // Training rejects a non-finite reading, a zero stride and an empty set.
    let mut bad = vec![[1.0f32; N_VARIABLES]; 4];
    bad[2][1] = f32::NAN;
    let pairs = [(bad.as_slice(), Softness::Soft)];
    let mut every = quick("lm", 1);
    every.stride = 1;
    assert!(matches!(
        train(&pairs, &every),
        Err(NetError::NonFinite { index: 17 })
    ));
    let ok = vec![[1.0f32; N_VARIABLES]; 4];
    let mut zero = quick("lm", 1);
    zero.stride = 0;
    assert!(matches!(
        train(&[(ok.as_slice(), Softness::Soft)], &zero),
        Err(NetError::Training(_))
    ));
    assert!(matches!(
        train(&[], &quick("lm", 1)),
        Err(NetError::Training(_))
    ));
    // A truncated weights file is a typed error too.
    let bytes = net.to_file(serde_json::json!({}))?.to_bytes()?;
    assert!(tactile_nets::io::TensorFile::from_bytes(&bytes[..bytes.len() / 2]).is_err());
    Ok(())
}

#[test]
fn rank_deficient_jacobians_train_to_a_documented_stop() -> Result<(), NetError> {
    // Every sample identical: the inputs never vary, so the first layer's weight columns are
    // copies of its bias columns (rank 1 per neuron) and two classes share one input.
    let same = vec![[2.0f32; N_VARIABLES]; 6];
    let pairs = [
        (same.as_slice(), Softness::Soft),
        (same.as_slice(), Softness::Hard),
    ];
    // Only one class and all-zero inputs: the residuals can reach zero along many directions.
    let zeros = vec![[0.0f32; N_VARIABLES]; 6];
    let one_class = [(zeros.as_slice(), Softness::Moderate)];
    for data in [&pairs[..], &one_class[..]] {
        let lm = SoftnessTrainConfig {
            optimiser: Optimiser::lm(),
            seed: 2,
            stride: 1,
        };
        let (net, report) = train(data, &lm)?;
        assert!(matches!(
            report.stop,
            Stop::Converged
                | Stop::Orthogonal
                | Stop::ResidualsZero
                | Stop::MachinePrecision
                | Stop::BudgetSpent
        ));
        let y = net.scores(data[0].0.as_flattened())?;
        assert!(y.iter().all(|v| v.is_finite()), "{y:?}");
        // Least squares on contradictory labels lands on their mean (½, 0, ½); one class on it.
        let target: [f32; 3] = if data.len() == 2 {
            [0.5, 0.0, 0.5]
        } else {
            [0.0, 1.0, 0.0]
        };
        for k in 0..3 {
            assert!(
                (y[k] - target[k]).abs() < 1e-3,
                "{y:?} vs {target:?} ({:?})",
                report.stop
            );
        }
    }
    Ok(())
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn outputs_stay_finite_for_any_finite_input(
        x in prop::array::uniform8(prop::num::f32::NORMAL | prop::num::f32::ZERO | prop::num::f32::SUBNORMAL),
        scale in prop_oneof![Just(1.0f32), Just(1e20), Just(f32::MAX)],
    ) {
        let net = committed_lm();
        let sample: Vec<f32> = x.iter().map(|v| (v * scale).clamp(-f32::MAX, f32::MAX)).collect();
        let y = net.sample_outputs(&sample).expect("finite input gives an output");
        prop_assert!(y.iter().all(|v| v.is_finite()), "{y:?}");
        let mut net = net;
        prop_assert!(net.classify(&sample).is_ok());
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
