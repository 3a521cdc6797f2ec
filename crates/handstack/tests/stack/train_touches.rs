//! What `handstack train contact-mlp` reads, and what it refuses: fingertip sessions written
//! through the recorder the binary records with (the microcontroller's frames on
//! `/hand0/tactile/mcu` and the labels), the board's inputs rebuilt from the frames; a tap
//! whose frames were not all received is skipped and counted; a cell the pad does not have,
//! too few taps of a cell, bags of another model or without the board's frames — each refused
//! with the file and the topic.

use fingertip_link::Frame;
use handstack::record::mcu::{McuTopic, mcu_topic};
use handstack::record::read::ReadError;
use handstack::record::{HAND_FRAME, LABELS, Labelled, Recorder};
use handstack::train::TrainError;
use handstack::train::contact_mlp::{PER_TAP, taps, train};
use std::path::{Path, PathBuf};

fn dir(name: &str) -> PathBuf {
    crate::fresh_dir("touches", name)
}

const T0: u64 = 1_700_000_000_000_000_000;
/// The board's cycle, µs (two conversions at OSR 1024).
const CYCLE_US: u32 = 6_180;
/// Frames at rest before each press, and pressed.
const REST: usize = 40;
const PRESSED: usize = 30;

/// Frame `i` of a press on `cell`: each sensor rising to its own height after its own delay,
/// a pattern per cell (a network separates them at once), a little apart per tap.
fn pressure(cell: u8, tap: usize, sensor: usize, i: usize) -> i32 {
    let rest = 101_300 + 10 * sensor as i32;
    let delay = (usize::from(cell) + sensor) % 3;
    let height = 400 + 300 * ((usize::from(cell) + 2 * sensor) % 4) as i32 + 5 * tap as i32;
    if i < delay { rest } else { rest + height }
}

/// A session at `bag` of `taps` (cell, whether one pressed frame is lost on the way), each
/// labelled `experiment` / `name` = `value` (`None`: the cell) over its pressed frames.
fn session(bag: &Path, experiment: &str, name: &str, taps: &[(u8, bool)], value: Option<f64>) {
    let rec = Recorder::create(bag).expect("recorder");
    let mut topic = McuTopic::new(&rec);
    let (mut t_ns, mut seq, mut t_us) = (T0, 0u8, 0u32);
    for (k, &(cell, lose)) in taps.iter().enumerate() {
        let mut frame = |p: [i32; 3], in_contact: bool, sent: bool| {
            let f = Frame {
                seq,
                t_us,
                pressure_pa: p,
                tared: true,
                in_contact,
                pad_cell: in_contact.then_some(0),
                ..Frame::default()
            };
            if sent {
                topic.record(t_ns, &f);
            }
            let stamp = t_ns;
            (seq, t_us, t_ns) = (seq.wrapping_add(1), t_us + CYCLE_US, t_ns + 6_180_000);
            stamp
        };
        for _ in 0..REST {
            frame([0, 1, 2].map(|s| pressure(cell, k, s, 0)), false, true);
        }
        let stamps: Vec<u64> = (0..PRESSED)
            .map(|i| {
                let p = [0, 1, 2].map(|s| pressure(cell, k, s, i + 1));
                frame(p, true, !(lose && i == PRESSED / 2))
            })
            .collect();
        rec.label(
            HAND_FRAME,
            &Labelled {
                experiment,
                name,
                value: value.unwrap_or(f64::from(cell)),
                start_ns: stamps[0],
                end_ns: stamps[PRESSED - 1],
            },
        );
    }
    rec.finish().expect("bag finished");
}

fn refused(bag: &Path) -> ReadError {
    match taps(&[bag.to_owned()]) {
        Err(e) => e,
        Ok(t) => panic!("{} read as {} taps", bag.display(), t.taps.len()),
    }
}

