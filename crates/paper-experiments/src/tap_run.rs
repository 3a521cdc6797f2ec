//! Seed 002 §IV-B end to end: ICM-20789 pad taps (hand-sim, simulated time)
//! → pressure trigger → 4 × 38 accelerometer / gyroscope window → contact locator → region →
//! moveL on the UR3 (the simulated one on loopback, or any controller `UrArm` reaches), through
//! the real ur_rtde. Shared by the `tap_to_move` example (the committed CNN as the locator; it
//! writes `docs/arm-tap-to-move.md`), the `tap_to_move` test (with a stand-in locator, to check
//! the trigger, the window and the moves on their own) and handstack's tap-to-UR3 scene.

use std::borrow::Borrow;
use std::net::Ipv4Addr;
use std::ops::RangeInclusive;
use std::path::{Path, PathBuf};
use std::time::Duration;

use hand_sim::imu_pad::{ImuPad, ImuPadConfig, TapSpec, TapWindow, WINDOW_SAMPLES, WINDOW_SIGNALS};
use hand_traits::{Arm, ContactLocator, ImuFrame, LinearMotion, Pose};
use handstack::tap_to_move::{RegionToGrid, TapToMove, TapToMoveConfig};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use ur_bridge::{UrArm, UrConfig, UrError};
use ur_sim::{SimConfig, TimeScale, UrSim};

use crate::cnn_eval::{self, Committed};
use tactile_nets::contact_cnn;

/// The 4 × 38 window of §IV-A: acc x, acc y (m/s²), gyro x, gyro y (rad/s).
pub type Window = [[f32; WINDOW_SAMPLES]; WINDOW_SIGNALS];

/// Rows a 1.2 mm tap can be placed on, per region group 0 / 1 / 2 (rows 1–8 / 9–16 / 17–24):
/// the rows whose every tap the 20 Pa pressure trigger sees, in every column. In hand-sim's pad
/// (seed 10, ten taps per position) the smallest rise of a 1.2 mm tap is ≥ 60 Pa on rows 7–21
/// in every column; 13–21 Pa on row 6 and 1.1–1.5 Pa on row 22 in columns 1 and 3; ≤ 2.2 Pa
/// on rows 1–5 and (docs/arm.md) 23–24, against 0.8 Pa rms noise. A tap the trigger misses
/// would shift every later tap's window onto the next tap. A property of the pad's pressure
/// coupling, not of the locator.
pub const TRIGGER_ROWS: [RangeInclusive<u8>; 3] = [7..=8, 9..=16, 17..=21];
/// Tap depth: the real-time test's depth (§IV-B), mm.
pub const DEPTH_MM: f64 = cnn_eval::REALTIME_DEPTH_UM as f64 / 1000.0;
/// The contact CNN the tap runs locate with: [`cnn_eval::REALTIME`].
pub const LOCATOR: Committed = cnn_eval::REALTIME;

/// Path of [`LOCATOR`]'s weights below the workspace root `root`.
pub fn locator_path(root: &Path) -> PathBuf {
    root.join(cnn_eval::MODEL_DIR).join(LOCATOR.file())
}
/// The pad's scene seed.
pub const PAD_SEED: u64 = 10;
/// Taps per region of the committed run and the scene: at least 10, so that one tap moves the
/// figure by at most 1.1 points.
pub const TAPS_PER_REGION: usize = 10;
/// Controller seconds per wall-clock second of the simulated UR3 in the committed run and the
/// scene: moves keep their controller-time profiles and end 10 × sooner in wall time.
pub const TIME_SCALE: f64 = 10.0;

/// `per_region` rounds of nine taps, regions 0…8 in order within a round; each tap on a row
/// drawn uniformly (ChaCha8 seeded by `seed`) from its region's [`TRIGGER_ROWS`], in the
/// region's column, [`DEPTH_MM`] deep.
pub fn schedule(seed: u64, per_region: usize) -> Vec<TapSpec> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..per_region)
        .flat_map(|_| 0..9u8)
        .map(|r| TapSpec {
            column: r % 3 + 1,
            row: rng.random_range(TRIGGER_ROWS[usize::from(r / 3)].clone()),
            depth_mm: DEPTH_MM,
        })
        .collect()
}

