//! `[experiment.*]` of the `handstack` binary: what it runs on a user's own, real hand. Every
//! device a scene names must name its hardware (`i2c_buses`, `i2c_bus`, `serial_port`,
//! `host`): this binary holds no simulator, and a device without hardware is an error here,
//! never a silent simulation.

use super::{Checker, ExperimentTable, SceneError, SceneFile};
use serde::Deserialize;
use toml::Spanned;

/// The experiments of a `handstack` scene (at least one).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Experiments {
    /// `[experiment.grasp]`: close the hand and hold with the fuzzy grasp loop.
    pub grasp: Option<Spanned<Grasp>>,
    /// `[experiment.readout]`: read the fingertip at rest, report its rate and noise.
    pub readout: Option<Spanned<Readout>>,
}

/// Closes the hand on what it holds and keeps the grip for `hold_s` with the fuzzy grasp loop
/// (Kim et al. 2020, §5 and §7), its torque limit inside `torque_band`.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Grasp {
    /// The least and greatest torque limit the loop may send, counts of 0…1023 (Kim et al.
    /// 2020, Table 5, give one band per object).
    pub torque_band: Spanned<[u16; 2]>,
    /// How long to hold, s (0.1…600).
    pub hold_s: Spanned<f64>,
    /// The fingers' goal position while closing, rad (default: hand-control's 0.2 rad).
    pub goal_rad: Option<Spanned<f32>>,
    /// Recover from servo hardware faults instead of ending at the first fault:
    /// `recover = { attempts = 2, within_s = 5 }` reboots a faulted servo up to `attempts`
    /// times; a fault not cleared within `within_s` ends the run. A lost device always ends it.
    pub recover: Option<Spanned<Recover>>,
}

/// `recover = { attempts, within_s }` of a grasp.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Recover {
    /// Reboots allowed in the run, 1…10.
    pub attempts: u32,
    /// How long the hand may stay in its safe state after a fault before the run ends,
    /// s (0.1…60).
    pub within_s: f64,
}

/// Reads the fingertip at rest: frame period and per-sensor noise at its OSR.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Readout {
    /// Frames to read, 2…100 000.
    pub frames: Spanned<usize>,
}

/// The hold's limits, checked once for every program that runs a grasp.
pub fn check_hold_s(hold: &Spanned<f64>, cx: &Checker<'_>) -> Result<(), SceneError> {
    if hold.get_ref().is_finite() && (0.1..=600.0).contains(hold.get_ref()) {
        return Ok(());
    }
    Err(cx.err(
        hold.span(),
        "experiment.grasp.hold_s",
        format!("is {}", hold.get_ref()),
        "0.1…600 s (Table 5 held 120)",
    ))
}

/// A readout's frame count and its fingertip, checked once for every program that reads out.
pub fn check_readout<X>(
    scene: &SceneFile<X>,
    r: &Spanned<Readout>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    if scene.sensors.fingertip.is_none() {
        return Err(cx.err(
            r.span(),
            "experiment.readout",
            "reads the fingertip the scene does not have",
            "[sensors.fingertip] with it",
        ));
    }
    let n = &r.get_ref().frames;
    if !(2..=100_000).contains(n.get_ref()) {
        return Err(cx.err(
            n.span(),
            "experiment.readout.frames",
            format!("is {}", n.get_ref()),
            "2…100 000",
        ));
    }
    Ok(())
}

/// A grasp's hand, controller and fingertip, checked once for every program that grasps.
pub fn check_grasp_parts<X>(
    scene: &SceneFile<X>,
    g: &Spanned<impl Sized>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    if scene.hand.is_none() {
        return Err(cx.err(
            g.span(),
            "experiment.grasp",
            "needs a hand",
            "[hand] with it",
        ));
    }
    if scene.controller.is_none() || scene.sensors.fingertip.is_none() {
        return Err(cx.err(
            g.span(),
            "experiment.grasp",
            "needs the fingertip and the grasp controller",
            "[sensors.fingertip] and [controller] with it",
        ));
    }
    Ok(())
}

impl ExperimentTable for Experiments {
    const ALLOWED: &'static str = "[experiment.grasp], [experiment.readout]";

