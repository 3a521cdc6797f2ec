//! `handstack calibrate SCENE`: the underactuated hand's potentiometers zeroed on the hand
//! itself. A potentiometer mounted again reads the open joint some degrees off the
//! `zero_deg` of `[sensors.underactuated] pot`, and every distal angle the softness net reads
//! carries that error. With the hand open and empty (each distal joint against its open stop,
//! 0°), the run averages [`READINGS`] readings of the four wipers and gives each finger the
//! `zero_deg` that reads its open joint as 0°, as the `pot = [...]` line to put in the scene;
//! the FSRs at rest besides (a strip preloaded by its mounting reads a force there). The
//! stepper is not moved; its driver's outputs are left off.

use crate::error::{Ending, RunError};
use crate::prompt::Unanswered;
use crate::runs::RunContext;
use crate::runs::figure::measured;
use crate::scene::Scene;
use crate::{Figure, Outcome};
use std::time::{Duration, Instant};
use underactuated_hand::calibration::{PotMount, adc_volts};

/// Readings averaged (about a second at the board's 19 ms sampling).
pub const READINGS: usize = 50;
/// The longest the readings may take.
const READ_WITHIN: Duration = Duration::from_secs(10);
/// How long one wait for a reading may take before the stop is looked at again.
const READ_WAIT: Duration = Duration::from_millis(50);

/// Calibrates the underactuated hand `scene` names: asks for the hand open and empty, reads it,
/// and gives each potentiometer's `zero_deg`.
///
/// Errors: a scene without the underactuated hand, the hand's (it cannot be opened, it stops
/// reporting), a stop at the question or while reading.
pub fn calibrate(scene: &Scene, cx: &RunContext<'_>) -> Result<Outcome, RunError> {
    let start = Instant::now();
    let (hand_scene, _) = crate::stack::hand::scene_hand(scene)?;
    let config = crate::stack::underactuated::config(scene, hand_scene);
    let mut hand = crate::stack::underactuated::open(scene)?;
    let fault = |e: &underactuated_hand::HandError| RunError::Ended {
        ending: Ending::Fault,
        what: format!("calibrate: hand: {e}; the stepper was not moved"),
    };
    cx.progress
        .say("Open the hand fully, with nothing in it, then press Enter.");
    match cx.prompter.answer(&cx.stop) {
        Ok(_) => {}
        Err(Unanswered::Stopped(reason)) => {
            hand.disable().map_err(|e| fault(&e))?;
            return Err(RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!(
                    "calibrate: stopped by {reason} before the hand was read; nothing changed"
                ),
            });
        }
        Err(Unanswered::Closed) => {
            hand.disable().map_err(|e| fault(&e))?;
            return Err(RunError::Ended {
                ending: Ending::Failed,
                what: "calibrate: the input ended before the hand was open".into(),
            });
        }
    }
    cx.progress
        .stage("calibrate: reading the open hand", READINGS as u64);
    let mut sums = [0.0f64; 8];
    let mut n = 0;
    let until = Instant::now() + READ_WITHIN;
    while n < READINGS {
        if let Some(reason) = cx.stop.reason() {
            hand.disable().map_err(|e| fault(&e))?;
            return Err(RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!("calibrate: stopped by {reason} while reading; nothing changed"),
            });
        }
        if Instant::now() > until {
            return Err(fault(&underactuated_hand::HandError::Setup(format!(
                "{n} of {READINGS} readings within {} s",
                READ_WITHIN.as_secs()
            ))));
        }
        if let Some(r) = hand.next_reading(READ_WAIT).map_err(|e| fault(&e))? {
            for (s, c) in sums.iter_mut().zip(r.codes) {
                *s += adc_volts(c, config.calibration.vref_v);
            }
            n += 1;
            cx.progress.advance(1);
        }
    }
    hand.disable().map_err(|e| fault(&e))?;
    let vcc = config.calibration.vref_v;
    let volts = sums.map(|s| s / n as f64);
    let now = config.calibration;
    let zeroed: [PotMount; 4] = core::array::from_fn(|k| now.pot[k].zeroed_at(volts[4 + k], vcc));
    let mut figures: Vec<Figure> = Vec::new();
    for k in 0..4 {
        figures.push(measured(
            &format!("open_angle_deg_{}", k + 1),
            &format!("finger {}: the open joint read as", k + 1),
            now.pot[k].angle_deg(volts[4 + k], vcc),
            "°",
        ));
    }
    for (k, z) in zeroed.iter().enumerate() {
        figures.push(measured(
            &format!("zero_deg_{}", k + 1),
            &format!("finger {}: zero_deg that reads it 0°", k + 1),
            z.zero_deg,
            "°",
        ));
    }
    let rest = (0..4)
        .map(|k| now.fsr.force_n(volts[k], vcc))
        .fold(0.0f64, f64::max);
    figures.push(measured(
        "rest_force_n",
        "the largest FSR force read at rest",
        rest,
        "N",
    ));
    let line = zeroed
        .iter()
        .map(|p| {
            format!(
                "{{ travel_deg = {}, zero_deg = {:.2} }}",
                p.travel_deg, p.zero_deg
            )
        })
        .collect::<Vec<_>>()
        .join(", ");
    Ok(Outcome {
        scene: scene.name.clone(),
        title: format!("Potentiometers of the hand on {}", hand.port()),
        figures,
        plots: Vec::new(),
        notes: vec![
            format!(
                "{n} readings of the open hand averaged; put in the scene's \
                 [sensors.underactuated]: pot = [{line}]"
            ),
            "the stepper was not moved; its driver's outputs are off".into(),
        ],
        wall_s: start.elapsed().as_secs_f64(),
    })
}
