//! Draws the calibration plots of docs/sim-calibration/ (SVG): paper figures against the
//! simulator's. Run: `cargo run -p hand-sim --example calibration_plots`.

use hand_sim::fingertip::{Cell, CellSet, ContactPatch, LawParams};
use hand_sim::imu_pad::ImuPadConfig;
use hand_sim::underactuated::{Material, Shape, UnderactuatedConfig, record_grasp};
use paper_fixtures::Table;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::error::Error;
use std::ops::Range;
use std::path::Path;

type Res = Result<(), Box<dyn Error>>;
const SENSOR_COLOURS: [RGBColor; 3] = [RED, GREEN, BLUE];

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// A captioned chart on `area` with both axes' ranges and descriptions.
fn chart<'a, 'b>(
    area: &'a DrawingArea<SVGBackend<'b>, Shift>,
    caption: impl AsRef<str>,
    x: (Range<f64>, &str),
    y: (Range<f64>, &str),
) -> Result<Chart<'a, 'b>, Box<dyn Error>> {
    let mut chart = ChartBuilder::on(area)
        .caption(caption.as_ref(), ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(x.0, y.0)?;
    chart.configure_mesh().x_desc(x.1).y_desc(y.1).draw()?;
    Ok(chart)
}

/// The series legend at `position`.
fn legend<'a, 'b: 'a>(chart: &mut Chart<'a, 'b>, position: SeriesLabelPosition) -> Res {
    chart
        .configure_series_labels()
        .position(position)
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()?;
    Ok(())
}

fn derived(name: &str) -> Result<Table, Box<dyn Error>> {
    let file = paper_fixtures::fixtures_dir().join("derived").join(name);
    Ok(Table::parse(file.clone(), &std::fs::read_to_string(file)?)?)
}

fn cell_of_label(label: f64) -> Option<Cell> {
    let tenths = (label * 10.0).round() as u8;
    Cell::new(tenths / 10, tenths % 10)
}

