//! The grasp loop soaked under random faults: the Table 5 cube held by the
//! Dynamixel driver over the simulated Protocol 2.0 bus (pty) and read by the simulated
//! fingertip through the MS5611 driver ([`crate::grasp_rig`]), for a long simulated time, with
//! fault windows drawn from a seeded RNG. Every cycle is checked as it runs:
//!
//! - a fault is seen in the first cycle its window touches, as the typed error of its kind
//!   (a lost or unframeable status packet and a silent servo: the driver's timeout; a bad CRC:
//!   its CRC error; a latched hardware error: the hardware-error bits; the fingertip's bus:
//!   the source's error; a NaN reading: the estimator's), and that cycle ends in the safe
//!   state;
//! - no fault appears outside a window and its recovery;
//! - after the window the loop grasps again (automatic recovery, a reboot where the servo
//!   latched an error);
//! - every cycle is logged or counted as dropped, in order, and the log stays bounded.
//!
//! `papers soak` (`cargo xtask soak`) runs an hour (360 000 cycles) per seed; the test runs a
//! short seeded soak.

use std::time::{Duration, Instant};

use core::fmt::Debug;

use dxl_sim::REPLY_LATENCY;
use hand_control::grasp_loop::{LoopFault, Mode, Recovery, TorqueBand};
use hand_control::{DEFAULT_REPLY_LATENCY, Error, faults_from_hardware_error};
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams};
use hand_traits::SafeAction;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::grasp_rig::{self as rig, INJECTED_HARDWARE_ERROR, Injected, Injection, RigError};

/// How a soak runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoakConfig {
    /// Seeds the fault schedule and the fingertip's noise.
    pub seed: u64,
    /// Simulated time, s.
    pub seconds: f64,
    /// No fault before this, s (tare, first contact and lift are done by then).
    pub first_fault_s: f64,
    /// Mean time from a window's end to the next one's start, s (drawn uniformly in ½…1½ ×).
    pub mean_gap_s: f64,
    /// Longest window, cycles (drawn uniformly from 1).
    pub max_window_cycles: u32,
    /// Cycles a recovery may take before it counts as a failure to recover.
    pub recovery_bound_cycles: u64,
    /// The driver's reply allowance: a lost reply costs its cycle this much wall time.
    pub reply_latency: Duration,
}

impl SoakConfig {
    /// One simulated hour at 100 Hz, a fault window every 2 s on average, windows up to
    /// 20 cycles, a real bus's 34 ms reply allowance.
    pub fn hour(seed: u64) -> SoakConfig {
        SoakConfig {
            seed,
            seconds: 3600.0,
            first_fault_s: 5.0,
            mean_gap_s: 2.0,
            max_window_cycles: 20,
            recovery_bound_cycles: 100,
            reply_latency: DEFAULT_REPLY_LATENCY,
        }
    }

    /// `seconds` of the same with windows up to 5 cycles and the simulator's generous reply
    /// allowance (a test on a loaded machine sees no timeout the soak did not inject).
    pub fn short(seed: u64, seconds: f64) -> SoakConfig {
        SoakConfig {
            seconds,
            max_window_cycles: 5,
            reply_latency: REPLY_LATENCY,
            ..SoakConfig::hour(seed)
        }
    }
}

/// What a soak saw of one kind of fault.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KindStats {
    /// The kind.
    pub kind: Injected,
    /// Windows injected.
    pub windows: u32,
    /// Windows whose fault the loop saw, as its typed error, with the safe state in that cycle.
    pub caught: u32,
    /// Most cycles from a window's first cycle to the cycle that saw it (0: the same cycle).
    pub worst_detect_cycles: u64,
    /// Longest wall time of a cycle that saw a fault and went safe, µs (a timeout's cycle
    /// waits for the driver's reply deadline).
    pub worst_to_safe_wall_us: u64,
    /// Most cycles from a window's end to grasping again.
    pub worst_recovery_cycles: u64,
}

