//! Seed 000's weighing rig (§2.2, Figure 3) as a device a user's `handstack` opens: the
//! fingertip's three MS5611 behind a TCA9548A on a simulated Arduino Mega running
//! ConfigurableFirmata (firmata-sim's board on a pty), under hand-sim's pad, on which weights
//! are placed from outside ([`FingertipBoard::place_gf`], or `place G` lines to the
//! `paper-scenes fingertip-board` process) as the paper placed them: on the whole pad.

use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use baro_drivers::sim::Conditions;
use firmata_sim::{BaroEnv, BoardKind, ChipBus, FirmwareKind, SimBoard, SimConfig as BoardConfig};
use hand_sim::fingertip::{
    Cell, CellSet, ContactPatch, FingertipConfig, FingertipPhysics, LawParams,
};
use rand::Rng;

use super::grasp_board::lock;
use crate::Error;
use crate::error::device;

/// What to build.
#[derive(Debug, Clone)]
pub struct FingertipBoardConfig {
    /// The seed of the sensors' baselines and noise.
    pub seed: u64,
    /// The board's baud rate (its sketch's).
    pub baud: u32,
    /// From the board's port opening to its version report.
    pub boot_delay: Duration,
    /// Another fingertip's skin (hand-sim's [`LawParams::other_skin`] of this seed); `None`:
    /// the calibrated fingertip the built-in models were trained on.
    pub skin: Option<u64>,
}

impl Default for FingertipBoardConfig {
    /// Seed 1, 115 200 baud, the real board's 1.6 s boot, the calibrated skin.
    fn default() -> Self {
        FingertipBoardConfig {
            seed: 1,
            baud: 115_200,
            boot_delay: Duration::from_millis(1600),
            skin: None,
        }
    }
}

/// The pad: its physics on the wall clock since `epoch`, and the weight on it.
struct Pad {
    physics: FingertipPhysics,
    epoch: Instant,
    last_ns: u64,
    placed_gf: f64,
}

impl Pad {
    /// Now on the pad's clock, never before its last change.
    fn now_ns(&self) -> u64 {
        u64::try_from(self.epoch.elapsed().as_nanos())
            .unwrap_or(u64::MAX)
            .max(self.last_ns)
    }
}

/// The rig: its board's port until dropped.
pub struct FingertipBoard {
    board: SimBoard,
    pad: Arc<Mutex<Pad>>,
}

impl FingertipBoard {
    /// Builds the pad (nothing on it) and starts its board.
    pub fn spawn(config: &FingertipBoardConfig) -> Result<FingertipBoard, Error> {
        let defaults = FingertipConfig::default();
        let law = config.skin.map_or(LawParams::CALIBRATED, |s| {
            LawParams::CALIBRATED.other_skin(s)
        });
        let physics = FingertipPhysics::new(
            law,
            sensor_baselines(config.seed, "fingertip-board"),
            defaults.drift_hpa_per_min,
        )?;
        let pad = Arc::new(Mutex::new(Pad {
            physics,
            epoch: Instant::now(),
            last_ns: 0,
            placed_gf: 0.0,
        }));
        let envs: [BaroEnv; 3] = core::array::from_fn(|k| {
            let pad = pad.clone();
            let temperature = defaults.temperature_c;
            Box::new(move |_board_ns: u64| {
                let mut p = lock(&pad);
                let t_ns = p.now_ns();
                Conditions {
                    pressure_mbar: p.physics.pressure_hpa(k, t_ns),
                    temperature_celsius: temperature,
                }
            }) as BaroEnv
        });
        let board = spawn_mega(envs, config.seed, config.baud, config.boot_delay)?;
        Ok(FingertipBoard { board, pad })
    }

    /// The board's port (a scene's `[sensors.fingertip] firmata_port`).
    pub fn path(&self) -> &Path {
        self.board.path()
    }

    /// From now on `gf` rests on the whole pad (0: nothing).
    ///
    /// Errors: a weight that is negative or not a number.
    pub fn place_gf(&self, gf: f64) -> Result<(), Error> {
        let mut p = lock(&self.pad);
        let now = p.now_ns();
        let all = Cell::all().fold(CellSet::EMPTY, CellSet::with);
        p.physics
            .set_contact(now, ContactPatch::from_kgf(all, gf / 1000.0))?;
        p.last_ns = now;
        p.placed_gf = gf;
        Ok(())
    }

    /// The weight on the pad, gf.
    pub fn placed_gf(&self) -> f64 {
        lock(&self.pad).placed_gf
    }
}

/// Three sensors' resting pressures, hPa: hand-sim's default baseline plus up to 1 hPa each,
/// drawn from `seed`'s stream `name` (as hand-sim's own fingertip draws them).
pub(crate) fn sensor_baselines(seed: u64, name: &str) -> [f64; 3] {
    let base = FingertipConfig::default().baseline_hpa;
    let mut rng = hand_sim::seed::stream(seed, name);
    core::array::from_fn(|_| base + rng.random::<f64>())
}

/// A Mega running ConfigurableFirmata with three MS5611 (pressures from `envs`) behind a
/// TCA9548A on its I2C, on a pty.
pub(crate) fn spawn_mega(
    envs: [BaroEnv; 3],
    seed: u64,
    baud: u32,
    boot_delay: Duration,
) -> Result<SimBoard, Error> {
    SimBoard::spawn(
        BoardConfig::default()
            .board(BoardKind::Mega2560)
            .firmware(FirmwareKind::Configurable)
            .baud(baud)
            .boot_delay(boot_delay)
            .bus(ChipBus::empty().with_fingertips(envs, seed)),
    )
    .map_err(|e| device("fingertip board", e.to_string()))
}
