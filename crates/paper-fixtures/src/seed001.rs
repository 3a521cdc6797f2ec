//! Seed 001: the underactuated four-finger hand and its softness classifier.

use crate::table::{constants_fixture, typed_fixture};

/// A published softness-classification result.
#[derive(Debug, Clone, PartialEq)]
pub struct SoftnessAccuracyRow {
    /// `regular` (specific shapes) or `irregular`.
    pub test_set: String,
    /// How many objects were tested.
    pub objects: u32,
    /// The reported accuracy, in percent.
    pub accuracy_pct: f64,
    /// How many were misclassified (stated for `regular`, derived for `irregular`).
    pub misclassified: u32,
}

/// A row of the paper's Table 1: a model object's shape, size and dimensions.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectDimensionRow {
    /// `rectangular`, `cylinder` or `sphere`.
    pub shape: String,
    /// `small`, `medium` or `big`.
    pub size: String,
    /// Extent along x, y, z, in millimetres (see the file's header for each shape's meaning).
    pub extent_mm: [f64; 3],
}

typed_fixture!(
    /// The two published accuracies: 95.83 % on 24 regular, 86.66 % on 30 irregular objects.
    softness_accuracy, softness_accuracy_in, "seed001_softness_accuracy", SoftnessAccuracyRow,
    |r| Ok(SoftnessAccuracyRow {
        test_set: r.str("test_set")?.to_string(),
        objects: r.u32("objects")?,
        accuracy_pct: r.f64("accuracy_pct")?,
        misclassified: r.u32("misclassified")?,
    })
);

typed_fixture!(
    /// Table 1: the nine shape × size model objects (each in three softnesses).
    table1_object_dimensions, table1_object_dimensions_in, "seed001_table1_object_dimensions",
    ObjectDimensionRow,
    |r| Ok(ObjectDimensionRow {
        shape: r.str("shape")?.to_string(),
        size: r.str("size")?.to_string(),
        extent_mm: [r.f64("x_mm")?, r.f64("y_mm")?, r.f64("z_mm")?],
    })
);

constants_fixture!("seed001_constants");
