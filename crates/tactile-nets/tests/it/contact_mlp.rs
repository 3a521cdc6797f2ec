//! The contact-area MLP: seeded determinism, save → load bit-identical for every head, typed
//! errors on bad input, stable activations, and the built-in model over arbitrary input.

use crate::common::{self, bits, rng};
use proptest::prelude::*;
use rand::Rng;
use tactile_nets::ContactLocator;
use tactile_nets::NetError;
use tactile_nets::activations::{log_sigmoid, sigmoid, softmax};
use tactile_nets::contact_mlp::{
    ContactExample, ContactMlp, Head, N_FEATURES, TapReading, features,
};
use tactile_nets::pretrained;
use tactile_nets::train::TrainConfig;

/// Where the three sensors sit under the pad, in (row, column) cell units.
const SENSORS: [[f32; 2]; 3] = [[1.0, 1.5], [4.0, 3.5], [1.5, 6.0]];

/// Synthetic taps from generator `seed`: every single cell and every pair of neighbours in a
/// row (24 + 20 contacts), each pressed at 0.5, 1 and 2 kgf. Each sensor's rise falls off with
/// its distance from the contact's centroid and grows with force and contact size (±5 %
/// seeded noise); it arrives later the farther it is, and never when it rose under 30 Pa.
fn taps(seed: u64) -> Vec<ContactExample> {
    let mut rng = rng(seed);
    let singles = (0..24).map(|c| 1u32 << c);
    let pairs = (0..24).filter(|c| c % 6 != 5).map(|c| 0b11u32 << c);
    let mut out = Vec::new();
    for mask in singles.chain(pairs) {
        for force_kgf in [0.5f32, 1.0, 2.0] {
            let centroid = ContactExample::new(at_rest(), mask).centroid;
            let baseline: f32 = 101_000.0 + rng.random_range(-200.0..200.0);
            let mut held_pa = [0.0; 3];
            let mut arrival_ms = [None; 3];
            for (k, [r, c]) in SENSORS.into_iter().enumerate() {
                let d = ((centroid[0] - r).powi(2) + (centroid[1] - c).powi(2)).sqrt();
                let size = (mask.count_ones() as f32).sqrt();
                let rise = force_kgf
                    * 3000.0
                    * size
                    * (-d / 2.0).exp()
                    * (1.0 + rng.random_range(-0.05..0.05));
                held_pa[k] = baseline + rise;
                arrival_ms[k] = (rise >= 30.0).then(|| 1.0 + 4.0 * d + rng.random_range(-0.5..0.5));
            }
            let reading = TapReading {
                baseline_pa: [baseline; 3],
                held_pa,
                arrival_ms,
            };
            out.push(ContactExample::new(reading, mask));
        }
    }
    out
}

/// A reading with nothing pressed (for [`ContactExample::new`]'s centroid only).
fn at_rest() -> TapReading {
    TapReading {
        baseline_pa: [101_000.0; 3],
        held_pa: [101_000.0; 3],
        arrival_ms: [None; 3],
    }
}

fn tiny(seed: u64) -> TrainConfig {
    common::quick(seed, 5, 16, 3e-3, 0.001)
}