/// What a soak measured.
#[derive(Debug, Clone, PartialEq)]
pub struct SoakReport {
    /// The configuration.
    pub config: SoakConfig,
    /// Cycles run.
    pub cycles: u64,
    /// Cycles in the log at the end.
    pub logged: u64,
    /// Cycles dropped from the log (oldest first), counted.
    pub log_dropped: u64,
    /// Ticks the loop missed (a cycle overran its period).
    pub missed_ticks: u64,
    /// Reboots the loop sent.
    pub reboots: u32,
    /// Per kind, in [`Injected::ALL`] order.
    pub kinds: Vec<KindStats>,
    /// Every broken expectation (empty when the soak passed).
    pub violations: Vec<String>,
    /// Wall time, s.
    pub wall_s: f64,
    /// The process's peak resident set, KiB (Linux `VmHWM`), at the end.
    pub peak_rss_kib: Option<u64>,
}

impl SoakReport {
    /// Windows injected, of every kind.
    pub fn windows(&self) -> u32 {
        self.kinds.iter().map(|k| k.windows).sum()
    }
}

/// The seeded fault windows of `c`: each of a random kind and length, separated by gaps.
pub fn schedule(c: &SoakConfig, period_s: f64) -> Vec<Injection> {
    let mut rng = ChaCha8Rng::seed_from_u64(c.seed ^ 0x50A4);
    let mut out = Vec::new();
    let mut t = c.first_fault_s;
    // The last window ends with time left to recover in.
    let end = c.seconds - c.recovery_bound_cycles as f64 * period_s - c.mean_gap_s;
    loop {
        let cycles = rng.random_range(1..=c.max_window_cycles.max(1));
        let kind = Injected::ALL[rng.random_range(0..Injected::ALL.len())];
        let until = t + f64::from(cycles) * period_s;
        if until > end {
            break;
        }
        out.push(Injection {
            from_s: t,
            until_s: until,
            kind,
        });
        t = until + c.mean_gap_s * rng.random_range(0.5..1.5);
    }
    out
}

/// Whether `fault` (the loop's typed error) is what `kind` must produce.
fn expected<SE: Debug, PE: Debug>(kind: Injected, fault: &LoopFault<SE, PE, Error>) -> bool {
    let timeout = |e: &Error| matches!(e, Error::Timeout { .. });
    let crc = |e: &Error| matches!(e, Error::Crc { .. });
    match (kind, fault) {
        (
            Injected::DropStatus | Injected::GarbleStatus | Injected::Silent,
            LoopFault::State(e) | LoopFault::Command(e),
        ) => timeout(e),
        (Injected::Crc, LoopFault::State(e) | LoopFault::Command(e)) => crc(e),
        (Injected::HardwareError, LoopFault::Hardware(f)) => {
            f.contains(faults_from_hardware_error(INJECTED_HARDWARE_ERROR))
        }
        (Injected::TactileBus, LoopFault::Source(_)) => true,
        (Injected::NanFrame, LoopFault::Estimate(_)) => true,
        _ => false,
    }
}

/// Where one window stands while the soak runs.
#[derive(Debug, Clone, Copy)]
struct Window {
    index: usize,
    first_cycle: Option<u64>,
    caught: bool,
    ended_at: Option<u64>,
}

