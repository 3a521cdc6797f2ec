//! `handstack` on a bench without fingertip hardware: the same command line ([`handstack::cli`]),
//! every I2C bus a scene names served by an MS5611 chip model (baro-drivers' `sim`) instead of
//! `/dev/i2c-*`, in real time. The hand and the arm stay real devices: a servo bus (a USB
//! adapter, or `dxl-sim` on a pty), a UR controller (or `ur-sim`). The project's tests run it
//! so, against `dxl-sim` in its own process, with real signals.
//!
//! ```text
//! dxl-sim --servo mx28:1 --servo mx28:2          # prints /dev/pts/N
//! cargo run -p handstack --example bench_rig -- run rig.toml   # its serial_port = /dev/pts/N
//! ```
//!
//! The model fingertip rests at 1000 mbar and is pressed by 1, 2 and 3 mbar (sensors 1–3)
//! from `HANDSTACK_RIG_PRESS_S` seconds after start (default 0.3; `never`: an empty hand).
//! For the tests of a run's endings, two faults of the rig's own: `HANDSTACK_RIG_PANIC_S`
//! makes a sensor read panic from that many seconds after start on (a bug in a part's code),
//! `HANDSTACK_RIG_SLOW_MS` adds that much to every conversion wait (a bus far slower than the
//! loop's rate).

use baro_drivers::sim::{Conditions, Ms5611Sim, SimClock};
use embedded_hal::delay::DelayNs;
use hand_control::grasp_loop::{LoopClock, StdClock};
use handstack::stack::platform::{I2cBus, Platform};
use std::time::{Duration, Instant};

/// Chip models on a wall clock.
struct Rig {
    /// The chips' conversion clock, advanced by the drivers' delays as they sleep.
    chips: SimClock,
    /// The frames' and the loop's clock.
    wall: StdClock,
    /// When the pad is pressed (`None`: never).
    press_at: Option<Duration>,
    /// When a sensor read starts to panic (`None`: never).
    panic_at: Option<Duration>,
    /// Added to every conversion wait.
    slow: Duration,
    start: Instant,
}

/// Sleeps as a driver asks (and `slow` more), and moves the chips' clock on by as much.
struct RigDelay(SimClock, Duration);

impl DelayNs for RigDelay {
    fn delay_ns(&mut self, ns: u32) {
        std::thread::sleep(Duration::from_nanos(u64::from(ns)) + self.1);
        self.0.advance_ns(u64::from(ns));
    }
}

impl Platform for Rig {
    fn open_i2c(&self, path: &str) -> Result<I2cBus, String> {
        // Sensor k of the scene's list is pressed by k + 1 mbar; any other bus is the third.
        let k = path
            .rsplit('-')
            .next()
            .and_then(|n| n.parse::<u32>().ok())
            .unwrap_or(2);
        let (press_at, panic_at, start) = (self.press_at, self.panic_at, self.start);
        let env = move |_t_ns: u64| {
            if panic_at.is_some_and(|at| start.elapsed() >= at) {
                panic!(
                    "the rig's sensor {} model failed (HANDSTACK_RIG_PANIC_S)",
                    k + 1
                );
            }
            let pressed = press_at.is_some_and(|at| start.elapsed() >= at);
            Conditions {
                pressure_mbar: 1000.0 + if pressed { f64::from(k) + 1.0 } else { 0.0 },
                temperature_celsius: 25.0,
            }
        };
        Ok(I2cBus::new(Ms5611Sim::new(env, self.chips.clone())))
    }

    fn delay(&self) -> Box<dyn DelayNs + Send> {
        Box::new(RigDelay(self.chips.clone(), self.slow))
    }

    fn clock(&self) -> Box<dyn LoopClock + Send> {
        Box::new(self.wall)
    }
}

/// The seconds in environment variable `name` (`never` or absent: `default`).
fn seconds(name: &str, default: Option<Duration>) -> Result<Option<Duration>, String> {
    match std::env::var(name) {
        Ok(v) if v == "never" => Ok(None),
        Ok(v) => match v.parse::<f64>() {
            Ok(s) if s.is_finite() && s >= 0.0 => Ok(Some(Duration::from_secs_f64(s))),
            _ => Err(format!("error: {name} is `{v}`: seconds, or `never`")),
        },
        Err(_) => Ok(default),
    }
}

fn main() -> std::process::ExitCode {
    let env =
        seconds("HANDSTACK_RIG_PRESS_S", Some(Duration::from_millis(300))).and_then(|press| {
            let panic = seconds("HANDSTACK_RIG_PANIC_S", None)?;
            let slow = seconds("HANDSTACK_RIG_SLOW_MS", None)?.map(|s| s / 1000);
            Ok((press, panic, slow.unwrap_or_default()))
        });
    let (press_at, panic_at, slow) = match env {
        Ok(v) => v,
        Err(e) => {
            eprintln!("{e}");
            return std::process::ExitCode::from(2);
        }
    };
    let start = Instant::now();
    handstack::cli::main(&|| {
        Box::new(Rig {
            chips: SimClock::new(),
            wall: StdClock::new(),
            press_at,
            panic_at,
            slow,
            start,
        })
    })
}
