//! `[sim]`: the simulated physics of a paper scene (hand-sim's scene config), checked against
//! the parts: a simulated device gets the sensor knobs the scene gives its part (OSR, pressure
//! mode); a device the scene reads from real hardware, or none, must not be simulated.
//! `[sim.arm]` is ur-sim's UR controller simulator, for an `[arm]` without a host.

use super::Experiments;
use hand_sim::scene::SceneConfig;
use handstack::scene::parts::HandModel;
use handstack::scene::{Checker, SceneError, SceneFile};
use serde::Deserialize;
use toml::Spanned;
use toml::de::{DeTable, DeValue, Deserializer, ValueDeserializer};
use ur_sim::TimeScale;

/// `[sim.arm]`: how ur-sim's UR controller simulator runs when the scene's `[arm]` names no
/// host. The arm itself is still reached through ur_rtde on loopback; nothing here reaches the
/// runner.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ArmSim {
    /// `time_scale`: controller seconds per wall-clock second (`ur_sim::SimConfig::
    /// time_scale`; default 1, real time). Moves keep their controller-time profiles and RTDE
    /// `timestamp`s; they end `time_scale` × sooner on the wall clock.
    pub time_scale: TimeScale,
}

/// The `[sim.arm]` table as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ArmSimTable {
    time_scale: Option<Spanned<f64>>,
}

/// The `[sim]` table alone, parsed again from the text so its errors keep their spans.
#[derive(Deserialize, Default)]
struct SimOnly {
    #[serde(default)]
    sim: Option<Spanned<SceneConfig>>,
}

/// The knobs a `[sim.*]` table must not repeat (they belong to `[sensors.*]`), found by a
/// second, lenient parse that keeps their spans.
#[derive(Deserialize, Default)]
struct Knobs {
    #[serde(default)]
    sim: Option<SimKnobs>,
}
#[derive(Deserialize, Default)]
struct SimKnobs {
    fingertip: Option<KnobTable>,
    imu_pad: Option<KnobTable>,
}
#[derive(Deserialize, Default)]
struct KnobTable {
    osr: Option<Spanned<toml::Value>>,
    baro_mode: Option<Spanned<toml::Value>>,
}

