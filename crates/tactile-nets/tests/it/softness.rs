//! The softness classifier: save → load bit-identical, seeded determinism for both
//! optimisers, typed errors on bad input and bad files, rank-deficient Jacobians, and finite
//! outputs of the built-in model for huge inputs.

use crate::common::{bits, rng};
use proptest::prelude::*;
use rand::Rng;
use tactile_nets::pretrained;
use tactile_nets::softness::{N_VARIABLES, RANGE_MARGIN, SoftnessNet};
use tactile_nets::softness_train::{
    AdamConfig, LmConfig, Optimiser, SoftnessTrainConfig, Stop, train,
};
use tactile_nets::{NetError, RunError};
use tactile_nets::{Softness, SoftnessClassifier};

/// One labelled grasp: its series of samples (four forces, N, then four distal angles, °).
type Grasp = (Vec<[f32; N_VARIABLES]>, Softness);

/// `per_class` synthetic grasps of each class from generator `seed`, classes in turn: 43
/// samples (0.1 s apart) of four fingers closing on an object, each finger's force rising to
/// 5–15 N while its angle travels the more the softer the object (±20 % seeded per finger,
/// ±0.05 noise on every reading).
fn grasps(seed: u64, per_class: usize) -> Vec<Grasp> {
    let mut rng = rng(seed);
    let mut out = Vec::new();
    for _ in 0..per_class {
        for class in Softness::ALL {
            let travel_per_n = match class {
                Softness::Soft => 4.0,
                Softness::Moderate => 1.5,
                Softness::Hard => 0.3,
            };
            let peak: [f32; 4] = core::array::from_fn(|_| rng.random_range(5.0..15.0));
            let own: [f32; 4] = core::array::from_fn(|_| rng.random_range(0.8..1.2));
            let series = (0..43)
                .map(|i| {
                    let t = i as f32 / 42.0;
                    let mut s = [0.0f32; N_VARIABLES];
                    for f in 0..4 {
                        let force = peak[f] * t;
                        s[f] = force + rng.random_range(-0.05..0.05);
                        s[4 + f] = 10.0 * t
                            + travel_per_n * own[f] * force
                            + rng.random_range(-0.05..0.05);
                    }
                    s
                })
                .collect();
            out.push((series, class));
        }
    }
    out
}

/// The borrowed form [`train`] reads.
fn refs(grasps: &[Grasp]) -> Vec<(&[[f32; N_VARIABLES]], Softness)> {
    grasps.iter().map(|(s, c)| (s.as_slice(), *c)).collect()
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

#[test]
fn training_is_deterministic_and_save_load_is_bit_identical() -> Result<(), NetError> {
    let train_set = grasps(1, 4);
    let train_set = refs(&train_set);
    let tests = grasps(2, 2);
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
        let path = std::env::temp_dir().join(format!(
            "tactile-nets-softness-{opt}-{}.safetensors",
            std::process::id()
        ));
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

/// The built-in net states the range it was trained on and counts the readings of a grasp
/// that lie outside it.
#[test]
fn readings_outside_the_training_range_are_counted() -> Result<(), NetError> {
    let net = pretrained::SOFTNESS;
    let range = net.scale().range();
    // Each variable's midpoint: inside.
    let mid: Vec<f32> = range.iter().map(|[lo, hi]| 0.5 * (lo + hi)).collect();
    let inside = mid.repeat(5);
    let a = net.assess(&inside)?;
    assert_eq!((a.samples, a.readings_outside), (5, 0));
    assert_eq!(a.class, net.predict(&inside)?);
    // Finger 1's force ten spans past its maximum in two of the five samples.
    let mut outside = inside.clone();
    for s in [1, 3] {
        let [lo, hi] = range[0];
        outside[s * N_VARIABLES] = hi + 10.0 * (hi - lo);
    }
    assert_eq!(net.assess(&outside)?.readings_outside, 2);
    // Just past the maximum, within the margin: still inside.
    let mut near = inside;
    let [lo, hi] = range[4];
    near[4] = hi + 0.5 * RANGE_MARGIN * (hi - lo);
    assert_eq!(net.assess(&near)?.readings_outside, 0);
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let mut net = pretrained::softness()?;
    assert!(matches!(
        net.sample_outputs(&[0.0; 7]),
        Err(RunError::Shape {
            expected: 8,
            got: 7
        })
    ));
    assert!(matches!(
        net.classify(&[]),
        Err(RunError::Shape {
            expected: 8,
            got: 0
        })
    ));
    assert!(matches!(
        net.classify(&[1.0; 12]),
        Err(RunError::Shape {
            expected: 16,
            got: 12
        })
    ));
    let mut series = vec![1.0f32; 3 * N_VARIABLES];
    series[N_VARIABLES + 5] = f32::NAN;
    assert!(matches!(
        net.classify(&series),
        Err(RunError::NonFinite { index: 13 })
    ));
    series[N_VARIABLES + 5] = f32::INFINITY;
    assert!(matches!(
        net.classify(&series),
        Err(RunError::NonFinite { index: 13 })
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

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn outputs_stay_finite_for_any_finite_input(
        x in prop::array::uniform8(prop::num::f32::NORMAL | prop::num::f32::ZERO | prop::num::f32::SUBNORMAL),
        scale in prop_oneof![Just(1.0f32), Just(1e20), Just(f32::MAX)],
    ) {
        let net = pretrained::softness().expect("built-in model");
        let sample: Vec<f32> = x.iter().map(|v| (v * scale).clamp(-f32::MAX, f32::MAX)).collect();
        let y = net.sample_outputs(&sample).expect("finite input gives an output");
        prop_assert!(y.iter().all(|v| v.is_finite()), "{y:?}");
        let mut net = net;
        prop_assert!(net.classify(&sample).is_ok());
    }
}
