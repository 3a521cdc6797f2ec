//! Checks after parsing: values in range and parts that can work together. Each error keeps
//! the span of the offending key.

use super::parts::{HandModel, Locator};
use super::{Location, SceneError, SceneFile};
use hand_sim::scene::SceneConfig;
use serde::Deserialize;
use std::ops::Range;
use toml::Spanned;

/// The MS5611's oversampling ratios (datasheet p. 2).
pub(crate) const OSRS: [u16; 5] = [256, 512, 1024, 2048, 4096];
/// Baud rates a Dynamixel Protocol 2.0 servo accepts (ROBOTIS e-manual, Baud Rate (8)).
const DXL_BAUDS: [u32; 8] = [
    9_600, 57_600, 115_200, 1_000_000, 2_000_000, 3_000_000, 4_000_000, 4_500_000,
];

struct Ctx<'a> {
    file: &'a str,
    text: &'a str,
}

impl Ctx<'_> {
    fn err(
        &self,
        span: Range<usize>,
        key: &str,
        problem: impl Into<String>,
        allowed: impl Into<String>,
    ) -> SceneError {
        SceneError::Invalid {
            file: self.file.to_owned(),
            at: Location::of(self.text, span.start),
            key: key.to_owned(),
            problem: problem.into(),
            allowed: allowed.into(),
        }
    }
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