    fn names(&self) -> Vec<&'static str> {
        [
            ("grasp", self.grasp.is_some()),
            ("readout", self.readout.is_some()),
        ]
        .into_iter()
        .filter_map(|(n, on)| on.then_some(n))
        .collect()
    }

    fn check(scene: &SceneFile<Self>, cx: &Checker<'_>) -> Result<(), SceneError> {
        if let Some(arm) = &scene.arm {
            return Err(cx.err(
                arm.span(),
                "arm",
                "is named, but no experiment of `handstack run` moves an arm",
                "no [arm] in a scene to run; `handstack node SCENE --part arm` runs an arm as a \
                 ROS 2 node (feature `cell`)",
            ));
        }
        if let (Some(hand), None) = (&scene.hand, &scene.experiment.get_ref().grasp) {
            return Err(cx.err(
                hand.span(),
                "hand",
                "is named, but no experiment of this scene moves it",
                "[experiment.grasp] with it, or no [hand]",
            ));
        }
        check_experiments(scene, scene.experiment.get_ref(), cx)
    }
}

/// The `[experiment]` of a scene `handstack node` runs: `handstack run`'s tables, none
/// required, and an `[arm]` welcome (the arm node moves it).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(transparent)]
pub struct NodeExperiments(pub Experiments);

impl ExperimentTable for NodeExperiments {
    const ALLOWED: &'static str = Experiments::ALLOWED;
    const REQUIRED: bool = false;

    fn names(&self) -> Vec<&'static str> {
        self.0.names()
    }

    fn check(scene: &SceneFile<Self>, cx: &Checker<'_>) -> Result<(), SceneError> {
        check_experiments(scene, &scene.experiment.get_ref().0, cx)
    }
}

/// The checks `handstack run` and `handstack node` share: real devices only, and each
/// experiment with its parts and in range.
fn check_experiments<X>(
    scene: &SceneFile<X>,
    x: &Experiments,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    hardware_only(scene, cx)?;
    if let Some(g) = &x.grasp {
        check_grasp_parts(scene, g, cx)?;
        let band = &g.get_ref().torque_band;
        let [lo, hi] = *band.get_ref();
        if lo > hi || hi > 1023 {
            return Err(cx.err(
                band.span(),
                "experiment.grasp.torque_band",
                format!("is [{lo}, {hi}]"),
                "[least, greatest] with least ≤ greatest ≤ 1023",
            ));
        }
        check_hold_s(&g.get_ref().hold_s, cx)?;
        if let Some(r) = &g.get_ref().recover {
            let Recover { attempts, within_s } = *r.get_ref();
            if !(1..=10).contains(&attempts)
                || !within_s.is_finite()
                || !(0.1..=60.0).contains(&within_s)
            {
                return Err(cx.err(
                    r.span(),
                    "experiment.grasp.recover",
                    format!("is {{ attempts = {attempts}, within_s = {within_s} }}"),
                    "attempts 1…10, within_s 0.1…60 s",
                ));
            }
        }
        if let Some(goal) = &g.get_ref().goal_rad {
            if !goal.get_ref().is_finite() {
                return Err(cx.err(
                    goal.span(),
                    "experiment.grasp.goal_rad",
                    format!("is {}", goal.get_ref()),
                    "a finite angle, rad",
                ));
            }
        }
    }
    if let Some(r) = &x.readout {
        check_readout(scene, r, cx)?;
    }
    Ok(())
}

/// Every device named must name its hardware, and no `[sim]`.
fn hardware_only<X>(scene: &SceneFile<X>, cx: &Checker<'_>) -> Result<(), SceneError> {
    const WHY: &str = "the handstack binary opens real devices only (the papers' simulated \
                       scenes run with `paper-scenes`)";
    if let Some(sim) = &scene.sim {
        return Err(cx.err(sim.span(), "sim", "simulates an environment", WHY));
    }
    let s = &scene.sensors;
    let missing = [
        s.fingertip
            .as_ref()
            .filter(|t| t.get_ref().i2c_buses.is_none())
            .map(|t| (t.span(), "sensors.fingertip", "i2c_buses")),
        s.imu_pad
            .as_ref()
            .filter(|p| !p.get_ref().is_real())
            .map(|p| (p.span(), "sensors.imu_pad", "i2c_bus` or `firmata_port")),
        s.underactuated
            .as_ref()
            .map(|u| (u.span(), "sensors.underactuated", "(none: simulated only)")),
        scene
            .hand
            .as_ref()
            .filter(|h| h.get_ref().serial_port.is_none())
            .map(|h| (h.span(), "hand", "serial_port")),
        scene
            .arm
            .as_ref()
            .filter(|a| a.get_ref().host.is_none())
            .map(|a| (a.span(), "arm", "host")),
    ];
    match missing.into_iter().flatten().next() {
        Some((span, key, field)) => {
            Err(cx.err(span, key, format!("names no hardware (`{field}`)"), WHY))
        }
        None => Ok(()),
    }
}
