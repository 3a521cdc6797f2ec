//! The official ROBOTIS SDK (`dynamixel_sdk`, from `$HANDSTACK_PYTHON`) drives the simulator
//! over the same pty: ping, broadcast ping, read / write, sync read / write, bulk read,
//! REG_WRITE / ACTION, REBOOT, FACTORY RESET. And the README's CI job, run as written: the built
//! `dxl-sim`, the job's SDK check (`ci/test_dxl_sim.py`) and the README's example program
//! (`examples/grasp_on_port`) on its pty, SIGTERM, a clean exit.

use std::io::{BufRead, BufReader, Read};
use std::path::PathBuf;
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use dxl_sim::{SimBus, SimConfig};

/// A bound on the script's run (it takes well under a second).
const SCRIPT_TIMEOUT: Duration = Duration::from_secs(60);
/// Bounds on `dxl-sim` printing its pty and on its stop.
const START_TIMEOUT: Duration = Duration::from_secs(10);
const STOP_TIMEOUT: Duration = Duration::from_secs(10);

const DXL_SIM: &str = env!("CARGO_BIN_EXE_dxl-sim");
const README: &str = include_str!("../../README.md");
const EXAMPLE: &str = include_str!("../../examples/grasp_on_port.rs");
const CHECK: &str = include_str!("../../ci/test_dxl_sim.py");
const CHECK_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/ci/test_dxl_sim.py");

/// `$HANDSTACK_PYTHON`, or `None` with a message (the test is skipped).
fn python() -> Option<std::ffi::OsString> {
    let python = std::env::var_os("HANDSTACK_PYTHON");
    if python.is_none() {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
    }
    python
}

/// Runs `child` to its end within `timeout` on another thread (its stdout and stderr piped);
/// kills it on the timeout.
fn wait_bounded(mut child: Child, timeout: Duration, what: &str) -> (ExitStatus, String, String) {
    let pid = child.id();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut out = String::new();
        let mut err = String::new();
        let _ = child.stdout.take().map(|mut s| s.read_to_string(&mut out));
        let _ = child.stderr.take().map(|mut s| s.read_to_string(&mut err));
        let _ = tx.send(child.wait().map(|s| (s, out, err)));
    });
    match rx.recv_timeout(timeout) {
        Ok(done) => done.expect("wait"),
        Err(_) => {
            let _ = Command::new("kill")
                .args(["-KILL", &pid.to_string()])
                .status();
            panic!("{what} did not end within {timeout:?}");
        }
    }
}

/// Runs `command` with stdout and stderr piped; bounded, and it must succeed.
fn run_ok(command: &mut Command, timeout: Duration, what: &str) -> String {
    let child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("spawn {what}: {e}"));
    let (status, out, err) = wait_bounded(child, timeout, what);
    assert!(status.success(), "{what} failed: {status}\n{out}\n{err}");
    out
}

#[test]
fn robotis_sdk_talks_to_the_simulator() {
    let Some(python) = python() else { return };
    let ids = [1u8, 2, 3];
    let (sim, _client) = SimBus::spawn(SimConfig::with_ids(&ids)).expect("pty");
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/python/sdk_against_sim.py"
    );
    let out = run_ok(
        Command::new(python)
            .arg(script)
            .arg(sim.client_path())
            .arg("1,2,3"),
        SCRIPT_TIMEOUT,
        "the SDK script",
    );
    println!("{out}");
    for line in [
        "ok: broadcast ping -> [1, 2, 3]",
        "ok: sync read 3 -> 200",
        "ok: bulk read PWM Limit",
        "ok: LED 0 after ACTION",
        "ok: PWM Limit 885 after factory reset",
        "DONE",
    ] {
        assert!(out.contains(line), "missing {line:?} in:\n{out}");
    }
    // The SDK's sync write reached the simulated servos (the last one was rebooted and reset
    // since, which the script checked).
    for (k, id) in ids[..2].iter().enumerate() {
        assert_eq!(
            sim.with_servo(*id, |s| s.get(100)),
            Some(100 + 50 * k as i32)
        );
    }
}

/// The README block after the `n`-th line "```{lang}" (from 0).
fn fenced(lang: &str, n: usize) -> &'static str {
    let open = format!("```{lang}\n");
    let (start, _) = README.match_indices(&open).nth(n).expect("a fenced block");
    let start = start + open.len();
    let len = README[start..].find("```").expect("closed");
    &README[start..start + len]
}

/// The arguments the README's job starts `dxl-sim` with (up to its output redirection).
fn readme_args() -> Vec<&'static str> {
    let line = fenced("yaml", 0)
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("dxl-sim "))
        .expect("the job starts dxl-sim");
    line.split_whitespace()
        .skip(1)
        .take_while(|w| !w.starts_with('>'))
        .collect()
}

