//! `handstack run SCENE --record DIR` as a user runs it (the `bench_rig` command line, `dxl-sim`
//! in its own process), the bag read back by readers no one here wrote — `rosbags` (metadata,
//! MCAP, types built from the bag's own message definitions, their RIHS01 hashes recomputed)
//! and Foxglove's `mcap` + `mcap-ros2-support` (`python/bag/read_bag.py`, needs
//! `$HANDSTACK_PYTHON`: skipped without it) — and by the Rust `mcap` crate with hand-zenoh's
//! CDR decoding. A run killed with SIGKILL mid-grasp leaves a bag both open, up to its last
//! flush; SIGINT ends a bag cleanly.

use crate::ending::{dir, is_torque_limit, scene, servos};
use crate::process::{finish, signal, text};
use hand_zenoh::msg::Message;
use hand_zenoh::msg::handstack_msgs::{Fault, GraspState, PressureFrame};
use hand_zenoh::msg::tactile_msgs::TactileState;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::time::{SystemTime, UNIX_EPOCH};

/// The topics a grasp run records when no fault occurs.
const GRASP_TOPICS: [&str; 6] = [
    "/hand0/tactile/raw",
    "/hand0/tactile_states",
    "/hand0/grasp/state",
    "/hand0/gripper/joint_states",
    "/hand0/gripper/command",
    "/handstack/figures",
];

/// `read_bag.py` on `bag`, or `None` (said on stderr) without `$HANDSTACK_PYTHON`.
pub(crate) fn read_in_python(bag: &Path) -> Option<Value> {
    let Some(python) = std::env::var_os("HANDSTACK_PYTHON") else {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
        return None;
    };
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../python/bag/read_bag.py");
    let out = Command::new(python)
        .arg(script)
        .arg(bag)
        .output()
        .expect("python runs");
    assert!(out.status.success(), "{}", text(&out.stderr));
    Some(serde_json::from_slice(&out.stdout).expect("JSON"))
}

/// Messages per topic, and each message's log time and CDR, read with the Rust `mcap` crate.
fn read_in_rust(bag: &Path) -> BTreeMap<String, Vec<(u64, Vec<u8>)>> {
    let file = std::fs::read_dir(bag)
        .expect("bag dir")
        .map(|e| e.expect("entry").path())
        .find(|p| p.extension().is_some_and(|e| e == "mcap"))
        .expect("an .mcap");
    let bytes = std::fs::read(file).expect("mcap");
    let mut topics: BTreeMap<String, Vec<(u64, Vec<u8>)>> = BTreeMap::new();
    for m in mcap::MessageStream::new(&bytes).expect("MCAP magic") {
        let m = m.expect("a readable message");
        assert_eq!(m.channel.message_encoding, "cdr");
        let schema = m.channel.schema.as_ref().expect("a schema");
        assert_eq!(schema.encoding, "ros2msg");
        topics
            .entry(m.channel.topic.clone())
            .or_default()
            .push((m.log_time, m.data.into_owned()));
    }
    topics
}

fn metadata_count(bag: &Path) -> u64 {
    let yaml = std::fs::read_to_string(bag.join("metadata.yaml")).expect("metadata.yaml");
    assert!(
        yaml.starts_with("rosbag2_bagfile_information:\n  version: 9\n"),
        "{yaml}"
    );
    yaml.lines()
        .find_map(|l| l.strip_prefix("  message_count: "))
        .and_then(|n| n.parse().ok())
        .expect("message_count")
}

fn now_ns() -> u64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .expect("after 1970")
        .as_nanos() as u64
}

/// The points of plot `title` in a run's JSON outcome.
fn plot_points(outcome: &Value, title: &str) -> Vec<(f64, f64)> {
    outcome["plots"]
        .as_array()
        .expect("plots")
        .iter()
        .find(|p| p["title"] == title)
        .expect("the plot")["lines"][0]["points"]
        .as_array()
        .expect("points")
        .iter()
        .map(|p| (p[0].as_f64().expect("x"), p[1].as_f64().expect("y")))
        .collect()
}

