//! The closed-loop grasp results table (`docs/grasping/results.csv`, written by the
//! `grasp_report` example from [`grasp_rig::hold`](crate::grasp_rig::hold)): one row per held
//! object (the six Table 5 objects, then the randomised ones), schema [`GraspResult`], which the
//! drift tests read back.

use crate::grasp_rig::Outcome;
use hand_sim::records::{self, DatasetError, Fixed, Schema};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The table, below the workspace root.
pub const RESULTS_FILE: &str = "docs/grasping/results.csv";

/// One row of the table: how a closed-loop hold of one object went.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GraspResult {
    /// The object's name.
    pub object: String,
    /// Least torque limit of its Table 5 band (MX-28 scale 0…1023).
    pub table5_min: u16,
    /// Greatest torque limit of its band.
    pub table5_max: u16,
    /// The torque limit the loop settled on.
    pub settled_torque: Fixed<f32, 1>,
    /// Least limit over the settled window.
    pub window_min: u16,
    /// Greatest limit over the settled window.
    pub window_max: u16,
    /// Time to settle, s.
    pub settling_time_s: Fixed<f64, 2>,
    /// Peak normal force, N.
    pub peak_force_n: Fixed<f64, 2>,
    /// Normal force at the end of the hold, N.
    pub final_force_n: Fixed<f64, 2>,
    /// Pad pressure at the end of the hold, Pa.
    pub final_pressure_pa: Fixed<f32, 0>,
    /// Held to the end: no slip, damage, drop or fault.
    pub held: bool,
    /// Protocol 2.0 packets the hand sent over the hold.
    pub packets_sent: u64,
    /// Status packets it received.
    pub packets_received: u64,
}

impl Schema for GraspResult {}

impl GraspResult {
    /// The row of a hold's outcome.
    pub fn new(o: &Outcome) -> Self {
        GraspResult {
            object: o.name.clone(),
            table5_min: o.band.0,
            table5_max: o.band.1,
            settled_torque: Fixed(o.settled_raw),
            window_min: o.window_raw.0,
            window_max: o.window_raw.1,
            settling_time_s: Fixed(o.settling_time_s),
            peak_force_n: Fixed(o.peak_force_n),
            final_force_n: Fixed(o.final_force_n),
            final_pressure_pa: Fixed(o.final_pressure_pa),
            held: !(o.slipped || o.damaged || o.dropped) && o.faults == 0,
            packets_sent: o.packets.sent,
            packets_received: o.packets.received,
        }
    }
}

/// The table's text for `rows`.
pub fn to_csv(rows: impl IntoIterator<Item = GraspResult>) -> String {
    records::render("", rows)
}

/// Reads the committed table below the workspace root `root`.
pub fn load(root: &Path) -> Result<Vec<GraspResult>, DatasetError> {
    Ok(records::read(&root.join(RESULTS_FILE))?
        .into_iter()
        .map(|r| r.record)
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_round_trip_and_bad_rows_are_named() -> Result<(), DatasetError> {
        let text = "object,table5_min,table5_max,settled_torque,window_min,window_max,\
                    settling_time_s,peak_force_n,final_force_n,final_pressure_pa,held,\
                    packets_sent,packets_received\n\
                    cube,80,400,265.7,264,267,0.00,3.95,3.89,178,true,36885,12305\n";
        let rows: Vec<GraspResult> = records::parse(Path::new("r.csv"), text)?
            .into_iter()
            .map(|r| r.record)
            .collect();
        assert_eq!((rows[0].settled_torque.0, rows[0].held), (265.7, true));
        assert_eq!(to_csv(rows), text);
        let e = records::parse::<GraspResult>(Path::new("r.csv"), &text.replace("true", "yes"))
            .expect_err("held is true or false");
        assert_eq!((e.line, e.column.as_deref()), (Some(2), Some("held")));
        Ok(())
    }

    #[test]
    fn the_committed_table_is_its_rows_written_again() -> Result<(), DatasetError> {
        let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
        let committed = std::fs::read_to_string(root.join(RESULTS_FILE)).map_err(|e| {
            DatasetError::new(
                Path::new(RESULTS_FILE),
                None,
                None,
                records::ErrorKind::Io(e),
            )
        })?;
        let rows = load(&root)?;
        assert_eq!(rows.len(), 26, "six Table 5 objects and 20 randomised ones");
        assert_eq!(to_csv(rows), committed);
        Ok(())
    }
}
