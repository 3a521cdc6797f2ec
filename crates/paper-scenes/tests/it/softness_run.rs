//! Seed 001's softness experiment through the installed `handstack` binary, on the simulated
//! hand board over its pty, as a user with the real hand runs it: `handstack run SCENE` closes
//! the hand at 1.5 mm/s, records 14 s from first contact, classifies, and leaves the hand as
//! `[hand] on_end` says — read back from the board afterwards. Also a Ctrl-C mid-close, a host
//! killed mid-close (the close is leased: the stepper stops by itself) and a board that
//! vanishes mid-run.

use crate::common::{bag_count, finish, handstack, signal, text};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use hand_sim::underactuated::Material;
use paper_scenes::devices::hand_board::{HandBoard, HandBoardConfig, STEPPER_DEVICE};

/// A whole run: the boot, about 6–8 s of approach to a 90 mm object, the 14 s window, the
/// release; generous for a loaded machine.
const RUN_TIMEOUT: Duration = Duration::from_secs(120);
/// How long a state the test waits for may take to come.
const WAIT: Duration = Duration::from_secs(20);

/// The hand's board with `material` (a 90 mm cylinder), a short boot.
fn board(material: Material) -> HandBoard {
    let mut config = HandBoardConfig::new(material);
    config.hand.object.size_mm = 90.0;
    config.boot_delay = Duration::from_millis(150);
    HandBoard::spawn(config).expect("the hand's board starts")
}

/// A scene for the hand on `board`'s port, in a directory of its own; `extra` goes at the end
/// of `[hand]`, `expect` is the class it should get.
fn scene(name: &str, board: &HandBoard, extra: &str, expect: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("handstack-softness-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scene dir");
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "title = \"What the hand holds\"\n[sensors.underactuated]\n[estimators.softness]\n\
             [hand]\nmodel = \"underactuated4\"\nserial_port = \"{}\"\n{extra}\
             [experiment.softness]\nexpect = \"{expect}\"\n",
            board.path().display()
        ),
    )
    .expect("scene written");
    path
}

fn start(scene: &Path) -> Child {
    start_with(scene, &[])
}

/// `handstack run SCENE ARGS…`.
fn start_with(scene: &Path, args: &[&std::ffi::OsStr]) -> Child {
    Command::new(handstack())
        .arg("run")
        .arg(scene)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("handstack starts")
}

