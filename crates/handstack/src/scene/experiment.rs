//! `[experiment.*]` of the `handstack` binary: what it runs on a user's own, real hand. Every
//! device a scene names must name its hardware (`i2c_buses`, `i2c_bus`, `firmata_port`,
//! `serial_port`, `host`): this binary holds no simulator, and a device without hardware is an
//! error here, never a silent simulation.

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
    /// `[experiment.softness]`: close the underactuated hand on an object and classify it.
    pub softness: Option<Spanned<Softness>>,
    /// `[experiment.weight]`: weights placed on the fingertip, each estimated by the force DNN.
    pub weight: Option<Spanned<Weight>>,
    /// `[experiment.tap_to_move]`: taps on the pad, located by the contact CNN, move the arm.
    pub tap_to_move: Option<Spanned<TapToMove>>,
    /// `[experiment.contact]`: taps on the fingertip's cells, located by its microcontroller.
    pub contact: Option<Spanned<Contact>>,
}

/// Contact location (Kim et al. 2020, §3–4) on the user's fingertip: for each cell of `cells`
/// the run asks for a tap there and reads where the fingertip's microcontroller located it
/// while the press was held: the contact MLP's cell on the 4 × 6 pad and Arrival-of-Time's
/// area on the 3 × 3 grid (the cells each reported most often on the press's plateau). Both need the sensors'
/// arrival times to the millisecond, which the board measures: the fingertip is its
/// `serial_port`. Figures: each located against the cell asked, and the accuracies.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Contact {
    /// The cells to tap, in order, each `[row, column]` counted from 1 (rows 1…4, columns
    /// 1…6; default each cell once, row by row); 1…240 of them.
    pub cells: Option<Spanned<Vec<[u8; 2]>>>,
    /// The longest wait for each tap, s (default 30; 1…600): no tap by then fails the run.
    pub wait_s: Option<Spanned<f64>>,
}

impl Contact {
    /// The cells it asks for, `(row, column)` from 1.
    pub fn cells(&self) -> Vec<(u8, u8)> {
        self.cells.as_ref().map_or_else(
            || {
                (1..=PAD_ROWS)
                    .flat_map(|r| (1..=PAD_COLS).map(move |c| (r, c)))
                    .collect()
            },
            |c| c.get_ref().iter().map(|&[r, c]| (r, c)).collect(),
        )
    }

    /// The longest wait for a tap, s.
    pub fn wait_s(&self) -> f64 {
        self.wait_s.as_ref().map_or(30.0, |w| *w.get_ref())
    }
}

use aot_locate::{COLS as PAD_COLS, ROWS as PAD_ROWS};

/// Tap-to-move (Al & Martinez-Hernandez, §IV-B) on the user's pad and arm: for
/// each region of `regions` the run asks for a tap there, waits for it (the pressure rising over
/// its rest), locates it with the built-in contact CNN from the accelerometer / gyroscope window
/// around it, and moves the arm from home to the region's grid pose; the arm goes home before
/// each tap. Figures: the regions located against those asked, the accuracy, the moves' times.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TapToMove {
    /// The regions to tap, in order, each 0…8 (row-major from the pad's first row; default
    /// each once, 0 to 8); 1…90 of them.
    pub regions: Option<Spanned<Vec<u8>>>,
    /// The longest wait for each tap, s (default 30; 1…600): no tap by then fails the run.
    pub wait_s: Option<Spanned<f64>>,
}

impl TapToMove {
    /// The regions it asks for.
    pub fn regions(&self) -> Vec<u8> {
        self.regions
            .as_ref()
            .map_or_else(|| (0..9).collect(), |r| r.get_ref().clone())
    }

    /// The longest wait for a tap, s.
    pub fn wait_s(&self) -> f64 {
        self.wait_s.as_ref().map_or(30.0, |w| *w.get_ref())
    }
}

/// The weights of Table 1 of Kim et al. 2020 (§2.2), gf: the default series.
pub const TABLE1_WEIGHTS_GF: [f64; 13] = [
    0.0, 50.0, 100.0, 110.0, 120.0, 130.0, 140.0, 150.0, 160.0, 170.0, 180.0, 190.0, 200.0,
];

