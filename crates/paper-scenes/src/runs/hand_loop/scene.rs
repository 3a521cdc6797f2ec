//! The full-hand scene's loop on the stack `devices` opens: the grasp stack of the first
//! object (the Table 5 world), the pad with the tap protocol's schedule, the arm; composed,
//! run, and reported as figures.

use super::{ArmPart, Estimators, HandLoop, PadPart, Stats, TapTrigger};
use crate::devices::fingertip::Fingertip;
use crate::devices::grasp::Environment;
use crate::runs::figure::{Target, measured, target};
use crate::runs::{Part, RunContext};
use crate::scene::PaperScene;
use crate::scene::experiments::WindowPlacement;
use hand_control::grasp_loop::{LoopClock, TorqueBand};
use hand_sim::imu_pad::ImuPad;
use hand_traits::{ImuFrame, TactileSource};
use handstack::RunError;
use handstack::scene::parts::Locator;
use handstack::tap_to_move::{RegionToGrid, TapToMoveConfig};
use paper_experiments::cnn_eval::{MODEL_DIR as CNN_DIR, model_file};
use paper_experiments::grasp_rig::{self, LIFT_AT_S};
use paper_experiments::tap_run;
use tactile_nets::contact_cnn::{ContactCnn, Variant};
use tactile_nets::contact_mlp::ContactMlp;

/// The pad's rate, Hz (seed 002 §III-C).
pub const PAD_HZ: u32 = 30;
/// Loop time the loop may run on after the hold for the arm to finish its moves, µs (in
/// simulated time the loop runs far ahead of the arm's wall-time controller).
pub const FINISH_MOVES_US: u64 = 600_000_000;

/// Whether `scene` names the whole hand: a simulated fingertip grasp and the pad's taps.
pub fn applies(scene: &PaperScene) -> bool {
    let f = &scene.file;
    let x = f.experiment.get_ref();
    let real = f
        .hand
        .as_ref()
        .is_some_and(|h| h.get_ref().serial_port.is_some())
        || f.sensors
            .imu_pad
            .as_ref()
            .is_some_and(|p| p.get_ref().is_real());
    x.grasp.is_some() && x.tap.is_some() && f.sensors.imu_pad.is_some() && !real
}

fn dev(device: &'static str) -> impl Fn(String) -> RunError {
    move |reason| RunError::Device { device, reason }
}

/// The loop over the opened stack (its pad hand-sim's, or that wrapped by a test).
pub type SimHandLoop<Pad = ImuPad> = HandLoop<
    Fingertip,
    fuzzy_mamdani::GraspController,
    hand_control::ServoHand,
    Box<dyn LoopClock>,
    Pad,
>;

/// The loop of a scene, built, with what the run keeps beside it.
pub struct Built<Pad = ImuPad> {
    /// The loop.
    pub hand_loop: SimHandLoop<Pad>,
    /// The grasp's world, where the stack is simulated (the fingertip, servo bus and physics
    /// on one clock).
    pub environment: Option<Environment>,
    /// The first grasp object's name.
    pub object: String,
    /// Loop time the hold ends, µs (lift at 3 s + `hold_s`).
    pub until_us: u64,
    /// Where the arm is connected.
    pub host: String,
    /// The arm's simulator, when the scene named no host.
    pub sim: Option<ur_sim::UrSim>,
}

/// Runs the fused loop of `scene`: the first grasp object closed, lifted at 3 s and held
/// `hold_s`, the pad's taps of one round located and sent to the arm, then on until the
/// arm's moves are done.
pub fn run(scene: &PaperScene, cx: &RunContext<'_>) -> Result<Part, crate::Error> {
    let Some(mut b) = build(scene, cx)? else {
        return Ok(Part::default());
    };
    b.hand_loop.run_until(b.until_us);
    b.hand_loop.finish_moves(FINISH_MOVES_US);
    if let Some(env) = &b.environment {
        env.fate()?;
    }
    Ok(b.figures())
}

