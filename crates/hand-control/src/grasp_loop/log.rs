//! The per-cycle log: one [`Sample`] for every cycle, faulted or not, and what it yields
//! (settled torque, settling time).

use hand_traits::{GripperState, PressureFrame, SafeAction};

use super::estimate::ContactEstimate;
use super::fault::FaultKind;

/// What the loop is doing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Averaging untouched frames as the pad's zero; nothing is commanded.
    Tare,
    /// Closed-loop grasping.
    Grasp,
    /// A fault put the actuator in its safe state; recovery per [`Recovery`](super::Recovery).
    Safe,
    /// Safe, and automatic recovery has given up (reboots exhausted).
    Halted,
}

/// The mode's name (`Grasp`), as a log line or a status shows it.
impl core::fmt::Display for Mode {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            Mode::Tare => "Tare",
            Mode::Grasp => "Grasp",
            Mode::Safe => "Safe",
            Mode::Halted => "Halted",
        })
    }
}

/// One cycle. Every field the cycle could not fill is `None`, so a faulted cycle is logged too.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample<const N: usize> {
    /// Cycle number from 0.
    pub cycle: u64,
    /// The cycle's scheduled time, µs.
    pub t_us: u64,
    /// The mode the cycle ended in.
    pub mode: Mode,
    /// The tactile frame read.
    pub frame: Option<PressureFrame<N>>,
    /// The contact estimate.
    pub estimate: Option<ContactEstimate>,
    /// The policy's torque limit before the band, counts.
    pub policy_raw: Option<u16>,
    /// The torque limit sent (inside the band), counts.
    pub torque_raw: Option<u16>,
    /// The goal sent with it, rad.
    pub goal_rad: Option<f32>,
    /// The actuator's state read after the command.
    pub state: Option<GripperState>,
    /// The first fault of the cycle.
    pub fault: Option<FaultKind>,
    /// The safe action sent this cycle.
    pub safe_action: Option<SafeAction>,
    /// Whether a reboot was sent this cycle.
    pub rebooted: bool,
}

impl<const N: usize> Sample<N> {
    /// A sample of cycle `cycle` at `t_us` with nothing filled in yet.
    pub fn new(cycle: u64, t_us: u64, mode: Mode) -> Self {
        Sample {
            cycle,
            t_us,
            mode,
            frame: None,
            estimate: None,
            policy_raw: None,
            torque_raw: None,
            goal_rad: None,
            state: None,
            fault: None,
            safe_action: None,
            rebooted: false,
        }
    }
}

/// How the commanded torque settled over a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settling {
    /// Mean torque limit sent over the final window, counts.
    pub settled_raw: f32,
    /// Least and greatest torque limit sent over the final window, counts.
    pub window_raw: (u16, u16),
    /// First time after which every torque sent stays within the tolerance of `settled_raw`, µs
    /// from the first command.
    pub settling_time_us: u64,
}

/// Tolerance of the settling time, counts: 2 % of the 0…1023 scale (the MS5611 noise through
/// the filtered rate moves the torque by several counts from cycle to cycle). The value the
/// grasp reports (`handstack`, docs/grasping) pass to [`settling`].
pub const SETTLE_TOL_RAW: f32 = 20.0;
/// Window at the end of a hold the settled torque is averaged over, µs (the grasp reports').
pub const SETTLE_WINDOW_US: u64 = 10_000_000;

/// The settling of `samples`' sent torque: `settled_raw` is the mean over the last `window_us`,
/// settling time the first command time after which every sent torque is within `tol_raw` of
/// it. `None` if nothing was sent.
///
/// ```
/// use hand_control::grasp_loop::{Mode, Sample, settling};
/// let mut log = Vec::new();
/// for (i, raw) in [900u16, 600, 300, 205, 200, 201, 200].into_iter().enumerate() {
///     let mut s = Sample::<3>::new(i as u64, i as u64 * 10_000, Mode::Grasp);
///     s.torque_raw = Some(raw);
///     log.push(s);
/// }
/// let st = settling(&log, 20_000, 5.0).unwrap();
/// assert_eq!(st.window_raw, (200, 201));
/// assert_eq!(st.settling_time_us, 30_000); // from 205 on, within 5 of 200.3
/// ```
pub fn settling<const N: usize>(
    samples: &[Sample<N>],
    window_us: u64,
    tol_raw: f32,
) -> Option<Settling> {
    let sent: Vec<(u64, u16)> = samples
        .iter()
        .filter_map(|s| s.torque_raw.map(|r| (s.t_us, r)))
        .collect();
    let &(t0, _) = sent.first()?;
    let &(t_end, _) = sent.last()?;
    let from = t_end.saturating_sub(window_us);
    let window: Vec<u16> = sent
        .iter()
        .filter(|(t, _)| *t >= from)
        .map(|&(_, r)| r)
        .collect();
    let settled_raw =
        window.iter().map(|&r| f32::from(r)).sum::<f32>() / window.len().max(1) as f32;
    let lo = window.iter().copied().min()?;
    let hi = window.iter().copied().max()?;
    // The last sample outside the tolerance; settled from the next one.
    let settled_from = sent
        .iter()
        .rposition(|&(_, r)| (f32::from(r) - settled_raw).abs() > tol_raw)
        .map_or(t0, |i| sent.get(i + 1).map_or(t_end, |s| s.0));
    Some(Settling {
        settled_raw,
        window_raw: (lo, hi),
        settling_time_us: settled_from - t0,
    })
}
