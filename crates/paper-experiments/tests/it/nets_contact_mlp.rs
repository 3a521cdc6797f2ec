//! The contact-area MLP: save → load bit-identical, seeded determinism, typed errors on bad
//! input, stable activations, and the drift check of the committed metrics.

use crate::common;

use common::{bits, quick, root};
use hand_traits::ContactLocator;
use paper_experiments::contact_eval::{self, METRICS_FILE, MODEL_DIR, SEED};
use paper_experiments::data::fingertip::{self, TapRecord};
use proptest::prelude::*;
use tactile_nets::NetError;
use tactile_nets::activations::{log_sigmoid, sigmoid, softmax};
use tactile_nets::contact_mlp::{ContactMlp, Head, N_FEATURES, features};
use tactile_nets::metrics::MetricsFile;
use tactile_nets::train::TrainConfig;

fn records() -> Vec<TapRecord> {
    fingertip::load(&root())
        .expect("the committed fingertip dataset parses")
        .records()
}

fn tiny(seed: u64) -> TrainConfig {
    quick(seed, 5, 16, 3e-3, 0.001)
}

#[test]
fn training_is_deterministic_and_save_load_is_bit_identical() -> Result<(), NetError> {
    let records = records();
    let (train, test) = contact_eval::split(&records, 4096);
    let train: Vec<_> = train.iter().map(|r| r.example()).collect();
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
        let dir = common::temp_dir("mlp")?;
        let path = dir.join(format!("{}.safetensors", head.name()));
        a.save(&path)?;
        let loaded = ContactMlp::load(&path)?;
        std::fs::remove_file(&path)?;
        assert_eq!(loaded.head(), head);
        assert_eq!(loaded.catalogue(), a.catalogue());
        for r in &test {
            let x = features(&r.reading);
            assert_eq!(bits(&a.outputs(&x)?), bits(&loaded.outputs(&x)?));
            assert_eq!(a.predict(&x)?, loaded.predict(&x)?);
        }
    }
    Ok(())
}

#[test]
fn bad_input_gives_typed_errors() -> Result<(), NetError> {
    let records = records();
    let (train, _) = contact_eval::split(&records, 256);
    let train: Vec<_> = train.iter().map(|r| r.example()).collect();
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
    Ok(())
}

#[test]
fn committed_metrics_match_a_re_evaluation_of_the_committed_weights() -> Result<(), NetError> {
    let records = records();
    let committed = MetricsFile::from_json(&std::fs::read_to_string(
        root().join(MODEL_DIR).join(METRICS_FILE),
    )?)?;
    let loaded = contact_eval::load_committed(&root(), &records)?;
    let fresh = contact_eval::metrics_file(&loaded, SEED);
    assert_eq!(
        committed.rows.len(),
        5 * contact_eval::Mlp::ALL.len(),
        "5 OSRs x (2 paper-recipe heads, the chosen and the two off-lattice models)"
    );
    let drift = committed.drift(&fresh, 1e-9);
    assert!(drift.is_empty(), "committed metrics drifted: {drift:#?}");
    Ok(())
}

/// The off-lattice model learns the one cell under each centroid, and its training draws are
/// not the held-out jittered set: a draw of the held-out seed would repeat its offsets.
#[test]
fn off_lattice_training_taps_are_labelled_by_their_centroid_cell_and_are_not_the_held_out_set()
-> Result<(), Box<dyn std::error::Error>> {
    let lattice = records();
    let examples = contact_eval::off_lattice_examples(&lattice, &[], 256);
    let (train, _) = contact_eval::split(&lattice, 256);
    assert_eq!(examples.len(), train.len());
    for (e, r) in examples.iter().zip(&train) {
        let cell = r.tap.centroid_mm().and_then(contact_eval::cell_at);
        assert_eq!(Some(e.mask), cell.map(|c| 1u32 << c), "{:?}", r.tap);
        // On the lattice, the centroid target is the touched cells' own centroid.
        let own = aot_locate::CellSet::from_bits(r.tap.mask).and_then(|c| c.centroid());
        let own = own.expect("a contact");
        assert!(
            (e.centroid[0] - own[0]).abs() < 1e-5 && (e.centroid[1] - own[1]).abs() < 1e-5,
            "{:?} vs {own:?}",
            e.centroid
        );
    }
    let held_out = fingertip::load_set(&root(), fingertip::TapSet::Jittered)?;
    let mut seeds = contact_eval::OFF_LATTICE_TRAIN_SEEDS.to_vec();
    seeds.extend(contact_eval::OFF_LATTICE_VALIDATION_SEEDS);
    seeds.sort_unstable();
    seeds.dedup();
    assert_eq!(seeds.len(), 23, "23 distinct draws");
    let (taps, series) =
        hand_sim::fingertip::dataset::jittered_taps(contact_eval::OFF_LATTICE_TRAIN_SEEDS[0])?;
    let draw = fingertip::parse(&taps, &series)?;
    assert_eq!(draw.taps().len(), held_out.taps().len());
    // Off the lattice the centroid target carries the shift, in cells of 3 mm (x right is a
    // higher column, y up a lower row).
    let shifted = draw.records();
    for (e, r) in contact_eval::off_lattice_examples(&[], &shifted, 256)
        .iter()
        .zip(shifted.iter().filter(|r| r.tap.osr == 256))
    {
        let own = aot_locate::CellSet::from_bits(r.tap.mask).and_then(|c| c.centroid());
        let own = own.expect("a contact");
        let [dx, dy] = r.tap.offset_mm;
        assert!(
            (e.centroid[0] - (own[0] - dy / 3.0)).abs() < 1e-4,
            "{:?}",
            r.tap
        );
        assert!(
            (e.centroid[1] - (own[1] + dx / 3.0)).abs() < 1e-4,
            "{:?}",
            r.tap
        );
    }
    let same = draw
        .taps()
        .iter()
        .zip(held_out.taps())
        .filter(|(a, b)| a.offset_mm == b.offset_mm)
        .count();
    assert!(
        same < draw.taps().len() / 100,
        "{same} taps share their offset"
    );
    Ok(())
}

