//! Hardware bring-up: read the fingertip at rest and report the frame period and each
//! sensor's noise (standard deviation, Pa) at its OSR.

use super::Part;
use super::figure::measured;
use crate::error::{Ending, RunError};
use crate::progress::Progress;
use crate::record::grasp::RawTopic;
use crate::record::{Recorder, now_ns};
use crate::stop::Stop;
use crate::{Line, Plot};
use hand_traits::{PressureFrame, TactileSource};

/// Reads `n` frames from `source` (any fingertip of three sensors) and reports its rate and
/// noise; a read error ends the readout with that error, `stop` with how many frames it read.
/// With `record`, each frame is recorded as it is read (`/hand0/tactile/raw`).
pub fn run<S>(
    source: &mut S,
    n: usize,
    progress: &dyn Progress,
    stop: &Stop,
    record: Option<&Recorder>,
) -> Result<Part, RunError>
where
    S: TactileSource<Frame = PressureFrame<3>> + ?Sized,
    RunError: From<S::Error>,
{
    progress.stage("readout: fingertip frames", n as u64);
    let mut frames = Vec::with_capacity(n);
    let mut raw = record.map(RawTopic::new);
    for _ in 0..n {
        if let Some(reason) = stop.reason() {
            return Err(RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!(
                    "readout: stopped by {reason} after {} of {n} frames",
                    frames.len()
                ),
            });
        }
        let frame = source.read_frame()?;
        if let Some(raw) = &mut raw {
            raw.record(now_ns(), &frame.pressure_pa);
        }
        frames.push(frame);
        progress.advance(1);
    }
    let mut part = Part::default();
    let span_us = frames.last().map_or(0, |f| f.t_us) - frames.first().map_or(0, |f| f.t_us);
    part.figures
        .push(measured("frames", "frames read", n as f64, ""));
    part.figures.push(measured(
        "frame_period_ms",
        "mean frame period (three sensors)",
        span_us as f64 * 1e-3 / (n - 1).max(1) as f64,
        "ms",
    ));
    for k in 0..3 {
        let v: Vec<f64> = frames.iter().map(|f| f64::from(f.pressure_pa[k])).collect();
        let mean = v.iter().sum::<f64>() / v.len() as f64;
        let sd = (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (v.len() - 1).max(1) as f64)
            .sqrt();
        part.figures.push(measured(
            &format!("sensor{}_mean_pa", k + 1),
            &format!("sensor {}: mean pressure", k + 1),
            mean,
            "Pa",
        ));
        part.figures.push(measured(
            &format!("sensor{}_sd_pa", k + 1),
            &format!("sensor {}: standard deviation", k + 1),
            sd,
            "Pa",
        ));
    }
    let t0 = frames.first().map_or(0, |f| f.t_us);
    part.plots.push(Plot::Lines {
        title: "Fingertip at rest".into(),
        x_label: "time (s)".into(),
        y_label: "pressure (Pa)".into(),
        lines: (0..3)
            .map(|k| Line {
                label: format!("sensor {}", k + 1),
                points: frames
                    .iter()
                    .map(|f| ((f.t_us - t0) as f64 * 1e-6, f64::from(f.pressure_pa[k])))
                    .collect(),
            })
            .collect(),
    });
    Ok(part)
}