/// The 38 frames around the trigger as hand-sim cuts a training window (trigger = frame 19).
pub fn window(frames: &[ImuFrame]) -> Window {
    let centre = frames.get(WINDOW_SAMPLES / 2).map_or(0, |f| f.t_us);
    TapWindow::extract(frames, centre)
        .map(|w| w.signals)
        .unwrap_or([[f32::NAN; WINDOW_SAMPLES]; WINDOW_SIGNALS])
}

/// The window as the CNN reads it: channel-major, acc in mm/s², gyro in mrad/s
/// ([`contact_cnn::SI_TO_INPUT`]).
pub fn cnn_window(frames: &[ImuFrame]) -> [f32; WINDOW_SAMPLES * WINDOW_SIGNALS] {
    let w = window(frames);
    core::array::from_fn(|i| w[i / WINDOW_SAMPLES][i % WINDOW_SAMPLES] * contact_cnn::SI_TO_INPUT)
}

/// The experiment with its window placed like the training windows: `training_centre_frames`
/// after the trigger at frame 19 of 38.
pub fn training_aligned() -> TapToMoveConfig {
    TapToMoveConfig::centred_after_trigger(cnn_eval::training_centre_frames())
}

/// One cycle's outcome.
#[derive(Debug, Clone, Copy)]
pub struct Row {
    /// The tapped region.
    pub region: u16,
    /// The tapped grid row, 1…24.
    pub row: u8,
    /// The region the locator named.
    pub located: u16,
    /// The locator's confidence.
    pub confidence: f32,
    /// Trigger time minus the start of the press, s (simulated pad time).
    pub trigger_after_press_s: f64,
    /// Whether the trigger fell inside the tap's press / hold / release.
    pub trigger_in_tap: bool,
    /// Trigger to the window's last frame, s (simulated pad time).
    pub window_s: f64,
    /// Wall time of the locator, s.
    pub locate_s: f64,
    /// Wall time of the moveL to the grid pose, s (the controller's time over the simulator's
    /// time scale).
    pub move_s: f64,
    /// Controller time of the moveL to the grid pose (RTDE `timestamp` before and after), s:
    /// the same at any time scale, and on hardware.
    pub move_controller_s: f64,
    /// Final TCP distance from the located region's grid pose, m.
    pub tcp_error_m: f64,
}

/// Runs one cycle per tap of `taps` with `locator` against a simulator on 127.0.0.`octet`
/// whose controller time runs `time_scale` × the wall clock.
pub fn run<L, B>(
    octet: u8,
    time_scale: TimeScale,
    taps: Vec<TapSpec>,
    experiment_config: TapToMoveConfig,
    locator: &mut L,
    to_input: impl FnMut(&[ImuFrame]) -> B,
) -> Result<Vec<Row>, String>
where
    L: ContactLocator,
    B: Borrow<L::Input>,
{
    let sim = UrSim::start(SimConfig {
        address: Ipv4Addr::new(127, 0, 0, octet),
        time_scale,
        ..SimConfig::default()
    })
    .map_err(|e| e.to_string())?;
    let mut arm = connect(&format!("127.0.0.{octet}"))?;
    let pad = ImuPadConfig {
        taps,
        ..ImuPadConfig::default()
    };
    let pad = ImuPad::new(&pad, PAD_SEED).map_err(|e| e.to_string())?;
    run_on(&mut arm, pad, experiment_config, locator, to_input)
        .map_err(|e| format!("{e}; sim log {:?}", sim.log()))
}

/// Connects to the UR controller at `host` with the experiment's move timeout.
pub fn connect(host: &str) -> Result<UrArm, String> {
    let mut config = UrConfig::new(host);
    config.move_timeout = Duration::from_secs(20);
    UrArm::connect(config).map_err(|e| e.to_string())
}