/// A one-cell held-out set: `draws` shifted draws of the one-cell contact on every cell at
/// every force and each of `osrs`, every shift within half a cell and off every border (so
/// the touched cell is the one under the centroid), and offsets of its own, not `others'`.
fn check_one_cell_set(
    set: fingertip::TapSet,
    osrs: &[u16],
    draws: u32,
    others: &[fingertip::TapSet],
) -> Result<usize, Box<dyn std::error::Error>> {
    use hand_sim::fingertip::dataset::TAP_FORCES_KGF;
    let data = fingertip::load_set(&root(), set)?;
    let per_osr = 24 * TAP_FORCES_KGF.len() * draws as usize;
    assert_eq!(data.taps().len(), osrs.len() * per_osr, "{set:?}");
    let mut seen = std::collections::BTreeMap::new();
    for r in data.records() {
        assert!(osrs.contains(&r.tap.osr), "{:?}", r.tap);
        assert_eq!(r.tap.mask.count_ones(), 1, "{:?}", r.tap);
        assert!(r.tap.offset_mm.iter().all(|d| d.abs() < 1.5), "{:?}", r.tap);
        let under = r.tap.centroid_mm().and_then(contact_eval::cell_at);
        assert_eq!(under.map(|c| 1u32 << c), Some(r.tap.mask), "{:?}", r.tap);
        *seen
            .entry((r.tap.osr, r.tap.mask, r.tap.force_kgf))
            .or_insert(0u32) += 1;
    }
    assert_eq!(seen.len(), osrs.len() * 24 * TAP_FORCES_KGF.len());
    assert!(seen.values().all(|&n| n == draws), "{seen:?}");
    for &other in others {
        let theirs: std::collections::BTreeSet<_> = fingertip::load_set(&root(), other)?
            .taps()
            .iter()
            .filter(|t| t.mask.count_ones() == 1)
            .map(|t| (t.mask, t.offset_mm.map(f32::to_bits)))
            .collect();
        let shared = data
            .taps()
            .iter()
            .filter(|t| theirs.contains(&(t.mask, t.offset_mm.map(f32::to_bits))))
            .count();
        assert!(
            shared < data.taps().len() / 100,
            "{shared} taps of {set:?} repeat an offset of {other:?}"
        );
    }
    Ok(per_osr)
}

/// The single-cell held-out set (the larger 24-area set): 14 draws per cell and force
/// at every OSR, 1008 taps per OSR; and the OSR-256 set added to judge the quadratic-base
/// search: 42 draws at OSR 256 only, 3024 taps. Neither repeats the other's or the jittered
/// set's offsets.
#[test]
fn the_one_cell_sets_hold_their_taps_off_every_border() -> Result<(), Box<dyn std::error::Error>> {
    use fingertip::TapSet::{Jittered, SingleCell, SingleCellOsr256};
    use hand_sim::fingertip::dataset::{
        SINGLE_CELL_DRAWS, SINGLE_CELL_OSR256, SINGLE_CELL_OSR256_DRAWS, TAP_OSRS,
    };
    let per_osr = check_one_cell_set(SingleCell, &TAP_OSRS, SINGLE_CELL_DRAWS, &[Jittered])?;
    assert_eq!(per_osr, 1008);
    let n = check_one_cell_set(
        SingleCellOsr256,
        &[SINGLE_CELL_OSR256],
        SINGLE_CELL_OSR256_DRAWS,
        &[Jittered, SingleCell],
    )?;
    assert_eq!(n, 3024);
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
        let mlp = committed(Head::CellSet);
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

fn committed(head: Head) -> ContactMlp {
    ContactMlp::load(
        &root()
            .join(MODEL_DIR)
            .join(contact_eval::model_file(4096, head)),
    )
    .expect("committed model loads")
}
