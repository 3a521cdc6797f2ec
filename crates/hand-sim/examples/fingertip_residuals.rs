//! Prints the fingertip law against seed 000 Tables 1 and 2 as Markdown tables
//! (the calibration tables in docs/sim-calibration.md).

use hand_sim::fingertip::{Cell, CellSet, ContactPatch, LawParams};
use paper_fixtures::{Record, Table};

fn compare(r: &Record<'_>, sim: [f64; 3]) -> String {
    ["rise1_hpa", "rise2_hpa", "rise3_hpa"]
        .iter()
        .enumerate()
        .map(|(k, c)| {
            let p = r.f64(c).unwrap();
            format!("{p:.2} / {:.2} ({:+.2})", sim[k], sim[k] - p)
        })
        .collect::<Vec<_>>()
        .join(" | ")
}

fn derived(name: &str) -> Table {
    let file = paper_fixtures::fixtures_dir().join("derived").join(name);
    Table::parse(file.clone(), &std::fs::read_to_string(file).unwrap()).unwrap()
}

fn main() {
    let law = LawParams::CALIBRATED;
    println!(
        "| Table 2 row | sensor 1 paper / sim (err) | sensor 2 | sensor 3 |\n|---|---|---|---|"
    );
    for r in derived("seed000_table2_rise.csv").records() {
        let label = r.f64("average_area").unwrap();
        let tenths = (label * 10.0).round() as u8;
        let cell = Cell::new(tenths / 10, tenths % 10).unwrap();
        let kgf = r.f64("force_kgf").unwrap();
        let sim = law.steady_rise_hpa(&ContactPatch::from_kgf(CellSet::EMPTY.with(cell), kgf));
        println!("| area {label}, {kgf} kgf | {} |", compare(&r, sim));
    }
    println!(
        "\n| Table 1 weight | sensor 1 paper / sim (err) | sensor 2 | sensor 3 |\n|---|---|---|---|"
    );
    let all = Cell::all().fold(CellSet::EMPTY, CellSet::with);
    for r in derived("seed000_table1_rise.csv").records().skip(1) {
        let gf = r.f64("weight_gf").unwrap();
        let sim = law.steady_rise_hpa(&ContactPatch::from_kgf(all, gf / 1000.0));
        println!("| {gf} gf | {} |", compare(&r, sim));
    }
}
