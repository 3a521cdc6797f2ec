//! What `handstack train contact-cnn` reads, and what it refuses: tap sessions written through
//! the recorder the binary records with (`/pad0/imu` and the labels), read back as windows;
//! bags of another model, labels that do not cover a window, a region the pad does not have,
//! too few taps of a region — each refused with the file and the topic.

use hand_traits::ImuFrame;
use handstack::record::pad::{ImuTopic, PAD_FRAME};
use handstack::record::read::ReadError;
use handstack::record::{LABELS, Labelled, Recorder};
use handstack::train::TrainError;
use handstack::train::contact_cnn::{SHIFT_FRAMES, taps, train};
use std::path::{Path, PathBuf};
use tactile_nets::contact_cnn::{SI_TO_INPUT, WINDOW};

fn dir(name: &str) -> PathBuf {
    crate::fresh_dir("taps", name)
}

const T0: u64 = 1_700_000_000_000_000_000;
/// The pad's frame period, ns (30 Hz).
const PERIOD_NS: u64 = 33_333_333;
/// Frames of rest between taps.
const REST: usize = 10;

/// The frame `i` of a tap of `region`: acc x / y and gyro x / y each a ramp whose slope and
/// sign say the region (a pattern a network separates at once), at rest outside the tap.
fn frame(region: u8, i: usize, tapping: bool) -> ImuFrame {
    let r = f32::from(region);
    let s = if tapping {
        (i as f32 + 1.0) * 1e-3
    } else {
        0.0
    };
    ImuFrame {
        t_us: 0,
        accel_mps2: [s * (r - 4.0), s * (r % 3.0 - 1.0), 9.81],
        gyro_rps: [s * 0.1 * (r / 3.0 - 1.0), -s * 0.1 * r, 0.0],
        pressure_pa: None,
    }
}

/// A tap session at `bag`: for each region, `REST` frames at rest, then a window of `WINDOW`
/// frames labelled `experiment` / `name` = region over `covered` of them, then rest again.
fn session(bag: &Path, experiment: &str, name: &str, regions: &[u8], covered: usize) {
    let rec = Recorder::create(bag).expect("recorder");
    let mut imu = ImuTopic::new(&rec);
    let mut t = T0;
    for &r in regions {
        let mut write = |f: ImuFrame, t: &mut u64| {
            imu.record(*t, &f);
            *t += PERIOD_NS;
        };
        for i in 0..REST {
            write(frame(r, i, false), &mut t);
        }
        let start_ns = t;
        for i in 0..WINDOW {
            write(frame(r, i, true), &mut t);
        }
        rec.label(
            PAD_FRAME,
            &Labelled {
                experiment,
                name,
                value: f64::from(r),
                start_ns,
                end_ns: start_ns + (covered as u64 - 1) * PERIOD_NS,
            },
        );
    }
    for i in 0..REST {
        imu.record(t, &frame(0, i, false));
        t += PERIOD_NS;
    }
    rec.finish().expect("bag finished");
}

fn refused(bag: &Path) -> ReadError {
    match taps(&[bag.to_owned()]) {
        Err(e) => e,
        Ok(t) => panic!("{} read as {} taps", bag.display(), t.len()),
    }
}