impl<Pad> Built<Pad>
where
    Pad: TactileSource<Frame = ImuFrame>,
    Pad::Error: core::fmt::Display,
{
    /// The loop's figures so far.
    pub fn figures(&self) -> Part {
        let mut part = Part::default();
        let l = &self.hand_loop;
        figures(
            l.stats(),
            l.overruns(),
            l.fault(),
            &self.object,
            &self.host,
            &mut part,
        );
        part
    }
}

/// Builds the fused loop of `scene` on the simulated stack (`None`: the scene names no
/// grasp or no tap).
pub fn build(scene: &PaperScene, cx: &RunContext<'_>) -> Result<Option<Built>, crate::Error> {
    build_with(scene, cx, |pad| pad)
}

/// [`build`] with the pad handed through `wrap` first (a test injects the pad's faults there).
pub fn build_with<Pad>(
    scene: &PaperScene,
    cx: &RunContext<'_>,
    wrap: impl FnOnce(ImuPad) -> Pad,
) -> Result<Option<Built<Pad>>, crate::Error>
where
    Pad: TactileSource<Frame = ImuFrame>,
    Pad::Error: core::fmt::Display,
{
    let x = scene.file.experiment.get_ref();
    let (Some(g), Some(tap)) = (&x.grasp, &x.tap) else {
        return Ok(None);
    };
    let (g, tap) = (g.get_ref(), tap.get_ref());
    cx.progress.stage("full hand: one control loop", 0);
    // The grasp: the first object of the scene, in its Table 5 band.
    let table5 = paper_fixtures::seed000::table5_grasp_torque()?;
    let name = g.objects.get_ref().first().cloned().unwrap_or_default();
    let row = table5
        .iter()
        .find(|r| r.object == name)
        .ok_or_else(|| dev("hand loop")(format!("{name} is not in Table 5")))?;
    let (lo, hi) = (row.torque_min as u16, row.torque_max as u16);
    let band = TorqueBand::new(lo, hi).map_err(|e| dev("hand loop")(e.to_string()))?;
    let grasp = crate::devices::grasp::open(scene, cx, &name, band, g.seed)?;
    let config = grasp.config;
    // The estimators.
    let force = crate::runs::weight::force_dnn(scene, &cx.root)?;
    let locators = scene.locators();
    let mlp = if locators.contains(&Locator::Mlp) {
        let (file, _) = x
            .contact
            .as_ref()
            .map(|c| c.get_ref().mlp)
            .unwrap_or_default()
            .file_and_label(grasp_rig::OSR);
        let dir = cx.root.join(paper_experiments::contact_eval::MODEL_DIR);
        Some(ContactMlp::load(&dir.join(file))?)
    } else {
        None
    };
    let estimators = Estimators::new(force, mlp, config.tare_cycles);
    // The pad, its trigger and the CNN, as the tap scene builds them.
    let trigger = match tap.window {
        WindowPlacement::Aligned => tap_run::training_aligned(),
        WindowPlacement::Trigger => TapToMoveConfig::default(),
    };
    let pad = PadPart {
        pad: wrap(crate::devices::pad::open(
            scene,
            crate::devices::pad::schedule(scene, *tap.taps_per_region.get_ref()),
        )?),
        rate_hz: PAD_HZ,
        trigger: TapTrigger::new(trigger),
        cnn: ContactCnn::load(&cx.root.join(CNN_DIR).join(model_file(Variant::Paper)))?,
        to_input: tap_run::cnn_window,
    };
    // The arm.
    let arm = crate::devices::arm::open_in(scene, cx)?;
    let grid = RegionToGrid::ur3_default().map_err(|e| dev("arm")(e.to_string()))?;
    let arm_part = ArmPart::new(arm.arm, grid, trigger.motion);
    let policy = fuzzy_mamdani::grasp_controller()
        .with_torque_band(config.band.min_raw(), config.band.max_raw());
    let hand_loop = HandLoop::new(
        grasp.tip,
        policy,
        grasp.hand,
        grasp.clock,
        config,
        estimators,
        pad,
        arm_part,
    )
    .map_err(|e| dev("hand loop")(e.to_string()))?;
    let hold_s = *g.hold_s.get_ref();
    Ok(Some(Built {
        hand_loop,
        environment: grasp.environment,
        object: name,
        until_us: ((LIFT_AT_S + hold_s) * 1e6) as u64,
        host: arm.host,
        sim: arm.sim,
    }))
}

