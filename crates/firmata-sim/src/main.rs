//! `firmata-sim`: a simulated Arduino running Firmata on a pseudo-terminal.
//!
//! Prints the pty's path (`/dev/pts/N`) on one line, then serves the board in real time until
//! SIGINT or SIGTERM, and exits 0. The board resets each time its port opens.

use std::io::Write;
use std::process::ExitCode;
use std::str::FromStr;
use std::time::Duration;

use baro_drivers::sim::Conditions;
use clap::{Parser, ValueEnum};
use firmata_sim::{
    BoardKind, ChipBus, ConstantVolts, FirmwareKind, REST_MBAR, SimBoard, SimConfig,
};
use imu_icm20789::sim::TrueState;
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// A simulated Arduino running Firmata on a pseudo-terminal.
#[derive(Debug, Parser)]
#[command(
    name = "firmata-sim",
    version,
    about = "A simulated Arduino running Firmata on a pseudo-terminal, for client tests"
)]
struct Args {
    /// The pin set.
    #[arg(long, value_enum, default_value_t = Board::Uno)]
    board: Board,
    /// The sketch: StandardFirmata 2.5.9 or ConfigurableFirmata 2.10.1 (with steppers).
    #[arg(long, value_enum, default_value_t = Sketch::Configurable)]
    firmware: Sketch,
    /// The sketch's baud rate.
    #[arg(long, default_value_t = 57_600)]
    baud: u32,
    /// From the port opening to the version report, ms (bootloader and setup()).
    #[arg(long = "boot-ms", default_value_t = 1600)]
    boot_ms: u64,
    /// An analog pin's constant voltage, AN=VOLTS (e.g. A0=1.25); repeat for each pin.
    #[arg(long = "analog", value_name = "AN=VOLTS")]
    analog: Vec<AnalogPin>,
    /// The three fingertip barometers' pressures, mbar (behind the TCA9548A at 0x70).
    #[arg(
        long = "fingertip-mbar",
        value_name = "P0,P1,P2",
        value_delimiter = ',',
        num_args = 3
    )]
    fingertip_mbar: Option<Vec<f64>>,
    /// No fingertip barometers (nor their switch) on the I2C bus.
    #[arg(long)]
    no_fingertips: bool,
    /// No ICM-20789 on the I2C bus.
    #[arg(long)]
    no_imu: bool,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
enum Board {
    Uno,
    Mega2560,
}

#[derive(Debug, Clone, Copy, ValueEnum)]
enum Sketch {
    Standard,
    Configurable,
}

/// One `--analog`.
#[derive(Debug, Clone, Copy)]
struct AnalogPin {
    channel: u8,
    volts: f32,
}

impl FromStr for AnalogPin {
    type Err = String;

    fn from_str(s: &str) -> Result<AnalogPin, String> {
        let (pin, volts) = s
            .split_once('=')
            .ok_or_else(|| format!("{s:?} is not AN=VOLTS"))?;
        let channel = pin
            .strip_prefix('A')
            .and_then(|n| n.parse::<u8>().ok())
            .filter(|n| *n < 16)
            .ok_or_else(|| format!("{pin:?} is not an analog pin A0 … A15"))?;
        let volts = volts
            .parse::<f32>()
            .ok()
            .filter(|v| (0.0..=5.0).contains(v))
            .ok_or_else(|| format!("{volts:?} is not a voltage in 0 … 5"))?;
        Ok(AnalogPin { channel, volts })
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("firmata-sim: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run(args: &Args) -> std::io::Result<()> {
    // Registered before the board starts, so a signal during start-up still ends cleanly.
    let mut signals = Signals::new([SIGINT, SIGTERM])?;
    let mut bus = ChipBus::empty();
    if !args.no_fingertips {
        let mbar = args
            .fingertip_mbar
            .clone()
            .unwrap_or_else(|| vec![REST_MBAR; 3]);
        let env = |p: f64| -> firmata_sim::BaroEnv {
            Box::new(move |_| Conditions {
                pressure_mbar: p,
                temperature_celsius: 25.0,
            })
        };
        bus = bus.with_fingertips([env(mbar[0]), env(mbar[1]), env(mbar[2])], 1);
    }
    if !args.no_imu {
        bus = bus.with_icm20789(
            Box::new(|_| TrueState {
                accel_mps2: [0.0, 0.0, 9.81],
                gyro_rps: [0.0; 3],
                pressure_pa: REST_MBAR * 100.0,
                temperature_c: 25.0,
            }),
            2,
        );
    }
    let volts = ConstantVolts::default();
    for pin in &args.analog {
        volts.set(pin.channel, pin.volts);
    }
    let sim = SimBoard::spawn(SimConfig {
        board: match args.board {
            Board::Uno => BoardKind::Uno,
            Board::Mega2560 => BoardKind::Mega2560,
        },
        firmware: match args.firmware {
            Sketch::Standard => FirmwareKind::Standard,
            Sketch::Configurable => FirmwareKind::Configurable,
        },
        baud: args.baud,
        boot_delay: Duration::from_millis(args.boot_ms),
        bus,
        volts,
        analog: None,
    })?;
    let mut out = std::io::stdout().lock();
    writeln!(out, "{}", sim.path().display())?;
    // A CI job or test waits for this line through a pipe: it must not sit in a buffer.
    out.flush()?;
    drop(out);
    let _ = signals.forever().next();
    drop(sim);
    Ok(())
}
