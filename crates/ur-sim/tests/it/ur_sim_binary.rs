//! The README's CI job, run as written: the built `ur-sim` with the job's arguments, the job's
//! ur_rtde check (`ci/test_ur_sim.py`), SIGTERM, a clean exit with every port closed.

use std::io::{BufRead, BufReader, Read};
use std::net::{SocketAddr, TcpStream};
use std::process::{Child, Command, ExitStatus, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

const UR_SIM: &str = env!("CARGO_BIN_EXE_ur-sim");
const README: &str = include_str!("../../README.md");
const CHECK: &str = include_str!("../../ci/test_ur_sim.py");
const CHECK_PATH: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/ci/test_ur_sim.py");
/// Off the other sim_bridge tests' 127.0.0.11–18 and the unit test's .21.
const HOST: &str = "127.0.0.20";
/// Bounds on start-up, the ur_rtde check, and the stop.
const START_TIMEOUT: Duration = Duration::from_secs(10);
const CHECK_TIMEOUT: Duration = Duration::from_secs(60);
const STOP_TIMEOUT: Duration = Duration::from_secs(10);

/// The README block after the line "```{lang}".
fn fenced(lang: &str) -> &'static str {
    let open = format!("```{lang}\n");
    let start = README.find(&open).expect("a fenced block") + open.len();
    let len = README[start..].find("```").expect("closed");
    &README[start..start + len]
}

/// The arguments the README's job starts `ur-sim` with (up to its output redirection).
fn readme_args() -> Vec<&'static str> {
    let line = fenced("yaml")
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("ur-sim "))
        .expect("the job starts ur-sim");
    line.split_whitespace()
        .skip(1)
        .take_while(|w| !w.starts_with('>'))
        .collect()
}

#[test]
fn readme_shows_the_check_and_the_commands_this_test_runs() {
    assert_eq!(
        fenced("python"),
        CHECK,
        "README's python block is ci/test_ur_sim.py"
    );
    let job = fenced("yaml");
    for line in [
        "cargo install ur-sim --locked",
        "python ci/test_ur_sim.py",
        "grep -q \"^rtde \"",
    ] {
        assert!(job.contains(line), "README's job lacks {line:?}");
    }
    assert!(
        !readme_args().contains(&"--host"),
        "the test picks the host"
    );
}

/// Runs `child` to its end within `timeout` on another thread; kills it on the timeout.
fn wait_bounded(mut child: Child, timeout: Duration, what: &str) -> (ExitStatus, String) {
    let pid = child.id();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut out = String::new();
        let _ = child.stdout.take().map(|mut s| s.read_to_string(&mut out));
        let _ = tx.send(child.wait().map(|s| (s, out)));
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

#[test]
fn ur_sim_runs_the_readme_job_and_stops_cleanly_on_sigterm() {
    let Some(python) = std::env::var_os("HANDSTACK_PYTHON") else {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
        return;
    };
    let mut sim = Command::new(UR_SIM)
        .args(readme_args())
        .args(["--host", HOST])
        .stdout(Stdio::piped())
        .spawn()
        .expect("spawn ur-sim");
    let pid = sim.id().to_string();
    // The printed lines, read on a thread so the wait for them is bounded.
    let (tx, lines) = mpsc::channel();
    let stdout = sim.stdout.take().expect("piped");
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            let _ = tx.send(line);
        }
    });
    let deadline = Instant::now() + START_TIMEOUT;
    let mut listening: Vec<(String, SocketAddr)> = Vec::new();
    while !listening.iter().any(|(service, _)| service == "rtde") {
        let left = deadline.saturating_duration_since(Instant::now());
        let Ok(line) = lines.recv_timeout(left) else {
            let _ = Command::new("kill").args(["-KILL", &pid]).status();
            panic!("no rtde line within {START_TIMEOUT:?}; got {listening:?}");
        };
        let (service, address) = line.split_once(' ').expect("SERVICE ADDRESS");
        listening.push((service.to_owned(), address.parse().expect("an address")));
    }
    let services: Vec<&str> = listening.iter().map(|(s, _)| s.as_str()).collect();
    assert_eq!(services, ["dashboard", "script", "rtde"]);
    let ports: Vec<u16> = listening.iter().map(|(_, a)| a.port()).collect();
    assert_eq!(ports, [29999, 30003, 30004]);

    let check = Command::new(python)
        .arg(CHECK_PATH)
        .arg(HOST)
        .stdout(Stdio::piped())
        .spawn()
        .expect("spawn python");
    let (status, out) = wait_bounded(check, CHECK_TIMEOUT, "ci/test_ur_sim.py");
    assert!(
        status.success(),
        "ci/test_ur_sim.py failed: {status}\n{out}"
    );
    assert!(out.contains("reached their targets"), "{out}");

    let sent = Command::new("kill").args(["-TERM", &pid]).status();
    assert!(sent.is_ok_and(|s| s.success()), "SIGTERM sent");
    let (status, _) = wait_bounded(sim, STOP_TIMEOUT, "ur-sim after SIGTERM");
    assert_eq!(status.code(), Some(0), "clean exit: {status}");
    for (service, address) in &listening {
        assert!(
            TcpStream::connect_timeout(address, Duration::from_secs(1)).is_err(),
            "{service} port {address} still open"
        );
    }
}

#[test]
fn an_unknown_model_or_time_scale_is_a_usage_error() {
    for (args, says) in [
        (&["--model", "ur5"][..], "possible values: ur3"),
        (&["--time-scale", "0"][..], "must be finite and positive"),
        (&["--host", "localhost:1"][..], "--host"),
    ] {
        let out = Command::new(UR_SIM)
            .args(args)
            .output()
            .expect("run ur-sim");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "nothing listened");
    }
}
