//! In-memory entry points for coverage-guided fuzzing: the simulator's RTDE, dashboard and
//! script-intake request handling, fed from a byte slice instead of a socket.
//!
//! Each call builds a fresh simulator state (no listener, no socket, no thread outliving the
//! call), runs the bytes through the same code the TCP servers run, advances the controller a
//! bounded number of control cycles (so that commands and moves start), and returns what the
//! server wrote back. Deterministic: the same bytes give the same answer.
//!
//! ```
//! let reply = ur_sim::fuzzing::dashboard(b"robotmode\n");
//! assert_eq!(
//!     String::from_utf8_lossy(&reply),
//!     "Connected: Universal Robots Dashboard Server\nRobotmode: RUNNING\n"
//! );
//! ```

use std::sync::{Arc, Mutex};

use super::rtde::Streaming;
use super::{Shared, SimConfig};

/// RTDE's package framing and types, for a fuzzer's seed packages.
pub use super::wire::{
    DATA_PACKAGE, GET_URCONTROL_VERSION, PAUSE, REQUEST_PROTOCOL_VERSION, SETUP_INPUTS,
    SETUP_OUTPUTS, START, package,
};

/// Control cycles run after the input ends, so that the last command can start a move.
const TICKS_AFTER_INPUT: usize = 8;
/// Control cycles run after each script program handed to the controller.
const TICKS_PER_PROGRAM: usize = 4;

fn fresh() -> Shared {
    Shared::new(SimConfig::default())
}

fn tick(shared: &Shared) {
    let dt = shared.config.control_period.as_secs_f64();
    shared.lock().tick(dt);
}

/// RTDE (port 30004): `input` is what a client sends; returns the server's packages. The
/// controller runs ur_rtde's control script (register offset 0) as after a ur_rtde connect,
/// so input registers drive its commands; one control cycle runs after each package. START
/// answers with one data package instead of a streaming thread.
pub fn rtde(input: &[u8]) -> Vec<u8> {
    let shared = Arc::new(fresh());
    shared.lock().start_script(0);
    let out = Arc::new(Mutex::new(Vec::new()));
    // An error ends the connection, as on a socket; what was written before it stands.
    let _ = super::rtde::serve_io(&shared, input, &out, 1, Streaming::Once, tick);
    for _ in 0..TICKS_AFTER_INPUT {
        tick(&shared);
    }
    let mut out = out.lock().unwrap_or_else(|e| e.into_inner());
    core::mem::take(&mut *out)
}

/// Dashboard (port 29999): `input` is what a client sends; returns the server's lines (the
/// greeting first). One control cycle runs after each answered line.
pub fn dashboard(input: &[u8]) -> Vec<u8> {
    let shared = fresh();
    let mut out = Vec::new();
    let _ = super::dashboard::serve_io(&shared, input, &mut out, tick);
    out
}

/// Script intake (port 30003): `input` is what a client sends; returns the controller's log
/// (`textmsg` lines and safety events), one line each. A few control cycles run after each
/// program and after the input ends.
pub fn script(input: &[u8]) -> Vec<u8> {
    let shared = fresh();
    let _ = super::serve_script_io(&shared, input, |s| {
        for _ in 0..TICKS_PER_PROGRAM {
            tick(s);
        }
    });
    for _ in 0..TICKS_AFTER_INPUT {
        tick(&shared);
    }
    let c = shared.lock();
    let mut out = Vec::new();
    for line in &c.log {
        out.extend_from_slice(line.as_bytes());
        out.push(b'\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire;

    /// The packages in `bytes`, in order.
    fn packages(mut bytes: &[u8]) -> Vec<(u8, Vec<u8>)> {
        let mut all = Vec::new();
        while let Some(p) = wire::read_package(&mut bytes).expect("framed") {
            all.push(p);
        }
        all
    }

    #[test]
    fn rtde_accepts_protocol_version_2_and_streams_one_package() {
        let mut input = wire::package(wire::REQUEST_PROTOCOL_VERSION, &[0, 2]).unwrap();
        let mut setup = 125.0_f64.to_be_bytes().to_vec();
        setup.extend_from_slice(b"timestamp,actual_q");
        input.extend(wire::package(wire::SETUP_OUTPUTS, &setup).unwrap());
        input.extend(wire::package(wire::START, &[]).unwrap());
        let reply = rtde(&input);
        let p = packages(&reply);
        assert_eq!(p[0], (wire::REQUEST_PROTOCOL_VERSION, vec![1]), "accepted");
        assert_eq!(p[1], (wire::SETUP_OUTPUTS, b"\x01DOUBLE,VECTOR6D".to_vec()));
        assert_eq!(p[2], (wire::START, vec![1]));
        // Recipe 1: the timestamp (two packages before START, one cycle each) then the home joints.
        assert_eq!(p[3].0, wire::DATA_PACKAGE);
        assert_eq!(p[3].1.len(), 1 + 8 + 48);
        let t = f64::from_be_bytes(p[3].1[1..9].try_into().unwrap());
        assert!((t - 0.016).abs() < 1e-12, "{t}");
        assert_eq!(p.len(), 4);
        assert_eq!(reply, rtde(&input), "deterministic");
    }

    #[test]
    fn dashboard_answers_robotmode() {
        let reply = dashboard(b"robotmode\nnonsense \xff\n");
        assert_eq!(
            String::from_utf8_lossy(&reply),
            "Connected: Universal Robots Dashboard Server\nRobotmode: RUNNING\n\
             could not understand: 'nonsense \u{fffd}'\n"
        );
    }

    #[test]
    fn script_logs_what_it_runs_and_what_not() {
        let log = script(
            b"def rtde_control():\n# HEADER_BEGIN\n    global reg_offset_int = # int register offset\n0\n    def signal_ready():\n    def process_cmd(cmd):\nend\ndef other():\nend\n",
        );
        assert_eq!(
            String::from_utf8_lossy(&log),
            "RTDE Control Script Loaded\nscript not run: not ur_rtde's control script (17 bytes)\n"
        );
    }
}