/// Table 2 parity: every (row, sensor) point, paper rise on x, simulated on y.
fn fingertip_table2(out: &Path) -> Res {
    let root = SVGBackend::new(out, (640, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = chart(
        &root,
        "Fingertip vs seed 000 Table 2 (single cell, 5/7/9 kgf)",
        (-5.0..75.0, "paper rise, hPa"),
        (-5.0..75.0, "simulated rise, hPa"),
    )?;
    chart
        .draw_series(LineSeries::new(
            [(-5.0, -5.0), (75.0, 75.0)],
            BLACK.mix(0.4),
        ))?
        .label("y = x");
    let law = LawParams::CALIBRATED;
    for (k, col) in ["rise1_hpa", "rise2_hpa", "rise3_hpa"].iter().enumerate() {
        let mut points = Vec::new();
        for r in derived("seed000_table2_rise.csv")?.records() {
            let cell = cell_of_label(r.f64("average_area")?).ok_or("label off the pad")?;
            let sim = law.steady_rise_hpa(&ContactPatch::from_kgf(
                CellSet::EMPTY.with(cell),
                r.f64("force_kgf")?,
            ));
            points.push((r.f64(col)?, sim[k]));
        }
        let colour = SENSOR_COLOURS[k];
        chart
            .draw_series(
                points
                    .into_iter()
                    .map(|p| Circle::new(p, 4, colour.filled())),
            )?
            .label(format!("sensor {}", k + 1))
            .legend(move |(x, y)| Circle::new((x, y), 4, colour.filled()));
    }
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    root.present()?;
    Ok(())
}

/// Table 1: whole-pad rise against weight, paper points and simulated lines.
fn fingertip_table1(out: &Path) -> Res {
    let root = SVGBackend::new(out, (640, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = chart(
        &root,
        "Fingertip vs seed 000 Table 1 (whole pad, 0-200 gf)",
        (0.0..210.0, "weight, gf"),
        (0.0..1.4, "rise, hPa"),
    )?;
    let law = LawParams::CALIBRATED;
    let all = Cell::all().fold(CellSet::EMPTY, CellSet::with);
    let table = derived("seed000_table1_rise.csv")?;
    for (k, col) in ["rise1_hpa", "rise2_hpa", "rise3_hpa"].iter().enumerate() {
        let colour = SENSOR_COLOURS[k];
        let sim = (0..=200).map(|gf| {
            (
                f64::from(gf),
                law.steady_rise_hpa(&ContactPatch::from_kgf(all, f64::from(gf) / 1000.0))[k],
            )
        });
        chart
            .draw_series(LineSeries::new(sim, colour))?
            .label(format!("sensor {} sim (line) / paper (dots)", k + 1))
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
        let paper: Vec<(f64, f64)> = table.map(|r| Ok((r.f64("weight_gf")?, r.f64(col)?)))?;
        chart.draw_series(
            paper
                .into_iter()
                .map(|p| Circle::new(p, 4, colour.filled())),
        )?;
    }
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    root.present()?;
    Ok(())
}

/// The ICM pad's depth → force curve against seed 002's three published points.
fn imu_pad_force_depth(out: &Path) -> Res {
    let curve = ImuPadConfig::default().mechanics.curve()?;
    let root = SVGBackend::new(out, (640, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = chart(
        &root,
        "ICM-20789 pad: force vs contact depth (seed 002 Fig. 6B / 7B)",
        (0.6..1.8, "contact depth, mm"),
        (0.0..16.0, "force, N"),
    )?;
    let sim = (60..=180)
        .map(|d| f64::from(d) / 100.0)
        .map(|d| (d, curve.force_n(d)));
    chart
        .draw_series(LineSeries::new(sim, BLUE))?
        .label("simulator")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 16, y)], BLUE));
    let paper: Vec<(f64, f64)> = paper_fixtures::seed002::force_depth()?
        .iter()
        .map(|r| (r.depth_mm, r.measured_n))
        .collect();
    chart
        .draw_series(paper.into_iter().map(|p| Circle::new(p, 5, RED.filled())))?
        .label("paper (measured)")
        .legend(|(x, y)| Circle::new((x, y), 5, RED.filled()));
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    root.present()?;
    Ok(())
}

/// Fig. 9 of seed 001, simulated: finger-1 force and distal angle over a grasp of an 80 mm
/// cylinder in each softness.
fn underactuated_fig9(out: &Path) -> Res {
    let root = SVGBackend::new(out, (900, 420)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(450);
    let materials = [
        (Material::Sponge, "soft (sponge)", BLUE),
        (Material::SiliconeRubber, "moderate (silicone)", GREEN),
        (Material::Wood, "hard (wood)", RED),
    ];
    let mut series = Vec::new();
    for (m, name, colour) in materials {
        let mut config = UnderactuatedConfig::default();
        config.object.shape = Shape::Cylinder;
        config.object.size_mm = 80.0;
        config.object.material = m;
        let g = record_grasp(&config, 1, 10.0)?;
        let t0 = g.frames.first().map_or(0, |f| f.t_us);
        let pts: Vec<(f64, f64, f64)> = g
            .frames
            .iter()
            .map(|f| {
                (
                    (f.t_us - t0) as f64 * 1e-6,
                    f64::from(f.force_n[0]),
                    f64::from(f.distal_angle_rad[0]).to_degrees(),
                )
            })
            .collect();
        series.push((name, colour, pts));
    }
    for (area, title, y_max, pick) in [
        (&left, "finger 1 force, N", 45.0, 1usize),
        (&right, "finger 1 distal angle, deg", 95.0, 2),
    ] {
        let mut chart = chart(
            area,
            format!("Seed 001 Fig. 9, simulated: {title}"),
            (0.0..14.0, "time since first contact, s"),
            (0.0..y_max, ""),
        )?;
        for (name, colour, pts) in &series {
            let colour = *colour;
            let line = pts.iter().map(|p| (p.0, if pick == 1 { p.1 } else { p.2 }));
            chart
                .draw_series(LineSeries::new(line, colour))?
                .label(*name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
        }
        legend(&mut chart, SeriesLabelPosition::LowerRight)?;
    }
    root.present()?;
    Ok(())
}

fn main() -> Res {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/sim-calibration");
    fingertip_table2(&dir.join("fingertip-table2.svg"))?;
    fingertip_table1(&dir.join("fingertip-table1.svg"))?;
    imu_pad_force_depth(&dir.join("imu-pad-force-depth.svg"))?;
    underactuated_fig9(&dir.join("underactuated-fig9.svg"))?;
    println!("plots written to {}", dir.display());
    Ok(())
}