/// The Table 1 protocol of Kim et al. 2020 on the user's fingertip: the pad is tared unloaded, then each
/// weight is placed when the run asks for it (answered on stdin: Enter, or the weight actually
/// placed in gf), the pressures left to settle and averaged, and the force DNN's estimate of
/// the average compared with the weight. The built-in networks were trained on 0–200 gf.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Weight {
    /// The weights to place, in order, gf (default Table 1's 13: 0, 50, 100, 110 … 200); 1…50
    /// of them, each 0…1000.
    pub weights_gf: Option<Spanned<Vec<f64>>>,
    /// How far an estimate may be from its weight, gf (default 2; 0.01…100): a weight read
    /// further off fails the run (exit status 4) after every weight is placed. The paper's DNN
    /// came within 1.17 gf of every Table 1 row.
    pub tolerance_gf: Option<Spanned<f64>>,
    /// How long the pad settles after each answer before its pressures count, s (default 1;
    /// 0…30).
    pub settle_s: Option<Spanned<f64>>,
    /// How long the settled pressures are averaged, s (default 1; 0.1…30): the paper's
    /// "average measured values".
    pub average_s: Option<Spanned<f64>>,
    /// Clear the pad and tare again before each weight (default false: one tare, the paper's
    /// protocol). Barometers drift (the simulated ones 0.1 hPa/min, ~17 gf/min on a whole-pad
    /// load): a tare before each weight keeps the drift of a long series out of its estimates.
    /// A collect session always tares before each weight.
    pub tare_each_weight: Option<Spanned<bool>>,
}

/// What a [`Weight`] experiment does, its defaults filled in.
#[derive(Debug, Clone, PartialEq)]
pub struct WeighPlan {
    /// The weights, gf, in order.
    pub weights_gf: Vec<f64>,
    /// The tolerance, gf.
    pub tolerance_gf: f64,
    /// Settling time, s.
    pub settle_s: f64,
    /// Averaging time, s.
    pub average_s: f64,
    /// Whether the pad is cleared and tared again before each weight.
    pub tare_each_weight: bool,
}

impl Weight {
    /// The series it asks for.
    pub fn plan(&self) -> WeighPlan {
        let or = |v: &Option<Spanned<f64>>, x: f64| v.as_ref().map_or(x, |v| *v.get_ref());
        WeighPlan {
            weights_gf: self
                .weights_gf
                .as_ref()
                .map_or_else(|| TABLE1_WEIGHTS_GF.to_vec(), |w| w.get_ref().clone()),
            tolerance_gf: or(&self.tolerance_gf, 2.0),
            settle_s: or(&self.settle_s, 1.0),
            average_s: or(&self.average_s, 1.0),
            tare_each_weight: self.tare_each_weight.as_ref().is_some_and(|t| *t.get_ref()),
        }
    }
}

/// Closes the underactuated hand on what it holds at constant velocity, open loop, records its
/// four forces and four distal angles from first contact for `window_s` at 10 Hz, holds, and
/// classifies the object soft, moderate or hard with tactile-nets' built-in softness net (the
/// underactuated-hand softness paper, §3.1–3.3). The built-in net was trained on closes at
/// 1.5 mm/s recorded for 14 s: other values run, outside the conditions it learned (a net of
/// the user's own, `[estimators.softness] weights`, learns the scene's).
///
/// With `objects`, the run grasps several objects in turn, asking for each ("Put a soft object
/// in the hand…") and opening the hand between them, and reports how many it classified as
/// asked; `handstack collect` records each grasp with its class, to train a net on.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Softness {
    /// The class the object should get (`soft`, `moderate` or `hard`): the run fails (exit
    /// status 4) when the hand says otherwise. Absent: the class is reported only.
    pub expect: Option<Spanned<String>>,
    /// The objects to grasp in turn, by class (`["soft", "moderate", "hard", …]`), each asked
    /// for before its close; instead of `expect`.
    pub objects: Option<Spanned<Vec<Spanned<String>>>>,
    /// The tendon's closing speed, mm/s (default 1.5; 0.1…20).
    pub closing_speed_mm_s: Option<Spanned<f64>>,
    /// The window from first contact, s (default 14, the paper's; 1…60).
    pub window_s: Option<Spanned<f64>>,
    /// The longest approach before first contact, s (default 60; 1…600): a hand that has
    /// touched nothing by then is empty, and the run fails.
    pub approach_timeout_s: Option<Spanned<f64>>,
}

