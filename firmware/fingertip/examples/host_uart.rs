//! The fingertip on a pseudo-terminal: the firmware's pipeline on the host, over the board's
//! bus layout (three MS5611 chip models behind a TCA9548A model, pressed by hand-sim's
//! fingertip physics), sending its UART frames in real time to a pty, as the board sends them
//! to a USB serial adapter. A host reads it as it reads the board (`handstack`'s
//! `[sensors.fingertip] serial_port`).
//!
//! `cargo run --release --example host_uart [-- --seed N] [--skin N] [--speed X]` prints the
//! pty's path on one line, then runs until it is killed. `--skin N`: another fingertip, whose
//! silicone responds as hand-sim's `LawParams::other_skin(N)` (the built-in models were trained
//! on the calibrated one). `--speed X`: the board's clock runs X times as fast as the wall
//! clock (frames and presses alike; for tests that tap many times). Lines on stdin press the
//! pad:
//!
//! - `tap ROW COL [KGF]`: one cell (1-based, 4 × 6) pressed for 0.4 s, at 5 kgf by default;
//! - `press ROW COL [KGF]`: pressed until `release`;
//! - `release`.
//!
//! Frames are sent whether or not a host has the port open (a UART has no one to ask); one
//! that the pty cannot take is lost, as on the wire.

use std::cell::RefCell;
use std::io::{BufRead, Write};
use std::process::ExitCode;
use std::rc::Rc;
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::time::{Duration, Instant};

use baro_drivers::sim::SimClock;
use baro_drivers::{Address, Ms5611};
use fingertip::{Config, Fingertip, frame};
use hand_sim::fingertip::geometry::aot_geometry;
use hand_sim::fingertip::{CellSet, ContactPatch, FingertipPhysics, LawParams};
use serial2::SerialPort;

#[path = "common/board.rs"]
mod board;

/// How long a `tap` holds the cell, ns (as the host harness's presses).
const TAP_NS: u64 = 400_000_000;
/// A press's force when the line names none, kgf (the lightest of Table 2's).
const DEFAULT_KGF: f64 = 5.0;
/// The pad's resting pressures, hPa (the host harness's).
const BASELINE_HPA: [f64; 3] = [1013.2, 1012.9, 1013.4];

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("host_uart: {e}");
            ExitCode::FAILURE
        }
    }
}

/// What a line on stdin asks for.
enum Command {
    Press {
        cells: CellSet,
        kgf: f64,
        for_ns: Option<u64>,
    },
    Release,
}

fn parse(line: &str) -> Result<Command, String> {
    let words: Vec<&str> = line.split_whitespace().collect();
    let cell = |row: &str, col: &str, kgf: Option<&&str>| -> Result<(CellSet, f64), String> {
        let n = |w: &str| {
            w.parse::<u8>()
                .map_err(|_| format!("{w:?} is not a row or column"))
        };
        let cells = CellSet::rect(n(row)?, n(col)?, 1, 1)
            .ok_or_else(|| format!("cell {row}, {col} is off the 4 × 6 pad"))?;
        let kgf = kgf.map_or(Ok(DEFAULT_KGF), |k| {
            k.parse::<f64>()
                .ok()
                .filter(|k| k.is_finite() && *k >= 0.0)
                .ok_or_else(|| format!("{k:?} is not a force in kgf"))
        })?;
        Ok((cells, kgf))
    };
    match words.as_slice() {
        ["tap", row, col, rest @ ..] if rest.len() <= 1 => {
            let (cells, kgf) = cell(row, col, rest.first())?;
            Ok(Command::Press {
                cells,
                kgf,
                for_ns: Some(TAP_NS),
            })
        }
        ["press", row, col, rest @ ..] if rest.len() <= 1 => {
            let (cells, kgf) = cell(row, col, rest.first())?;
            Ok(Command::Press {
                cells,
                kgf,
                for_ns: None,
            })
        }
        ["release"] => Ok(Command::Release),
        _ => Err(format!(
            "{line:?}: expected `tap ROW COL [KGF]`, `press ROW COL [KGF]` or `release`"
        )),
    }
}

