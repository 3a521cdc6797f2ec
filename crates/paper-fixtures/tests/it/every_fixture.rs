//! Every file in `fixtures/paper/` parses, cites its seed, and has a typed loader.

use paper_fixtures::{Table, fixtures_dir};

/// The files the typed loaders read. A new fixture file must get a loader and a test.
const KNOWN: [&str; 13] = [
    "seed000_area_labels",
    "seed000_constants",
    "seed000_table1_weight",
    "seed000_table2_contact_area",
    "seed000_table5_grasp_torque",
    "seed001_constants",
    "seed001_softness_accuracy",
    "seed001_table1_object_dimensions",
    "seed002_constants",
    "seed002_force_depth",
    "seed002_pressure_modes",
    "seed002_table1_cnn_accuracy",
    "seed002_yeoh",
];

#[test]
fn every_paper_fixture_parses_cites_its_seed_and_is_known() {
    let mut names: Vec<String> = std::fs::read_dir(fixtures_dir().join("paper"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "csv"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, KNOWN);
    for name in &names {
        let table = Table::load(name).unwrap();
        assert!(!table.is_empty(), "{name} has rows");
        let seed = &name[4..7];
        let cites = table.citation().join(" ");
        assert!(
            cites.contains(&format!("Seed {seed}")),
            "{name} cites seed {seed}: {cites}"
        );
    }
}

#[test]
fn every_constant_has_a_unit_and_cites_its_section() {
    let files = [
        paper_fixtures::seed000::constants().unwrap(),
        paper_fixtures::seed001::constants().unwrap(),
        paper_fixtures::seed002::constants().unwrap(),
    ];
    for constants in &files {
        let mut count = 0;
        for (name, constant) in constants.iter() {
            let cites = constant
                .source
                .as_deref()
                .is_some_and(|s| s.starts_with('§'));
            assert!(cites, "{name} cites a section");
            assert!(!constant.unit.is_empty(), "{name} has a unit");
            count += 1;
        }
        assert!(count >= 15, "every row parsed: {count}");
    }
}

#[test]
fn errors_name_the_file_line_and_column() {
    let bad = Table::parse("t.csv".into(), "# src\nname,value\nx,1.5\ny,abc\n").unwrap();
    let err = bad.map(|r| r.f64("value")).unwrap_err();
    assert_eq!(
        err.to_string(),
        "t.csv:4: column `value`: `abc` is not a finite number"
    );
    let nan = Table::parse("t.csv".into(), "# src\nv\nNaN\n").unwrap();
    assert!(nan.map(|r| r.f64("v")).is_err(), "NaN is rejected");
    let missing = bad.map(|r| r.f64("nope")).unwrap_err();
    assert!(
        missing
            .to_string()
            .contains("no column `nope` (columns: name, value)")
    );
    let uncited = Table::parse("t.csv".into(), "a\n1\n").unwrap_err();
    assert!(uncited.to_string().contains("no citation"));
    let late = Table::parse("t.csv".into(), "# src\na\n# late\n1\n").unwrap_err();
    assert_eq!(late.to_string(), "t.csv:3: comment after the header");
}
