//! Seed 002 §IV-B on the arm side, end to end: ICM-20789 pad taps (hand-sim, simulated time) →
//! pressure trigger → 4 × 38 accelerometer / gyroscope window → locator → region → moveL on the
//! simulated UR3, through the real ur_rtde. Shared by the `tap_to_move` example (which writes
//! `docs/arm-tap-to-move.md`) and the `tap_to_move` test (which checks every row).
//!
//! The locator is [`Scheduled`]: it answers the region each tap was scheduled on. It stands in
//! for the CNN (branch issue-8-cnn) so that the run checks the trigger, the window and the
//! moves for all 9 regions; it measures no recognition accuracy.

use std::net::Ipv4Addr;
use std::time::Duration;

use hand_sim::imu_pad::{ImuPad, ImuPadConfig, TapSpec, TapWindow, WINDOW_SAMPLES, WINDOW_SIGNALS};
use hand_traits::{Contact, ContactLocator, ImuFrame};
use ur_bridge::experiment::{TapToMove, TapToMoveConfig};
use ur_bridge::sim::{SimConfig, UrSim};
use ur_bridge::{RegionToGrid, UrArm, UrConfig};

/// The 4 × 38 window of §IV-A: acc x, acc y, gyro x, gyro y.
type Window = [[f32; WINDOW_SAMPLES]; WINDOW_SIGNALS];

/// Rows tapped for region groups 0 / 1 / 2. In hand-sim's pad a 1.2 mm tap on rows 1–5 or
/// 23–24 raises the pressure by ≤ 5.5 Pa (0.8 Pa rms noise), under any usable trigger
/// threshold (docs/arm.md); rows 6–22 rise ≥ 55 Pa.
pub(crate) const ROWS: [u8; 3] = [8, 12, 18];
/// Tap depth: the real-time CNN's training depth (§IV-B), mm.
pub(crate) const DEPTH_MM: f64 = 1.2;
/// The pad's scene seed.
pub(crate) const PAD_SEED: u64 = 10;

/// Answers the scheduled regions in order (a stand-in for the CNN: no recognition measured).
struct Scheduled {
    regions: Vec<u16>,
    next: usize,
}

impl ContactLocator for Scheduled {
    type Input = Window;
    type Error = &'static str;
    fn locate(&mut self, _: &Window) -> Result<Contact, &'static str> {
        let region = *self
            .regions
            .get(self.next)
            .ok_or("more taps than scheduled")?;
        self.next += 1;
        Ok(Contact {
            region,
            regions: 9,
            confidence: 1.0,
        })
    }
}

/// The 38 frames around the trigger as hand-sim cuts a training window (trigger = frame 19).
fn window(frames: &[ImuFrame]) -> Window {
    let centre = frames.get(WINDOW_SAMPLES / 2).map_or(0, |f| f.t_us);
    TapWindow::extract(frames, centre)
        .map(|w| w.signals)
        .unwrap_or([[f32::NAN; WINDOW_SAMPLES]; WINDOW_SIGNALS])
}

/// One cycle's outcome.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Row {
    /// The tapped (and located) region.
    pub(crate) region: u16,
    /// The region the locator named.
    pub(crate) located: u16,
    /// Trigger time minus the start of the press, s (simulated pad time).
    pub(crate) trigger_after_press_s: f64,
    /// Whether the trigger fell inside the tap's press / hold / release.
    pub(crate) trigger_in_tap: bool,
    /// Trigger to the window's last frame, s (simulated pad time).
    pub(crate) window_s: f64,
    /// Wall time of the locator, s.
    pub(crate) locate_s: f64,
    /// Wall time of the moveL to the grid pose, s.
    pub(crate) move_s: f64,
    /// Final TCP distance from the grid pose, m.
    pub(crate) tcp_error_m: f64,
}

/// Runs 9 cycles, one tap per region, against a simulator on 127.0.0.`octet`.
pub(crate) fn run(octet: u8) -> Result<Vec<Row>, String> {
    let taps: Vec<TapSpec> = (0..9u8)
        .map(|r| TapSpec {
            column: r % 3 + 1,
            row: ROWS[usize::from(r / 3)],
            depth_mm: DEPTH_MM,
        })
        .collect();
    let pad_config = ImuPadConfig {
        taps,
        ..ImuPadConfig::default()
    };
    let mut pad = ImuPad::new(&pad_config, PAD_SEED).map_err(|e| e.to_string())?;
    let scheduled: Vec<u16> = pad
        .taps()
        .iter()
        .map(|t| u16::from(t.position.region()))
        .collect();
    let mut locator = Scheduled {
        regions: scheduled.clone(),
        next: 0,
    };

    let sim = UrSim::start(SimConfig {
        address: Ipv4Addr::new(127, 0, 0, octet),
        ..SimConfig::default()
    })
    .map_err(|e| e.to_string())?;
    let mut config = UrConfig::new(format!("127.0.0.{octet}"));
    config.move_timeout = Duration::from_secs(20);
    let mut arm = UrArm::connect(config).map_err(|e| e.to_string())?;
    let grid = RegionToGrid::ur3_default().map_err(|e| e.to_string())?;
    let mut experiment = TapToMove::new(&grid, TapToMoveConfig::default());

    let timing = pad_config.timing;
    let mut rows = Vec::with_capacity(9);
    for (k, region) in scheduled.iter().enumerate() {
        let report = experiment
            .cycle(&mut pad, &mut locator, &mut arm, window)
            .map_err(|e| format!("cycle {k}: {e}; sim log {:?}", sim.log()))?;
        let press_s = pad.taps()[k].start_s + timing.lead_s;
        let t = report.trigger_t_us as f64 * 1e-6;
        let target = grid.pose(report.region).map_err(|e| e.to_string())?;
        let at = arm.tool_pose().map_err(|e| e.to_string())?;
        rows.push(Row {
            region: *region,
            located: report.region,
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

/// The rows as a markdown report.
pub(crate) fn markdown(rows: &[Row]) -> String {
    let mut md = String::from(
        "# Tap-to-move run (seed 002 §IV-B, arm side)\n\nWritten by `cargo xtask demo tap-to-move`. \
         hand-sim ICM-20789 pad (seed 10), one 1.2 mm tap per region on rows 8 / 12 / 18, pressure \
         trigger 20 Pa, 4 × 38 window, stand-in locator answering the scheduled region (no \
         recognition measured: see docs/arm.md), moveL at 0.25 m/s, 1.2 m/s² on the simulated UR3 \
         through ur_rtde 1.6.5. Pad times are simulated; locate and move times are wall time on \
         this machine.\n\n\
         | region tapped | located | trigger after press start (in tap) | window completes | locate | moveL to grid pose | final TCP error |\n\
         |---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        md += &format!(
            "| {} | {} | {:.3} s ({}) | +{:.3} s | {:.1} µs | {:.3} s | {:.2e} m |\n",
            r.region,
            r.located,
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