/// The loop's figures.
pub fn figures(
    st: &Stats,
    overruns: u64,
    fault: Option<&super::LoopFaultReport>,
    object: &str,
    host: &str,
    part: &mut Part,
) {
    let t = &st.compute;
    let (mean, p99, max) = (t.mean_us(), t.percentile_us(99), t.max_us());
    let f = &mut part.figures;
    f.push(measured(
        "loop_cycles",
        &format!("fused loop: 10 ms cycles run ({object} held, arm at {host})"),
        st.cycles as f64,
        "",
    ));
    for (key, label, v) in [
        ("loop_compute_mean_us", "mean", mean),
        ("loop_compute_p99_us", "p99", p99),
        ("loop_compute_max_us", "max", max),
    ] {
        f.push(measured(
            key,
            &format!("fused loop: compute per cycle, {label} (wall, waiting excluded)"),
            v,
            "µs",
        ));
    }
    f.push(measured(
        "loop_jitter_max_us",
        "fused loop: max |cycle start − tick| (loop clock)",
        st.jitter_max_us as f64,
        "µs",
    ));
    f.push(target(
        measured(
            "loop_overruns",
            "fused loop: ticks missed (FixedRate)",
            overruns as f64,
            "",
        ),
        Target::AtMost(0.0),
    ));
    f.push(measured(
        "loop_pad_reads",
        "fused loop: ICM-20789 frames read (30 Hz)",
        st.pad_reads as f64,
        "",
    ));
    f.push(measured(
        "loop_cnn_triggers",
        &format!(
            "fused loop: taps located by the CNN (regions {})",
            list(&st.located)
        ),
        st.cnn_triggers as f64,
        "",
    ));
    f.push(measured(
        "loop_arm_moves_started",
        "fused loop: moveL started (async)",
        st.moves_started as f64,
        "",
    ));
    f.push(measured(
        "loop_arm_moves_completed",
        "fused loop: moveL completed",
        st.moves_completed as f64,
        "",
    ));
    f.push(measured(
        "loop_fingertip_contacts",
        &format!(
            "fused loop: fingertip contacts (last AoT area {}, MLP area {})",
            area(st.aot_area),
            area(st.mlp_area)
        ),
        st.contacts as f64,
        "",
    ));
    f.push(measured(
        "loop_force_final_gf",
        "fused loop: force DNN, last estimate",
        st.force_gf.map_or(f64::NAN, f64::from),
        "gf",
    ));
    f.push(measured(
        "loop_torque_final_raw",
        "fused loop: torque limit last sent",
        st.torque_raw.map_or(f64::NAN, f64::from),
        "",
    ));
    let Some(r) = fault else {
        f.push(measured("loop_fault", "fused loop: faults (none)", 0.0, ""));
        return;
    };
    let t_s = r.t_us as f64 * 1e-6;
    let label = format!(
        "fused loop: fault of {} in cycle {} at t = {t_s:.2} s ({}); hand {}",
        r.device, r.cycle, r.reason, r.mode
    );
    f.push(measured("loop_fault", &label, 1.0, ""));
    f.push(measured(
        "loop_fault_t_s",
        "fused loop: fault time",
        t_s,
        "s",
    ));
}

/// Values as a person lists them: `1, 4, 7` (`none` when empty).
fn list<T: core::fmt::Display>(values: &[T]) -> String {
    if values.is_empty() {
        return "none".to_owned();
    }
    values
        .iter()
        .map(T::to_string)
        .collect::<Vec<_>>()
        .join(", ")
}

/// An area, or `none` before the first.
fn area<T: core::fmt::Display>(a: Option<T>) -> String {
    a.map_or_else(|| "none".to_owned(), |a| a.to_string())
}
