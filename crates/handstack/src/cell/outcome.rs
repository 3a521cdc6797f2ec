//! A cell run as an [`Outcome`]: its figures in the summary table every command prints.

use super::launch::CellRun;
use crate::Outcome;
use crate::runs::figure::measured as figure;

/// The `q`-quantile (nearest rank) of `v`; NaN when empty.
pub fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    if s.is_empty() {
        return f64::NAN;
    }
    s.sort_by(f64::total_cmp);
    let rank = ((q * s.len() as f64).ceil() as usize).clamp(1, s.len());
    s[rank - 1]
}

/// The outcome of `run`, named after the cell file's stem.
pub fn outcome(name: &str, run: &CellRun) -> Outcome {
    let r = &run.report;
    let latency: Vec<f64> = r.rows.iter().map(|x| x.contact_latency_s * 1e3).collect();
    let moves: Vec<f64> = r.rows.iter().map(|x| x.move_s).collect();
    let n = r.rows.len().max(1) as f64;
    Outcome {
        scene: name.to_owned(),
        title: run.cell.title.clone(),
        notes: Vec::new(),
        figures: vec![
            figure(
                "taps",
                "taps handled across the cell",
                r.rows.len() as f64,
                "",
            ),
            figure(
                "discovery_s",
                "coordinator open → every node in the graph",
                r.discovery_s,
                "s",
            ),
            figure(
                "contact_latency_p50_ms",
                "contact: pad node publish → coordinator, p50",
                quantile(&latency, 0.5),
                "ms",
            ),
            figure(
                "contact_latency_max_ms",
                "contact: pad node publish → coordinator, max",
                quantile(&latency, 1.0),
                "ms",
            ),
            figure(
                "move_mean_s",
                "goal published → arm's tcp_pose there, mean (wall)",
                moves.iter().sum::<f64>() / n,
                "s",
            ),
            figure(
                "tcp_error_max_m",
                "arm's distance from the goal when it arrived, max",
                r.rows.iter().map(|x| x.tcp_error_m).fold(0.0, f64::max),
                "m",
            ),
            figure(
                "contacts_before_listening",
                "contacts published before the coordinator listened",
                r.rows.first().map_or(0.0, |x| (x.seq - 1).max(0) as f64),
                "",
            ),
            figure(
                "lost_contacts",
                "contacts lost (pad sequence gaps)",
                r.lost_contacts as f64,
                "",
            ),
            figure(
                "malformed",
                "samples dropped as malformed",
                r.malformed as f64,
                "",
            ),
        ],
        plots: Vec::new(),
        wall_s: run.wall_s,
    }
}
