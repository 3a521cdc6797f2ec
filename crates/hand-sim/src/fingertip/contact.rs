//! Contacts on the fingertip pad: which cells, how hard, and when.

use super::geometry::CellSet;

/// One contact: a set of cells pressed with a total normal force shared equally among them.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPatch {
    /// The contacted cells.
    pub cells: CellSet,
    /// Total normal force, newton (≥ 0).
    pub force_n: f64,
}

impl ContactPatch {
    /// No contact.
    pub const NONE: ContactPatch = ContactPatch {
        cells: CellSet::EMPTY,
        force_n: 0.0,
    };

    /// `cells` pressed with `kgf` kilogram-force (the unit of seed 000 Table 2).
    pub fn from_kgf(cells: CellSet, kgf: f64) -> ContactPatch {
        ContactPatch {
            cells,
            force_n: kgf * KGF_N,
        }
    }

    /// The force in kilogram-force.
    pub fn force_kgf(&self) -> f64 {
        self.force_n / KGF_N
    }
}

/// One kilogram-force in newton.
pub const KGF_N: f64 = 9.806_65;

/// A contact held from `start_ns` until `end_ns` of simulated time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactEvent {
    /// When the contact begins, ns.
    pub start_ns: u64,
    /// When it is released, ns.
    pub end_ns: u64,
    /// Where and how hard.
    pub patch: ContactPatch,
}
