//! pyfirmata2 2.5.1 (from `$HANDSTACK_PYTHON`, the workspace venv) drives the `firmata-sim`
//! binary: its firmware query and capability-based set-up, analog reporting, and an I2C
//! register read through its generic sysex API. And the README's CI job, run as written:
//! `ci/test_firmata_sim.py` against the binary started with the job's arguments; SIGTERM, a
//! clean exit.

use std::io::{BufRead, BufReader, Read};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::mpsc;
use std::time::Duration;

const SIM: &str = env!("CARGO_BIN_EXE_firmata-sim");
const README: &str = include_str!("../../README.md");
const CHECK: &str = include_str!("../../ci/test_firmata_sim.py");
const CHECK_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/ci/test_firmata_sim.py");
const SCRIPT: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/python/pyfirmata2_against_sim.py"
);
/// A bound on a script's run (pyfirmata2 waits 5 s for the reset at each open).
const SCRIPT_TIMEOUT: Duration = Duration::from_secs(60);

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

/// Runs `child` to its end within `timeout` (stdout and stderr piped); kills it on the timeout.
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

fn run_ok(command: &mut Command, what: &str) -> String {
    let child = command
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap_or_else(|e| panic!("spawn {what}: {e}"));
    let (status, out, err) = wait_bounded(child, SCRIPT_TIMEOUT, what);
    assert!(status.success(), "{what} failed: {status}\n{out}\n{err}");
    out
}

/// The README block after the `n`-th "```{lang}" line.
fn fenced(lang: &str, n: usize) -> &'static str {
    let open = format!("```{lang}\n");
    let (start, _) = README.match_indices(&open).nth(n).expect("a fenced block");
    let start = start + open.len();
    let len = README[start..].find("```").expect("closed");
    &README[start..start + len]
}

/// The arguments the README's job starts `firmata-sim` with.
fn readme_args() -> Vec<&'static str> {
    fenced("yaml", 0)
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("firmata-sim "))
        .expect("the job starts firmata-sim")
        .split_whitespace()
        .skip(1)
        .take_while(|w| !w.starts_with('>'))
        .collect()
}

#[test]
fn readme_shows_the_ci_job_and_check_this_test_runs() {
    assert_eq!(
        fenced("python", 0),
        CHECK,
        "README's python block is ci/test_firmata_sim.py"
    );
    let job = fenced("yaml", 0);
    for line in [
        "pip install pyfirmata2==2.5.1",
        "cargo install firmata-sim --locked",
        "python ci/test_firmata_sim.py \"$(cat firmata-sim.out)\"",
    ] {
        assert!(job.contains(line), "README's job lacks {line:?}");
    }
}

#[test]
fn pyfirmata2_drives_the_simulator_binary_and_it_stops_cleanly_on_sigterm() {
    let Some(python) = python() else { return };
    let mut sim = Command::new(SIM)
        .args(readme_args())
        .stdout(Stdio::piped())
        .spawn()
        .expect("spawn firmata-sim");
    let pid = sim.id().to_string();
    // A failing script must not leave the simulator running.
    let _guard = crate::KillOnDrop(pid.clone());
    let stdout = sim.stdout.take().expect("piped");
    let (tx, lines) = mpsc::channel();
    std::thread::spawn(move || {
        let mut line = String::new();
        let _ = BufReader::new(stdout).read_line(&mut line);
        let _ = tx.send(line);
    });
    let Ok(line) = lines.recv_timeout(Duration::from_secs(10)) else {
        let _ = Command::new("kill").args(["-KILL", &pid]).status();
        panic!("firmata-sim printed no pty");
    };
    let pty = line.trim_end().to_owned();
    assert!(pty.starts_with("/dev/pts/"), "{line:?}");

    let out = run_ok(
        Command::new(&python).arg(CHECK_PATH).arg(&pty),
        "ci/test_firmata_sim.py",
    );
    assert!(
        out.contains("firmata-sim: StandardFirmata (2, 5), A0 = 0.2502"),
        "{out}"
    );

    let out = run_ok(
        Command::new(&python).arg(SCRIPT).arg(&pty),
        "the pyfirmata2 script",
    );
    println!("{out}");
    for line in [
        "ok: firmware StandardFirmata (2, 5), protocol (2, 5)",
        "ok: 6 analog, 14 digital pins", // pyfirmata2 counts A0–A5 apart
        "ok: A0 = 0.2502 (",
        "ok: I2C reply from 0x77 register 0xa2: C1 = 40127",
        "DONE",
    ] {
        assert!(out.contains(line), "missing {line:?} in:\n{out}");
    }

    let sent = Command::new("kill").args(["-TERM", &pid]).status();
    assert!(sent.is_ok_and(|s| s.success()), "SIGTERM sent");
    let (status, _, _) = wait_bounded(sim, Duration::from_secs(10), "firmata-sim after SIGTERM");
    assert_eq!(status.code(), Some(0), "clean exit: {status}");
}

#[test]
fn a_bad_option_is_a_usage_error() {
    for (args, says) in [
        (&["--analog", "A16=1"][..], "not an analog pin"),
        (&["--analog", "A0=7"][..], "not a voltage"),
        (&["--board", "nano"][..], "nano"),
    ] {
        let out = Command::new(SIM)
            .args(args)
            .output()
            .expect("run firmata-sim");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty());
    }
}
