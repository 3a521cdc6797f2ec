//! The contact CNN: save → load bit-identical, seeded determinism, typed errors on bad input,
//! the plain-array path against dfdx's forward, finite softmax, and the drift check of the
//! committed metrics.

use crate::common;

use common::{bits, quick, root};
use hand_traits::ContactLocator;
use paper_experiments::cnn_eval::{
    self, Case, METRICS_FILE, MODEL_DIR, NOISY_COPIES, SEED, SNR_DB,
};
use paper_experiments::data::imu_pad::{self, CHANNELS, Dataset, WINDOW, WINDOW_VALUES};
use proptest::prelude::*;
use tactile_nets::NetError;
use tactile_nets::activations::softmax;
use tactile_nets::contact_cnn::{ContactCnn, Variant};
use tactile_nets::metrics::MetricsFile;
use tactile_nets::train::TrainConfig;

fn taps() -> Dataset {
    imu_pad::load(&root()).expect("the committed imu_pad dataset parses")
}

fn tiny(seed: u64) -> TrainConfig {
    quick(seed, 2, 32, 1e-3, 0.0)
}

/// The 1.6 mm taps' windows and regions (360 taps: a small, quick training set).
fn depth_set(taps: &Dataset) -> (Vec<[f32; WINDOW_VALUES]>, Vec<u8>) {
    let t = Case::Depth(1600).taps(taps);
    (
        t.iter().filter_map(|&i| taps.window_values(i)).collect(),
        t.iter().map(|&i| taps.taps[i].region).collect(),
    )
}

#[test]
fn dataset_is_the_papers_collection() {
    let taps = taps();
    assert_eq!(taps.len(), 2880, "72 positions x 8 depths x 5 repeats");
    assert_eq!(taps.windows.dim(), (2880, CHANNELS, WINDOW));
    assert_eq!(
        taps.depths_um(),
        [200, 400, 600, 800, 1000, 1200, 1400, 1600]
    );
    // Region = 3 · row group + column − 1 (§IV-A: 3 groups of 8 rows × 3 columns).
    assert!(
        taps.taps.iter().all(|t| usize::from(t.region)
            == 3 * ((usize::from(t.row) - 1) / 8) + usize::from(t.column) - 1)
    );
    // Augmentation: 1 + 20 windows per tap (5 → 105 per position); the copies are the tap
    // plus noise at 30 dB per signal.
    let one = Case::Depth(800).taps(&taps);
    let a = cnn_eval::augment(&taps, &one[..2], NOISY_COPIES, SNR_DB, SEED);
    assert_eq!(a.windows.len(), 2 * 21);
    let (orig, copies) = (&a.windows[0], &a.windows[1..21]);
    assert_eq!(Some(*orig), taps.window_values(one[0]));
    for c in 0..4 {
        let s = &orig[c * 38..(c + 1) * 38];
        let power = s.iter().map(|v| v * v).sum::<f32>() / 38.0;
        let noise: f32 = copies
            .iter()
            .flat_map(|w| (0..38).map(move |i| (w[c * 38 + i] - s[i]).powi(2)))
            .sum::<f32>()
            / (20.0 * 38.0);
        let snr_db = 10.0 * (power / noise).log10();
        assert!((snr_db - 30.0).abs() < 0.6, "signal {c}: {snr_db} dB");
    }
}