#[test]
fn readme_names_the_example_and_shows_the_ci_job_this_test_runs() {
    assert!(
        README.contains("`examples/grasp_on_port.rs`")
            && EXAMPLE.contains("ServoHand::open(&port")
            && EXAMPLE.contains("fuzzy_mamdani::grasp_controller()"),
        "README names the example, which opens the port it is given"
    );
    assert_eq!(
        fenced("python", 0),
        CHECK,
        "README's python block is ci/test_dxl_sim.py"
    );
    let job = fenced("yaml", 0);
    for line in [
        "cargo install dxl-sim --locked",
        "python ci/test_dxl_sim.py \"$(cat dxl-sim.out)\"",
    ] {
        assert!(job.contains(line), "README's job lacks {line:?}");
    }
    assert!(
        fenced("sh", 0).contains(&format!("dxl-sim {}", readme_args().join(" "))),
        "the example runs against the job's dxl-sim"
    );
}

/// `target/<profile>/examples/grasp_on_port`: Cargo builds the examples for `cargo test`, next
/// to the directory of this test executable (`target/<profile>/deps`).
fn example_binary() -> PathBuf {
    let exe = std::env::current_exe().expect("test executable");
    let profile = exe
        .parent()
        .and_then(|deps| deps.parent())
        .expect("target/<profile>");
    profile.join("examples").join("grasp_on_port")
}

#[test]
fn dxl_sim_runs_the_readme_job_and_example_and_stops_cleanly_on_sigterm() {
    let Some(python) = python() else { return };
    let mut sim = Command::new(DXL_SIM)
        .args(readme_args())
        .stdout(Stdio::piped())
        .spawn()
        .expect("spawn dxl-sim");
    let pid = sim.id().to_string();
    // The printed line, read on a thread so the wait for it is bounded.
    let (tx, lines) = mpsc::channel();
    let stdout = sim.stdout.take().expect("piped");
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let Ok(line) = lines.recv_timeout(START_TIMEOUT) else {
        let _ = Command::new("kill").args(["-KILL", &pid]).status();
        panic!("dxl-sim printed no pty within {START_TIMEOUT:?}");
    };
    let pty = line.trim_end().to_owned();
    assert!(pty.starts_with("/dev/pts/"), "{line:?}");

    let out = run_ok(
        Command::new(python).arg(CHECK_PATH).arg(&pty),
        SCRIPT_TIMEOUT,
        "ci/test_dxl_sim.py",
    );
    assert!(out.contains("servo 1 reached its goal"), "{out}");

    // The README's example on the same bus; the fingertip at rest, as the README's `sh` shows.
    let fingertip = std::env::temp_dir().join(format!("grasp_on_port-{}.txt", std::process::id()));
    std::fs::write(&fingertip, "101.3\n").expect("write the reading");
    let out = run_ok(
        Command::new(example_binary()).arg(&pty).arg(&fingertip),
        SCRIPT_TIMEOUT,
        "examples/grasp_on_port",
    );
    let _ = std::fs::remove_file(&fingertip);
    println!("{out}");
    assert!(out.starts_with("mode Grasp after "), "{out}");
    assert!(out.contains(" cycles, 0 faults\n"), "{out}");
    let torque: u16 = out
        .lines()
        .find_map(|l| {
            l.strip_prefix("torque limit ")?
                .strip_suffix(" of 1023")?
                .parse()
                .ok()
        })
        .unwrap_or_else(|| panic!("no torque line in {out}"));
    assert!((1..=1023).contains(&torque), "{torque}");
    let position: f64 = out
        .lines()
        .find_map(|l| l.strip_prefix("hand at ")?.split(' ').next()?.parse().ok())
        .unwrap_or_else(|| panic!("no hand line in {out}"));
    // The servos closed to the example's goal pose in the second they ran.
    assert!((position - 2.6).abs() < 0.01, "{position}");

    let sent = Command::new("kill").args(["-TERM", &pid]).status();
    assert!(sent.is_ok_and(|s| s.success()), "SIGTERM sent");
    let (status, _, _) = wait_bounded(sim, STOP_TIMEOUT, "dxl-sim after SIGTERM");
    assert_eq!(status.code(), Some(0), "clean exit: {status}");
}

#[test]
fn a_servo_the_simulator_does_not_run_is_a_usage_error() {
    for (args, says) in [
        // Named as a scene file names it: known, but not simulated.
        (
            &["--servo", "xm430:1"][..],
            "the simulator runs mx28 only; xm430 is a control table for the driver",
        ),
        (
            &["--servo", "XM430-W350:1"][..],
            "the simulator runs mx28 only",
        ),
        (&["--servo", "ax12:1"][..], "unknown model \"ax12\""),
        (&["--servo", "mx28:253"][..], "not a number in 0–252"),
        (
            &["--servo", "mx28:1", "--servo", "mx28:1"][..],
            "given twice",
        ),
        (&[][..], "--servo"),
    ] {
        let out = Command::new(DXL_SIM)
            .args(args)
            .output()
            .expect("run dxl-sim");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "no pty printed");
    }
}
