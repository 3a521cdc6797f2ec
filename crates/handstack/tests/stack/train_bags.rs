//! What `handstack train force` reads, and what it refuses: collect sessions written through
//! the recorder the binary records with, read back as training steps; bags that are truncated,
//! unlabelled, another device's or another model's, each refused with the file and the topic.

use hand_zenoh::msg::handstack_msgs::PressureFrame;
use handstack::record::grasp::RawTopic;
use handstack::record::read::ReadError;
use handstack::record::{HAND_FRAME, LABELS, Labelled, Recorder};
use handstack::train::force::{steps, train};
use handstack::train::{TrainError, held_out_at};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> PathBuf {
    crate::fresh_dir("train", name)
}

const T0: u64 = 1_700_000_000_000_000_000;
const MS: u64 = 1_000_000;

/// A collect session's bag at `bag`: for each `(weight, rise Pa)` a tare of 3 frames at
/// 100 000 Pa and the weight's 3 frames `rise` above it, each labelled (`experiment`), frames
/// 10 ms apart.
fn session(bag: &Path, experiment: &str, weights: &[(f64, f32)]) {
    let rec = Recorder::create(bag).expect("recorder");
    let mut raw = RawTopic::new(&rec);
    let mut t = T0;
    let window = |raw: &mut RawTopic<'_>, p: f32, t: &mut u64| {
        let start = *t;
        for _ in 0..3 {
            raw.record(*t, &[p, p + 1.0, p - 1.0]);
            *t += 10 * MS;
        }
        (start, *t - 10 * MS)
    };
    for &(w, rise) in weights {
        let (start_ns, end_ns) = window(&mut raw, 100_000.0, &mut t);
        let label = |name, value| Labelled {
            experiment,
            name,
            value,
            start_ns,
            end_ns,
        };
        rec.label(HAND_FRAME, &label("tare", 0.0));
        let (start_ns, end_ns) = window(&mut raw, 100_000.0 + rise, &mut t);
        rec.label(
            HAND_FRAME,
            &Labelled {
                start_ns,
                end_ns,
                ..label("weight_gf", w)
            },
        );
    }
    rec.finish().expect("bag finished");
}

/// A bag at `bag` of one fingertip frame and no label (a run recorded with `--record`, or a
/// collect session stopped at its first question).
fn unlabelled(bag: &Path) -> PathBuf {
    let rec = Recorder::create(bag).expect("recorder");
    RawTopic::new(&rec).record(T0, &[1.0, 2.0, 3.0]);
    rec.finish().expect("bag finished");
    bag.to_owned()
}

fn mcap(bag: &Path) -> PathBuf {
    std::fs::read_dir(bag)
        .expect("bag")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .find(|p| p.extension().is_some_and(|x| x == "mcap"))
        .expect("an .mcap")
}

#[test]
fn a_session_reads_back_as_steps_each_tared_on_the_tare_before_it() {
    let d = dir("good");
    session(
        &d.join("session-001"),
        "weight",
        &[(10.0, 100.0), (20.0, 200.0)],
    );
    // A session stopped at its first question recorded frames but no label: skipped.
    unlabelled(&d.join("session-002"));
    let bags = handstack::collect::bags(std::slice::from_ref(&d)).expect("bags");
    assert_eq!(bags.len(), 2);
    let s = steps(&bags).expect("steps");
    assert_eq!(s.len(), 2);
    assert_eq!((s[0].weight_gf, s[1].weight_gf), (10.0, 20.0));
    // 100 Pa over the tare is 1 hPa on each sensor, frame by frame.
    assert_eq!(s[0].rises_hpa, vec![[1.0, 1.0, 1.0]; 3]);
    assert_eq!(s[1].mean_hpa(), [2.0, 2.0, 2.0]);
    // A resumed collect sees the weights recorded.
    let sessions = handstack::collect::Sessions::open(&d).expect("sessions");
    assert!(sessions.has("weight", "weight_gf", 20.0));
    assert!(!sessions.has("weight", "weight_gf", 30.0));
    assert_eq!(sessions.next_session(), d.join("session-003"));
    let _ = std::fs::remove_dir_all(&d);
}

