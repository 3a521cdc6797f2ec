//! Softness classification on the underactuated hand (seed 001): the hand's ADC codes (four
//! FSR dividers, four distal potentiometers) → forces and angles by the hand's calibration →
//! the 8-variable sample → the committed softness net, its class updated every sample.
//!
//! The device is hand-sim's underactuated hand: one grasp each of a sponge, a silicone-rubber
//! and a wooden object is simulated once, its ADC codes recorded at 10 Hz from first contact
//! to 14 s later (seed 001 §3.1), and replayed in a loop — the hand's physics is simulated
//! up front so a cycle costs what the controller computes, not the simulator's integration.
//! The net's class of a series is the largest *mean* output over its samples
//! (`SoftnessNet::predict`); the cycle keeps the running sums, so its class after a grasp's
//! last sample is the class of the whole series.

use crate::CycleError;
use crate::replay::Replay;
use hand_sim::scene::Model;
use hand_sim::underactuated::{Material, SensorCodes, Underactuated, UnderactuatedConfig};
use hand_traits::{FingerFrame, Softness};
use paper_experiments::data::underactuated::N_VARIABLES;
use paper_experiments::softness_eval::{METRICS_FILE, MODEL_DIR, model_file};
use tactile_nets::metrics::MetricsFile;
use tactile_nets::softness::{CLASSES, SoftnessNet};

/// Samples per second (seed 001 §3.1).
pub const SAMPLE_HZ: f64 = 10.0;
/// The optimiser whose selected model the cycle runs (the paper's Levenberg–Marquardt).
pub const OPTIMISER: &str = "lm";

/// One recorded read: which grasp, which sample of it, the codes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Read {
    /// Index of the grasp in the recording.
    pub grasp: usize,
    /// Sample index within the grasp (0 = first contact).
    pub sample: usize,
    /// The eight ADC codes.
    pub codes: SensorCodes,
}

/// One cycle's result.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftnessOut {
    /// The read replayed.
    pub read: Read,
    /// The decoded sample, in the net's order (N, then degrees).
    pub sample: [f32; N_VARIABLES],
    /// The class of the grasp's series so far.
    pub class: Softness,
}

/// The softness cycle.
pub struct SoftnessCycle {
    hand: Underactuated,
    reads: Replay<Read>,
    net: SoftnessNet,
    grasp: Option<usize>,
    sum: [f64; CLASSES],
    n: u32,
}

impl SoftnessCycle {
    /// Records the three grasps and loads the selected committed LM model.
    pub fn new() -> Result<Self, CycleError> {
        let mut reads = Vec::new();
        let mut calibration = None;
        for (grasp, material) in Material::ALL.into_iter().enumerate() {
            let mut config = UnderactuatedConfig::default();
            config.object.material = material;
            let hand = record(&config, 20 + grasp as u64, grasp, &mut reads)?;
            calibration.get_or_insert(hand);
        }
        let hand = calibration.ok_or_else(|| CycleError::Config("no grasp recorded".into()))?;
        let reads = Replay::new(reads).ok_or_else(|| CycleError::Config("no reads".into()))?;
        Ok(SoftnessCycle {
            hand,
            reads,
            net: selected_net()?,
            grasp: None,
            sum: [0.0; CLASSES],
            n: 0,
        })
    }

    /// Decode: the next ADC read, converted by the hand's nominal sensor laws.
    pub fn decode(&mut self) -> (Read, FingerFrame<4>) {
        let read = *self.reads.next_item();
        (read, self.hand.decode(&read.codes))
    }

    /// Estimate: the net's 8 variables (forces in N, then distal angles in degrees).
    pub fn estimate(frame: &FingerFrame<4>) -> [f32; N_VARIABLES] {
        core::array::from_fn(|j| {
            if j < 4 {
                frame.force_n[j]
            } else {
                frame.distal_angle_rad[j - 4].to_degrees()
            }
        })
    }

    /// Policy: the sample's outputs added to its grasp's running sums; the class so far.
    pub fn policy(
        &mut self,
        grasp: usize,
        sample: &[f32; N_VARIABLES],
    ) -> Result<Softness, CycleError> {
        if self.grasp != Some(grasp) {
            self.grasp = Some(grasp);
            self.sum = [0.0; CLASSES];
            self.n = 0;
        }
        let y = self.net.sample_outputs(sample)?;
        for (s, y) in self.sum.iter_mut().zip(y) {
            *s += f64::from(y);
        }
        self.n += 1;
        // Largest mean, ties to the softer class, as `SoftnessNet::predict`.
        let best = (1..CLASSES).fold(0, |b, k| if self.sum[k] > self.sum[b] { k } else { b });
        Softness::from_index(best).ok_or_else(|| CycleError::Config("no class".into()))
    }

    /// One full cycle.
    pub fn cycle(&mut self) -> Result<SoftnessOut, CycleError> {
        let (read, frame) = self.decode();
        let sample = Self::estimate(&frame);
        let class = self.policy(read.grasp, &sample)?;
        Ok(SoftnessOut {
            read,
            sample,
            class,
        })
    }

    /// Reads in one round of the replay.
    pub fn reads_per_round(&self) -> usize {
        self.reads.len()
    }

    /// The net the cycle runs.
    pub fn net(&self) -> &SoftnessNet {
        &self.net
    }
}

/// Simulates one grasp (as `hand_sim::underactuated::record_grasp`, keeping the raw codes)
/// and appends its reads; returns the hand, whose calibration decodes them.
fn record(
    config: &UnderactuatedConfig,
    seed: u64,
    grasp: usize,
    out: &mut Vec<Read>,
) -> Result<Underactuated, CycleError> {
    let mut hand = Underactuated::new(config, seed)?;
    let step = hand.step_ns();
    while hand.first_contact_ns().is_none() && hand.steps() * step < hand.end_ns() {
        hand.step_to((hand.steps() + 1) * step)?;
    }
    let start = hand
        .first_contact_ns()
        .ok_or_else(|| CycleError::Config(format!("grasp {grasp} never touched")))?;
    let period = (1e9 / SAMPLE_HZ).round() as u64;
    let samples = hand.end_ns().saturating_sub(start) / period;
    for k in 0..=samples {
        hand.step_to(start + k * period)?;
        out.push(Read {
            grasp,
            sample: k as usize,
            codes: hand.read_codes(),
        });
    }
    Ok(hand)
}

/// The committed model of [`OPTIMISER`] that `metrics.json`'s `selected` row names.
fn selected_net() -> Result<SoftnessNet, CycleError> {
    let dir = crate::workspace_root().join(MODEL_DIR);
    let text = std::fs::read_to_string(dir.join(METRICS_FILE))
        .map_err(|e| CycleError::Config(format!("{MODEL_DIR}/{METRICS_FILE}: {e}")))?;
    let metrics = MetricsFile::from_json(&text)?;
    let key = format!("{OPTIMISER}_seed");
    let seed = metrics
        .row("selected")
        .and_then(|r| r.values.get(&key))
        .ok_or_else(|| CycleError::Config(format!("{METRICS_FILE}: no selected {key}")))?;
    Ok(SoftnessNet::load(
        &dir.join(model_file(OPTIMISER, *seed as u64)),
    )?)
}