#[test]
fn a_recorded_grasp_reads_back_in_rosbags_mcap_and_rust_as_the_run_printed_it() {
    let servos = servos();
    let dir = dir("record");
    let bag = dir.join("grasp-bag");
    let scene = scene(&dir, &servos.path, None, 1.0);
    let run = Command::new(crate::process::built("examples/bench_rig"))
        .arg("run")
        .arg(&scene)
        .arg("--json")
        .arg("--record")
        .arg(&bag)
        .output()
        .expect("the rig runs");
    let err = text(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{err}");
    let outcome: Value = serde_json::from_slice(&run.stdout).expect("JSON outcome");
    let outcome = &outcome[0];
    // What the run printed: its figures, the torque limit it sent and the pressure rise it saw
    // each cycle (a 1 s hold: all of it inside the plots' first 10 s).
    let figures: Vec<(String, f64)> = outcome["figures"]
        .as_array()
        .expect("figures")
        .iter()
        .map(|f| {
            (
                f["name"].as_str().expect("name").to_owned(),
                f["value"].as_f64().expect("value"),
            )
        })
        .collect();
    let torques = plot_points(outcome, "Grasp: torque limit sent (lift at 3 s)");
    let rises = plot_points(outcome, "Grasp: mean pad pressure rise");
    assert!(
        err.contains(&format!("recorded {} messages to ", metadata_count(&bag))),
        "{err}"
    );

    // The Rust mcap crate and hand-zenoh's CDR: every topic, every message decodes.
    let rust = read_in_rust(&bag);
    let mut want = GRASP_TOPICS.to_vec();
    want.sort_unstable();
    assert_eq!(rust.keys().map(String::as_str).collect::<Vec<_>>(), want);
    let total: usize = rust.values().map(Vec::len).sum();
    assert_eq!(total as u64, metadata_count(&bag));
    let states: Vec<GraspState> = rust["/hand0/grasp/state"]
        .iter()
        .map(|(_, cdr)| GraspState::from_cdr(cdr).expect("a GraspState"))
        .collect();
    let seen: Vec<f64> = states
        .iter()
        .filter(|s| !s.pressure_pa.is_nan())
        .map(|s| f64::from(s.pressure_pa))
        .collect();
    let printed: Vec<f64> = rises.iter().map(|p| p.1).collect();
    // The same f32 values: equal after the same widening.
    assert_eq!(seen, printed);
    assert_eq!(rust["/hand0/gripper/command"].len(), torques.len());
    assert_eq!(rust["/handstack/figures"].len(), figures.len());
    // Each fingertip frame twice: ours, and the tactile toolbox's TactileState (one sensor,
    // `fingertip`, the same three pressures, the same stamp).
    let raw: Vec<(u64, Vec<f32>)> = rust["/hand0/tactile/raw"]
        .iter()
        .map(|(t, cdr)| {
            (
                *t,
                PressureFrame::from_cdr(cdr).expect("a frame").pressure_pa,
            )
        })
        .collect();
    let tactile: Vec<(u64, Vec<f32>)> = rust["/hand0/tactile_states"]
        .iter()
        .map(|(t, cdr)| {
            let s = TactileState::from_cdr(cdr).expect("a TactileState");
            assert_eq!(s.sensors.len(), 1);
            assert_eq!(s.sensors[0].name, "fingertip");
            (*t, s.sensors[0].values.clone())
        })
        .collect();
    assert!(!raw.is_empty());
    assert_eq!(tactile, raw);

    let Some(py) = read_in_python(&bag) else {
        let _ = std::fs::remove_dir_all(&dir);
        return;
    };
    let rb = &py["rosbags"];
    let topics = rb["topics"].as_object().expect("topics");
    let names: Vec<&str> = topics.keys().map(String::as_str).collect();
    assert_eq!(names, want);
    let mut sum = 0;
    for (name, t) in topics {
        // metadata.yaml's counts are the messages the .mcap holds; the hash the bag declares is
        // the one rosbags computes from the definition the bag carries.
        assert_eq!(t["count"], t["declared_count"], "{name}");
        assert_eq!(t["count"].as_u64(), Some(rust[name].len() as u64), "{name}");
        assert_eq!(t["declared_hash"], t["hash_from_definition"], "{name}");
        assert_eq!(t["qos"], 1, "{name}");
        sum += t["count"].as_u64().expect("count");
    }
    assert_eq!(rb["message_count"].as_u64(), Some(sum));
    assert_eq!(rb["ros_distro"], "jazzy");
    // rosbags' duration is end − start + 1 ns, from the messages' times.
    let times: Vec<u64> = rust.values().flatten().map(|m| m.0).collect();
    let (first, last) = (times.iter().min().unwrap(), times.iter().max().unwrap());
    assert_eq!(rb["start_ns"].as_u64(), Some(*first));
    assert_eq!(rb["duration_ns"].as_u64(), Some(last - first + 1));
    // Decoded values: each cycle's pressure rise and torque limit as the run printed them
    // (effort = limit / 1023, f32: within 1e-6), each figure's value exactly.
    let state_msgs = topics["/hand0/grasp/state"]["messages"]
        .as_array()
        .expect("msgs");
    let py_rises: Vec<f64> = state_msgs
        .iter()
        .filter_map(|m| m["pressure_pa"].as_f64())
        .collect();
    assert_eq!(py_rises, printed);
    assert!(state_msgs.iter().all(|m| m["frame_id"] == "hand0"));
    let efforts: Vec<f64> = topics["/hand0/gripper/command"]["messages"]
        .as_array()
        .expect("msgs")
        .iter()
        .map(|m| m["effort"].as_f64().expect("effort"))
        .collect();
    assert_eq!(efforts.len(), torques.len());
    for (e, (_, t)) in efforts.iter().zip(&torques) {
        assert!(
            (e - t / 1023.0).abs() < 1e-6,
            "effort {e} for torque limit {t}"
        );
    }
    let py_figures: Vec<(String, f64)> = topics["/handstack/figures"]["messages"]
        .as_array()
        .expect("msgs")
        .iter()
        .map(|m| {
            (
                m["name"].as_str().expect("name").to_owned(),
                m["value"].as_f64().expect("value"),
            )
        })
        .collect();
    assert_eq!(py_figures, figures);
    let py_tactile: Vec<&Value> = topics["/hand0/tactile_states"]["messages"]
        .as_array()
        .expect("msgs")
        .iter()
        .map(|m| &m["sensors"][0]["values"])
        .collect();
    let py_raw: Vec<&Value> = topics["/hand0/tactile/raw"]["messages"]
        .as_array()
        .expect("msgs")
        .iter()
        .map(|m| &m["pressure_pa"])
        .collect();
    assert_eq!(py_tactile, py_raw);
    assert_eq!(
        topics["/hand0/tactile_states"]["messages"][0]["sensors"][0]["name"],
        "fingertip"
    );

    // Foxglove's reader on the .mcap alone: the ros2 profile, ros2msg schemas, CDR, rosbag2's
    // channel metadata, the same counts and values.
    let mc = &py["mcap"];
    assert_eq!(mc["profile"], "ros2", "{mc}");
    for (name, t) in mc["topics"].as_object().expect("topics") {
        assert_eq!(t["schema_encoding"], "ros2msg");
        assert_eq!(t["message_encoding"], "cdr");
        assert_eq!(
            t["metadata_keys"],
            serde_json::json!(["offered_qos_profiles", "topic_type_hash"])
        );
        assert_eq!(t["count"], topics[name]["count"], "{name}");
        assert_eq!(t["messages"], topics[name]["messages"], "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_killed_mid_grasp_leaves_a_bag_readable_up_to_its_last_second() {
    let servos = servos();
    let dir = dir("record-kill");
    let bag = dir.join("killed");
    let scene = scene(&dir, &servos.path, None, 20.0);
    let run = std::process::Command::new(crate::process::built("examples/bench_rig"))
        .arg("run")
        .arg(&scene)
        .arg("--record")
        .arg(&bag)
        .env("HANDSTACK_RIG_PRESS_S", "0.3")
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the rig starts");
    // 2.5 s of the loop's commands, then SIGKILL: no handler, no summary, no last flush.
    servos.lines.wait_for("250 loop commands", |l| {
        l.iter().filter(|l| is_torque_limit(l)).count() >= 250
    });
    signal(run.id(), "KILL");
    let killed_at = now_ns();
    let _ = finish(run);

    let rust = read_in_rust(&bag);
    let total: u64 = rust.values().map(|m| m.len() as u64).sum();
    let last = rust
        .values()
        .flatten()
        .map(|m| m.0)
        .max()
        .expect("messages");
    let first = rust
        .values()
        .flatten()
        .map(|m| m.0)
        .min()
        .expect("messages");
    let lost_s = (killed_at - last) as f64 * 1e-9;
    let kept_s = (last - first) as f64 * 1e-9;
    eprintln!(
        "killed run: {total} messages over {kept_s:.2} s readable, the last {lost_s:.2} s before \
         the kill lost; {} bytes",
        std::fs::metadata(bag.join("killed_0.mcap")).map_or(0, |m| m.len())
    );
    // Flushed every second: at most that (and a little scheduling) is lost.
    assert!(lost_s < 1.5, "{lost_s} s lost");
    assert!(kept_s > 1.5, "only {kept_s} s kept");
    // metadata.yaml counts what was flushed: it is rewritten right after each flush (a kill
    // between the two leaves it one flush behind, never ahead).
    let counted = metadata_count(&bag);
    assert!(counted <= total && counted > 0, "{counted} of {total}");
    for (_, cdr) in &rust["/hand0/grasp/state"] {
        GraspState::from_cdr(cdr).expect("a GraspState");
    }

    if let Some(py) = read_in_python(&bag) {
        let rb = &py["rosbags"];
        // rosbags' message_count is metadata.yaml's; its messages are the file's.
        assert_eq!(rb["message_count"].as_u64(), Some(counted));
        for (name, t) in rb["topics"].as_object().expect("topics") {
            assert_eq!(t["count"].as_u64(), Some(rust[name].len() as u64), "{name}");
            assert!(
                t["declared_count"].as_u64() <= t["count"].as_u64(),
                "{name}"
            );
        }
        for (name, t) in py["mcap"]["topics"].as_object().expect("topics") {
            assert_eq!(t["count"].as_u64(), Some(rust[name].len() as u64), "{name}");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sigint_ends_a_recording_with_its_summary_and_the_runs_ending() {
    let servos = servos();
    let dir = dir("record-sigint");
    let bag = dir.join("stopped");
    let scene = scene(&dir, &servos.path, None, 20.0);
    let run = std::process::Command::new(crate::process::built("examples/bench_rig"))
        .arg("run")
        .arg(&scene)
        .arg("--record")
        .arg(&bag)
        .env("HANDSTACK_RIG_PRESS_S", "0.3")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the rig starts");
    servos.lines.wait_for("50 loop commands", |l| {
        l.iter().filter(|l| is_torque_limit(l)).count() >= 50
    });
    signal(run.id(), "INT");
    let out = finish(run);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    let count = metadata_count(&bag);
    assert!(
        err.contains(&format!("recorded {count} messages to ")),
        "{err}"
    );
    // A clean end: the summary section is there and agrees with metadata.yaml.
    let bytes = std::fs::read(bag.join("stopped_0.mcap")).expect("mcap");
    let summary = mcap::Summary::read(&bytes)
        .expect("a readable summary")
        .expect("a summary");
    let stats = summary.stats.expect("statistics");
    assert_eq!(stats.message_count, count);
    let rust = read_in_rust(&bag);
    let faults: Vec<Fault> = rust["/handstack/fault"]
        .iter()
        .map(|(_, cdr)| Fault::from_cdr(cdr).expect("a Fault"))
        .collect();
    let ending = faults.last().expect("the run's ending");
    assert!(ending.ends_run && ending.source == "run", "{ending:?}");
    assert!(ending.what.contains("stopped by SIGINT"), "{}", ending.what);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn recording_into_a_directory_with_files_fails_before_anything_moves() {
    let servos = servos();
    let dir = dir("record-not-empty");
    let bag = dir.join("taken");
    std::fs::create_dir_all(&bag).expect("dir");
    std::fs::write(bag.join("notes.txt"), "mine").expect("a file");
    let scene = scene(&dir, &servos.path, None, 1.0);
    let out = Command::new(crate::process::built("examples/bench_rig"))
        .arg("run")
        .arg(&scene)
        .arg("--record")
        .arg(&bag)
        .output()
        .expect("the rig runs");
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(
        err,
        format!(
            "error: cannot record into {}: the directory is not empty (a bag is a directory of \
             its own: name a new one)\n",
            bag.display()
        )
    );
    // Nothing was sent to the servos (the simulator printed its pty path, no packet), and the
    // user's file is untouched.
    assert_eq!(
        servos.lines.snapshot().len(),
        1,
        "{:?}",
        servos.lines.snapshot()
    );
    assert_eq!(
        std::fs::read_to_string(bag.join("notes.txt")).unwrap(),
        "mine"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
