//! Every way a run ends leaves the hand in its declared end state — tested as a user meets it:
//! `handstack`'s command line (the `bench_rig` example: [`handstack::cli::main`] with model
//! MS5611 fingertip buses, everything else the binary's) as its own process, `dxl-sim` as
//! another on a pseudo-terminal, real signals (SIGINT, SIGTERM, SIGHUP; SIGKILL of the servo
//! bus), and what the servos were left doing read back over Protocol 2.0 and from `dxl-sim
//! --trace`.
//!
//! "Within two control cycles" is counted on the bus: the state reads (one SYNC READ a cycle)
//! the simulator executed after the signal was sent and before the end action's first packet.

use crate::process::{DxlSim, SIM_REPLY_TIMEOUT_MS, built, finish, signal, text};
use hand_control::control_table::MX_28;
use hand_zenoh::msg::handstack_msgs::GraspState;
use hand_zenoh::msg::sensor_msgs::JointState;
use handstack::record::read::Recording;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// The servos of these runs: [`DxlSim`] with its bus trace, read back as (Torque Enable, Present
/// Position).
pub(crate) fn servos() -> DxlSim {
    DxlSim::start(&["--trace"])
}

fn read_back(servos: &DxlSim) -> Vec<(i32, i32)> {
    servos.read_back(MX_28.torque_enable.address, MX_28.present_position.address)
}

/// Trace lines that are a cycle's state read, a loop command's torque limit, and the two
/// packets an end action can start with.
fn is_state_read(l: &str) -> bool {
    l.contains(" sync_read ")
}
pub(crate) fn is_torque_limit(l: &str) -> bool {
    l.contains(" sync_write Goal PWM ")
}
fn is_torque_off(l: &str) -> bool {
    l.ends_with(" sync_write Torque Enable 1=0 2=0")
}
/// A goal position to open (the servos start at 2048; the loop closes towards 130).
fn is_opening(l: &str) -> bool {
    l.contains(" sync_write Goal Position 1=20")
}

/// The simulated time (s) a trace line starts with.
fn time_s(l: &str) -> f64 {
    l.split(' ')
        .next()
        .and_then(|t| t.parse().ok())
        .expect("a time")
}

/// A scene for the rig's fingertip and the servos at `port`, ending with `on_end` (none: the
/// default), holding `hold_s`.
pub(crate) fn scene(dir: &Path, port: &str, on_end: Option<&str>, hold_s: f64) -> PathBuf {
    let on_end = on_end.map_or_else(String::new, |a| format!("on_end = \"{a}\"\n"));
    let text = format!(
        "title = \"bench rig\"\n[sensors.fingertip]\nosr = 256\n\
         i2c_buses = [\"rig-0\", \"rig-1\", \"rig-2\"]\n[controller]\npreset = \"grasp\"\n\
         [hand]\nmodel = \"mx28\"\nids = [1, 2]\nserial_port = \"{port}\"\n\
         reply_timeout_ms = {SIM_REPLY_TIMEOUT_MS}\n{on_end}[experiment.grasp]\ntorque_band = [250, 320]\n\
         hold_s = {hold_s}\n"
    );
    let path = dir.join("rig.toml");
    std::fs::write(&path, text).expect("scene");
    path
}