impl Softness {
    /// The class it expects, if any (checked when the scene is read).
    pub fn expected(&self) -> Option<hand_traits::Softness> {
        self.expect.as_ref().and_then(|e| class_named(e.get_ref()))
    }

    /// The objects it asks for in turn (checked when the scene is read); empty without
    /// `objects`.
    pub fn objects(&self) -> Vec<hand_traits::Softness> {
        self.objects.as_ref().map_or_else(Vec::new, |o| {
            o.get_ref()
                .iter()
                .filter_map(|c| class_named(c.get_ref()))
                .collect()
        })
    }

    /// The close and recording it asks for.
    pub fn plan(&self) -> underactuated_hand::grasp::GraspPlan {
        let d = underactuated_hand::grasp::GraspPlan::default();
        let or = |v: &Option<Spanned<f64>>, x: f64| v.as_ref().map_or(x, |v| *v.get_ref());
        underactuated_hand::grasp::GraspPlan {
            closing_speed_mm_s: or(&self.closing_speed_mm_s, d.closing_speed_mm_s),
            window_s: or(&self.window_s, d.window_s),
            approach_timeout_s: or(&self.approach_timeout_s, d.approach_timeout_s),
            ..d
        }
    }
}

/// A softness class by its name in a scene file.
pub fn class_named(name: &str) -> Option<hand_traits::Softness> {
    hand_traits::Softness::ALL
        .into_iter()
        .find(|c| class_name(*c) == name)
}