#[test]
fn training_is_deterministic_save_load_bit_identical_and_frozen_matches_dfdx()
-> Result<(), NetError> {
    let taps = taps();
    let (w, r) = depth_set(&taps);
    for variant in Variant::ALL {
        let (a, log_a) = ContactCnn::train(&w, &r, variant, &tiny(3))?;
        let (b, log_b) = ContactCnn::train(&w, &r, variant, &tiny(3))?;
        let (c, _) = ContactCnn::train(&w, &r, variant, &tiny(4))?;
        assert_eq!(bits(&log_a.epoch_loss), bits(&log_b.epoch_loss));
        common::assert_seeded(
            &a.to_file()?.to_bytes()?,
            &b.to_file()?.to_bytes()?,
            &c.to_file()?.to_bytes()?,
        );
        let dir = common::temp_dir("cnn")?;
        let path = dir.join(format!("{}.safetensors", variant.name()));
        a.save(&path)?;
        let loaded = ContactCnn::load(&path)?;
        std::fs::remove_file(&path)?;
        assert_eq!(loaded.variant(), variant);
        let mut worst = 0.0f32;
        for x in w.iter().step_by(7) {
            assert_eq!(bits(&a.logits(x)?), bits(&loaded.logits(x)?));
            assert_eq!(bits(&a.logits_dfdx(x)?), bits(&loaded.logits_dfdx(x)?));
            assert_eq!(a.predict(x)?, loaded.predict(x)?);
            let (f, d) = (a.logits(x)?, a.logits_dfdx(x)?);
            for (p, q) in f.iter().zip(&d) {
                worst = worst.max((p - q).abs() / q.abs().max(1.0));
            }
        }
        assert!(worst <= 1e-5, "{variant:?}: plain-array vs dfdx {worst}");
        let batch = a.classify_batch(&w)?;
        assert!(
            w.iter()
                .zip(&batch)
                .all(|(x, &k)| a.predict(x).is_ok_and(|p| p.region == k))
        );
    }
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let taps = taps();
    let (w, r) = depth_set(&taps);
    let (mut cnn, _) = ContactCnn::train(&w[..40], &r[..40], Variant::Small, &tiny(1))?;
    assert!(matches!(
        cnn.locate(&[0.0; WINDOW_VALUES - 1]),
        Err(NetError::Shape {
            expected: WINDOW_VALUES,
            got: 151
        })
    ));
    assert!(matches!(cnn.locate(&[]), Err(NetError::Shape { .. })));
    let mut x = w[0];
    x[77] = f32::NAN;
    assert!(matches!(
        cnn.locate(&x),
        Err(NetError::NonFinite { index: 77 })
    ));
    x[77] = f32::INFINITY;
    assert!(matches!(
        cnn.locate(&x),
        Err(NetError::NonFinite { index: 77 })
    ));
    // A finite value far outside the training range: a finite answer or the typed overflow.
    x = [f32::MAX; WINDOW_VALUES];
    match cnn.locate(&x) {
        Ok(c) => assert!(c.region < 9 && c.confidence.is_finite()),
        Err(e) => assert!(matches!(e, NetError::NonFiniteOutput { .. }), "{e}"),
    }
    let c = cnn.locate(&w[0])?;
    assert_eq!(c.regions, 9);
    assert!(c.region < 9 && (0.0..=1.0).contains(&c.confidence));
    assert!(matches!(
        ContactCnn::train(&w[..3], &[0, 9, 1], Variant::Small, &tiny(1)),
        Err(NetError::Training(_))
    ));
    assert!(matches!(
        ContactCnn::train(&w[..3], &r[..2], Variant::Small, &tiny(1)),
        Err(NetError::Training(_))
    ));
    Ok(())
}

#[test]
fn committed_metrics_match_a_re_evaluation_of_the_committed_weights() -> Result<(), NetError> {
    let taps = taps();
    let committed = MetricsFile::from_json(&std::fs::read_to_string(
        root().join(MODEL_DIR).join(METRICS_FILE),
    )?)?;
    // Every Table I row × protocol × grouping of every net is committed.
    for variant in Variant::ALL {
        for grouping in ["samples", "taps"] {
            for protocol in ["trials", "kfold"] {
                for case in Case::all(&taps) {
                    let label = format!("{}/{grouping}/{protocol}/{}", variant.name(), case.name());
                    assert!(committed.row(&label).is_some(), "{label} not committed");
                }
            }
        }
    }
    let mut fresh = Vec::new();
    for which in cnn_eval::COMMITTED {
        let (acc, conf) = cnn_eval::evaluate_committed(&root(), &taps, which)?;
        fresh.push(cnn_eval::committed_row(which, acc, &conf));
    }
    let only_committed = MetricsFile {
        rows: committed
            .rows
            .iter()
            .filter(|r| r.label.starts_with("committed/"))
            .cloned()
            .collect(),
        ..committed.clone()
    };
    let drift = only_committed.drift(&cnn_eval::metrics_file(fresh, SEED), 1e-9);
    assert!(drift.is_empty(), "committed metrics drifted: {drift:#?}");
    Ok(())
}

proptest! {
    #[test]
    fn softmax_is_finite_for_huge_logits(
        logits in prop::collection::vec(
            prop_oneof![prop::num::f32::NORMAL, Just(f32::MAX), Just(-f32::MAX),
                        Just(1e30f32), Just(-1e30f32)], 9..=9),
    ) {
        let p = softmax(&logits).unwrap_or_default();
        prop_assert_eq!(p.len(), 9);
        prop_assert!(p.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)));
        prop_assert!((p.iter().sum::<f32>() - 1.0).abs() < 1e-4);
    }

    #[test]
    fn the_cnn_never_panics_and_gives_a_distribution_or_a_typed_error(
        x in prop::collection::vec(
            prop_oneof![-1e4f32..1e4, prop::num::f32::ANY], WINDOW_VALUES),
    ) {
        let mut cnn = ContactCnn::load(
            &root().join(MODEL_DIR).join(cnn_eval::model_file(Variant::Small)),
        ).expect("committed model loads");
        match cnn.locate(&x) {
            Ok(c) => {
                prop_assert!(x.iter().all(|v| v.is_finite()));
                prop_assert!(c.region < 9 && (0.0..=1.0).contains(&c.confidence));
            }
            Err(NetError::NonFinite { index }) => prop_assert!(!x[index].is_finite()),
            Err(NetError::NonFiniteOutput { .. }) => prop_assert!(x.iter().all(|v| v.is_finite())),
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }
}
