//! The force / weight DNN: seeded determinism, save → load bit-identical, every width trains
//! and others are refused, typed errors on bad input, frozen inference against dfdx, and stable
//! outputs for any input.

use crate::common::{self, bits, rng};
use proptest::prelude::*;
use rand::Rng;
use std::sync::OnceLock;
use tactile_nets::ForceEstimator;
use tactile_nets::NetError;
use tactile_nets::force_dnn::{ForceDnn, HIDDEN, OUTPUT_SPAN, WIDTHS, WeightSample, tared_table};
use tactile_nets::frozen::{HyperbolicTangent, Layer, Logistic};
use tactile_nets::pretrained::{self, ForceModel};
use tactile_nets::train::TrainConfig;

/// The rated range the synthetic table spans, gf.
const RANGE_GF: [f32; 2] = [0.0, 200.0];

/// A synthetic weight table: 21 weights, 0 to 200 gf, on three sensors whose pressures (hPa)
/// rise with the weight, each with its own gain and a slight curve, plus seeded noise of
/// ±0.01 hPa; tared on its 0 gf row.
fn table() -> Vec<WeightSample> {
    let mut rng = rng(11);
    let rest = [1191.25, 1199.02, 1018.04];
    let gain = [0.0071, 0.0053, 0.0063]; // hPa per gf
    let rows: Vec<(f64, [f64; 3])> = (0..=20)
        .map(|i| {
            let w = f64::from(i) * 10.0;
            let p = core::array::from_fn(|k| {
                let noise = if i == 0 {
                    0.0
                } else {
                    rng.random_range(-0.01..0.01)
                };
                rest[k] + gain[k] * w * (1.0 + 0.001 * w) + noise
            });
            (w, p)
        })
        .collect();
    tared_table(&rows).expect("the table has a 0 gf row")
}

fn tiny(seed: u64) -> Vec<TrainConfig> {
    vec![common::quick(seed, 30, 16, 1e-2, 0.0)]
}

/// The built-in Table 1 model, parsed once.
fn built_in() -> &'static ForceDnn {
    static MODEL: OnceLock<ForceDnn> = OnceLock::new();
    MODEL.get_or_init(|| pretrained::force_dnn(ForceModel::Table1).expect("built-in model"))
}

#[test]
fn training_is_deterministic_and_save_load_is_bit_identical() -> Result<(), NetError> {
    let table = table();
    let (a, log_a) = ForceDnn::train(&table, RANGE_GF, &tiny(3))?;
    let (b, log_b) = ForceDnn::train(&table, RANGE_GF, &tiny(3))?;
    let (c, _) = ForceDnn::train(&table, RANGE_GF, &tiny(4))?;
    assert_eq!(log_a.epoch_loss.len(), 30);
    assert_eq!(bits(&log_a.epoch_loss), bits(&log_b.epoch_loss));
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
    assert_eq!(loaded.range_gf(), RANGE_GF);
    for s in &table {
        let (x, y) = (
            a.estimate_gf(&s.rise_hpa)?,
            loaded.estimate_gf(&s.rise_hpa)?,
        );
        assert_eq!(x.to_bits(), y.to_bits());
        let (x, y) = (
            a.estimate_gf_dfdx(&s.rise_hpa)?,
            loaded.estimate_gf_dfdx(&s.rise_hpa)?,
        );
        assert_eq!(x.to_bits(), y.to_bits());
    }
    // An empty file (no metadata, no tensors) is not a force DNN.
    assert!(ForceDnn::from_file(&tactile_nets::io::TensorFile::new()).is_err());
    Ok(())
}