/// Waits until `done` holds for the board's stepper, polling its state (bounded).
fn wait_stepper(board: &HandBoard, what: &str, done: impl Fn(firmata_sim::StepperState) -> bool) {
    let deadline = Instant::now() + WAIT;
    loop {
        if board.board().stepper(STEPPER_DEVICE).is_some_and(&done) {
            return;
        }
        assert!(Instant::now() < deadline, "no {what} within {WAIT:?}");
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn handstack_run_classifies_soft_moderate_and_hard_objects_and_releases_the_hand() {
    let boards = [
        (Material::Sponge, "soft"),
        (Material::SiliconeRubber, "moderate"),
        (Material::Wood, "hard"),
    ]
    .map(|(m, class)| (board(m), class));
    // The three hands close at once, each from its own `handstack` process; the hard object's
    // run is recorded (`--record`).
    let bag = std::env::temp_dir().join(format!("handstack-softness-bag-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&bag);
    let runs: Vec<Child> = boards
        .iter()
        .map(|(b, class)| {
            let scene = scene(class, b, "", class);
            match *class {
                "hard" => start_with(&scene, &["--record".as_ref(), bag.as_os_str()]),
                _ => start(&scene),
            }
        })
        .collect();
    for ((b, class), run) in boards.iter().zip(runs) {
        let out = finish(run, RUN_TIMEOUT);
        let (stdout, stderr) = (text(&out.stdout), text(&out.stderr));
        assert_eq!(out.status.code(), Some(0), "{class}: {stdout}\n{stderr}");
        let row = stdout
            .lines()
            .find(|l| l.contains("class: "))
            .unwrap_or_else(|| panic!("no class row: {stdout}"));
        assert!(row.contains(&format!("class: {class} ")), "{row}");
        assert!(row.trim_end().ends_with("yes"), "{row}");
        assert!(
            stdout.contains("samples from t₁ to t₁ + 14 s                            141")
                || stdout
                    .lines()
                    .any(|l| l.contains("samples from t₁") && l.contains(" 141 ")),
            "{stdout}"
        );
        // `on_end` by default: released — back at open, the driver's outputs off, not moving.
        assert!(
            stdout.contains("hand released: opened to 0 steps"),
            "{stdout}"
        );
        // The last bytes the run wrote (outputs off) may reach the board just after it exits.
        wait_stepper(b, "outputs off", |s| !s.enabled);
        let s = b.board().stepper(STEPPER_DEVICE).expect("configured");
        assert_eq!(
            (s.position, s.running, s.enabled),
            (0, false, false),
            "{class}"
        );
        let truth = b.truth();
        assert_eq!(truth.shaft_steps, 0, "{class}: the tendon is let out again");
    }
    // The recording: every reading of the hand (the approach and the 141 samples of the window),
    // the class once, the figures; as metadata.yaml counts them.
    let yaml = std::fs::read_to_string(bag.join("metadata.yaml")).expect("metadata.yaml");
    let count = |topic: &str| bag_count(&yaml, topic);
    assert!(count("/hand0/fingers/raw") > 141, "{yaml}");
    // Each reading's four FSR forces also as the tactile toolbox's TactileState.
    assert_eq!(
        count("/hand0/tactile_states"),
        count("/hand0/fingers/raw"),
        "{yaml}"
    );
    assert_eq!(count("/hand0/softness"), 1, "{yaml}");
    // first contact, samples, class, three mean outputs, readings outside the range.
    assert_eq!(count("/handstack/figures"), 7, "{yaml}");
    let file = format!("handstack-softness-bag-{}_0.mcap", std::process::id());
    assert!(bag.join(file).exists());
    let _ = std::fs::remove_dir_all(&bag);
}

#[test]
fn the_wrong_class_fails_the_run_and_the_hand_is_still_released() {
    // A sponge the scene calls hard.
    let b = board(Material::Sponge);
    let out = finish(start(&scene("wrong", &b, "", "hard")), RUN_TIMEOUT);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(4), "{stderr}");
    assert!(
        stderr.contains("the hand classified the object soft")
            && stderr.contains("the scene expects hard")
            && stderr.contains("hand released"),
        "{stderr}"
    );
    // The outputs-off the run sends last reaches the board at the line's pace, after the
    // process may have ended.
    wait_stepper(&b, "outputs off", |s| !s.enabled);
    let s = b.board().stepper(STEPPER_DEVICE).expect("configured");
    assert_eq!((s.position, s.running, s.enabled), (0, false, false));
}

#[test]
fn ctrl_c_mid_close_stops_the_stepper_and_applies_on_end_hold() {
    let b = board(Material::Wood);
    let run = start(&scene("sigint", &b, "on_end = \"hold\"\n", "hard"));
    // Closing: the stepper has left zero.
    wait_stepper(&b, "closing stepper", |s| s.running && s.position > 50);
    signal(run.id(), "INT");
    let out = finish(run, WAIT);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(
        stderr.contains("stopped by SIGINT") && stderr.contains("holds at"),
        "{stderr}"
    );
    // Hold: stopped where it was, outputs on.
    let s = b.board().stepper(STEPPER_DEVICE).expect("configured");
    assert!(!s.running && s.enabled && s.position > 50, "{s:?}");
}

#[test]
fn a_host_killed_mid_close_leaves_the_stepper_stopping_within_its_lease() {
    let b = board(Material::Wood);
    let run = start(&scene("sigkill", &b, "", "hard"));
    wait_stepper(&b, "closing stepper", |s| s.running && s.position > 50);
    let killed = Instant::now();
    signal(run.id(), "KILL");
    let _ = finish(run, WAIT);
    // No end action could run: the lease the host last renewed runs out on the board.
    wait_stepper(&b, "stopped stepper", |s| !s.running);
    let stopped_after = killed.elapsed();
    let lease = underactuated_hand::LEASE;
    assert!(
        stopped_after <= lease + Duration::from_millis(300),
        "the stepper ran {stopped_after:?} after the host died (lease {lease:?})"
    );
}

#[test]
fn a_board_that_vanishes_mid_close_ends_the_run_as_a_fault_naming_it() {
    let b = board(Material::Wood);
    let path = b.path().display().to_string();
    let run = start(&scene("vanish", &b, "", "hard"));
    wait_stepper(&b, "closing stepper", |s| s.running && s.position > 50);
    drop(b);
    let out = finish(run, WAIT);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stderr}");
    assert!(
        stderr.contains(&format!("hand: board on {path}")) && stderr.contains("leased"),
        "{stderr}"
    );
    assert!(
        !stderr.contains("Os {") && !stderr.contains("kind:"),
        "{stderr}"
    );
}

#[test]
fn a_board_that_resets_mid_close_ends_the_run_as_a_fault_and_its_stepper_stops() {
    let b = board(Material::Wood);
    let run = start(&scene("reset", &b, "", "hard"));
    wait_stepper(&b, "closing stepper", |s| s.running && s.position > 50);
    b.board().inject(firmata_sim::Fault::Reset);
    let out = finish(run, WAIT);
    let stderr = text(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{stderr}");
    assert!(
        stderr.contains("it restarted (reset or power loss); its stepper stopped"),
        "{stderr}"
    );
    // The restarted sketch has no stepper configured: nothing drives the tendon any more.
    assert_eq!(b.board().stepper(STEPPER_DEVICE), None);
    let at = b.truth().shaft_steps;
    assert!(at > 50, "{at}");
}
