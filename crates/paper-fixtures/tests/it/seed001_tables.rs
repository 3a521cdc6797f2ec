//! Every row of seed 001's fixtures parsed and checked against what the paper says of it.

use paper_fixtures::seed001;

#[test]
fn accuracies_are_the_correct_fraction_of_the_objects() {
    let rows = seed001::softness_accuracy().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(
        (rows[0].test_set.as_str(), rows[0].objects),
        ("regular", 24)
    );
    assert_eq!(
        (rows[1].test_set.as_str(), rows[1].objects),
        ("irregular", 30)
    );
    for row in &rows {
        let exact = f64::from(row.objects - row.misclassified) / f64::from(row.objects) * 100.0;
        // The paper truncates to two decimals (26/30 = 86.666… is printed 86.66).
        assert!(
            exact >= row.accuracy_pct && exact - row.accuracy_pct < 0.01,
            "{row:?}: {exact}"
        );
    }
}

#[test]
fn nine_model_objects_in_three_shapes_and_three_sizes() {
    let rows = seed001::table1_object_dimensions().unwrap();
    assert_eq!(rows.len(), 9);
    for (row, (shape, size, diameter)) in
        rows.iter()
            .zip(["rectangular", "cylinder", "sphere"].iter().flat_map(|s| {
                [("small", 65.0), ("medium", 80.0), ("big", 90.0)].map(|(z, d)| (*s, z, d))
            }))
    {
        assert_eq!((row.shape.as_str(), row.size.as_str()), (shape, size));
        assert_eq!(row.extent_mm[0], diameter, "{row:?}");
        assert_eq!(row.extent_mm[1], diameter, "{row:?}");
        let z = match shape {
            "rectangular" => 80.0,
            "cylinder" => 100.0,
            _ => diameter,
        };
        assert_eq!(row.extent_mm[2], z, "{row:?}");
    }
    let c = seed001::constants().unwrap();
    assert_eq!(
        c.value("model_objects", "count").unwrap(),
        3.0 * rows.len() as f64,
        "× 3 softnesses"
    );
}

#[test]
fn constants_describe_an_8_4_4_3_network_over_4_fingers() {
    let c = seed001::constants().unwrap();
    let count = |n| c.value(n, "count").unwrap();
    assert_eq!(
        count("features"),
        2.0 * count("fingers"),
        "a force and an angle per finger"
    );
    assert_eq!(c.value("hidden_neurons", "neurons").unwrap(), 4.0);
    assert_eq!(count("hidden_layers"), 2.0);
    assert_eq!(count("classes"), 3.0);
    assert!(c.value("fsr_min", "g").unwrap() < c.value("fsr_max", "g").unwrap());
    assert!(
        c.value("joint_limit", "deg").unwrap() < c.value("potentiometer_travel", "deg").unwrap()
    );
    assert_eq!(c.value("series_end", "s").unwrap(), 14.0);
}
