//! Seed 000: the barometric fingertip, its force DNN, AoT / MLP contact location and the fuzzy
//! grasp controller (Kim et al., Sensors 2020).

use crate::table::{constants_fixture, typed_fixture};

/// A row of Table 1: a weight, the three pressures it produced and the paper's DNN estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightRow {
    /// The object's weight, in gram-force.
    pub weight_gf: f64,
    /// The three fingertip pressures, in hPa.
    pub pressure_hpa: [f64; 3],
    /// The paper's DNN estimate ("Expect. Weight"), in gram-force.
    pub expected_weight_gf: f64,
}

/// A row of Table 2: a contact force, the three pressures, the contact size and its eq. 4 label.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactAreaRow {
    /// The gripper's contact force, in kilogram-force.
    pub force_kgf: f64,
    /// The three fingertip pressures, in hPa.
    pub pressure_hpa: [f64; 3],
    /// Contact size in cells of the 4 × 6 grid (0: no contact).
    pub size: u32,
    /// The eq. 4 average-area label (0: no contact).
    pub average_area: f64,
}

/// A row of Table 5: the torque-limit range that holds an object without damage or release.
#[derive(Debug, Clone, PartialEq)]
pub struct GraspTorqueRow {
    /// The object (`cube`, `cylinder`, `cone`, `ellipsoid`, `paper_cup`, `scroll_tissue`).
    pub object: String,
    /// The least torque limit that holds it, on the MX-28 scale 0…1023.
    pub torque_min: u32,
    /// The greatest torque limit that does not damage it, on the same scale.
    pub torque_max: u32,
}

/// One of the area labels §4 gives by example (`Arr_1 = 1.1`, `Arr_6 = 1.6`, `Arr_24 = 4.6`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaLabelRow {
    /// The area's number, 1…24.
    pub area: u32,
    /// Its unique label.
    pub label: f64,
}

fn pressures(r: &crate::Record<'_>) -> Result<[f64; 3], crate::FixtureError> {
    Ok([
        r.f64("sensor1_hpa")?,
        r.f64("sensor2_hpa")?,
        r.f64("sensor3_hpa")?,
    ])
}

typed_fixture!(
    /// Table 1: weight vs three pressures vs the paper's DNN estimate (13 rows).
    table1_weight, table1_weight_in, "seed000_table1_weight", WeightRow,
    |r| Ok(WeightRow {
        weight_gf: r.f64("weight_gf")?,
        pressure_hpa: pressures(&r)?,
        expected_weight_gf: r.f64("expected_weight_gf")?,
    })
);

typed_fixture!(
    /// Table 2: contact force, pressures, size and eq. 4 label (14 rows, two zero-force baselines).
    table2_contact_area, table2_contact_area_in, "seed000_table2_contact_area", ContactAreaRow,
    |r| Ok(ContactAreaRow {
        force_kgf: r.f64("force_kgf")?,
        pressure_hpa: pressures(&r)?,
        size: r.u32("size")?,
        average_area: r.f64("average_area")?,
    })
);

typed_fixture!(
    /// Table 5: torque min / max per grasped object (6 rows).
    table5_grasp_torque, table5_grasp_torque_in, "seed000_table5_grasp_torque", GraspTorqueRow,
    |r| Ok(GraspTorqueRow {
        object: r.str("object")?.to_string(),
        torque_min: r.u32("torque_min")?,
        torque_max: r.u32("torque_max")?,
    })
);

typed_fixture!(
    /// The three area labels §4 states (areas 1, 6 and 24).
    area_labels, area_labels_in, "seed000_area_labels", AreaLabelRow,
    |r| Ok(AreaLabelRow { area: r.u32("area")?, label: r.f64("label")? })
);

constants_fixture!("seed000_constants");
