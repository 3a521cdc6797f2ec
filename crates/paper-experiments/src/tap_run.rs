//! Seed 002 §IV-B end to end: ICM-20789 pad taps (hand-sim, simulated time)
//! → pressure trigger → 4 × 38 accelerometer / gyroscope window → contact locator → region →
//! moveL on the UR3 (the simulated one on loopback, or any controller `UrArm` reaches), through
//! the real ur_rtde. Shared by the `tap_to_move` example (the committed CNN as the locator; it
//! writes `docs/arm-tap-to-move.md`), the `tap_to_move` test (with a stand-in locator, to check
//! the trigger, the window and the moves on their own) and handstack's tap-to-UR3 scene.

use std::borrow::Borrow;
use std::net::Ipv4Addr;
use std::time::Duration;

use hand_sim::imu_pad::{ImuPad, ImuPadConfig, TapSpec, TapWindow, WINDOW_SAMPLES, WINDOW_SIGNALS};
use hand_traits::{ContactLocator, ImuFrame};
use ur_bridge::sim::{SimConfig, UrSim};
use ur_bridge::tap_to_move::{TapToMove, TapToMoveConfig};
use ur_bridge::{RegionToGrid, UrArm, UrConfig};

/// The 4 × 38 window of §IV-A: acc x, acc y (m/s²), gyro x, gyro y (rad/s).
pub type Window = [[f32; WINDOW_SAMPLES]; WINDOW_SIGNALS];

/// Rows tapped for region groups 0 / 1 / 2, one triple per round. In hand-sim's pad a 1.2 mm
/// tap on rows 1–5 or 23–24 raises the pressure by ≤ 5.5 Pa (0.8 Pa rms noise), under any
/// usable trigger threshold (docs/arm.md); rows 6–22 rise ≥ 55 Pa.
pub const ROUNDS: [[u8; 3]; 3] = [[8, 12, 18], [7, 13, 19], [6, 10, 20]];
/// Tap depth: the real-time CNN's training depth (§IV-B), mm.
pub const DEPTH_MM: f64 = 1.2;
/// The pad's scene seed.
pub const PAD_SEED: u64 = 10;

/// Nine taps a round, regions 0…8 in order, on the rows of `rounds`.
pub fn schedule(rounds: &[[u8; 3]]) -> Vec<TapSpec> {
    rounds
        .iter()
        .flat_map(|rows| {
            (0..9u8).map(move |r| TapSpec {
                column: r % 3 + 1,
                row: rows[usize::from(r / 3)],
                depth_mm: DEPTH_MM,
            })
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

/// The window as the CNN reads it: channel-major, acc in mm/s², gyro in mrad/s (the units of
/// hand-sim's tap dataset it was trained on).
pub fn cnn_window(frames: &[ImuFrame]) -> [f32; WINDOW_SAMPLES * WINDOW_SIGNALS] {
    let w = window(frames);
    core::array::from_fn(|i| w[i / WINDOW_SAMPLES][i % WINDOW_SAMPLES] * 1e3)
}

/// Frames from the trigger to the centre hand-sim's training windows are cut around (the middle
/// of press + hold + release, `TapTiming::centre_s`), less the ~1 frame the trigger lags the
/// press: where a window must sit to look like the CNN's training data.
pub fn training_centre_frames() -> usize {
    let c = ImuPadConfig::default();
    let t = c.timing;
    let centre_after_press_s = 0.5 * (t.press_s + t.hold_s + t.release_s);
    ((centre_after_press_s * c.sample_rate_hz).round() as usize).saturating_sub(1)
}

/// The experiment with its window placed like the training windows: `training_centre_frames`
/// after the trigger at frame 19 of 38.
pub fn training_aligned() -> TapToMoveConfig {
    let shift = training_centre_frames().min(WINDOW_SAMPLES / 2);
    TapToMoveConfig {
        frames_before: WINDOW_SAMPLES / 2 - shift,
        frames_after: WINDOW_SAMPLES / 2 + shift,
        ..TapToMoveConfig::default()
    }
}

/// One cycle's outcome.
#[derive(Debug, Clone, Copy)]
pub struct Row {
    /// The tapped region.
    pub region: u16,
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
    /// Wall time of the moveL to the grid pose, s.
    pub move_s: f64,
    /// Final TCP distance from the located region's grid pose, m.
    pub tcp_error_m: f64,
}

/// Runs one cycle per tap of `taps` with `locator` against a simulator on 127.0.0.`octet`.
pub fn run<L, B>(
    octet: u8,
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
    for k in 0..pad.taps().len() {
        let report = experiment
            .cycle(&mut pad, locator, arm, &mut to_input)
            .map_err(|e| format!("cycle {k}: {e}"))?;
        let tap = &pad.taps()[k];
        let press_s = tap.start_s + timing.lead_s;
        let t = report.trigger_t_us as f64 * 1e-6;
        let target = grid.pose(report.region).map_err(|e| e.to_string())?;
        let at = arm.tool_pose().map_err(|e| e.to_string())?;
        rows.push(Row {
            region: u16::from(tap.position.region()),
            located: report.region,
            confidence: report.confidence,
            trigger_after_press_s: t - press_s,
            trigger_in_tap: t >= press_s
                && t <= press_s + timing.press_s + timing.hold_s + timing.release_s,
            window_s: report.window_wait_us as f64 * 1e-6,
            locate_s: report.locate_s,
            move_s: report.move_s,
            tcp_error_m: at.distance_m(target),
        });
    }
    Ok(rows)
}

/// The rows as a markdown report, with `locator` named in its header.
pub fn markdown(rows: &[Row], locator: &str, window: &str) -> String {
    let correct = rows.iter().filter(|r| r.located == r.region).count();
    let mut md = format!(
        "## {window}\n\n\
         hand-sim ICM-20789 pad (seed {PAD_SEED}), {n} taps of {DEPTH_MM} mm ({rounds} per \
         region, rows {ROUNDS:?} for region groups 0 / 1 / 2), pressure trigger 20 Pa, 4 × 38 \
         window ({window}); locator: {locator}; moveL at 0.25 m/s, 1.2 m/s² to the located region's grid \
         pose on the simulated UR3 through ur_rtde 1.6.5. Pad times are simulated; locate and \
         move times are wall time on this machine.\n\n\
         **Located correctly: {correct} / {n} = {pct:.1} %** (paper, real time: 93 %, §V / \
         Fig. 8D).\n\n\
         | region tapped | located | confidence | trigger after press start (in tap) | window completes | locate | moveL to grid pose | final TCP error |\n\
         |---|---|---|---|---|---|---|---|\n",
        n = rows.len(),
        rounds = rows.len() / 9,
        pct = 100.0 * correct as f64 / rows.len().max(1) as f64,
    );
    for r in rows {
        md += &format!(
            "| {} | {} | {:.3} | {:.3} s ({}) | +{:.3} s | {:.1} µs | {:.3} s | {:.2e} m |\n",
            r.region,
            r.located,
            r.confidence,
            r.trigger_after_press_s,
            if r.trigger_in_tap { "yes" } else { "no" },
            r.window_s,
            r.locate_s * 1e6,
            r.move_s,
            r.tcp_error_m
        );
    }
    md
}
