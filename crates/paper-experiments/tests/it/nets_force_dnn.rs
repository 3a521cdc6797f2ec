//! The force / weight DNN: seeded determinism, save → load bit-identical, typed errors on bad
//! input, frozen inference against dfdx, stable outputs for any input, and the drift check of
//! the committed metrics.

use crate::common;

use common::root;
use hand_traits::ForceEstimator;
use paper_experiments::data::weights::{self, WeightSample};
use paper_experiments::force_eval::{self, METRICS_FILE, MODEL_DIR, RATED_RANGE_GF, SEED};
use proptest::prelude::*;
use std::sync::OnceLock;
use tactile_nets::NetError;
use tactile_nets::force_dnn::{ForceDnn, HIDDEN, OUTPUT_SPAN, WIDTHS};
use tactile_nets::frozen::{HyperbolicTangent, Layer, Logistic};
use tactile_nets::metrics::MetricsFile;
use tactile_nets::train::TrainConfig;

/// Table 1 tared on its 0 gf row.
fn table() -> Vec<WeightSample> {
    let rows: Vec<(f64, [f64; 3])> = paper_fixtures::seed000::table1_weight()
        .expect("Table 1 fixture parses")
        .iter()
        .map(|r| (r.weight_gf, r.pressure_hpa))
        .collect();
    weights::tared_table(&rows).expect("Table 1 has a 0 gf row")
}

fn tiny(seed: u64) -> Vec<TrainConfig> {
    vec![TrainConfig {
        epochs: 30,
        batch_size: 16,
        learning_rate: 1e-2,
        l2: 0.0,
        seed,
        progress: false,
        label: String::new(),
    }]
}

fn bits(v: f32) -> u32 {
    v.to_bits()
}

fn committed() -> &'static ForceDnn {
    static MODEL: OnceLock<ForceDnn> = OnceLock::new();
    MODEL.get_or_init(|| {
        ForceDnn::load(&root().join(MODEL_DIR).join(force_eval::TABLE_FILE))
            .expect("committed model loads")
    })
}

#[test]
fn training_is_deterministic_and_save_load_is_bit_identical() -> Result<(), NetError> {
    let table = table();
    let (a, log_a) = ForceDnn::train(&table, RATED_RANGE_GF, &tiny(3))?;
    let (b, log_b) = ForceDnn::train(&table, RATED_RANGE_GF, &tiny(3))?;
    let (c, _) = ForceDnn::train(&table, RATED_RANGE_GF, &tiny(4))?;
    assert_eq!(log_a.epoch_loss.len(), 30);
    assert_eq!(
        log_a
            .epoch_loss
            .iter()
            .map(|&v| bits(v))
            .collect::<Vec<_>>(),
        log_b
            .epoch_loss
            .iter()
            .map(|&v| bits(v))
            .collect::<Vec<_>>()
    );
    common::assert_seeded(
        &a.to_file()?.to_bytes()?,
        &b.to_file()?.to_bytes()?,
        &c.to_file()?.to_bytes()?,
    );
    let dir = common::temp_dir("force")?;
    let path = dir.join("force.safetensors");
    a.save(&path)?;
    let loaded = ForceDnn::load(&path)?;
    std::fs::remove_dir_all(&dir)?;
    assert_eq!(loaded.range_gf(), RATED_RANGE_GF);
    for s in &table {
        let (x, y) = (
            a.estimate_gf(&s.rise_hpa)?,
            loaded.estimate_gf(&s.rise_hpa)?,
        );
        assert_eq!(bits(x), bits(y));
        let (x, y) = (
            a.estimate_gf_dfdx(&s.rise_hpa)?,
            loaded.estimate_gf_dfdx(&s.rise_hpa)?,
        );
        assert_eq!(bits(x), bits(y));
    }
    // A contact-MLP file is not a force DNN.
    assert!(ForceDnn::from_file(&tactile_nets::io::TensorFile::new()).is_err());
    Ok(())
}