/// Runs one soak. Errors: the world could not be built or failed on the way (not a fault of
/// the loop's: the bus simulator itself).
pub fn soak(c: &SoakConfig) -> Result<SoakReport, RigError> {
    let started = Instant::now();
    let object = ObjectParams::table5(ObjectKind::Cube, &RigParams::default())?;
    let (world, mut hand) = rig::world(object, c.seed)?;
    hand.set_reply_latency(c.reply_latency);
    let mut cfg = rig::config(TorqueBand::new(80, 400)?);
    cfg.safe_action = SafeAction::HoldLastSafeEffort;
    cfg.recovery = Recovery::Automatic {
        cooldown_us: 100_000,
        max_reboots: u32::MAX,
    };
    let period_us = cfg.period_us;
    let period_s = period_us as f64 * 1e-6;
    let windows = schedule(c, period_s);
    world.borrow_mut().injections = windows.clone();
    let mut l = rig::grasp_loop(&world, hand, cfg)?;

    let mut kinds: Vec<KindStats> = Injected::ALL
        .iter()
        .map(|&kind| KindStats {
            kind,
            windows: windows.iter().filter(|w| w.kind == kind).count() as u32,
            caught: 0,
            worst_detect_cycles: 0,
            worst_to_safe_wall_us: 0,
            worst_recovery_cycles: 0,
        })
        .collect();
    let stats = |kinds: &mut [KindStats], k: Injected| -> usize {
        kinds.iter().position(|s| s.kind == k).unwrap_or(0)
    };
    let mut violations = Vec::new();
    let mut say = |v: String| {
        // A broken soak says what broke first; thousands of repeats say nothing more.
        if violations.len() < 50 {
            violations.push(v);
        }
    };
    let mut open: Option<Window> = None;
    let mut next = 0;
    let mut cycle = 0u64;
    let end_us = (c.seconds * 1e6) as u64;
    // Events the loop has reported in all (kept + dropped): its event log is bounded too.
    let mut events_seen = 0u64;
    loop {
        let wall = Instant::now();
        let s = *l.cycle();
        let wall_us = wall.elapsed().as_micros() as u64;
        if s.cycle != cycle {
            say(format!("cycle {cycle} logged as {}", s.cycle));
        }
        cycle += 1;
        let t_s = s.t_us as f64 * 1e-6;
        // The window this cycle is in, if a new one has started.
        if next < windows.len() && t_s >= windows[next].from_s {
            if let Some(w) = open.take() {
                close(&windows, &w, &mut say);
            }
            open = Some(Window {
                index: next,
                first_cycle: Some(s.cycle),
                caught: false,
                ended_at: None,
            });
            next += 1;
        }
        // The loop's new events, counted over its life: the event log drops its older half
        // when full, so its length alone cannot say what is new.
        let events = l.events();
        let total = l.events_dropped() + events.len() as u64;
        let new_events =
            usize::try_from(total - events_seen).map_or(events.len(), |n| n.min(events.len()));
        let fresh = &events[events.len() - new_events..];
        events_seen = total;
        if let Some(kind) = s.fault {
            match open.as_mut() {
                Some(w) => {
                    let inj = windows[w.index];
                    let k = stats(&mut kinds, inj.kind);
                    let typed = fresh.iter().any(|e| expected(inj.kind, &e.fault));
                    if !w.caught && w.ended_at.is_none() {
                        if !typed {
                            say(format!(
                                "{:?} at {:.2} s: seen as {kind:?} ({:?})",
                                inj.kind,
                                t_s,
                                fresh.first().map(|e| &e.fault)
                            ));
                        }
                        if !matches!(s.mode, Mode::Safe | Mode::Halted) {
                            say(format!(
                                "{:?} at {t_s:.2} s: cycle ended in {:?}",
                                inj.kind, s.mode
                            ));
                        }
                        w.caught = typed;
                        let st = &mut kinds[k];
                        st.caught += u32::from(typed);
                        st.worst_detect_cycles = st
                            .worst_detect_cycles
                            .max(s.cycle - w.first_cycle.unwrap_or(s.cycle));
                        st.worst_to_safe_wall_us = st.worst_to_safe_wall_us.max(wall_us);
                    }
                }
                None => say(format!(
                    "a {kind:?} fault at {t_s:.2} s outside any window: {:?}",
                    fresh.first().map(|e| &e.fault)
                )),
            }
        }
        if s.mode == Mode::Halted {
            say(format!("halted at {t_s:.2} s"));
        }
        if let Some(w) = open.as_mut() {
            let inj = windows[w.index];
            if w.ended_at.is_none() && t_s >= inj.until_s {
                w.ended_at = Some(s.cycle);
            }
            if let Some(end) = w.ended_at {
                let k = stats(&mut kinds, inj.kind);
                if s.mode == Mode::Grasp {
                    let st = &mut kinds[k];
                    st.worst_recovery_cycles = st.worst_recovery_cycles.max(s.cycle - end);
                    close(&windows, w, &mut say);
                    open = None;
                } else if s.cycle - end > c.recovery_bound_cycles {
                    say(format!(
                        "{:?} ended at {:.2} s: no recovery in {} cycles",
                        inj.kind, inj.until_s, c.recovery_bound_cycles
                    ));
                    close(&windows, w, &mut say);
                    open = None;
                }
            }
        }
        if let Some(e) = world.borrow_mut().world_error.take() {
            return Err(e);
        }
        if s.t_us + period_us >= end_us {
            break;
        }
    }
    if let Some(w) = open.take() {
        close(&windows, &w, &mut say);
    }
    let logged = l.log().len() as u64;
    if logged + l.log_dropped() != cycle {
        say(format!(
            "{cycle} cycles, {logged} logged + {} dropped",
            l.log_dropped()
        ));
    }
    if l.log().len() > l.config().log_capacity {
        say(format!("the log holds {logged} > its capacity"));
    }
    Ok(SoakReport {
        config: *c,
        cycles: cycle,
        logged,
        log_dropped: l.log_dropped(),
        missed_ticks: l.missed_ticks(),
        reboots: l.reboots(),
        kinds,
        violations,
        wall_s: started.elapsed().as_secs_f64(),
        peak_rss_kib: peak_rss_kib(),
    })
}