#[test]
fn a_fingertip_session_trains_on_the_boards_inputs_and_skips_a_tap_with_a_frame_lost() {
    let d = dir("good");
    // Three cells, three rounds; the second round's cell 9 loses a frame.
    let mut asked: Vec<(u8, bool)> = Vec::new();
    for round in 0..3 {
        for cell in [0u8, 9, 23] {
            asked.push((cell, round == 1 && cell == 9));
        }
    }
    asked.push((9, false));
    session(&d.join("session-001"), "contact", "cell", &asked, None);
    let read = taps(&[d.join("session-001")]).expect("taps");
    assert_eq!((read.taps.len(), read.skipped), (9, 1));
    // The pressed frames but the first (a sensor still to arrive) are on the plateau, and the
    // detector has seen the contact arrive by then.
    assert!(
        read.taps
            .iter()
            .all(|t| t.held.len() == PRESSED - 1 && t.held.iter().all(|h| h.reading.is_some())),
        "{:?}",
        read.taps.iter().map(|t| t.held.len()).collect::<Vec<_>>()
    );
    let trained = train(&read, 8, false).expect("trained");
    let figure = |name: &str| trained.figure(name).unwrap_or_else(|| panic!("no {name}"));
    assert_eq!((figure("taps"), figure("taps_skipped")), (9.0, 1.0));
    // The second tap of each cell held out; PER_TAP held frames of each of the rest.
    assert_eq!(figure("heldout_taps"), 3.0);
    assert_eq!(figure("train_samples"), (6 * PER_TAP) as f64);
    assert_eq!(figure("heldout_accuracy_pct"), 100.0);
    // The board said cell 0 throughout: right for cell 0's held-out tap only.
    assert!((figure("builtin_accuracy_pct") - 100.0 / 3.0).abs() < 1e-9);
    // The same taps and seed, the same model.
    let again = train(&read, 8, false).expect("trained");
    let probe = [1.0, 2.0, 0.5, 0.3, 0.5, 0.2, 0.0, 6.0, 12.0];
    assert_eq!(
        trained.model.outputs(&probe).expect("outputs"),
        again.model.outputs(&probe).expect("outputs")
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn too_few_taps_and_bad_fingertip_bags_are_refused_naming_the_file_and_topic() {
    let d = dir("bad");
    // One tap of cell 23 cannot be both held out and learnt.
    session(
        &d.join("few"),
        "contact",
        "cell",
        &[(0, false), (0, false), (23, false)],
        None,
    );
    let few = taps(&[d.join("few")]).expect("taps");
    match train(&few, 8, false) {
        Err(TrainError::TooFew {
            what,
            found: 1,
            needed: 2,
            ..
        }) => assert_eq!(what, "taps of cell 23 (row 4, column 6)"),
        Err(e) => panic!("{e}"),
        Ok(_) => panic!("trained on one tap of cell 23"),
    }
    // A cell the pad does not have.
    session(
        &d.join("cell"),
        "contact",
        "cell",
        &[(0, false)],
        Some(24.0),
    );
    let e = refused(&d.join("cell"));
    assert!(
        matches!(&e, ReadError::Content { topic, .. } if topic == LABELS),
        "{e}"
    );
    assert!(e.to_string().contains("the pad has cells 0…23"), "{e}");
    // Labels of another experiment's model.
    session(
        &d.join("other"),
        "softness",
        "class",
        &[(0, false)],
        Some(1.0),
    );
    let e = refused(&d.join("other"));
    assert!(e.to_string().contains("none of `contact`"), "{e}");
    // Labels over no frame of the board: a bag of another device.
    let rec = Recorder::create(&d.join("device")).expect("recorder");
    rec.label(
        HAND_FRAME,
        &Labelled {
            experiment: "contact",
            name: "cell",
            value: 3.0,
            start_ns: T0,
            end_ns: T0 + 1,
        },
    );
    rec.finish().expect("bag");
    let e = refused(&d.join("device"));
    assert!(
        matches!(&e, ReadError::MissingTopic { topic, .. } if *topic == mcu_topic()),
        "{e}"
    );
    assert!(e.to_string().contains("device"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}
