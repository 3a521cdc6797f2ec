//! The fingertip law against seed 000 Tables 1 and 2 (as `fixtures/derived/` holds their rises).
//! Tolerances are the fit's documented residuals (docs/sim-calibration/fingertip.md), not tuned targets.

use hand_sim::fingertip::{Cell, CellSet, ContactPatch, LawParams};
use paper_fixtures::Table;

/// Worst single-point error allowed against Table 2, hPa: the fit's worst residual is sensor 3
/// at area 1.5, where Table 2 itself plateaus (28.1 → 43.5 → 43.3 hPa for 5 → 7 → 9 kgf) while
/// sensor 3 at area 1.1 climbs to 61 hPa — no law monotone in a distance-weighted load can do
/// both, so the fit splits the difference there.
const TABLE2_WORST_HPA: f64 = 13.0;
/// RMS error allowed over all of Table 2's points, hPa.
const TABLE2_RMS_HPA: f64 = 6.0;

fn derived(name: &str) -> Table {
    let root = paper_fixtures::fixtures_dir();
    let file = root.join("derived").join(format!("{name}.csv"));
    Table::parse(file.clone(), &std::fs::read_to_string(file).unwrap()).unwrap()
}

fn cell_of_label(label: f64) -> Cell {
    let tenths = (label * 10.0).round() as u8;
    Cell::new(tenths / 10, tenths % 10).unwrap()
}

#[test]
fn table2_single_cell_rises_within_the_documented_residuals() {
    let law = LawParams::CALIBRATED;
    let mut sq = 0.0;
    let mut n = 0.0;
    for r in derived("seed000_table2_rise").records() {
        let cell = cell_of_label(r.f64("average_area").unwrap());
        let patch = ContactPatch::from_kgf(CellSet::EMPTY.with(cell), r.f64("force_kgf").unwrap());
        let sim = law.steady_rise_hpa(&patch);
        for (k, col) in ["rise1_hpa", "rise2_hpa", "rise3_hpa"].iter().enumerate() {
            let paper = r.f64(col).unwrap();
            let err = sim[k] - paper;
            assert!(
                err.abs() <= TABLE2_WORST_HPA,
                "line {}: sensor {} sim {:.2} paper {paper}",
                r.line(),
                k + 1,
                sim[k]
            );
            sq += err * err;
            n += 1.0;
        }
    }
    let rms = (sq / n).sqrt();
    assert!(rms <= TABLE2_RMS_HPA, "rms {rms:.2} hPa");
}

#[test]
fn table2_orderings_hold() {
    let law = LawParams::CALIBRATED;
    let at = |label: f64, kgf: f64| {
        law.steady_rise_hpa(&ContactPatch::from_kgf(
            CellSet::EMPTY.with(cell_of_label(label)),
            kgf,
        ))
    };
    for kgf in [5.0, 7.0, 9.0] {
        let a11 = at(1.1, kgf);
        let a15 = at(1.5, kgf);
        // Row 1 is far from the bottom sensor 2: it barely moves (≤ 3.3 hPa in Table 2), but it
        // moves (1.3 / 3.3 hPa at 9 kgf, both repeats): the pad has no blind sensor.
        assert!(a11[1] < a11[0] && a11[1] < a11[2] && a15[1] < a15[0] && a15[1] < a15[2]);
        assert!(a11[1] > 0.3 && a15[1] > 0.3, "{kgf} kgf: {a11:?} {a15:?}");
        // Area 1.1 (left) rises sensor 3 (top left) more than sensor 1.
        assert!(a11[2] > a11[0], "{kgf} kgf: {a11:?}");
    }
    // Area 1.5 (right) rises sensor 1 (top right) the most at 9 kgf: 69.8 vs 43.3 hPa.
    let a15 = at(1.5, 9.0);
    assert!(a15[0] > a15[2], "{a15:?}");
    // More force, more rise, for every sensor at both areas.
    for label in [1.1, 1.5] {
        for k in 0..3 {
            assert!(at(label, 5.0)[k] < at(label, 7.0)[k] && at(label, 7.0)[k] < at(label, 9.0)[k]);
        }
    }
}

#[test]
fn table1_whole_pad_rises_grow_with_weight_and_stay_within_the_documented_residual_at_200_gf() {
    let law = LawParams::CALIBRATED;
    let all = Cell::all().fold(CellSet::EMPTY, CellSet::with);
    let mut previous = [0.0; 3];
    for r in derived("seed000_table1_rise").records().skip(1) {
        let gf = r.f64("weight_gf").unwrap();
        let sim = law.steady_rise_hpa(&ContactPatch::from_kgf(all, gf / 1000.0));
        for k in 0..3 {
            assert!(sim[k] > previous[k], "{gf} gf: monotone in weight");
        }
        previous = sim;
        if gf == 200.0 {
            for (k, col) in ["rise1_hpa", "rise2_hpa", "rise3_hpa"].iter().enumerate() {
                let paper = r.f64(col).unwrap();
                // Worst documented residual 0.55 hPa (sensor 1): the σy = 3.1 mm that Table 2's
                // sensor-2 readings and a blind-free pad need costs Table 1's low end (another
                // rig) this much (docs/sim-calibration/fingertip.md).
                assert!(
                    (sim[k] - paper).abs() < 0.6,
                    "sensor {}: sim {:.3} paper {paper}",
                    k + 1,
                    sim[k]
                );
            }
        }
    }
}

/// The paper localises every one of 3 × 3 and 24 areas from three sensors (§3–4, Figures 10–11):
/// every sensor must feel every single cell. 0.3 hPa is aot-locate's arrival threshold (30 Pa).
#[test]
fn every_sensor_feels_every_cell_at_5_kgf() {
    let law = LawParams::CALIBRATED;
    for cell in Cell::all() {
        let rise = law.steady_rise_hpa(&ContactPatch::from_kgf(CellSet::EMPTY.with(cell), 5.0));
        assert!(rise.iter().all(|r| *r > 0.3), "{cell:?}: {rise:?}");
    }
}
