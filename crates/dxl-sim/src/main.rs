//! `dxl-sim`: simulated Dynamixel Protocol 2.0 servos on a pseudo-terminal, for tests of code
//! that drives a Dynamixel bus (the ROBOTIS SDK, `hand-control`'s `ServoHand`, …).
//!
//! Prints the pty's path (`/dev/pts/N`) on one line, then serves the servos in real time until
//! SIGINT or SIGTERM, and exits 0. With `--trace`, every instruction the servos execute follows
//! on stdout, one line each: the time since the bus started (s), the instruction, the ID and
//! the registers it names by their e-Manual names, e.g. `1.020000 sync_write Goal PWM 1=254
//! 2=254` or `3.100000 sync_write Torque Enable 1=0 2=0`.
//!
//! Models are named as a handstack scene file names them (`mx28`, `xm430`, `rh_p12_rn`); the
//! simulator runs the MX-28(2.0).

use std::io::Write;
use std::process::ExitCode;
use std::str::FromStr;

use clap::Parser;
use dxl_sim::{Pace, SIMULATED_MODELS, SimBus, SimConfig};
use hand_control::control_table::ControlTable;
use hand_control::protocol::MAX_ID;
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// Simulated Dynamixel Protocol 2.0 servos on a pseudo-terminal.
#[derive(Debug, Parser)]
#[command(
    name = "dxl-sim",
    version,
    about = "Simulated Dynamixel Protocol 2.0 servos on a pseudo-terminal, for bus tests"
)]
struct Args {
    /// A servo on the bus, MODEL:ID (e.g. `mx28:1`); repeat for each servo. IDs 0–252.
    #[arg(long = "servo", value_name = "MODEL:ID", required = true)]
    servos: Vec<Servo>,
    /// Print every instruction the servos execute on stdout, one line each, after the path.
    #[arg(long)]
    trace: bool,
}

/// One `--servo` (its model is one the simulator runs).
#[derive(Debug, Clone, Copy)]
struct Servo {
    id: u8,
}

/// A `--servo` value the simulator cannot run.
#[derive(Debug, thiserror::Error)]
enum ServoError {
    #[error("{0:?} is not MODEL:ID")]
    Form(String),
    #[error("unknown model {given:?}; the models: {known}")]
    UnknownModel { given: String, known: String },
    #[error("the simulator runs {simulated} only; {model} is a control table for the driver")]
    NotSimulated {
        model: &'static str,
        simulated: String,
    },
    #[error("servo ID {0:?} is not a number in 0–252")]
    Id(String),
}

fn keys(tables: &[&ControlTable]) -> String {
    tables.iter().map(|t| t.key).collect::<Vec<_>>().join(", ")
}

impl FromStr for Servo {
    type Err = ServoError;

    fn from_str(s: &str) -> Result<Servo, ServoError> {
        let (model, id) = s
            .split_once(':')
            .ok_or_else(|| ServoError::Form(s.to_owned()))?;
        let table = ControlTable::by_name(model).ok_or_else(|| ServoError::UnknownModel {
            given: model.to_owned(),
            known: ControlTable::keys(),
        })?;
        if !SIMULATED_MODELS
            .iter()
            .any(|t| t.model_number == table.model_number)
        {
            return Err(ServoError::NotSimulated {
                model: table.key,
                simulated: keys(&SIMULATED_MODELS),
            });
        }
        let id = id
            .parse()
            .ok()
            .filter(|id| *id <= MAX_ID)
            .ok_or_else(|| ServoError::Id(id.to_owned()))?;
        Ok(Servo { id })
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    let mut ids: Vec<u8> = args.servos.iter().map(|s| s.id).collect();
    ids.sort_unstable();
    if let Some(w) = ids.windows(2).find(|w| w[0] == w[1]) {
        let message = format!("servo ID {} is given twice", w[0]);
        <Args as clap::CommandFactory>::command()
            .error(clap::error::ErrorKind::ArgumentConflict, message)
            .exit();
    }
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("dxl-sim: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> std::io::Result<()> {
    // Registered before the bus starts, so a signal during start-up still ends in a clean stop.
    let mut signals = Signals::new([SIGINT, SIGTERM])?;
    let ids: Vec<u8> = args.servos.iter().map(|s| s.id).collect();
    // The client end stays open here: the pty lives as long as one end of each side is open.
    let (mut bus, _client) = SimBus::spawn(SimConfig {
        pace: Pace::WallClock,
        trace: args.trace,
        ..SimConfig::with_ids(&ids)
    })?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "{}", bus.client_path().display())?;
    // A CI job or test waits for this line through a pipe: it must not sit in a buffer.
    out.flush()?;
    drop(out);
    if let Some(trace) = bus.take_trace() {
        // Each line as it comes (a test reads them while the client runs); the thread ends
        // when the bus is dropped and its sender with it.
        std::thread::spawn(move || {
            let mut out = std::io::stdout();
            for line in trace {
                if writeln!(out, "{line}").and_then(|()| out.flush()).is_err() {
                    return;
                }
            }
        });
    }
    let _ = signals.forever().next();
    // Stops the simulator thread (within its 20 ms read timeout) and closes the pty.
    drop(bus);
    Ok(())
}
