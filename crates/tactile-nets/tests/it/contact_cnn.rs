//! The contact CNN: seeded determinism, save → load bit-identical, the plain-array path against
//! dfdx's forward for every variant, typed errors on bad input, finite softmax, and the
//! built-in model over arbitrary input.

use crate::common::{self, bits, rng};
use proptest::prelude::*;
use rand::Rng;
use tactile_nets::ContactLocator;
use tactile_nets::NetError;
use tactile_nets::activations::softmax;
use tactile_nets::contact_cnn::{
    ContactCnn, DfdxCnn, REGIONS, StaticContactCnn, Variant, WINDOW, WINDOW_VALUES,
};
use tactile_nets::pretrained;
use tactile_nets::train::TrainConfig;

fn tiny(seed: u64) -> TrainConfig {
    common::quick(seed, 2, 32, 1e-3, 0.0)
}

/// Synthetic taps: `per_region` windows of each of the 9 regions (3 column × 3 row groups),
/// regions in turn. A tap is a pulse 12 samples in whose sign and size on acc x and gyro y
/// follow the column, on acc y and gyro x the row group; seeded ±20 % on its size and noise
/// of ±10 (mm/s² or mrad/s) on every sample.
fn windows(per_region: usize) -> (Vec<[f32; WINDOW_VALUES]>, Vec<u8>) {
    let mut rng = rng(5);
    let (mut w, mut r) = (Vec::new(), Vec::new());
    for _ in 0..per_region {
        for region in 0..REGIONS as u8 {
            let (group, col) = (f32::from(region / 3) - 1.0, f32::from(region % 3) - 1.0);
            let size = [100.0 * col, 100.0 * group, 50.0 * group, 50.0 * col];
            let gain: f32 = rng.random_range(0.8..1.2);
            w.push(core::array::from_fn(|i| {
                let (channel, t) = (i / WINDOW, (i % WINDOW) as f32);
                let pulse = (-((t - 12.0) / 5.0).powi(2)).exp();
                10.0 + gain * size[channel] * pulse + rng.random_range(-10.0..10.0)
            }));
            r.push(region);
        }
    }
    (w, r)
}

#[test]
fn training_is_deterministic_save_load_bit_identical_and_frozen_matches_dfdx()
-> Result<(), NetError> {
    let (w, r) = windows(40);
    let dir = common::temp_dir("cnn")?;
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
        let path = dir.join(format!("{}.safetensors", variant.name()));
        a.save(&path)?;
        let loaded = ContactCnn::load(&path)?;
        assert_eq!(loaded.variant(), variant);
        assert_eq!(loaded, a);
        // dfdx's forward of the same weights, loaded from the file's tensors by dfdx's names.
        let reference = DfdxCnn::of(&loaded)?;
        let mut worst = 0.0f32;
        for x in w.iter().step_by(7) {
            assert_eq!(bits(&a.logits(x)?), bits(&loaded.logits(x)?));
            assert_eq!(a.predict(x)?, loaded.predict(x)?);
            let (f, d) = (a.logits(x)?, reference.logits(x)?);
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
    std::fs::remove_dir_all(&dir)?;
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let (w, r) = windows(5);
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
fn the_trigger_offset_travels_with_the_weights_and_is_checked() -> Result<(), NetError> {
    // The built-in models were trained on windows centred 16 frames after the trigger.
    for v in Variant::ALL {
        assert_eq!(
            pretrained::contact_cnn(v)?.trigger_offset(),
            Some(16),
            "{v:?}"
        );
    }
    let (w, r) = windows(5);
    let (cnn, _) = ContactCnn::train(&w[..40], &r[..40], Variant::Small, &tiny(1))?;
    assert_eq!(cnn.trigger_offset(), None);
    let back = ContactCnn::from_file(&cnn.clone().with_trigger_offset(19)?.to_file()?)?;
    assert_eq!(back.trigger_offset(), Some(19));
    assert!(matches!(
        cnn.clone().with_trigger_offset(20),
        Err(NetError::Training(_))
    ));
    // A file whose metadata holds a bad offset: a typed error, not a default.
    for bad in ["\"16\"", "-1", "20"] {
        let mut file = cnn.to_file()?;
        let meta = file.metadata().replacen(
            '{',
            &format!("{{\"window_centre_after_trigger_frames\":{bad},"),
            1,
        );
        file.set_metadata(meta);
        let e = ContactCnn::from_file(&file).expect_err(bad);
        assert!(
            e.to_string().contains("trigger") || e.to_string().contains("frame"),
            "{bad}: {e}"
        );
    }
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
        let mut cnn = pretrained::contact_cnn(Variant::Small).expect("built-in model");
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

/// `stat` locates as `file` on `taps`: the same regions and range flags, logits within 1e-4 of
/// the largest (the dense layers add in another order and skip no zeros), the same trigger
/// offset and typed errors.
fn agree<const F: usize, const FLAT: usize, const H: usize>(
    stat: &StaticContactCnn<F, FLAT, H>,
    file: &ContactCnn,
    taps: &[[f32; WINDOW_VALUES]],
) -> Result<(), NetError> {
    let variant = file.variant();
    assert_eq!(stat.variant(), variant);
    assert_eq!(stat.trigger_offset(), file.trigger_offset());
    for w in taps {
        let (a, b) = (file.predict(w)?, stat.predict(w)?);
        assert_eq!(
            (a.region, a.in_range),
            (b.region, b.in_range),
            "{variant:?}"
        );
        let (la, lb) = (file.logits(w)?, stat.logits(w)?);
        let top = la.iter().fold(1.0f32, |m, v| m.max(v.abs()));
        for (x, y) in la.iter().zip(lb) {
            assert!((x - y).abs() <= 1e-4 * top, "{variant:?}: {x} vs {y}");
        }
    }
    assert!(stat.predict(&[0.0; 3]).is_err());
    let mut nan = [0.0f32; WINDOW_VALUES];
    nan[5] = f32::NAN;
    assert!(stat.predict(&nan).is_err());
    Ok(())
}

/// The `'static` built-in CNNs (no `std`) locate as their weights files do.
#[test]
fn the_static_built_in_cnns_locate_as_their_weights_files() -> Result<(), NetError> {
    use tactile_nets::pretrained::{CONTACT_CNN_PAPER, CONTACT_CNN_SMALL, CONTACT_CNN_WIDE};
    let mut rng = rng(11);
    let (mut taps, _) = windows(4);
    // Random windows too, some far outside the training range.
    for k in 0..40 {
        let spread = if k % 10 == 0 { 1e6 } else { 800.0 };
        taps.push(core::array::from_fn(|_| rng.random_range(-spread..spread)));
    }
    agree(
        &CONTACT_CNN_PAPER,
        &pretrained::contact_cnn(Variant::Paper)?,
        &taps,
    )?;
    agree(
        &CONTACT_CNN_SMALL,
        &pretrained::contact_cnn(Variant::Small)?,
        &taps,
    )?;
    agree(
        &CONTACT_CNN_WIDE,
        &pretrained::contact_cnn(Variant::Wide)?,
        &taps,
    )?;
    let mut cnn = CONTACT_CNN_PAPER;
    assert_eq!(cnn.locate(&[0.0; WINDOW_VALUES])?.regions, 9);
    Ok(())
}
