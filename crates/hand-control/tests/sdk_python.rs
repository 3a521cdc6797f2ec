//! The official ROBOTIS SDK (`dynamixel_sdk`, from `$HANDSTACK_PYTHON`) drives the simulator
//! over the same pty: ping, broadcast ping, read / write, sync read / write, bulk read,
//! REG_WRITE / ACTION, REBOOT, FACTORY RESET.

use std::io::Read;
use std::process::{Command, Stdio};
use std::sync::mpsc;
use std::time::Duration;

use hand_control::sim::{SimBus, SimConfig};

/// A bound on the script's run (it takes well under a second).
const SCRIPT_TIMEOUT: Duration = Duration::from_secs(60);

#[test]
fn robotis_sdk_talks_to_the_simulator() {
    let Some(python) = std::env::var_os("HANDSTACK_PYTHON") else {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
        return;
    };
    let ids = [1u8, 2, 3];
    let (sim, _client) = SimBus::spawn(SimConfig::with_ids(&ids)).expect("pty");
    let script = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/python/sdk_against_sim.py"
    );
    let mut child = Command::new(python)
        .arg(script)
        .arg(sim.client_path())
        .arg("1,2,3")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn python");
    let pid = child.id();
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let mut out = String::new();
        let mut err = String::new();
        let _ = child.stdout.take().map(|mut s| s.read_to_string(&mut out));
        let _ = child.stderr.take().map(|mut s| s.read_to_string(&mut err));
        let status = child.wait();
        let _ = tx.send((status, out, err));
    });
    let Ok((status, out, err)) = rx.recv_timeout(SCRIPT_TIMEOUT) else {
        let _ = Command::new("kill").arg(pid.to_string()).status();
        panic!("the SDK script did not finish within {SCRIPT_TIMEOUT:?}");
    };
    assert!(
        status.map(|s| s.success()).unwrap_or(false),
        "script failed:\n{out}\n{err}"
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