/// Validates `scene` (the text of `file`) and returns its physics with the sensor knobs applied.
pub(crate) fn check(scene: &SceneFile, file: &str, text: &str) -> Result<SceneConfig, SceneError> {
    let cx = Ctx { file, text };
    let mut sim = scene
        .sim
        .as_ref()
        .map(|s| s.get_ref().clone())
        .unwrap_or_default();
    let sim_span = scene.sim.as_ref().map_or(0..0, Spanned::span);
    let knobs: Knobs = toml::from_str(text).unwrap_or_default();
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
            if !OSRS.contains(osr.get_ref()) {
                return Err(cx.err(
                    osr.span(),
                    "sensors.fingertip.osr",
                    format!("is {}, an OSR the MS5611 does not have", osr.get_ref()),
                    "256, 512, 1024, 2048, 4096",
                ));
            }
            if let Some(a) = &tip.get_ref().address {
                if ![0x76, 0x77].contains(a.get_ref()) {
                    return Err(cx.err(
                        a.span(),
                        "sensors.fingertip.address",
                        format!("is {:#04x}", a.get_ref()),
                        "0x76 or 0x77 (MS5611 CSB pin)",
                    ));
                }
            }
            match &tip.get_ref().i2c_buses {
                Some(buses) => {
                    if buses.get_ref().len() != 3 {
                        return Err(cx.err(
                            buses.span(),
                            "sensors.fingertip.i2c_buses",
                            format!("names {} buses", buses.get_ref().len()),
                            "three device paths, one per MS5611",
                        ));
                    }
                    if sim.fingertip.is_some() {
                        return Err(cx.err(
                            sim_span,
                            "sim.fingertip",
                            "simulates a fingertip the scene reads from real chips",
                            "no [sim.fingertip] with sensors.fingertip.i2c_buses",
                        ));
                    }
                }
                None => {
                    let mut tip_sim = sim.fingertip.take().unwrap_or_default();
                    tip_sim.osr = *osr.get_ref();
                    sim.fingertip = Some(tip_sim);
                }
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
        Some(pad) if pad.get_ref().i2c_bus.is_none() => {
            let mut pad_sim = sim.imu_pad.take().unwrap_or_default();
            pad_sim.baro_mode = pad.get_ref().pressure_mode;
            sim.imu_pad = Some(pad_sim);
        }
        Some(_) if sim.imu_pad.is_some() => {
            return Err(cx.err(
                sim_span,
                "sim.imu_pad",
                "simulates a pad the scene reads from a real chip",
                "no [sim.imu_pad] with sensors.imu_pad.i2c_bus",
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

    // Estimators.
    let e = &scene.estimators;
    if let Some(f) = &e.force {
        if s.fingertip.is_none() {
            return Err(cx.err(
                f.span(),
                "estimators.force",
                "needs the fingertip's pressures",
                "[sensors.fingertip] with it",
            ));
        }
    }
    if let Some(c) = &e.contact {
        let locators = &c.get_ref().locators;
        if locators.get_ref().is_empty() {
            return Err(cx.err(
                locators.span(),
                "estimators.contact.locators",
                "is empty",
                "one or more of \"aot\", \"ranging\", \"mlp\", \"cnn\"",
            ));
        }
        for l in locators.get_ref() {
            let (needs, ok) = match l {
                Locator::Cnn => (
                    "[sensors.imu_pad] (the CNN reads ICM-20789 windows)",
                    s.imu_pad.is_some(),
                ),
                _ => (
                    "[sensors.fingertip] (it reads the three MS5611)",
                    s.fingertip.is_some(),
                ),
            };
            if !ok {
                return Err(cx.err(
                    locators.span(),
                    "estimators.contact.locators",
                    format!("names \"{}\" without its sensor", l.name()),
                    needs,
                ));
            }
        }
    }
    if let Some(soft) = &e.softness {
        if s.underactuated.is_none() {
            return Err(cx.err(
                soft.span(),
                "estimators.softness",
                "classifies grasps of the underactuated hand the scene does not have",
                "[sensors.underactuated] with it",
            ));
        }
    }

    // Controller, hand, arm.
    if let Some(c) = &scene.controller {
        let c_ref = c.get_ref();
        if c_ref.preset.get_ref() != "grasp" {
            return Err(cx.err(
                c_ref.preset.span(),
                "controller.preset",
                format!("is \"{}\"", c_ref.preset.get_ref()),
                "\"grasp\" (seed 000 §6)",
            ));
        }
        if scene.hand.is_none() {
            return Err(cx.err(
                c.span(),
                "controller",
                "is a grasp controller without a hand",
                "[hand] with it",
            ));
        }
    }
    if let Some(h) = &scene.hand {
        let hr = h.get_ref();
        let mut ids = hr.ids.clone();
        ids.sort_unstable();
        ids.dedup();
        if hr.ids.is_empty() || ids.len() != hr.ids.len() || ids.iter().any(|&i| i > 252) {
            return Err(cx.err(
                h.span(),
                "hand.ids",
                format!("is {:?}", hr.ids),
                "one or more distinct IDs 0…252",
            ));
        }
        if let Some(b) = &hr.baud {
            if !DXL_BAUDS.contains(b.get_ref()) {
                return Err(cx.err(
                    b.span(),
                    "hand.baud",
                    format!("is {}", b.get_ref()),
                    "9600, 57600, 115200, 1000000, 2000000, 3000000, 4000000, 4500000",
                ));
            }
        }
        if hr.model != HandModel::Mx28 && scene.controller.is_some() && sim.grasp.is_some() {
            return Err(cx.err(
                h.span(),
                "hand.model",
                "is not the MX-28 the simulated Table 5 rig models",
                "\"mx28\" with [sim.grasp]",
            ));
        }
    }
    if let Some(a) = &scene.arm {
        let m = &a.get_ref().model;
        if m.get_ref() != "ur3" {
            return Err(cx.err(
                m.span(),
                "arm.model",
                format!("is \"{}\"", m.get_ref()),
                "\"ur3\" (seed 002's arm)",
            ));
        }
    }

    // Experiments and what each needs.
    let x = scene.experiment.get_ref();
    if x.names().is_empty() {
        return Err(cx.err(
            scene.experiment.span(),
            "experiment",
            "names no experiment",
            "one or more of [experiment.weight], [experiment.contact], [experiment.grasp], [experiment.softness], [experiment.tap], [experiment.readout]",
        ));
    }
    if let Some(w) = &x.weight {
        if s.fingertip.is_none() || e.force.is_none() {
            return Err(cx.err(
                w.span(),
                "experiment.weight",
                "needs the fingertip and the force DNN",
                "[sensors.fingertip] and [estimators.force] with it",
            ));
        }
        let steps = &w.get_ref().steps;
        if !(1..=hand_sim::fingertip::dataset::WEIGHT_STEPS).contains(steps.get_ref()) {
            return Err(cx.err(
                steps.span(),
                "experiment.weight.steps",
                format!("is {}", steps.get_ref()),
                "1…20 (10 gf each, Table 1's 0–200 gf)",
            ));
        }
    }
    if let Some(c) = &x.contact {
        let fingertip_locators = e.contact.as_ref().is_some_and(|l| {
            l.get_ref()
                .locators
                .get_ref()
                .iter()
                .any(|l| *l != Locator::Cnn)
        });
        if s.fingertip.is_none() || !fingertip_locators {
            return Err(cx.err(c.span(), "experiment.contact", "needs the fingertip and a fingertip locator", "[sensors.fingertip] and [estimators.contact] locators with \"aot\", \"ranging\" or \"mlp\""));
        }
    }
    if let Some(sx) = &x.softness {
        if s.underactuated.is_none() || e.softness.is_none() {
            return Err(cx.err(
                sx.span(),
                "experiment.softness",
                "needs the underactuated hand and the softness classifier",
                "[sensors.underactuated] and [estimators.softness] with it",
            ));
        }
    }
    if let Some(t) = &x.tap {
        let cnn = e
            .contact
            .as_ref()
            .is_some_and(|l| l.get_ref().locators.get_ref().contains(&Locator::Cnn));
        if s.imu_pad.is_none() || !cnn || scene.arm.is_none() {
            return Err(cx.err(
                t.span(),
                "experiment.tap",
                "needs the ICM-20789 pad, the CNN locator and the arm",
                "[sensors.imu_pad], [estimators.contact] locators with \"cnn\", and [arm]",
            ));
        }
        if s.imu_pad
            .as_ref()
            .is_some_and(|p| p.get_ref().i2c_bus.is_some())
        {
            return Err(cx.err(
                t.span(),
                "experiment.tap",
                "schedules its taps on the simulated pad",
                "sensors.imu_pad without i2c_bus",
            ));
        }
        let rounds = &t.get_ref().rounds;
        if !(1..=3).contains(rounds.get_ref()) {
            return Err(cx.err(
                rounds.span(),
                "experiment.tap.rounds",
                format!("is {}", rounds.get_ref()),
                "1…3 rounds of nine taps",
            ));
        }
    }
    if let Some(g) = &x.grasp {
        let Some(h) = &scene.hand else {
            return Err(cx.err(
                g.span(),
                "experiment.grasp",
                "needs a hand",
                "[hand] with it",
            ));
        };
        if scene.controller.is_none() || s.fingertip.is_none() {
            return Err(cx.err(
                g.span(),
                "experiment.grasp",
                "needs the fingertip and the grasp controller",
                "[sensors.fingertip] and [controller] with it",
            ));
        }
        if h.get_ref().serial_port.is_none() {
            if h.get_ref().model != HandModel::Mx28 {
                return Err(cx.err(
                    h.span(),
                    "hand.model",
                    "is simulated, and the simulated Table 5 rig has MX-28 fingers",
                    "\"mx28\", or a serial_port for real hardware",
                ));
            }
            let osr = s.fingertip.as_ref().map(|f| *f.get_ref().osr.get_ref());
            if osr != Some(paper_experiments::grasp_rig::OSR) {
                return Err(cx.err(
                    g.span(),
                    "experiment.grasp",
                    "runs the simulated rig's 100 Hz loop, which reads the fingertip at OSR 1024",
                    "sensors.fingertip.osr = 1024",
                ));
            }
        }
        for o in g.get_ref().objects.get_ref() {
            if hand_sim::grasp::ObjectKind::from_name(o).is_none() {
                return Err(cx.err(
                    g.get_ref().objects.span(),
                    "experiment.grasp.objects",
                    format!("names \"{o}\""),
                    "cube, cylinder, cone, ellipsoid, paper_cup, scroll_tissue (seed 000 Table 5)",
                ));
            }
        }
        let hold = &g.get_ref().hold_s;
        if !(hold.get_ref().is_finite() && (0.1..=600.0).contains(hold.get_ref())) {
            return Err(cx.err(
                hold.span(),
                "experiment.grasp.hold_s",
                format!("is {}", hold.get_ref()),
                "0.1…600 s after the lift (Table 5: 120)",
            ));
        }
    }
    if let Some(r) = &x.readout {
        if s.fingertip.is_none() {
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
    }
    for (name, needs_sim) in [
        ("weight", x.weight.is_some()),
        ("contact", x.contact.is_some()),
    ] {
        let real = s
            .fingertip
            .as_ref()
            .is_some_and(|t| t.get_ref().i2c_buses.is_some());
        if needs_sim && real {
            return Err(cx.err(
                scene.experiment.span(),
                &format!("experiment.{name}"),
                "presses the simulated pad, but the fingertip is real (i2c_buses)",
                "a simulated fingertip, or [experiment.readout] on real chips",
            ));
        }
    }
    Ok(sim)
}
