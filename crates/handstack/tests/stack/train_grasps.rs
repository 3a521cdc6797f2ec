//! What `handstack train softness` reads, and what it refuses: grasp sessions written through
//! the recorder the binary records with (`/hand0/fingers/raw` and the labels), read back at
//! 10 Hz from first contact; too few grasps of a class, a class the net does not have, labels
//! over no readings and bags of another model — each refused with the file and the topic.

use hand_traits::Softness;
use hand_zenoh::msg::handstack_msgs::FingerFrame;
use handstack::record::read::ReadError;
use handstack::record::{HAND_FRAME, LABELS, Labelled, Recorder};
use handstack::train::TrainError;
use handstack::train::softness::{grasps, train};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> PathBuf {
    crate::fresh_dir("grasps", name)
}

const T0: u64 = 1_700_000_000_000_000_000;
/// The hand's reading period, ns (its board reports every 20 ms).
const PERIOD_NS: u64 = 20_000_000;
/// Readings before first contact.
const APPROACH: u64 = 25;
/// Readings from first contact to the end of the window (1 s, both ends).
const WINDOW: u64 = 51;

/// Reading `i` of grasp `g` of `class` from first contact: forces rising and angles settling
/// at a pace each class has (a pattern a network separates at once), a little apart per grasp.
fn reading(class: usize, g: usize, i: u64) -> [f32; 8] {
    let t = i as f32 / WINDOW as f32;
    let spread = 1.0 + 0.02 * g as f32;
    let force = (0.5 + 1.5 * class as f32) * (0.1 + t) * spread;
    let angle = (40.0 - 15.0 * class as f32) * (1.0 - (-3.0 * t).exp()) * spread;
    [force, force, force, force, angle, angle, angle, angle]
}

/// A grasp session at `bag`: each of `classes` an approach, a window labelled `experiment` /
/// `name` = class over the readings from first contact to `covered` readings later.
fn session(bag: &Path, experiment: &str, name: &str, classes: &[f64], covered: u64) {
    let rec = Recorder::create(bag).expect("recorder");
    let topic = rec.topic::<FingerFrame>("/hand0/fingers/raw");
    let mut t = T0;
    for (g, &class) in classes.iter().enumerate() {
        let write = |s: [f32; 8], t: &mut u64| {
            let msg = FingerFrame {
                header: hand_zenoh::convert::header(*t as i64, HAND_FRAME),
                force_n: s[..4].to_vec(),
                distal_angle_rad: s[4..].iter().map(|a| a.to_radians()).collect(),
            };
            rec.write(topic, *t, &msg);
            *t += PERIOD_NS;
        };
        for _ in 0..APPROACH {
            write([0.0, 0.0, 0.0, 0.0, 2.0, 2.0, 2.0, 2.0], &mut t);
        }
        let start_ns = t;
        for i in 0..WINDOW {
            write(reading(class as usize, g, i), &mut t);
        }
        // Over no reading: a nanosecond after the first.
        let (start_ns, end_ns) = match covered {
            0 => (start_ns + 1, start_ns + 1),
            n => (start_ns, start_ns + (n - 1) * PERIOD_NS),
        };
        rec.label(
            HAND_FRAME,
            &Labelled {
                experiment,
                name,
                value: class,
                start_ns,
                end_ns,
            },
        );
    }
    rec.finish().expect("bag finished");
}

fn refused(bag: &Path) -> ReadError {
    match grasps(&[bag.to_owned()]) {
        Err(e) => e,
        Ok(g) => panic!("{} read as {} grasps", bag.display(), g.len()),
    }
}

/// Soft, moderate, hard, … `n` grasps.
fn rounds(n: usize) -> Vec<f64> {
    (0..n).map(|i| (i % 3) as f64).collect()
}

#[test]
fn a_grasp_session_reads_back_at_10_hz_from_first_contact() {
    let d = dir("good");
    session(
        &d.join("session-001"),
        "softness",
        "class",
        &rounds(3),
        WINDOW,
    );
    let bags = handstack::collect::bags(std::slice::from_ref(&d)).expect("bags");
    let g = grasps(&bags).expect("grasps");
    assert_eq!(g.iter().map(|g| g.class).collect::<Vec<_>>(), Softness::ALL);
    for (k, grasp) in g.iter().enumerate() {
        // 1 s at 10 Hz, both ends; every fifth reading (20 ms apart), from first contact.
        assert_eq!(grasp.series.len(), 11);
        for (j, s) in grasp.series.iter().enumerate() {
            let want = reading(k, k, 5 * j as u64);
            assert!((s[0] - want[0]).abs() < 1e-6, "{j}: {s:?} vs {want:?}");
            assert!((s[4] - want[4]).abs() < 1e-3, "{j}: {s:?} vs {want:?}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn separable_grasps_train_to_a_net_that_classifies_the_held_out_ones() {
    let d = dir("train");
    session(
        &d.join("session-001"),
        "softness",
        "class",
        &rounds(9),
        WINDOW,
    );
    let g = grasps(&[d.join("session-001")]).expect("grasps");
    let trained = train(&g, 8).expect("trained");
    let figure = |name: &str| trained.figure(name).unwrap_or_else(|| panic!("no {name}"));
    assert_eq!(figure("grasps"), 9.0);
    // The second grasp of each class held out.
    assert_eq!(figure("heldout_grasps"), 3.0);
    assert_eq!(figure("train_samples"), 6.0 * 11.0);
    assert_eq!(figure("heldout_accuracy_pct"), 100.0);
    // The same grasps and seed, the same weights.
    let again = train(&g, 8).expect("trained");
    assert_eq!(trained.model.flat(), again.model.flat());
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn too_few_grasps_and_bad_grasp_bags_are_refused_naming_the_file_and_topic() {
    let d = dir("bad");
    // No hard object twice.
    session(&d.join("few"), "softness", "class", &rounds(5), WINDOW);
    let g = grasps(&[d.join("few")]).expect("grasps");
    match train(&g, 8) {
        Err(e @ TrainError::TooFew { found: 1, .. }) => {
            let text = e.to_string();
            assert!(
                text.starts_with("1 grasps of hard objects recorded"),
                "{text}"
            );
            assert!(text.contains("at least 2"), "{text}");
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("trained without a second hard object"),
    }
    // A class the net does not have.
    let bag = d.join("class");
    session(&bag, "softness", "class", &[3.0], WINDOW);
    let text = refused(&bag).to_string();
    assert!(text.contains(&bag.display().to_string()), "{text}");
    assert!(
        text.contains(&format!(
            "{LABELS}: `class` = 3: the classes are 0 soft, 1 moderate, 2 hard"
        )),
        "{text}"
    );
    // A label over no reading.
    let bag = d.join("empty");
    session(&bag, "softness", "class", &[1.0], 0);
    let text = refused(&bag).to_string();
    assert!(
        text.contains("`class` = moderate covers no /hand0/fingers/raw reading"),
        "{text}"
    );
    // Another model's training data.
    let bag = d.join("taps");
    session(&bag, "tap_to_move", "region", &[3.0], WINDOW);
    let text = refused(&bag).to_string();
    assert!(
        text.contains("labels of `tap_to_move`, none of `softness`"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