#[test]
fn training_is_deterministic_and_save_load_is_bit_identical() -> Result<(), NetError> {
    let (train, test) = (taps(1), taps(2));
    let dir = common::temp_dir("mlp")?;
    for head in Head::ALL {
        let (a, log_a) = ContactMlp::train(&train, head, &tiny(3))?;
        let (b, log_b) = ContactMlp::train(&train, head, &tiny(3))?;
        let (c, _) = ContactMlp::train(&train, head, &tiny(4))?;
        assert_eq!(bits(&log_a.epoch_loss), bits(&log_b.epoch_loss));
        common::assert_seeded(
            &a.to_file()?.to_bytes()?,
            &b.to_file()?.to_bytes()?,
            &c.to_file()?.to_bytes()?,
        );
        let path = dir.join(format!("{}.safetensors", head.name()));
        a.save(&path)?;
        let loaded = ContactMlp::load(&path)?;
        assert_eq!(loaded.head(), head);
        assert_eq!(loaded.catalogue(), a.catalogue());
        for r in &test {
            let x = features(&r.reading);
            assert_eq!(bits(&a.outputs(&x)?), bits(&loaded.outputs(&x)?));
            assert_eq!(a.predict(&x)?, loaded.predict(&x)?);
        }
    }
    std::fs::remove_dir_all(&dir)?;
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let train = taps(1);
    let (mut mlp, _) = ContactMlp::train(&train[..8], Head::CellSet, &tiny(1))?;
    assert!(matches!(
        mlp.locate(&[0.0; N_FEATURES - 1]),
        Err(NetError::Shape {
            expected: N_FEATURES,
            got: 8
        })
    ));
    assert!(matches!(mlp.locate(&[]), Err(NetError::Shape { .. })));
    let mut x = [0.0f32; N_FEATURES];
    x[4] = f32::NAN;
    assert!(matches!(
        mlp.locate(&x),
        Err(NetError::NonFinite { index: 4 })
    ));
    x[4] = f32::NEG_INFINITY;
    assert!(matches!(
        mlp.locate(&x),
        Err(NetError::NonFinite { index: 4 })
    ));
    let c = mlp.locate(&features(&train[0].reading))?;
    assert_eq!(c.regions, 24);
    assert!(c.region < 24 && (0.0..=1.0).contains(&c.confidence));
    assert!(matches!(
        ContactMlp::train(&[], Head::CellSet, &tiny(1)),
        Err(NetError::Training(_))
    ));
    Ok(())
}

proptest! {
    #[test]
    fn activations_are_finite_for_any_logit(
        x in prop::num::f32::ANY.prop_filter("not NaN", |v| !v.is_nan()),
        logits in prop::collection::vec(
            prop_oneof![prop::num::f32::NORMAL, Just(f32::MAX), Just(-f32::MAX),
                        Just(f32::INFINITY), Just(f32::NEG_INFINITY)], 1..32),
    ) {
        let s = sigmoid(x);
        prop_assert!((0.0..=1.0).contains(&s));
        if x.is_finite() {
            prop_assert!(log_sigmoid(x).is_finite() && log_sigmoid(x) <= 0.0);
        }
        let p = softmax(&logits).unwrap_or_default();
        prop_assert_eq!(p.len(), logits.len());
        prop_assert!(p.iter().all(|v| v.is_finite() && (0.0..=1.0).contains(v)));
        prop_assert!((p.iter().sum::<f32>() - 1.0).abs() < 1e-4);
    }

    #[test]
    fn the_mlp_never_panics_and_outputs_are_finite_or_a_typed_error(
        x in prop::collection::vec(prop::num::f32::ANY, N_FEATURES),
    ) {
        let mlp = built_in();
        match mlp.predict(&x) {
            Ok(p) => {
                prop_assert!(x.iter().all(|v| v.is_finite()));
                prop_assert!(p.region < 24 && (0.0..=1.0).contains(&p.confidence));
                let probs = mlp.cell_probabilities(&x).ok().flatten().unwrap_or([f32::NAN; 24]);
                prop_assert!(probs.iter().all(|v| (0.0..=1.0).contains(v)));
            }
            Err(NetError::NonFinite { index }) => prop_assert!(!x[index].is_finite()),
            Err(NetError::NonFiniteOutput { .. }) => prop_assert!(x.iter().all(|v| v.is_finite())),
            Err(e) => prop_assert!(false, "unexpected error {e}"),
        }
    }
}

/// The built-in OSR 4096 model, a cell-set head (so it has cell probabilities).
fn built_in() -> &'static ContactMlp {
    static MODEL: std::sync::OnceLock<ContactMlp> = std::sync::OnceLock::new();
    MODEL.get_or_init(|| {
        let mlp = pretrained::contact_mlp(4096).expect("built-in model");
        assert_eq!(mlp.head(), Head::CellSet);
        mlp
    })
}
