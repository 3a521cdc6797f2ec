//! The `handstack` binary as `cargo install handstack` leaves it: run from an empty directory,
//! away from this repository, on a user's own scene file. `check` validates without opening
//! anything; `run` opens the devices and, on a machine without them, fails before anything
//! moves, naming the device and its path; a bad scene exits non-zero and says why.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// A fresh empty directory outside the repository (the system's temp dir).
fn empty_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("handstack-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

/// Runs the binary in `dir` with no workspace variables, so nothing can point it back here.
fn handstack(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_handstack"))
        .args(args)
        .current_dir(dir)
        .env_remove("HANDSTACK_FIXTURES")
        .env_remove("CARGO_MANIFEST_DIR")
        .output()
        .expect("runs")
}

const SCENE: &str = "title = \"my hand\"\n[sensors.fingertip]\nosr = 1024\n\
    i2c_buses = [\"/dev/i2c-handstack-none-1\", \"/dev/i2c-handstack-none-2\", \"/dev/i2c-handstack-none-3\"]\n\
    [controller]\npreset = \"grasp\"\n[hand]\nmodel = \"mx28\"\nserial_port = \"/dev/ttyUSB-handstack-none\"\n\
    [experiment.grasp]\ntorque_band = [250, 320]\nhold_s = 5\n";

#[test]
fn outside_the_repository_check_validates_and_run_fails_before_anything_moves() {
    let dir = empty_dir("user");
    std::fs::write(dir.join("my-hand.toml"), SCENE).expect("write");
    let out = handstack(&dir, &["check", "my-hand.toml"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        "my-hand.toml: ok (grasp)\n"
    );
    let out = handstack(&dir, &["run", "--json", "my-hand.toml"]);
    let _ = std::fs::remove_dir_all(&dir);
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    // The sensors are opened first: the missing fingertip bus is the error, by its path.
    assert!(
        err.contains("cannot open sensors.fingertip at /dev/i2c-handstack-none-1"),
        "{err}"
    );
    let outcomes: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(outcomes, serde_json::json!([]));
}

#[test]
fn a_bad_scene_exits_non_zero_and_says_why() {
    let dir = empty_dir("bad");
    std::fs::write(
        dir.join("bad.toml"),
        "title = \"x\"\n[sensors.fingertip]\nosr = 300\n[experiment.readout]\nframes = 5\n",
    )
    .expect("write");
    for cmd in ["check", "run"] {
        let out = handstack(&dir, &[cmd, "bad.toml"]);
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(
            err.contains("bad.toml:3:7: `sensors.fingertip.osr` is 300"),
            "{err}"
        );
        assert!(err.contains("256, 512, 1024, 2048, 4096"), "{err}");
        assert!(!String::from_utf8_lossy(&out.stdout).contains("figure"));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `collect` records weight, tap or grasp sessions: a scene that runs anything else is refused
/// before a session directory is made; a scene that does not parse, as `run` refuses it.
#[test]
fn collect_refuses_a_scene_without_weights_taps_or_objects_to_grasp() {
    let dir = empty_dir("collect");
    std::fs::write(dir.join("my-hand.toml"), SCENE).expect("write");
    let out = handstack(&dir, &["collect", "my-hand.toml", "--into", "sessions"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "my-hand.toml: `handstack collect` records one experiment's training data, \
             [experiment.weight] (the force DNN's), [experiment.contact] (the contact \
             MLP's), [experiment.tap_to_move] (the contact CNN's) or [experiment.softness] \
             with `objects` (the softness net's)"
        ),
        "{err}"
    );
    assert!(err.contains("the scene runs grasp"), "{err}");
    assert!(!dir.join("sessions").exists());
    let out = handstack(&dir, &["collect", "none.toml", "--into", "sessions"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&out.stderr).contains("none.toml: cannot read"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `calibrate` zeroes the underactuated hand's potentiometers: a scene without that hand is
/// refused before anything is opened.
#[test]
fn calibrate_refuses_a_scene_without_the_underactuated_hand() {
    let dir = empty_dir("calibrate");
    std::fs::write(dir.join("my-hand.toml"), SCENE).expect("write");
    let out = handstack(&dir, &["calibrate", "my-hand.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains(
            "my-hand.toml: `handstack calibrate` zeroes the underactuated hand's \
             potentiometers, and the scene names no such hand"
        ),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}
