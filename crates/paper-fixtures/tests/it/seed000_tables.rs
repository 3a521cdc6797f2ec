//! Every row of seed 000's fixtures parsed and checked against what the paper says of it.

use paper_fixtures::seed000;

#[test]
fn table1_has_13_increasing_weights_with_monotone_pressures() {
    let rows = seed000::table1_weight().unwrap();
    assert_eq!(rows.len(), 13);
    assert_eq!(rows[0].weight_gf, 0.0);
    assert_eq!(rows[12].weight_gf, 200.0);
    for pair in rows.windows(2) {
        assert!(
            pair[1].weight_gf > pair[0].weight_gf,
            "weights increase: {pair:?}"
        );
        for s in 0..3 {
            // The paper linearises a monotone but non-linear response (§2.2).
            assert!(
                pair[1].pressure_hpa[s] >= pair[0].pressure_hpa[s],
                "sensor {s} monotone: {pair:?}"
            );
        }
    }
    for row in &rows {
        for p in row.pressure_hpa {
            // MS5611 range is 10…1200 mbar; sensor 2 at 200 gf reads 1200.06, just above it.
            assert!((1000.0..=1200.1).contains(&p), "{row:?}");
        }
    }
}

#[test]
fn table1_paper_dnn_worst_error_is_1_17_gf_at_120_gf() {
    let rows = seed000::table1_weight().unwrap();
    let worst = rows
        .iter()
        .max_by(|a, b| {
            let ea = (a.expected_weight_gf - a.weight_gf).abs();
            let eb = (b.expected_weight_gf - b.weight_gf).abs();
            ea.total_cmp(&eb)
        })
        .unwrap();
    assert_eq!(worst.weight_gf, 120.0);
    assert!(((worst.weight_gf - worst.expected_weight_gf) - 1.17).abs() < 1e-9);
}

#[test]
fn table2_has_two_blocks_each_opened_by_a_zero_force_baseline() {
    let rows = seed000::table2_contact_area().unwrap();
    assert_eq!(rows.len(), 14);
    for (i, row) in rows.iter().enumerate() {
        assert!([0.0, 5.0, 7.0, 9.0].contains(&row.force_kgf), "{row:?}");
        assert_eq!(
            row.force_kgf == 0.0,
            row.size == 0,
            "size 0 exactly for no contact: {row:?}"
        );
        assert_eq!(row.size == 0, row.average_area == 0.0, "{row:?}");
        assert_eq!(
            i % 7 == 0,
            row.force_kgf == 0.0,
            "a baseline opens each block of 7: {row:?}"
        );
        for p in row.pressure_hpa {
            assert!((1005.0..1100.0).contains(&p), "{row:?}");
        }
        if row.size == 0 {
            // §4: "Each pressure sensor has an initial value of 1010.xx".
            assert!(
                row.pressure_hpa
                    .iter()
                    .all(|p| (1010.0..1011.0).contains(p)),
                "{row:?}"
            );
        } else {
            // Labels of single cells are row.column of the 4 × 6 grid.
            let tenths = (row.average_area * 10.0).round() as u32;
            assert!(
                (1..=4).contains(&(tenths / 10)) && (1..=6).contains(&(tenths % 10)),
                "{row:?}"
            );
        }
    }
}

#[test]
fn table2_sensor1_rise_grows_with_force_in_each_block() {
    let rows = seed000::table2_contact_area().unwrap();
    for block in rows.chunks(7) {
        let baseline = block[0].pressure_hpa[0];
        let rises: Vec<f64> = block[1..]
            .iter()
            .map(|r| r.pressure_hpa[0] - baseline)
            .collect();
        assert!(rises.iter().all(|&r| r > 5.0), "{rises:?}");
        for pair in rises.chunks(2).collect::<Vec<_>>().windows(2) {
            assert!(pair[1][0] > pair[0][1], "5 < 7 < 9 kgf: {rises:?}");
        }
    }
}

#[test]
fn table5_torque_ranges_are_inside_the_mx28_scale() {
    let rows = seed000::table5_grasp_torque().unwrap();
    let objects: Vec<&str> = rows.iter().map(|r| r.object.as_str()).collect();
    assert_eq!(
        objects,
        [
            "cube",
            "cylinder",
            "cone",
            "ellipsoid",
            "paper_cup",
            "scroll_tissue"
        ]
    );
    let scale = seed000::constants()
        .unwrap()
        .value("torque_limit_max_raw", "count")
        .unwrap();
    for row in &rows {
        assert!(
            0 < row.torque_min && row.torque_min < row.torque_max,
            "{row:?}"
        );
        assert!(f64::from(row.torque_max) <= scale, "{row:?}");
    }
}

#[test]
fn area_labels_follow_row_dot_column_on_the_4x6_grid() {
    let rows = seed000::area_labels().unwrap();
    assert_eq!(rows.iter().map(|r| r.area).collect::<Vec<_>>(), [1, 6, 24]);
    for row in &rows {
        let (r, c) = ((row.area - 1) / 6 + 1, (row.area - 1) % 6 + 1);
        assert!(
            (row.label - (f64::from(r) + f64::from(c) / 10.0)).abs() < 1e-9,
            "{row:?}"
        );
    }
}

#[test]
fn constants_agree_with_each_other() {
    let c = seed000::constants().unwrap();
    let grid = |name| c.value(name, "count").unwrap();
    assert_eq!(grid("aot_grid_cells"), 9.0);
    assert_eq!(grid("mlp_grid_cells"), 24.0);
    assert_eq!(
        grid("sensor_modules_per_hand_module"),
        2.0 * grid("sensors_per_fingertip")
    );
    assert_eq!(c.value("mlp_hidden_1", "neurons").unwrap(), 64.0);
    assert_eq!(c.value("mlp_hidden_2", "neurons").unwrap(), 32.0);
    assert!((0.0..1.0).contains(&c.value("mlp_dropout", "1").unwrap()));
    let forces: Vec<f64> = ["low", "mid", "high"]
        .iter()
        .map(|f| c.value(&format!("contact_force_{f}"), "kgf").unwrap())
        .collect();
    let table2: Vec<f64> = seed000::table2_contact_area()
        .unwrap()
        .iter()
        .map(|r| r.force_kgf)
        .collect();
    assert!(
        forces.iter().all(|f| table2.contains(f)),
        "Table 2 uses the forces of Figure 9"
    );
}
