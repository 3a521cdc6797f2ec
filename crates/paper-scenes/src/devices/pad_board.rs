//! Seed 002's tactile pad as a device a user's `handstack` opens: the ICM-20789 under Ecoflex
//! on a simulated Arduino Mega running ConfigurableFirmata (firmata-sim's board on a pty), as
//! the paper reads it (§III-C). The pad rests until it is tapped from outside
//! ([`PadBoard::tap`], or `tap R` lines to the `paper-scenes pad-board` process): then
//! hand-sim's pad presses region R as the paper's UR3 tapped it — one tap of its protocol (rest,
//! press, hold, release: 1.4 s of a 3 s slot), 1.2 mm deep, on a row of the region drawn from the
//! board's seed — on the wall clock.

use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use firmata_sim::{BoardKind, ChipBus, FirmwareKind, SimBoard, SimConfig as BoardConfig};
use hand_sim::imu_pad::tap::{PadTruth, RealisedTap};
use hand_sim::imu_pad::{ImuPadConfig, TapSpec};
use paper_experiments::tap_run::{DEPTH_MM, TRIGGER_ROWS};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::grasp_board::lock;
use crate::Error;
use crate::error::device;

/// The pad's regions (3 × 3).
pub const REGIONS: u8 = 9;

/// What to build.
#[derive(Debug, Clone)]
pub struct PadBoardConfig {
    /// The seed of the chip's noise, the rows the taps fall on and each tap's errors.
    pub seed: u64,
    /// The board's baud rate (its sketch's).
    pub baud: u32,
    /// From the board's port opening to its version report.
    pub boot_delay: Duration,
    /// Another pad than the paper's, drawn from this seed (hand-sim's
    /// `ImuPadConfig::other_pad`: its chip up to a row off, its tilt per newton scaled), on
    /// which the built-in contact CNN misplaces taps; `None`: the paper's pad.
    pub skin: Option<u64>,
}

impl Default for PadBoardConfig {
    /// Seed 10 (the tap scene's), 115 200 baud, the real board's 1.6 s boot.
    fn default() -> Self {
        PadBoardConfig {
            seed: 10,
            baud: 115_200,
            boot_delay: Duration::from_millis(1600),
            skin: None,
        }
    }
}

/// The pad's state: its truth since the last tap, on the wall clock since `epoch`.
struct Pad {
    config: ImuPadConfig,
    truth: PadTruth,
    epoch: Instant,
    rng: ChaCha8Rng,
    taps: Vec<RealisedTap>,
}

/// The pad and its board, until dropped.
pub struct PadBoard {
    board: SimBoard,
    pad: Arc<Mutex<Pad>>,
}

impl PadBoard {
    /// Builds the pad at rest and starts its board.
    pub fn spawn(config: &PadBoardConfig) -> Result<PadBoard, Error> {
        let paper = ImuPadConfig {
            taps: Vec::new(),
            ..ImuPadConfig::default()
        };
        let pad_config = match config.skin {
            Some(seed) => paper.other_pad(seed),
            None => paper,
        };
        let truth = PadTruth::new(Vec::new(), &pad_config);
        let pad = Arc::new(Mutex::new(Pad {
            config: pad_config,
            truth,
            epoch: Instant::now(),
            rng: ChaCha8Rng::seed_from_u64(config.seed),
            taps: Vec::new(),
        }));
        let env = {
            let pad = pad.clone();
            Box::new(move |t_us: u64| lock(&pad).truth.state(t_us))
        };
        let board = SimBoard::spawn(
            BoardConfig::default()
                .board(BoardKind::Mega2560)
                .firmware(FirmwareKind::Configurable)
                .baud(config.baud)
                .boot_delay(config.boot_delay)
                .bus(ChipBus::empty().with_icm20789(env, config.seed)),
        )
        .map_err(|e| device("pad board", e.to_string()))?;
        Ok(PadBoard { board, pad })
    }

    /// The board's port (a scene's `[sensors.imu_pad] firmata_port`).
    pub fn path(&self) -> &Path {
        self.board.path()
    }

    /// Taps region `region` (0…8, row-major from the pad's first row) now: its rest, press,
    /// hold and release follow on the wall clock. A tap replaces one still under way.
    ///
    /// Errors: a region outside 0…8.
    pub fn tap(&self, region: u8) -> Result<RealisedTap, Error> {
        if region >= REGIONS {
            return Err(device(
                "pad board",
                format!("region {region}: the pad has regions 0…8"),
            ));
        }
        let mut p = lock(&self.pad);
        let now_s = p.epoch.elapsed().as_secs_f64();
        let row = p
            .rng
            .random_range(TRIGGER_ROWS[usize::from(region / 3)].clone());
        let spec = TapSpec {
            column: region % 3 + 1,
            row,
            depth_mm: DEPTH_MM,
        };
        p.config.timing.start_s = now_s;
        let curve = p.config.mechanics.curve()?;
        let tap = {
            let Pad { config, rng, .. } = &mut *p;
            RealisedTap::realise(&spec, 0, config, &curve, rng)?
        };
        p.truth = PadTruth::new(vec![tap], &p.config);
        p.taps.push(tap);
        Ok(tap)
    }

    /// Every tap so far, in order.
    pub fn taps(&self) -> Vec<RealisedTap> {
        lock(&self.pad).taps.clone()
    }
}
