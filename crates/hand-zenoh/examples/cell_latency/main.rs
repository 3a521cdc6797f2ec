//! The cell on loopback, measured (`docs/cell.md`): end-to-end latency
//! frame-publish → subscriber (p50 / p99 / max), loss by sequence gaps after discovery, and
//! the CPU each process takes, for 1, 4 and 16 hands × 3 fingertips at 100 Hz plus one pad
//! (`sensor_msgs/Imu` and a `PressureFrame`, 30 Hz each), over this crate's nodes (`rmw`) and
//! over bare Zenoh pub/sub with the same payload bytes (`bare`, the floor).
//!
//! One binary, re-executed in roles, each its own process:
//!
//! ```text
//! cell_latency [--seconds 10] [--hands 1,4,16] [--modes rmw,bare] [--rounds 1]   orchestrator: JSON
//! cell_latency router --listen tcp/127.0.0.1:P [--seconds CAP]
//! cell_latency hands --first K --count N --connect E [--seconds CAP] [--bare]
//! cell_latency pad --connect E [--seconds CAP] [--bare]
//! cell_latency sink --connect E --hands N [--pad] --seconds S [--bare]
//! cell_latency costs [--calls N]     each step of both paths timed in this process (JSON)
//! ```
//!
//! A hand is one node (`/handK`, `tactile`) with one `PressureFrame` publisher per
//! fingertip, `/handK/tactile/raw0..2` (3 float32 pressures, a synthetic ramp). Every role but
//! the orchestrator runs until its stdin closes or its `--seconds` cap passes.

mod args;
mod costs;
mod orchestrate;
mod publish;
mod sink;
mod topics;

use std::process::ExitCode;

fn main() -> ExitCode {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let args = args::Args::new(&argv);
    let result = match argv.first().map(String::as_str) {
        Some("router") => publish::router(&args),
        Some("hands") => publish::hands(&args),
        Some("pad") => publish::pad(&args),
        Some("sink") => sink::run(&args),
        Some("costs") => costs::run(&args),
        Some(r) if !r.starts_with("--") => Err(format!("unknown role {r}").into()),
        _ => orchestrate::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!(
                "cell_latency {}: {e}",
                argv.first().map_or("", String::as_str)
            );
            ExitCode::FAILURE
        }
    }
}

/// The error every role returns.
type Error = Box<dyn std::error::Error + Send + Sync>;