#[test]
fn every_width_trains_and_round_trips_and_others_are_refused() -> Result<(), NetError> {
    let table = table();
    assert_eq!(
        (built_in().hidden(), built_in().range_gf()),
        (HIDDEN, RANGE_GF)
    );
    for w in WIDTHS {
        let (m, _) = ForceDnn::train_width(&table, RANGE_GF, &tiny(5), w)?;
        assert_eq!(m.hidden(), w);
        // The width is read back from the tensors' shapes.
        let back = ForceDnn::from_file(&m.to_file()?)?;
        assert_eq!(back.hidden(), w);
        let x = &table[3].rise_hpa;
        assert_eq!(m.estimate_gf(x)?.to_bits(), back.estimate_gf(x)?.to_bits());
    }
    assert!(matches!(
        ForceDnn::train_width(&table, RANGE_GF, &tiny(5), 5),
        Err(NetError::Training(_))
    ));
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let mut dnn = pretrained::force_dnn(ForceModel::Table1)?;
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
        ForceDnn::train(&[], RANGE_GF, &tiny(1)),
        Err(NetError::Training(_))
    ));
    assert!(matches!(
        ForceDnn::train(&table(), RANGE_GF, &[]),
        Err(NetError::Training(_))
    ));
    // The rises its training table gave 100 gf (the crate docs' example).
    let f = dnn.estimate_force(&[0.71, 0.53, 0.63])?;
    assert!((f.gram_force() - 100.0).abs() < 5.0, "{}", f.gram_force());
    Ok(())
}

#[test]
fn frozen_inference_agrees_with_dfdx_on_seeded_inputs() -> Result<(), NetError> {
    let mut rng = rng(21);
    for model in ForceModel::ALL {
        let dnn = pretrained::force_dnn(model)?;
        for _ in 0..500 {
            let x: [f32; 3] = core::array::from_fn(|_| rng.random_range(-0.5..2.0));
            let (fast, slow) = (dnn.estimate_gf(&x)?, dnn.estimate_gf_dfdx(&x)?);
            // 1e-5 on the sigmoid output is 1e-5 / 0.8 × 200 gf = 2.5e-3 gf.
            let unit = 200.0 / (OUTPUT_SPAN[1] - OUTPUT_SPAN[0]);
            assert!(
                (fast - slow).abs() <= 1e-5 * unit,
                "{model:?} {x:?}: {fast} vs {slow}"
            );
        }
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
        let [lo, hi] = RANGE_GF;
        let slack = (hi - lo) / 8.0 + 1e-3; // the sigmoid's 0..1 beyond the 0.1..0.9 span
        match built_in().estimate_gf(&x) {
            Ok(gf) => prop_assert!(gf >= lo - slack && gf <= hi + slack, "{gf}"),
            Err(NetError::NonFinite { index }) => prop_assert!(!x[index].is_finite()),
            Err(NetError::NonFiniteOutput { .. }) => prop_assert!(x.iter().all(|v| v.is_finite())),
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }
}

/// Mixup rows lie between neighbouring weights only (never across a gap to a further one):
/// each weight between its pair's, each rise between the pair's frames' extremes; the count is
/// per frame of the lighter weight; the same seed gives the same rows, pairs without frames
/// give none.
#[test]
fn mixup_rows_lie_between_neighbouring_weights_and_follow_their_seed() {
    use tactile_nets::force_dnn::mixup;
    let a = [[1.0f32, 2.0, 3.0], [1.2, 2.2, 3.2]];
    let b = [[2.0f32, 4.0, 6.0]];
    let c = [[3.0f32, 6.0, 9.0], [3.1, 6.1, 9.1], [2.9, 5.9, 8.9]];
    let steps: [(f32, &[[f32; 3]]); 3] = [(10.0, &a), (20.0, &b), (30.0, &c)];
    let rows = mixup(&steps, 3, 5);
    assert_eq!(rows.len(), 3 * 2 + 3);
    for r in &rows[..6] {
        assert!((10.0..=20.0).contains(&r.weight_gf), "{r:?}");
        assert!((1.0..=2.0).contains(&r.rise_hpa[0]), "{r:?}");
        assert!((3.0..=6.0).contains(&r.rise_hpa[2]), "{r:?}");
    }
    for r in &rows[6..] {
        assert!((20.0..=30.0).contains(&r.weight_gf), "{r:?}");
        assert!((2.0..=3.1).contains(&r.rise_hpa[0]), "{r:?}");
    }
    assert_eq!(rows, mixup(&steps, 3, 5));
    assert_ne!(rows, mixup(&steps, 3, 6));
    let empty: [(f32, &[[f32; 3]]); 2] = [(10.0, &a), (20.0, &[])];
    assert!(mixup(&empty, 3, 5).is_empty());
}