/// A softness class's name in a scene file and a report.
pub fn class_name(class: hand_traits::Softness) -> &'static str {
    match class {
        hand_traits::Softness::Soft => "soft",
        hand_traits::Softness::Moderate => "moderate",
        hand_traits::Softness::Hard => "hard",
    }
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
    const ALLOWED: &'static str = "[experiment.grasp], [experiment.readout], \
        [experiment.softness], [experiment.weight], [experiment.tap_to_move], \
        [experiment.contact]";

    fn names(&self) -> Vec<&'static str> {
        [
            ("grasp", self.grasp.is_some()),
            ("readout", self.readout.is_some()),
            ("softness", self.softness.is_some()),
            ("weight", self.weight.is_some()),
            ("tap_to_move", self.tap_to_move.is_some()),
            ("contact", self.contact.is_some()),
        ]
        .into_iter()
        .filter_map(|(n, on)| on.then_some(n))
        .collect()
    }

    fn check(scene: &SceneFile<Self>, cx: &Checker<'_>) -> Result<(), SceneError> {
        let x = scene.experiment.get_ref();
        if let (Some(arm), None) = (&scene.arm, &x.tap_to_move) {
            return Err(cx.err(
                arm.span(),
                "arm",
                "is named, but no experiment of this scene moves it",
                "[experiment.tap_to_move] with it, or no [arm]; `handstack node SCENE --part \
                 arm` runs an arm as a ROS 2 node (feature `cell`)",
            ));
        }
        if let (Some(hand), None, None) = (&scene.hand, &x.grasp, &x.softness) {
            return Err(cx.err(
                hand.span(),
                "hand",
                "is named, but no experiment of this scene moves it",
                "[experiment.grasp] or [experiment.softness] with it, or no [hand]",
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
        if let Some(h) = scene.underactuated_hand() {
            return Err(cx.err(
                h.span(),
                "hand.model",
                "is the underactuated hand, which has no ROS 2 node",
                "a servo hand for `handstack node`; `handstack run` runs the underactuated hand",
            ));
        }
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
        if let Some(h) = scene.underactuated_hand() {
            return Err(cx.err(
                h.span(),
                "hand.model",
                "is the underactuated hand, which the servo grasp loop cannot drive",
                "a servo hand (`mx28`, `xm430`, `rh_p12_rn`) for [experiment.grasp]; \
                 [experiment.softness] runs the underactuated hand",
            ));
        }
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
    if let Some(s) = &x.softness {
        check_softness(scene, s, cx)?;
    }
    if let Some(w) = &x.weight {
        check_weight(scene, w, cx)?;
    }
    if let Some(t) = &x.tap_to_move {
        check_tap_to_move(scene, t, cx)?;
    }
    if let Some(c) = &x.contact {
        check_contact(scene, c, cx)?;
    }
    Ok(())
}

/// A contact experiment's fingertip (its microcontroller) and values.
fn check_contact<X>(
    scene: &SceneFile<X>,
    c: &Spanned<Contact>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    let mcu = scene
        .sensors
        .fingertip
        .as_ref()
        .is_some_and(|t| t.get_ref().serial_port.is_some());
    if !mcu {
        return Err(cx.err(
            c.span(),
            "experiment.contact",
            "needs the fingertip's microcontroller",
            "[sensors.fingertip] with `serial_port`: Arrival-of-Time and the contact MLP need \
             the sensors' arrival times to the millisecond, which the fingertip's board \
             measures",
        ));
    }
    if let Some(cells) = &c.get_ref().cells {
        let v = cells.get_ref();
        let bad = v
            .iter()
            .find(|[r, c]| !(1..=PAD_ROWS).contains(r) || !(1..=PAD_COLS).contains(c));
        if v.is_empty() || v.len() > 240 || bad.is_some() {
            let what = match bad {
                Some([r, c]) => format!("holds [{r}, {c}]"),
                None => format!("has {} cells", v.len()),
            };
            return Err(cx.err(
                cells.span(),
                "experiment.contact.cells",
                what,
                "1…240 cells, each [row, column] with row 1…4 and column 1…6",
            ));
        }
    }
    check_ranges(
        [(&c.get_ref().wait_s, "experiment.contact.wait_s", 1.0, 600.0)],
        cx,
    )
}

/// A tap-to-move's pad, locator and arm, and its values.
fn check_tap_to_move<X>(
    scene: &SceneFile<X>,
    t: &Spanned<TapToMove>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    let cnn = scene.estimators.contact.as_ref().is_some_and(|l| {
        l.get_ref()
            .locators
            .get_ref()
            .contains(&super::parts::Locator::Cnn)
    });
    if scene.sensors.imu_pad.is_none() || scene.arm.is_none() || !cnn {
        return Err(cx.err(
            t.span(),
            "experiment.tap_to_move",
            "needs the ICM-20789 pad, the contact CNN and the arm",
            "[sensors.imu_pad], [estimators.contact] locators with \"cnn\", and [arm]",
        ));
    }
    if let Some(r) = &t.get_ref().regions {
        let v = r.get_ref();
        let bad = v.iter().find(|&&g| g > 8);
        if v.is_empty() || v.len() > 90 || bad.is_some() {
            let what = match bad {
                Some(g) => format!("holds {g}"),
                None => format!("has {} regions", v.len()),
            };
            return Err(cx.err(
                r.span(),
                "experiment.tap_to_move.regions",
                what,
                "1…90 regions, each 0…8",
            ));
        }
    }
    check_ranges(
        [(
            &t.get_ref().wait_s,
            "experiment.tap_to_move.wait_s",
            1.0,
            600.0,
        )],
        cx,
    )
}

/// A weight experiment's fingertip, force DNN and values.
fn check_weight<X>(
    scene: &SceneFile<X>,
    w: &Spanned<Weight>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    if scene.sensors.fingertip.is_none() || scene.estimators.force.is_none() {
        return Err(cx.err(
            w.span(),
            "experiment.weight",
            "needs the fingertip and a force DNN",
            "[sensors.fingertip] and [estimators.force] with it",
        ));
    }
    let x = w.get_ref();
    if let Some(ws) = &x.weights_gf {
        let v = ws.get_ref();
        let bad = v
            .iter()
            .find(|g| !(g.is_finite() && (0.0..=1000.0).contains(*g)));
        if v.is_empty() || v.len() > 50 || bad.is_some() {
            let what = match bad {
                Some(g) => format!("holds {g}"),
                None => format!("has {} weights", v.len()),
            };
            return Err(cx.err(
                ws.span(),
                "experiment.weight.weights_gf",
                what,
                "1…50 weights, each 0…1000 gf",
            ));
        }
    }
    check_ranges(
        [
            (
                &x.tolerance_gf,
                "experiment.weight.tolerance_gf",
                0.01,
                100.0,
            ),
            (&x.settle_s, "experiment.weight.settle_s", 0.0, 30.0),
            (&x.average_s, "experiment.weight.average_s", 0.1, 30.0),
        ],
        cx,
    )
}

/// A softness experiment's hand and its values.
fn check_softness<X>(
    scene: &SceneFile<X>,
    s: &Spanned<Softness>,
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    if scene.underactuated_hand().is_none() {
        return Err(cx.err(
            s.span(),
            "experiment.softness",
            "needs the underactuated hand",
            "[hand] with model = \"underactuated4\"",
        ));
    }
    if scene.sensors.underactuated.is_none() || scene.estimators.softness.is_none() {
        return Err(cx.err(
            s.span(),
            "experiment.softness",
            "needs the hand's sensors and the softness classifier",
            "[sensors.underactuated] and [estimators.softness] with it",
        ));
    }
    let x = s.get_ref();
    let classes = x.expect.iter().map(|e| (e, "experiment.softness.expect"));
    let listed = x.objects.iter().flat_map(|o| o.get_ref().iter());
    for (e, key) in classes.chain(listed.map(|e| (e, "experiment.softness.objects"))) {
        if class_named(e.get_ref()).is_none() {
            return Err(cx.err(
                e.span(),
                key,
                format!("is \"{}\"", e.get_ref()),
                "\"soft\", \"moderate\" or \"hard\"",
            ));
        }
    }
    if let Some(o) = &x.objects {
        if o.get_ref().is_empty() || x.expect.is_some() {
            return Err(cx.err(
                o.span(),
                "experiment.softness.objects",
                if x.expect.is_some() {
                    "is given with `expect`"
                } else {
                    "is empty"
                },
                "one or more classes to grasp in turn, instead of `expect`",
            ));
        }
    }
    check_ranges(
        [
            (
                &x.closing_speed_mm_s,
                "experiment.softness.closing_speed_mm_s",
                0.1,
                20.0,
            ),
            (&x.window_s, "experiment.softness.window_s", 1.0, 60.0),
            (
                &x.approach_timeout_s,
                "experiment.softness.approach_timeout_s",
                1.0,
                600.0,
            ),
        ],
        cx,
    )
}

/// Optional numbers, each `(value, key, least, greatest)`: finite and in its range if given.
fn check_ranges<const N: usize>(
    items: [(&Option<Spanned<f64>>, &str, f64, f64); N],
    cx: &Checker<'_>,
) -> Result<(), SceneError> {
    for (v, key, lo, hi) in items {
        if let Some(v) = v {
            let n = *v.get_ref();
            if !(n.is_finite() && (lo..=hi).contains(&n)) {
                return Err(cx.err(v.span(), key, format!("is {n}"), format!("{lo}…{hi}")));
            }
        }
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
            .filter(|t| !t.get_ref().is_real())
            .map(|t| {
                (
                    t.span(),
                    "sensors.fingertip",
                    "i2c_buses`, `firmata_port` or `serial_port",
                )
            }),
        s.imu_pad
            .as_ref()
            .filter(|p| !p.get_ref().is_real())
            .map(|p| (p.span(), "sensors.imu_pad", "i2c_bus` or `firmata_port")),
        s.underactuated
            .as_ref()
            // Read through the underactuated hand's board (whose `serial_port` is checked below).
            .filter(|_| scene.underactuated_hand().is_none())
            .map(|u| {
                (
                    u.span(),
                    "sensors.underactuated",
                    "[hand] model = \"underactuated4\"",
                )
            }),
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