/// A window is over: one that was never seen is a violation.
fn close(windows: &[Injection], w: &Window, say: &mut impl FnMut(String)) {
    if !w.caught {
        let inj = windows[w.index];
        say(format!(
            "{:?} from {:.2} s to {:.2} s: never seen as its typed error",
            inj.kind, inj.from_s, inj.until_s
        ));
    }
}

/// Linux's peak resident set of this process (`VmHWM` in `/proc/self/status`), KiB.
fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// The report as a Markdown table row per kind, plus the totals (for `papers soak` and
/// `docs/reliability.md`).
pub fn markdown(reports: &[SoakReport]) -> String {
    let mut out = String::from(
        "| fault | windows | caught, typed, safe in that cycle | worst cycles to see it | worst wall time of that cycle | worst cycles to grasp again |\n|---|---|---|---|---|---|\n",
    );
    for (i, kind) in Injected::ALL.iter().enumerate() {
        let all: Vec<&KindStats> = reports.iter().filter_map(|r| r.kinds.get(i)).collect();
        let sum = |f: fn(&KindStats) -> u32| all.iter().map(|k| f(k)).sum::<u32>();
        let max = |f: fn(&KindStats) -> u64| all.iter().map(|k| f(k)).max().unwrap_or(0);
        out.push_str(&format!(
            "| {kind:?} | {} | {} | {} | {:.1} ms | {} |\n",
            sum(|k| k.windows),
            sum(|k| k.caught),
            max(|k| k.worst_detect_cycles),
            max(|k| k.worst_to_safe_wall_us) as f64 / 1000.0,
            max(|k| k.worst_recovery_cycles),
        ));
    }
    out
}

/// A one-line summary of `r`.
pub fn summary(r: &SoakReport) -> String {
    format!(
        "seed {}: {:.0} s simulated, {} cycles ({} logged + {} dropped), {} windows, {} reboots, {} missed ticks, {} violations, peak RSS {} KiB, {:.1} s wall ({:.1} µs a cycle)",
        r.config.seed,
        r.config.seconds,
        r.cycles,
        r.logged,
        r.log_dropped,
        r.windows(),
        r.reboots,
        r.missed_ticks,
        r.violations.len(),
        r.peak_rss_kib.map_or_else(|| "?".into(), |k| k.to_string()),
        r.wall_s,
        r.wall_s * 1e6 / r.cycles.max(1) as f64,
    )
}