#[test]
fn every_width_trains_and_round_trips_and_others_are_refused() -> Result<(), NetError> {
    let table = table();
    assert_eq!(committed().hidden(), HIDDEN);
    for w in WIDTHS {
        let (m, _) = ForceDnn::train_width(&table, RATED_RANGE_GF, &tiny(5), w)?;
        assert_eq!(m.hidden(), w);
        // The width is read back from the tensors' shapes.
        let back = ForceDnn::from_file(&m.to_file()?)?;
        assert_eq!(back.hidden(), w);
        let x = &table[3].rise_hpa;
        assert_eq!(bits(m.estimate_gf(x)?), bits(back.estimate_gf(x)?));
    }
    assert!(matches!(
        ForceDnn::train_width(&table, RATED_RANGE_GF, &tiny(5), 5),
        Err(NetError::Training(_))
    ));
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let mut dnn = ForceDnn::load(&root().join(MODEL_DIR).join(force_eval::TABLE_FILE))?;
    assert!(matches!(
        dnn.estimate_force(&[0.1, 0.2]),
        Err(NetError::Shape {
            expected: 3,
            got: 2
        })
    ));
    assert!(matches!(
        dnn.estimate_force(&[0.0; 4]),
        Err(NetError::Shape { .. })
    ));
    assert!(matches!(
        dnn.estimate_force(&[0.1, f32::NAN, 0.2]),
        Err(NetError::NonFinite { index: 1 })
    ));
    assert!(matches!(
        dnn.estimate_force(&[0.1, 0.2, f32::INFINITY]),
        Err(NetError::NonFinite { index: 2 })
    ));
    assert!(matches!(
        ForceDnn::train(&table(), [5.0, 5.0], &tiny(1)),
        Err(NetError::Training(_))
    ));
    assert!(matches!(
        ForceDnn::train(&[], RATED_RANGE_GF, &tiny(1)),
        Err(NetError::Training(_))
    ));
    let f = dnn.estimate_force(&table()[2].rise_hpa)?;
    assert!((f.gram_force() - 100.0).abs() < 5.0, "{}", f.gram_force());
    Ok(())
}

#[test]
fn frozen_inference_agrees_with_dfdx_on_seeded_inputs() -> Result<(), NetError> {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
    for file in [force_eval::TABLE_FILE, force_eval::SIM_FILE] {
        let dnn = ForceDnn::load(&root().join(MODEL_DIR).join(file))?;
        for _ in 0..500 {
            let x: [f32; 3] = core::array::from_fn(|_| rng.random_range(-0.5..2.0));
            let (fast, slow) = (dnn.estimate_gf(&x)?, dnn.estimate_gf_dfdx(&x)?);
            // 1e-5 on the sigmoid output is 1e-5 / 0.8 × 200 gf = 2.5e-3 gf.
            let unit = 200.0 / (OUTPUT_SPAN[1] - OUTPUT_SPAN[0]);
            assert!(
                (fast - slow).abs() <= 1e-5 * unit,
                "{x:?}: {fast} vs {slow}"
            );
        }
    }
    Ok(())
}

#[test]
fn committed_metrics_match_a_re_evaluation_of_the_committed_weights() -> Result<(), NetError> {
    let table = table();
    let frames = weights::load_series(&root()).expect("the committed weight series parses");
    let committed = MetricsFile::from_json(&std::fs::read_to_string(
        root().join(MODEL_DIR).join(METRICS_FILE),
    )?)?;
    let models = force_eval::load_committed(&root(), &table)?;
    let fresh = force_eval::metrics_file(&models, &table, &frames, SEED)?;
    assert_eq!(committed.rows.len(), 4);
    let drift = committed.drift(&fresh, 1e-4);
    assert!(drift.is_empty(), "committed metrics drifted: {drift:#?}");
    // The target: the Table 1 fit within 0.5 gf on every row.
    let fit = fresh.row("table1/fit").expect("fit row");
    for s in &table {
        let key = force_eval::row_key(s.weight_gf);
        let gf = fit.values.get(&key).copied().unwrap_or(f64::NAN);
        assert!((gf - f64::from(s.weight_gf)).abs() <= 0.5, "{key}: {gf}");
    }
    Ok(())
}

proptest! {
    #[test]
    fn frozen_activations_are_finite_for_any_input(
        x in prop::array::uniform8(prop_oneof![
            prop::num::f32::NORMAL, Just(f32::MAX), Just(-f32::MAX),
            Just(f32::INFINITY), Just(f32::NEG_INFINITY)]),
    ) {
        prop_assert!(Logistic.forward(x).iter().all(|v| (0.0..=1.0).contains(v)));
        prop_assert!(HyperbolicTangent.forward(x).iter().all(|v| (-1.0..=1.0).contains(v)));
    }

    #[test]
    fn the_dnn_never_panics_and_stays_inside_its_saturation(
        x in prop::collection::vec(prop_oneof![
            prop::num::f32::ANY, -1.0f32..3.0, Just(f32::MAX), Just(-f32::MAX)], 3),
    ) {
        let [lo, hi] = RATED_RANGE_GF;
        let slack = (hi - lo) / 8.0 + 1e-3; // the sigmoid's 0..1 beyond the 0.1..0.9 span
        match committed().estimate_gf(&x) {
            Ok(gf) => prop_assert!(gf >= lo - slack && gf <= hi + slack, "{gf}"),
            Err(NetError::NonFinite { index }) => prop_assert!(!x[index].is_finite()),
            Err(NetError::NonFiniteOutput { .. }) => prop_assert!(x.iter().all(|v| v.is_finite())),
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }
}
