//! `ur-sim`: a simulated Universal Robots controller for ur_rtde tests, in place
//! of URSim in Docker: it starts in milliseconds and the unmodified ur_rtde client accepts it.
//!
//! Prints one line per listening port, `SERVICE ADDRESS` (`dashboard 127.0.0.1:29999`,
//! `script 127.0.0.1:30003`, `rtde 127.0.0.1:30004`), then runs until SIGINT or SIGTERM, closes
//! every connection and port, and exits 0.

use std::io::Write;
use std::net::Ipv4Addr;
use std::process::ExitCode;

use clap::{Parser, ValueEnum};
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;
use ur_bridge::kinematics::UrModel;
use ur_sim::{SimConfig, TimeScale, UrSim};

/// A simulated UR controller (dashboard, script intake and RTDE) that ur_rtde connects to.
#[derive(Debug, Parser)]
#[command(
    name = "ur-sim",
    version,
    about = "A simulated Universal Robots controller (dashboard, script, RTDE) for ur_rtde tests"
)]
struct Args {
    /// IPv4 address to listen on. ur_rtde uses fixed ports, so simulators side by side take
    /// 127.0.0.2, 127.0.0.3, …; an address beyond loopback exposes the simulated arm.
    #[arg(long, default_value_t = Ipv4Addr::LOCALHOST)]
    host: Ipv4Addr,
    /// The arm's geometry and joint limits.
    #[arg(long, value_enum, default_value_t = Model::Ur3)]
    model: Model,
    /// Simulated seconds per wall-clock second (1 = real time, 4 = moves four times faster).
    #[arg(long, default_value = "1")]
    time_scale: TimeScale,
}

/// The arm models the simulator has kinematics for.
#[derive(Debug, Clone, Copy, ValueEnum)]
enum Model {
    /// Universal Robots UR3 (CB3).
    Ur3,
}

impl Model {
    fn kinematics(self) -> UrModel {
        match self {
            Model::Ur3 => UrModel::ur3(),
        }
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("ur-sim: {} on {}: {e}", e.kind(), args.host);
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> std::io::Result<()> {
    // Registered before binding, so a signal during start-up still ends in a clean stop.
    let mut signals = Signals::new([SIGINT, SIGTERM])?;
    if !args.host.is_loopback() {
        eprintln!(
            "ur-sim: listening on {} beyond loopback: whoever reaches it can command the arm",
            args.host
        );
    }
    let sim = UrSim::start(SimConfig {
        address: args.host,
        model: args.model.kinematics(),
        time_scale: args.time_scale,
        ..SimConfig::default()
    })?;
    let mut out = std::io::stdout().lock();
    for (service, address) in sim.services() {
        writeln!(out, "{service} {address}")?;
    }
    // A CI job or test waits for these lines through a pipe: they must not sit in a buffer.
    out.flush()?;
    drop(out);
    let _ = signals.forever().next();
    // Closes every connection and listener and joins the simulator's threads.
    drop(sim);
    Ok(())
}