/// Runs one cycle per tap of `pad` with `locator`, moving `arm`.
pub fn run_on<L, B>(
    arm: &mut UrArm,
    mut pad: ImuPad,
    experiment_config: TapToMoveConfig,
    locator: &mut L,
    to_input: impl FnMut(&[ImuFrame]) -> B,
) -> Result<Vec<Row>, String>
where
    L: ContactLocator,
    B: Borrow<L::Input>,
{
    let mut to_input = to_input;
    let grid = RegionToGrid::ur3_default().map_err(|e| e.to_string())?;
    let mut experiment = TapToMove::new(&grid, experiment_config);

    let timing = pad.timing();
    let mut rows = Vec::with_capacity(pad.taps().len());
    let mut clocked = Clocked {
        arm,
        last_move_s: 0.0,
    };
    for k in 0..pad.taps().len() {
        let report = experiment
            .cycle(&mut pad, locator, &mut clocked, &mut to_input)
            .map_err(|e| format!("cycle {k}: {e}"))?;
        let move_controller_s = clocked.last_move_s;
        let arm = &mut *clocked.arm;
        let tap = &pad.taps()[k];
        let press_s = tap.start_s + timing.lead_s;
        let t = report.trigger_t_us as f64 * 1e-6;
        let target = grid.pose(report.region).map_err(|e| e.to_string())?;
        let at = arm.tool_pose().map_err(|e| e.to_string())?;
        rows.push(Row {
            region: u16::from(tap.position.region()),
            row: tap.position.row(),
            located: report.region,
            confidence: report.confidence,
            trigger_after_press_s: t - press_s,
            trigger_in_tap: t >= press_s
                && t <= press_s + timing.press_s + timing.hold_s + timing.release_s,
            window_s: report.window_wait_us as f64 * 1e-6,
            locate_s: report.locate_s,
            move_s: report.move_s,
            move_controller_s,
            tcp_error_m: at.distance_m(target),
        });
    }
    Ok(rows)
}

/// `UrArm` as the experiment's [`Arm`], keeping the controller-clock duration (RTDE
/// `timestamp`, the controller's own clock on hardware and in the simulator) of its last move.
struct Clocked<'a> {
    arm: &'a mut UrArm,
    last_move_s: f64,
}

impl Arm for Clocked<'_> {
    type Error = UrError;

    fn move_linear(&mut self, target: &Pose, motion: &LinearMotion) -> Result<(), UrError> {
        let t0 = self.arm.controller_time_s()?;
        self.arm.move_linear(target, motion)?;
        self.last_move_s = self.arm.controller_time_s()? - t0;
        Ok(())
    }

    fn tcp_pose(&mut self) -> Result<Pose, UrError> {
        Arm::tcp_pose(self.arm)
    }

    fn stop(&mut self) -> Result<(), UrError> {
        Arm::stop(self.arm)
    }
}

/// Taps located correctly and taps, per tapped region 0…8.
pub fn per_region(rows: &[Row]) -> [(usize, usize); 9] {
    let mut counts = [(0, 0); 9];
    for r in rows {
        if let Some(c) = counts.get_mut(usize::from(r.region)) {
            c.0 += usize::from(r.located == r.region);
            c.1 += 1;
        }
    }
    counts
}

/// `correct / n = pct %` with the percentage to one decimal.
pub fn fraction(correct: usize, n: usize) -> String {
    format!(
        "{correct} / {n} = {:.1} %",
        100.0 * correct as f64 / n.max(1) as f64
    )
}