/// Reads stdin on its own thread; a line that is not a command is answered on stderr.
fn commands() -> Receiver<Command> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        for line in std::io::stdin().lock().lines() {
            let Ok(line) = line else { return };
            if line.trim().is_empty() {
                continue;
            }
            match parse(&line) {
                Ok(c) => {
                    if tx.send(c).is_err() {
                        return;
                    }
                }
                Err(e) => eprintln!("host_uart: {e}"),
            }
        }
    });
    rx
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let (mut seed, mut skin, mut speed) = (1u64, None, 1.0f64);
    while let Some(a) = args.next() {
        match (a.as_str(), args.next()) {
            ("--seed", Some(s)) => seed = s.parse().map_err(|_| format!("--seed {s:?}"))?,
            ("--skin", Some(s)) => {
                skin = Some(s.parse::<u64>().map_err(|_| format!("--skin {s:?}"))?);
            }
            ("--speed", Some(s)) => {
                speed = s
                    .parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite() && (0.1..=100.0).contains(x))
                    .ok_or_else(|| format!("--speed {s:?}: a factor from 0.1 to 100"))?;
            }
            _ => {
                return Err(format!(
                    "unknown argument {a:?}; usage: host_uart [--seed N] [--skin N] [--speed X]"
                ));
            }
        }
    }
    let law = skin.map_or(LawParams::CALIBRATED, |s| {
        LawParams::CALIBRATED.other_skin(s)
    });
    let physics = FingertipPhysics::new(law, BASELINE_HPA, 0.0).map_err(|e| e.to_string())?;
    let physics = Rc::new(RefCell::new(physics));
    let clock = SimClock::new();
    let mux = board::mux(&physics, &clock, seed);
    let switch = xca9548a::Xca9548a::new(mux, xca9548a::SlaveAddr::default());
    let parts = switch.split();
    let ports = [parts.i2c0, parts.i2c1, parts.i2c2];
    let sensors = ports.map(|port| Ms5611::new_with_i2c(port, Address::CsbLow));
    let mut delay = clock.delay();
    let mut tip = Fingertip::new(sensors, &mut delay, Config::DEFAULT, aot_geometry())
        .map_err(|e| format!("start-up: {e:?}"))?;

    let (mut line, client) = SerialPort::pair().map_err(|e| format!("pty: {e}"))?;
    let path = std::fs::read_link(format!(
        "/proc/self/fd/{}",
        std::os::fd::AsRawFd::as_raw_fd(&client)
    ))
    .map_err(|e| format!("pty path: {e}"))?;
    // Closed: the host opens it (the pty holds what is sent until then, up to its buffer).
    drop(client);
    line.set_write_timeout(Duration::from_millis(1))
        .map_err(|e| format!("pty: {e}"))?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "{}", path.display()).map_err(|e| e.to_string())?;
    // A test waits for this line through a pipe: it must not sit in a buffer.
    out.flush().map_err(|e| e.to_string())?;

    let commands = commands();
    let (start, start_ns) = (Instant::now(), clock.now_ns());
    let mut release_at: Option<u64> = None;
    let mut seq = 0u8;
    loop {
        let now_ns = clock.now_ns();
        loop {
            let command = match commands.try_recv() {
                Ok(c) => c,
                Err(TryRecvError::Empty) => break,
                // stdin closed: the pad is left as it is, the board runs on.
                Err(TryRecvError::Disconnected) => break,
            };
            let mut p = physics.borrow_mut();
            match command {
                Command::Press { cells, kgf, for_ns } => {
                    p.set_contact(now_ns, ContactPatch::from_kgf(cells, kgf))
                        .map_err(|e| e.to_string())?;
                    release_at = for_ns.map(|d| now_ns + d);
                }
                Command::Release => {
                    p.set_contact(now_ns, ContactPatch::NONE)
                        .map_err(|e| e.to_string())?;
                    release_at = None;
                }
            }
        }
        if release_at.is_some_and(|t| t <= now_ns) {
            physics
                .borrow_mut()
                .set_contact(now_ns, ContactPatch::NONE)
                .map_err(|e| e.to_string())?;
            release_at = None;
        }
        let t_us = now_ns / 1_000;
        let bytes = match tip.cycle(&mut delay, t_us) {
            Ok(estimate) => frame::encode(&estimate, seq),
            Err(_) => frame::fault(t_us, seq),
        };
        seq = seq.wrapping_add(1);
        // The simulated clock ran through the cycle's conversions: the wall clock catches up.
        let due = start + Duration::from_secs_f64((clock.now_ns() - start_ns) as f64 / 1e9 / speed);
        if let Some(wait) = due.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
        // A frame the pty cannot take (no host, a full buffer) is lost, as on the wire.
        let _ = line.write_all(&bytes);
    }
}
