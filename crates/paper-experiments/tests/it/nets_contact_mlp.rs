//! The contact-area MLP against the papers' data: the drift check of the committed metrics,
//! the off-lattice model's training taps and the one-cell held-out sets. (Its own behaviour is
//! tested in tactile-nets.)

use crate::common::root;
use paper_experiments::contact_eval::{self, METRICS_FILE, MODEL_DIR, SEED};
use paper_experiments::data::fingertip::{self, TapRecord};
use tactile_nets::NetError;
use tactile_nets::metrics::MetricsFile;

fn records() -> Vec<TapRecord> {
    fingertip::load(&root())
        .expect("the committed fingertip dataset parses")
        .records()
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

/// The range the MLPs state (`contact_mlp::Z_RANGE` spreads of the training inputs) holds every
/// tap of the pad's dataset, training and held-out, at every OSR, for the float and the
/// fixed-point forms; the hardest tap pressed three times as hard is flagged.
#[test]
fn every_dataset_tap_is_in_range_and_a_press_three_times_the_hardest_is_not() -> Result<(), NetError>
{
    use tactile_nets::contact_mlp::features;
    use tactile_nets::pretrained::{
        CONTACT_MLP_OSRS, contact_mlp_static, fixed_contact_mlp_static,
    };
    let records = records();
    for osr in CONTACT_MLP_OSRS {
        let (float, fixed) = (
            contact_mlp_static(osr).ok_or(NetError::EmptyCatalogue)?,
            fixed_contact_mlp_static(osr).ok_or(NetError::EmptyCatalogue)?,
        );
        let taps = contact_eval::at_osr(&records, osr);
        let rise = |r: &&TapRecord| -> f32 {
            (0..3)
                .map(|k| r.reading.held_pa[k] - r.reading.baseline_pa[k])
                .sum()
        };
        for r in &taps {
            let x = features(&r.reading);
            assert!(float.predict(&x)?.in_range, "OSR {osr}: {:?}", r.reading);
            assert!(fixed.predict(&x)?.in_range, "OSR {osr}: {:?}", r.reading);
        }
        let hardest = taps
            .iter()
            .max_by(|a, b| rise(a).total_cmp(&rise(b)))
            .ok_or(NetError::EmptyCatalogue)?;
        let mut pressed = hardest.reading;
        for k in 0..3 {
            pressed.held_pa[k] += 2.0 * (pressed.held_pa[k] - pressed.baseline_pa[k]);
        }
        let x = features(&pressed);
        assert!(!float.predict(&x)?.in_range, "OSR {osr}: {pressed:?}");
        assert!(!fixed.predict(&x)?.in_range, "OSR {osr}: {pressed:?}");
    }
    Ok(())
}