/// A fresh directory for one test's files.
pub(crate) fn dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("handstack-end-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// `handstack run SCENE` on the rig, the pad pressed at `press` (`never`: an empty hand).
fn start_run(scene: &Path, press: &str) -> Child {
    start_rig(scene, &[("HANDSTACK_RIG_PRESS_S", press)])
}

/// `handstack run SCENE` on the rig with its environment `env` (see `examples/bench_rig.rs`).
fn start_rig(scene: &Path, env: &[(&str, &str)]) -> Child {
    start_rig_with(scene, env, &[])
}

/// [`start_rig`] with more arguments for `run`.
fn start_rig_with(scene: &Path, env: &[(&str, &str)], args: &[&std::ffi::OsStr]) -> Child {
    Command::new(built("examples/bench_rig"))
        .arg("run")
        .arg(scene)
        .args(args)
        .envs(env.iter().copied())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the rig starts")
}

/// Waits for 50 of the loop's commands (half a second of grasping), sends `sig`, and returns
/// the trace's length when it was sent.
fn grasp_then_signal(servos: &DxlSim, run: &Child, sig: &str) -> usize {
    servos.lines.wait_for("50 loop commands", |l| {
        l.iter().filter(|l| is_torque_limit(l)).count() >= 50
    });
    let sent_at = servos.lines.snapshot().len();
    signal(run.id(), sig);
    sent_at
}

/// The state reads after `from` before the first line `end` matches (which must come).
fn cycles_until(trace: &[String], from: usize, end: impl Fn(&str) -> bool) -> usize {
    let after = &trace[from..];
    let at = after
        .iter()
        .position(|l| end(l))
        .unwrap_or_else(|| panic!("no end action after the signal: {after:?}"));
    after[..at].iter().filter(|l| is_state_read(l)).count()
}

#[test]
fn ctrl_c_mid_grasp_turns_the_torque_off_within_two_cycles() {
    let servos = servos();
    let dir = dir("sigint");
    let run = start_run(&scene(&dir, &servos.path, Some("torque_off"), 20.0), "0.3");
    let sent_at = grasp_then_signal(&servos, &run, "INT");
    let out = finish(run);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(
        err.contains("stopped by SIGINT (Ctrl-C) at ") && err.contains("; hand torque off"),
        "{err}"
    );
    assert!(
        !err.contains("Some(") && !err.contains(" { "),
        "Debug text: {err}"
    );
    servos
        .lines
        .wait_for("torque off", |l| l.iter().any(|l| is_torque_off(l)));
    let cycles = cycles_until(&servos.lines.snapshot(), sent_at, is_torque_off);
    assert!(
        cycles <= 2,
        "{cycles} cycles after SIGINT before torque off"
    );
    for (torque, _) in read_back(&servos) {
        assert_eq!(torque, 0, "torque left on");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sigterm_mid_grasp_releases_the_hand_then_turns_the_torque_off_through_a_second_signal() {
    let servos = servos();
    let dir = dir("sigterm");
    let run = start_run(&scene(&dir, &servos.path, None, 20.0), "0.3");
    let sent_at = grasp_then_signal(&servos, &run, "TERM");
    // A second signal while the hand opens (a user pressing Ctrl-C again) does not cut the
    // release short.
    servos.lines.wait_for("the release", |l| {
        l[sent_at..].iter().any(|l| is_opening(l))
    });
    signal(run.id(), "INT");
    let out = finish(run);
    let err = text(&out.stderr);
    // The first signal's status.
    assert_eq!(out.status.code(), Some(143), "{err}");
    assert!(
        err.contains("stopped by SIGTERM at ")
            && err.contains("; hand released (opened to ")
            && err.ends_with("rad), then torque off\n"),
        "{err}"
    );
    // dxl-sim prints its trace as it goes: the run may end before the last line is read.
    servos
        .lines
        .wait_for("torque off", |l| l.iter().any(|l| is_torque_off(l)));
    let trace = servos.lines.snapshot();
    let cycles = cycles_until(&trace, sent_at, is_opening);
    assert!(
        cycles <= 2,
        "{cycles} cycles after SIGTERM before the release"
    );
    assert!(trace.iter().any(|l| is_torque_off(l)), "no torque off");
    // Open where the run found them (2048 = π rad), powered down.
    for (torque, position) in read_back(&servos) {
        assert_eq!(torque, 0, "torque left on");
        assert!((position - 2048).abs() <= 40, "not opened: {position}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGHUP (the terminal closing) with `on_end = "hold"`: the loop stops commanding within two
/// cycles and the hand keeps its grip, torque on, as the scene asked.
#[test]
fn sighup_mid_grasp_with_on_end_hold_keeps_the_grip_torque_on() {
    let servos = servos();
    let dir = dir("sighup");
    let run = start_run(&scene(&dir, &servos.path, Some("hold"), 20.0), "0.3");
    let sent_at = grasp_then_signal(&servos, &run, "HUP");
    let out = finish(run);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(129), "{err}");
    assert!(
        err.contains("stopped by SIGHUP at ")
            && err.contains("; hand holding its last safe effort (torque on)"),
        "{err}"
    );
    let trace = servos.lines.snapshot();
    let commands = trace[sent_at..]
        .iter()
        .filter(|l| is_torque_limit(l))
        .count();
    assert!(commands <= 2, "{commands} loop commands after SIGHUP");
    assert!(
        !trace[sent_at..]
            .iter()
            .any(|l| is_torque_off(l) || is_opening(l)),
        "the hold was not kept: {:?}",
        &trace[sent_at..]
    );
    for (torque, position) in read_back(&servos) {
        assert_eq!(torque, 1, "torque off");
        assert!(position < 2048 - 100, "not gripping: {position}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_servo_bus_that_dies_mid_hold_ends_the_run_at_once_saying_so() {
    let servos = servos();
    let dir = dir("bus");
    let bag = dir.join("bag");
    let run = start_rig_with(
        &scene(&dir, &servos.path, None, 20.0),
        &[("HANDSTACK_RIG_PRESS_S", "0.3")],
        &["--record".as_ref(), bag.as_os_str()],
    );
    servos.lines.wait_for("50 loop commands", |l| {
        l.iter().filter(|l| is_torque_limit(l)).count() >= 50
    });
    signal(servos.child.id(), "KILL");
    let killed = Instant::now();
    let out = finish(run);
    let after = killed.elapsed();
    let err = text(&out.stderr);
    // A 20 s hold, ended by the lost bus: the loop sees it in the cycle its exchange fails
    // (one cycle is 10 ms; the wall-clock bound leaves room for a loaded machine; the cycles
    // are counted below).
    assert!(
        after < Duration::from_secs(2),
        "ended {after:?} after the kill"
    );
    assert_eq!(out.status.code(), Some(3), "{err}");
    let expected = format!("hand: servo bus {} lost: ", servos.path);
    assert!(err.contains(&expected), "{err}");
    assert!(err.contains("(os error 5) at "), "{err}");
    assert!(
        err.contains("; hand end action `release` did not reach it: its servos keep their last command, torque limit "),
        "{err}"
    );
    assert!(
        !err.contains("Io(") && !err.contains("Os {"),
        "Debug text: {err}"
    );
    // Counted in cycles from the recording: each cycle's `grasp/state`, and `joint_states`
    // for each the servos answered. The run ends within two cycles of the last answer.
    let rec = Recording::open(&bag).expect("the bag");
    let states = rec
        .messages::<GraspState>("/hand0/grasp/state")
        .expect("grasp states");
    let answered = rec
        .messages::<JointState>("/hand0/gripper/joint_states")
        .expect("joint states");
    let last_answer = answered.last().map(|(t, _)| *t).expect("answers");
    let after = states.iter().filter(|(t, _)| *t > last_answer).count();
    eprintln!(
        "{after} cycles after the last answer; {} cycles, {} answered",
        states.len(),
        answered.len()
    );
    assert!(answered.len() >= 50, "{} answers", answered.len());
    assert!(
        after <= 2,
        "{after} cycles after the servos' last answer ({} cycles, {} answered)",
        states.len(),
        answered.len()
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_normal_run_holds_from_its_first_command_and_ends_released() {
    let servos = servos();
    let dir = dir("normal");
    let run = start_run(&scene(&dir, &servos.path, None, 1.0), "0.3");
    let out = finish(run);
    let (stdout, err) = (text(&out.stdout), text(&out.stderr));
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        stdout.contains("  hand released (opened to ") && stdout.contains("then torque off"),
        "{stdout}"
    );
    // dxl-sim prints its trace as it goes: the run may end before the last line is read.
    servos
        .lines
        .wait_for("torque off", |l| l.iter().any(|l| is_torque_off(l)));
    let trace = servos.lines.snapshot();
    // hold_s = 1 from the first command: the loop's torque limits span one second of the
    // servos' time (the simulator keeps wall time), whatever opening and taring took.
    let limits: Vec<&String> = trace.iter().filter(|l| is_torque_limit(l)).collect();
    let release = trace.iter().position(|l| is_opening(l)).expect("a release");
    let last_loop = trace[..release]
        .iter()
        .rev()
        .find(|l| is_torque_limit(l))
        .expect("loop commands");
    let held = time_s(last_loop) - time_s(limits[0]);
    assert!((0.97..=1.05).contains(&held), "held {held} s");
    assert!(trace[release..].iter().any(|l| is_torque_off(l)));
    for (torque, position) in read_back(&servos) {
        assert_eq!(torque, 0, "torque left on");
        assert!((position - 2048).abs() <= 40, "not opened: {position}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn closing_on_nothing_is_a_failed_grasp_not_a_met_target() {
    let servos = servos();
    let dir = dir("empty");
    let run = start_run(&scene(&dir, &servos.path, None, 20.0), "never");
    let out = finish(run);
    let (stdout, err) = (text(&out.stdout), text(&out.stderr));
    assert_eq!(out.status.code(), Some(4), "{err}");
    assert!(
        err.contains("grasp: the hand closed to its goal without the fingertip seeing contact"),
        "{err}"
    );
    assert!(!stdout.contains("yes"), "{stdout}");
    for (torque, _) in read_back(&servos) {
        assert_eq!(torque, 0, "torque left on");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `handstack node --part hand` ends the same way (feature `cell`): SIGINT to a node waiting for
/// its first goal → the scene's end action, the signal's exit status, what the hand was left
/// doing said.
#[cfg(feature = "cell")]
#[test]
fn sigint_ends_a_hand_node_through_its_end_action() {
    let servos = servos();
    let dir = dir("node-sigint");
    let (_router, endpoint) = hand_zenoh::node::Router::open_on_loopback().expect("router");
    let scene = scene(&dir, &servos.path, Some("torque_off"), 20.0);
    let mut node = Command::new(built("examples/bench_rig"))
        .arg("node")
        .arg(&scene)
        .args([
            "--part",
            "hand",
            "--namespace",
            "/hand0",
            "--connect",
            &endpoint,
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("handstack node starts");
    // Held open: a closed stdin is the node's normal stop, not what this test is about.
    let _stdin = node.stdin.take();
    // Ready: both servos powered (the node then waits for a goal).
    servos.lines.wait_for("torque on", |l| {
        l.iter().filter(|l| l.ends_with("Torque Enable=1")).count() >= 2
    });
    let sent_at = servos.lines.snapshot().len();
    signal(node.id(), "INT");
    let out = finish(node);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{err}");
    assert!(
        err.contains("/hand0 hand: ") && err.ends_with("; hand torque off\n"),
        "{err}"
    );
    servos.lines.wait_for("torque off", |l| {
        l[sent_at..].iter().any(|l| is_torque_off(l))
    });
    for (torque, _) in read_back(&servos) {
        assert_eq!(torque, 0, "torque left on");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A panic in a cycle (here a sensor model's code, as a bug in any part would) ends the hold
/// like any other ending: the hand gets the scene's end action — `hold`, so the torque stays on,
/// where the drop guard alone would have turned it off — and the status is a panic's, 101.
#[test]
fn a_panic_mid_grasp_still_gives_the_hand_the_scenes_end_action() {
    let servos = servos();
    let dir = dir("panic");
    let run = start_rig(
        &scene(&dir, &servos.path, Some("hold"), 20.0),
        &[
            ("HANDSTACK_RIG_PRESS_S", "0.3"),
            ("HANDSTACK_RIG_PANIC_S", "1.5"),
        ],
    );
    let out = finish(run);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(101), "{err}");
    assert!(
        err.contains("error: ")
            && err.contains("a bug in handstack: the rig's sensor")
            && err.contains("; hand holding its last safe effort (torque on)"),
        "{err}"
    );
    let trace = servos.lines.snapshot();
    assert!(
        trace.iter().any(|l| is_torque_limit(l)),
        "the loop grasped before the panic"
    );
    for (torque, _) in read_back(&servos) {
        assert_eq!(torque, 1, "`hold` keeps the torque on");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A fingertip far slower than the loop's rate: the loop's tare never finishes, so it never
/// commands; the run fails with that reason (exit 4) and the servos never get a torque limit.
#[test]
fn a_grasp_whose_loop_never_commands_fails_with_that_reason() {
    let servos = servos();
    let dir = dir("no-command");
    let run = start_rig(
        &scene(&dir, &servos.path, None, 20.0),
        &[
            ("HANDSTACK_RIG_PRESS_S", "0.3"),
            ("HANDSTACK_RIG_SLOW_MS", "400"),
        ],
    );
    let out = finish(run);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(4), "{err}");
    assert!(
        err.contains("grasp: the loop sent no command in 2.0 s (its tare did not finish)"),
        "{err}"
    );
    // The only motion written is the release (end action) back to where the hand was found:
    // one torque limit and one goal at the starting 2048, never the loop's closing goal.
    servos
        .lines
        .wait_for("torque off", |l| l.iter().any(|l| is_torque_off(l)));
    let trace = servos.lines.snapshot();
    let pwm = trace.iter().filter(|l| is_torque_limit(l)).count();
    let goals: Vec<&String> = trace
        .iter()
        .filter(|l| l.contains(" Goal Position "))
        .collect();
    assert!(
        pwm == 1 && goals.len() == 1 && goals[0].ends_with("Goal Position 1=2048 2=2048"),
        "a loop command was sent: {trace:?}"
    );
    for (torque, _) in read_back(&servos) {
        assert_eq!(torque, 0, "torque left on");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