/// The physics of `scene` (the text `cx` checks) with the sensor knobs applied, and the arm
/// simulator's settings.
pub(crate) fn check(
    scene: &SceneFile<Experiments>,
    cx: &Checker<'_>,
) -> Result<(SceneConfig, ArmSim), SceneError> {
    // `[sim.arm]` is taken out before hand-sim reads `[sim]` (its table knows no arm); both
    // parses keep the text's spans.
    let mut doc = DeTable::parse(cx.text()).map_err(|e| cx.syntax(&e))?;
    let arm_table = match doc.get_mut().get_mut("sim").map(Spanned::get_mut) {
        Some(DeValue::Table(t)) => t.remove("arm"),
        _ => None,
    };
    let only = SimOnly::deserialize(Deserializer::from(doc)).map_err(|e| cx.syntax(&e))?;
    let arm = match arm_table {
        Some(t) => arm_sim(scene, t, cx)?,
        None => ArmSim::default(),
    };
    let mut sim = only
        .sim
        .as_ref()
        .map(|s| s.get_ref().clone())
        .unwrap_or_default();
    let sim_span = scene.sim.as_ref().map_or(0..0, Spanned::span);
    let knobs: Knobs = toml::from_str(cx.text()).unwrap_or_default();
    let knobs = knobs.sim.unwrap_or_default();
    if let Some(v) = knobs.fingertip.as_ref().and_then(|t| t.osr.as_ref()) {
        return Err(cx.err(
            v.span(),
            "sim.fingertip.osr",
            "repeats a sensor knob",
            "`osr` in [sensors.fingertip] only",
        ));
    }
    if let Some(v) = knobs.imu_pad.as_ref().and_then(|t| t.baro_mode.as_ref()) {
        return Err(cx.err(
            v.span(),
            "sim.imu_pad.baro_mode",
            "repeats a sensor knob",
            "`pressure_mode` in [sensors.imu_pad] only",
        ));
    }

    let s = &scene.sensors;
    // Sensors: the fingertip.
    match &s.fingertip {
        Some(tip) => {
            let osr = &tip.get_ref().osr;
            if tip.get_ref().is_real() {
                if sim.fingertip.is_some() {
                    return Err(cx.err(
                        sim_span,
                        "sim.fingertip",
                        "simulates a fingertip the scene reads from real chips",
                        "no [sim.fingertip] with sensors.fingertip.i2c_buses or firmata_port",
                    ));
                }
            } else {
                let mut tip_sim = sim.fingertip.take().unwrap_or_default();
                tip_sim.osr = *osr.get_ref();
                sim.fingertip = Some(tip_sim);
            }
        }
        None => {
            if sim.fingertip.is_some() {
                return Err(cx.err(
                    sim_span,
                    "sim.fingertip",
                    "simulates a fingertip no sensor reads",
                    "[sensors.fingertip] with it",
                ));
            }
        }
    }
    // The ICM-20789 pad.
    match &s.imu_pad {
        Some(pad) if !pad.get_ref().is_real() => {
            let mut pad_sim = sim.imu_pad.take().unwrap_or_default();
            pad_sim.baro_mode = pad.get_ref().pressure_mode;
            sim.imu_pad = Some(pad_sim);
        }
        Some(_) if sim.imu_pad.is_some() => {
            return Err(cx.err(
                sim_span,
                "sim.imu_pad",
                "simulates a pad the scene reads from a real chip",
                "no [sim.imu_pad] with sensors.imu_pad.i2c_bus or firmata_port",
            ));
        }
        Some(_) => {}
        None if sim.imu_pad.is_some() => {
            return Err(cx.err(
                sim_span,
                "sim.imu_pad",
                "simulates a pad no sensor reads",
                "[sensors.imu_pad] with it",
            ));
        }
        None => {}
    }
    // The underactuated hand (simulated only).
    match (&s.underactuated, &sim.underactuated) {
        (Some(_), None) => sim.underactuated = Some(Default::default()),
        (None, Some(_)) => {
            return Err(cx.err(
                sim_span,
                "sim.underactuated",
                "simulates a hand no sensor reads",
                "[sensors.underactuated] with it",
            ));
        }
        _ => {}
    }

    if let Some(h) = &scene.hand {
        if h.get_ref().model != HandModel::MX28 && scene.controller.is_some() && sim.grasp.is_some()
        {
            return Err(cx.err(
                h.span(),
                "hand.model",
                "is not the MX-28 the simulated Table 5 rig models",
                "\"mx28\" with [sim.grasp]",
            ));
        }
    }
    Ok((sim, arm))
}

/// Checks `[sim.arm]` (`table`, as written) against the scene's `[arm]`.
fn arm_sim(
    scene: &SceneFile<Experiments>,
    table: Spanned<DeValue<'_>>,
    cx: &Checker<'_>,
) -> Result<ArmSim, SceneError> {
    let span = table.span();
    let written =
        ArmSimTable::deserialize(ValueDeserializer::from(table)).map_err(|e| cx.syntax(&e))?;
    match &scene.arm {
        None => {
            return Err(cx.err(
                span,
                "sim.arm",
                "simulates an arm no part names",
                "[arm] with it",
            ));
        }
        Some(a) if a.get_ref().host.is_some() => {
            return Err(cx.err(
                span,
                "sim.arm",
                "simulates an arm the scene reaches at a host",
                "no [sim.arm] with arm.host",
            ));
        }
        Some(_) => {}
    }
    let time_scale = match written.time_scale {
        Some(v) => TimeScale::new(*v.get_ref()).map_err(|e| {
            cx.err(
                v.span(),
                "sim.arm.time_scale",
                e.to_string(),
                "a finite positive number (1 = real time)",
            )
        })?,
        None => TimeScale::REAL_TIME,
    };
    Ok(ArmSim { time_scale })
}