/// The rows as a markdown report, with `locator` and the `window` placement named in its
/// header; `time_scale` is the simulated controller's.
pub fn markdown(rows: &[Row], locator: &str, window: &str, time_scale: TimeScale) -> String {
    let correct = rows.iter().filter(|r| r.located == r.region).count();
    let [g0, g1, g2] = TRIGGER_ROWS.map(|r| format!("{}–{}", r.start(), r.end()));
    let mut md = format!(
        "## {window}\n\n\
         **Set:** hand-sim ICM-20789 pad (seed {PAD_SEED}), {n} taps of {DEPTH_MM} mm, \
         {per} per region in {per} rounds of regions 0…8; each tap in its region's column on a \
         row drawn uniformly (ChaCha8, seed {PAD_SEED}) from the rows the pressure trigger sees: \
         {g0} / {g1} / {g2} for region groups 0 / 1 / 2. Pressure trigger 20 Pa, 4 × 38 window \
         ({window}); locator: {locator}; moveL at 0.25 m/s, 1.2 m/s² to the located region's grid \
         pose on the simulated UR3 through ur_rtde 1.6.5, the simulator's controller time running \
         {scale} × the wall clock (`SimConfig::time_scale`). Pad times are simulated; moveL times \
         are given in controller time (RTDE `timestamp`) and wall time; locate times are wall time \
         on this machine.\n\n\
         **Located correctly: {all}** (paper, real time: 93 %, §V / Fig. 8D).\n\n\
         | region | {heads} |\n|---|{dashes}\n| located | {cells} |\n\n\
         | region tapped | row | located | confidence | trigger after press start (in tap) | window completes | locate | moveL to grid pose (controller) | moveL (wall) | final TCP error |\n\
         |---|---|---|---|---|---|---|---|---|---|\n",
        n = rows.len(),
        per = rows.len() / 9,
        scale = time_scale.factor(),
        all = fraction(correct, rows.len()),
        heads = (0..9)
            .map(|r| r.to_string())
            .collect::<Vec<_>>()
            .join(" | "),
        dashes = "---|".repeat(9),
        cells = per_region(rows)
            .iter()
            .map(|&(c, n)| format!("{c} / {n}"))
            .collect::<Vec<_>>()
            .join(" | "),
    );
    for r in rows {
        md += &format!(
            "| {} | {} | {} | {:.3} | {:.3} s ({}) | +{:.3} s | {:.1} µs | {:.3} s | {:.3} s | {:.2e} m |\n",
            r.region,
            r.row,
            r.located,
            r.confidence,
            r.trigger_after_press_s,
            if r.trigger_in_tap { "yes" } else { "no" },
            r.window_s,
            r.locate_s * 1e6,
            r.move_controller_s,
            r.move_s,
            r.tcp_error_m
        );
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn schedule_is_seeded_round_robin_on_trigger_rows() {
        let taps = schedule(PAD_SEED, TAPS_PER_REGION);
        assert_eq!(taps.len(), 9 * TAPS_PER_REGION);
        assert_eq!(taps, schedule(PAD_SEED, TAPS_PER_REGION), "seeded");
        assert_ne!(taps, schedule(PAD_SEED + 1, TAPS_PER_REGION));
        for (k, t) in taps.iter().enumerate() {
            let region = t.position().expect("on the grid").region();
            assert_eq!(usize::from(region), k % 9, "regions 0…8 in every round");
            assert!(TRIGGER_ROWS[usize::from(region / 3)].contains(&t.row));
            assert_eq!(t.depth_mm, DEPTH_MM);
        }
        // Positions vary inside each region.
        for region in 0..9 {
            let mut rows: Vec<u8> = taps.iter().skip(region).step_by(9).map(|t| t.row).collect();
            rows.dedup();
            assert!(rows.len() > 1, "region {region}: {rows:?}");
        }
    }

    #[test]
    fn per_region_counts_each_tapped_region() {
        let row = |region, located| Row {
            region,
            row: 12,
            located,
            confidence: 1.0,
            trigger_after_press_s: 0.0,
            trigger_in_tap: true,
            window_s: 0.0,
            locate_s: 0.0,
            move_s: 0.0,
            move_controller_s: 0.0,
            tcp_error_m: 0.0,
        };
        let counts = per_region(&[row(4, 4), row(4, 1), row(0, 0), row(9, 9)]);
        assert_eq!(counts[4], (1, 2));
        assert_eq!(counts[0], (1, 1));
        assert_eq!(counts[1], (0, 0));
        assert_eq!(fraction(1, 2), "1 / 2 = 50.0 %");
        assert_eq!(fraction(0, 0), "0 / 0 = 0.0 %");
    }
}
