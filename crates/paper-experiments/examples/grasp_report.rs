//! Regenerates docs/grasping/: the closed-loop results table (`results.csv`) for the six
//! Table 5 objects and the 20 randomised ones, and one plot per Table 5 object of torque,
//! position, pad pressure and motor current over the first 10 s (as seed 000 Figures 23–24).
//! Run: `cargo run --profile test -p paper-experiments --example grasp_report`.

use paper_experiments::data::grasp_results::{self, GraspResult};
use paper_experiments::grasp_rig as support;

use hand_control::grasp_loop::TorqueBand;
use hand_sim::grasp::{ObjectKind, ObjectParams, RigParams, random_objects};
use paper_fixtures::seed000::table5_grasp_torque;
use plotters::prelude::*;
use std::error::Error;
use std::path::Path;

/// Seconds shown in the plots: closing, squeeze, lift at 3 s and the start of the hold.
const PLOT_S: f64 = 10.0;

fn main() -> Result<(), Box<dyn Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let out = root.join("docs/grasping");
    std::fs::create_dir_all(&out)?;
    let rig = RigParams::default();
    let mut rows = Vec::new();
    let mut row = |o: &support::Outcome| rows.push(GraspResult::new(o));
    for r in table5_grasp_torque()? {
        let kind = ObjectKind::from_name(&r.object).ok_or("a Table 5 object")?;
        let (lo, hi) = (r.torque_min as u16, r.torque_max as u16);
        let object = ObjectParams::calibrated(kind, lo, hi, &rig)?;
        let (o, l, w) = support::hold(&r.object, object, TorqueBand::new(lo, hi)?, 7)?;
        row(&o);
        plot(
            &out.join(format!("{}.svg", r.object)),
            &o,
            &l,
            &w.borrow().trace,
        )?;
    }
    for (i, r) in random_objects(42, 20, &rig)?.into_iter().enumerate() {
        let band = TorqueBand::new(r.range.min, r.range.max)?;
        let (o, _, _) = support::hold(&r.params.name.clone(), r.params, band, 100 + i as u64)?;
        row(&o);
    }
    let csv = grasp_results::to_csv(rows);
    std::fs::write(root.join(grasp_results::RESULTS_FILE), &csv)?;
    print!("{csv}");
    Ok(())
}

/// Four stacked panels over the first [`PLOT_S`] seconds.
fn plot(
    file: &Path,
    o: &support::Outcome,
    l: &support::SimLoop,
    truth: &[support::Truth],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(file, (720, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!(
            "{}: Table 5 band {}…{}, closed loop (lift at 3 s)",
            o.name, o.band.0, o.band.1
        ),
        ("sans-serif", 18),
    )?;
    let panels = root.split_evenly((4, 1));
    let t = |t_us: u64| t_us as f64 * 1e-6;
    let log = l.log();
    let series: [(&str, Vec<(f64, f64)>); 4] = [
        (
            "torque limit sent (0…1023)",
            log.iter()
                .filter_map(|s| s.torque_raw.map(|r| (t(s.t_us), f64::from(r))))
                .collect(),
        ),
        (
            "position (rad)",
            log.iter()
                .filter_map(|s| s.state.map(|st| (t(s.t_us), f64::from(st.position_rad))))
                .collect(),
        ),
        (
            "mean pad pressure rise (Pa)",
            log.iter()
                .filter_map(|s| s.estimate.map(|e| (t(s.t_us), f64::from(e.pressure_pa))))
                .collect(),
        ),
        (
            "motor current (A, simulator)",
            truth.iter().map(|p| (p.t_s, p.current_a)).collect(),
        ),
    ];
    for (area, (label, points)) in panels.iter().zip(series) {
        let points: Vec<_> = points.into_iter().filter(|p| p.0 <= PLOT_S).collect();
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
        let pad = ((hi - lo) * 0.1).max(1e-3);
        let mut chart = ChartBuilder::on(area)
            .margin(8)
            .x_label_area_size(30)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..PLOT_S, (lo - pad).min(0.0)..hi + pad)?;
        chart
            .configure_mesh()
            .x_desc("time (s)")
            .y_desc(label)
            .draw()?;
        chart.draw_series(LineSeries::new(points, BLUE))?;
    }
    root.present()?;
    Ok(())
}