#[test]
fn a_tap_session_reads_back_as_windows_with_frames_to_shift_them() {
    let d = dir("good");
    let regions: Vec<u8> = (0..9).collect();
    session(
        &d.join("session-001"),
        "tap_to_move",
        "region",
        &regions,
        WINDOW,
    );
    let bags = handstack::collect::bags(std::slice::from_ref(&d)).expect("bags");
    let taps = taps(&bags).expect("taps");
    assert_eq!(taps.len(), 9);
    for (tap, &r) in taps.iter().zip(&regions) {
        assert_eq!(tap.region, r);
        assert_eq!(tap.start, SHIFT_FRAMES);
        assert_eq!(tap.frames.len(), WINDOW + 2 * SHIFT_FRAMES);
        // The window as the run's CNN reads it: acc x of its first and last frames (mm/s²).
        let w = tap.window(0).expect("a window");
        let want = |i: usize| frame(r, i, true).accel_mps2[0] * SI_TO_INPUT;
        assert!((w[0] - want(0)).abs() < 1e-3, "{} vs {}", w[0], want(0));
        assert!((w[WINDOW - 1] - want(WINDOW - 1)).abs() < 1e-3);
        // Shifted by SHIFT_FRAMES earlier: rest frames come in first.
        let early = tap.window(-(SHIFT_FRAMES as isize)).expect("shifted");
        assert_eq!(early[0], 0.0);
        assert!(tap.window(SHIFT_FRAMES as isize + 1).is_none());
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn separable_taps_train_to_a_model_that_locates_the_held_out_ones() {
    let d = dir("train");
    let regions: Vec<u8> = (0..4).flat_map(|_| 0..9u8).collect();
    session(
        &d.join("session-001"),
        "tap_to_move",
        "region",
        &regions,
        WINDOW,
    );
    let t = taps(&[d.join("session-001")]).expect("taps");
    let trained = train(&t, 8, false).expect("trained");
    let figure = |name: &str| trained.figure(name).unwrap_or_else(|| panic!("no {name}"));
    assert_eq!(figure("taps"), 36.0);
    assert_eq!(figure("heldout_taps"), 9.0);
    assert_eq!(figure("heldout_accuracy_pct"), 100.0);
    // The same taps and seed, the same weights.
    let again = train(&t, 8, false).expect("trained");
    let w = t[2].window(0).expect("a window");
    assert_eq!(
        trained.model.logits(&w).expect("logits"),
        again.model.logits(&w).expect("logits")
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn too_few_taps_of_a_region_are_refused() {
    let d = dir("few");
    let regions: Vec<u8> = (0..9).chain(0..8).collect();
    session(
        &d.join("session-001"),
        "tap_to_move",
        "region",
        &regions,
        WINDOW,
    );
    let t = taps(&[d.join("session-001")]).expect("taps");
    match train(&t, 8, false) {
        Err(e @ TrainError::TooFew { found: 1, .. }) => {
            let text = e.to_string();
            assert!(text.starts_with("1 taps of region 8 recorded"), "{text}");
            assert!(text.contains("at least 2"), "{text}");
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("trained without a second tap of region 8"),
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn bad_tap_bags_are_refused_naming_the_file_and_topic() {
    let d = dir("bad");
    // A label over 20 frames, not a window.
    let bag = d.join("short");
    session(&bag, "tap_to_move", "region", &[3], 20);
    let text = refused(&bag).to_string();
    assert!(
        text.contains(&format!(
            "{LABELS}: `region` = 3 covers 20 frames, not a window of 38"
        )),
        "{text}"
    );
    // A region the pad does not have.
    let bag = d.join("region");
    session(&bag, "tap_to_move", "region", &[9], WINDOW);
    let text = refused(&bag).to_string();
    assert!(
        text.contains("`region` = 9: the pad has regions 0…8"),
        "{text}"
    );
    // Another model's training data.
    let bag = d.join("weights");
    session(&bag, "weight", "weight_gf", &[3], WINDOW);
    let e = refused(&bag);
    assert!(matches!(e, ReadError::Content { .. }), "{e}");
    assert!(
        e.to_string().contains(&format!(
            "{LABELS}: labels of `weight`, none of `tap_to_move`"
        )),
        "{e}"
    );
    // Labels, but no pad frames.
    let bag = d.join("no-frames");
    let rec = Recorder::create(&bag).expect("recorder");
    rec.label(
        PAD_FRAME,
        &Labelled {
            experiment: "tap_to_move",
            name: "region",
            value: 1.0,
            start_ns: T0,
            end_ns: T0,
        },
    );
    rec.finish().expect("bag finished");
    let e = refused(&bag);
    assert!(matches!(e, ReadError::MissingTopic { .. }), "{e}");
    assert!(e.to_string().contains("no /pad0/imu messages"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}
