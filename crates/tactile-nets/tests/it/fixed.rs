//! The fixed-point models against their float models over arbitrary input in and past the
//! training range: the force within a fraction of a gram-force, the contact decoded the same
//! (or, where two catalogue contacts score within the quantisation's error, a near tie), the
//! same typed errors. Their accuracy on the held-out sets is measured in paper-experiments
//! (`docs/trade.md`).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use tactile_nets::RunError;
use tactile_nets::contact_mlp::{N_FEATURES, TapReading, features};
use tactile_nets::pretrained::{
    CONTACT_MLP_OSRS, ForceModel, contact_mlp_static, fixed_contact_mlp_static,
};

#[test]
fn the_fixed_force_dnn_estimates_as_the_float_one() -> Result<(), RunError> {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    for model in ForceModel::ALL {
        let (float, fixed) = (model.dnn(), model.fixed_dnn());
        assert_eq!(float.range_gf(), fixed.range_gf());
        let mut worst = 0.0f32;
        for _ in 0..2000 {
            // 0–200 gf raise the sensors by up to ~1.3 hPa (Table 1); past that, saturation.
            let rise: [f32; 3] = core::array::from_fn(|_| rng.random_range(-0.2..4.0));
            let (a, b) = (float.estimate_gf(&rise)?, fixed.estimate_gf(&rise)?);
            worst = worst.max((a - b).abs());
        }
        println!("{model:?}: worst |fixed − float| {worst:.4} gf");
        assert!(worst < 0.5, "{model:?}: {worst} gf");
        assert_eq!(
            fixed.estimate_gf(&[0.1, 0.2]),
            Err(RunError::Shape {
                expected: 3,
                got: 2
            })
        );
        assert_eq!(
            fixed.estimate_gf(&[0.1, f32::NAN, 0.2]),
            Err(RunError::NonFinite { index: 1 })
        );
    }
    Ok(())
}

#[test]
fn the_fixed_contact_mlp_decodes_as_the_float_one() -> Result<(), RunError> {
    let mut rng = ChaCha8Rng::seed_from_u64(6);
    for osr in CONTACT_MLP_OSRS {
        let (Some(float), Some(fixed)) = (contact_mlp_static(osr), fixed_contact_mlp_static(osr))
        else {
            panic!("OSR {osr} is built in");
        };
        let (mut same, mut n, mut worst_conf) = (0, 0, 0.0f32);
        for _ in 0..2000 {
            let held: [f32; 3] =
                core::array::from_fn(|_| 101_000.0 + rng.random_range(0.0..6000.0));
            let arrival: [Option<f32>; 3] =
                core::array::from_fn(|_| rng.random_bool(0.9).then(|| rng.random_range(0.0..40.0)));
            let x = features(&TapReading {
                baseline_pa: [101_000.0; 3],
                held_pa: held,
                arrival_ms: arrival,
            });
            let (a, b) = (float.predict(&x)?, fixed.predict(&x)?);
            n += 1;
            if a.contact == b.contact {
                same += 1;
                worst_conf = worst_conf.max((a.confidence - b.confidence).abs());
            }
        }
        println!("OSR {osr}: {same} of {n} decoded alike; worst confidence gap {worst_conf:.4}");
        assert!(same * 100 >= n * 99, "OSR {osr}: {same} of {n}");
        // A logit's error is the layer's largest logit over 2^15 (block scaling), summed over a
        // contact's cells: a few hundredths of a logit, a few hundredths of posterior.
        assert!(worst_conf < 0.05, "OSR {osr}: {worst_conf}");
        assert_eq!(
            fixed.predict(&[0.0; N_FEATURES - 1]),
            Err(RunError::Shape {
                expected: N_FEATURES,
                got: N_FEATURES - 1
            })
        );
    }
    Ok(())
}
