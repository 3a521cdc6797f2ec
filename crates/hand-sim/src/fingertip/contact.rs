//! Contacts on the fingertip pad: which cells, how hard, and when.

use super::geometry::CellSet;

/// One contact: a set of cells pressed with a total normal force shared equally among them,
/// the whole patch shifted by `offset_mm` from the cell lattice (zero for a contact centred on
/// its cells; at most half a cell each way, [`MAX_OFFSET_MM`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPatch {
    /// The contacted cells.
    pub cells: CellSet,
    /// Total normal force, newton (≥ 0).
    pub force_n: f64,
    /// Shift of the whole patch in the pad plane (x right, y up), mm.
    pub offset_mm: [f64; 2],
}

/// The largest shift of a patch off its cells along either axis, mm: half the 3 mm cell
/// pitch (a larger shift is a contact on other cells).
pub const MAX_OFFSET_MM: f64 = super::geometry::PITCH_MM / 2.0;

/// Whether a shift is within [`MAX_OFFSET_MM`] along both axes (NaN is not).
pub fn offset_in_range(offset_mm: [f64; 2]) -> bool {
    offset_mm
        .iter()
        .all(|o| !o.is_nan() && o.abs() <= MAX_OFFSET_MM)
}

impl ContactPatch {
    /// No contact.
    pub const NONE: ContactPatch = ContactPatch {
        cells: CellSet::EMPTY,
        force_n: 0.0,
        offset_mm: [0.0, 0.0],
    };

    /// `cells` pressed with `kgf` kilogram-force (the unit of seed 000 Table 2).
    pub fn from_kgf(cells: CellSet, kgf: f64) -> ContactPatch {
        ContactPatch {
            cells,
            force_n: kgf * KGF_N,
            offset_mm: [0.0, 0.0],
        }
    }

    /// The same contact shifted by `offset_mm` (x right, y up) off its cells.
    pub fn shifted(self, offset_mm: [f64; 2]) -> ContactPatch {
        ContactPatch { offset_mm, ..self }
    }

    /// The load's centre on the pad, mm: the cells' centroid plus the shift.
    pub fn centroid_mm(&self) -> [f64; 2] {
        let [x, y] = super::geometry::centroid_mm(self.cells);
        [x + self.offset_mm[0], y + self.offset_mm[1]]
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