/// A collect session's labels as readers no one here wrote decode them: `rosbags` (the type
/// from the definition the bag carries, its hash matching the declared one) and Foxglove's
/// `mcap` + `mcap-ros2-support`. Needs `$HANDSTACK_PYTHON`; skipped without it.
#[test]
fn a_sessions_labels_read_back_in_rosbags_and_mcap() {
    let d = dir("python");
    let bag = d.join("session-001");
    session(&bag, "weight", &[(10.0, 100.0), (20.5, 200.0)]);
    let Some(py) = crate::record::read_in_python(&bag) else {
        let _ = std::fs::remove_dir_all(&d);
        return;
    };
    let topic = &py["rosbags"]["topics"][LABELS];
    assert_eq!(topic["type"], "handstack_msgs/msg/Label", "{py}");
    assert_eq!(
        topic["declared_hash"], topic["hash_from_definition"],
        "{py}"
    );
    let labels: Vec<(String, f64, u64, u64)> = topic["messages"]
        .as_array()
        .expect("messages")
        .iter()
        .map(|m| {
            assert_eq!(m["experiment"], "weight");
            assert_eq!(m["frame_id"], HAND_FRAME);
            (
                m["name"].as_str().expect("name").to_owned(),
                m["value"].as_f64().expect("value"),
                m["start_ns"].as_u64().expect("start"),
                m["end_ns"].as_u64().expect("end"),
            )
        })
        .collect();
    // Each window is three frames 10 ms apart; a tare, then its weight, twice.
    let at = |i: u64| T0 + i * 60 * MS;
    assert_eq!(
        labels,
        [
            ("tare".to_owned(), 0.0, at(0), at(0) + 20 * MS),
            (
                "weight_gf".to_owned(),
                10.0,
                at(0) + 30 * MS,
                at(0) + 50 * MS
            ),
            ("tare".to_owned(), 0.0, at(1), at(1) + 20 * MS),
            (
                "weight_gf".to_owned(),
                20.5,
                at(1) + 30 * MS,
                at(1) + 50 * MS
            ),
        ]
    );
    let theirs = &py["mcap"]["topics"][LABELS]["messages"];
    assert_eq!(theirs, &topic["messages"], "{py}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn the_held_out_weights_are_every_fourth_from_the_third_and_never_the_heaviest() {
    let held = |n: usize| (0..n).filter(|&i| held_out_at(i, n)).collect::<Vec<_>>();
    assert_eq!(held(20), [2, 6, 10, 14, 18]);
    assert_eq!(held(4), [2]);
    assert_eq!(held(3), Vec::<usize>::new());
    assert_eq!(held(7), [2]); // 6 is the heaviest
}

#[test]
fn too_few_weights_to_hold_one_out_is_refused() {
    let d = dir("few");
    session(
        &d.join("session-001"),
        "weight",
        &[(10.0, 100.0), (20.0, 200.0)],
    );
    let s =
        steps(&handstack::collect::bags(std::slice::from_ref(&d)).expect("bags")).expect("steps");
    match train(&s, 8, 2.0, false) {
        Err(e @ TrainError::TooFew { found: 2, .. }) => {
            assert!(e.to_string().contains("at least 4"), "{e}")
        }
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("trained on 2 weights"),
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// The error `steps` gives for the bag at `bag` named directly.
fn refused(bag: &Path) -> ReadError {
    match steps(&[bag.to_owned()]) {
        Err(e) => e,
        Ok(s) => panic!("{} read as {} steps", bag.display(), s.len()),
    }
}

#[test]
fn a_truncated_bag_is_refused_naming_the_file_and_resume_refuses_it_too() {
    let d = dir("truncated");
    let bag = d.join("session-001");
    session(&bag, "weight", &[(10.0, 100.0), (20.0, 200.0)]);
    let file = mcap(&bag);
    let bytes = std::fs::read(&file).expect("mcap");
    std::fs::write(&file, &bytes[..bytes.len() * 2 / 3]).expect("truncated");
    let e = refused(&bag);
    assert!(matches!(e, ReadError::Truncated { .. }), "{e}");
    let text = e.to_string();
    assert!(text.starts_with(&file.display().to_string()), "{text}");
    assert!(text.contains("is truncated after"), "{text}");
    let e = handstack::collect::Sessions::open(&d).expect_err("a truncated session");
    assert!(matches!(e, ReadError::Truncated { .. }), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_bag_without_labels_names_the_file_and_the_labels_topic() {
    let d = dir("unlabelled");
    let bag = unlabelled(&d.join("run"));
    let e = refused(&bag);
    let text = e.to_string();
    assert!(matches!(e, ReadError::MissingTopic { .. }), "{text}");
    assert!(
        text.starts_with(&mcap(&bag).display().to_string()),
        "{text}"
    );
    assert!(text.contains(&format!("no {LABELS} messages")), "{text}");
    assert!(text.contains("handstack collect"), "{text}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn another_devices_frames_or_another_models_labels_are_refused() {
    let d = dir("other");
    // The pad's nine pressures on the fingertip's topic.
    let bag = d.join("pad");
    let rec = Recorder::create(&bag).expect("recorder");
    let topic = rec.topic::<PressureFrame>("/hand0/tactile/raw");
    let frame = PressureFrame {
        pressure_pa: vec![1.0; 9],
        ..PressureFrame::default()
    };
    rec.write(topic, T0, &frame);
    let label = |name, value| Labelled {
        experiment: "weight",
        name,
        value,
        start_ns: T0,
        end_ns: T0,
    };
    rec.label(HAND_FRAME, &label("tare", 0.0));
    rec.finish().expect("bag finished");
    let e = refused(&bag);
    let text = e.to_string();
    assert!(matches!(e, ReadError::Content { .. }), "{text}");
    assert!(
        text.contains("/hand0/tactile/raw: frames of 9 pressures, not the fingertip's 3"),
        "{text}"
    );
    // Labels, but no fingertip frames at all.
    let bag = d.join("no-frames");
    let rec = Recorder::create(&bag).expect("recorder");
    rec.label(HAND_FRAME, &label("tare", 0.0));
    rec.finish().expect("bag finished");
    let text = refused(&bag).to_string();
    assert!(text.contains("no /hand0/tactile/raw messages"), "{text}");
    // Another experiment's labels.
    let bag = d.join("session-001");
    session(&bag, "contact", &[(3.0, 100.0)]);
    let e = refused(&bag);
    let text = e.to_string();
    assert!(matches!(e, ReadError::Content { .. }), "{text}");
    assert!(
        text.contains(&format!("{LABELS}: labels of `contact`, none of `weight`")),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// Through the binary: an unlabelled bag fails the command (status 1) naming file and topic,
/// and writes nothing.
#[test]
fn the_train_command_refuses_a_bad_bag_and_writes_nothing() {
    let d = dir("cli");
    let bag = unlabelled(&d.join("run"));
    let out_file = d.join("mine.safetensors");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_handstack"))
        .args(["train", "force"])
        .arg(&bag)
        .arg("--out")
        .arg(&out_file)
        .output()
        .expect("runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(
        stderr.starts_with(&format!("error: {}: no {LABELS}", mcap(&bag).display())),
        "{stderr}"
    );
    assert!(!out_file.exists());
    assert!(!d.join("mine.metrics.json").exists());
    let _ = std::fs::remove_dir_all(&d);
}
