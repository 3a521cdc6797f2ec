//! The fingertip pad on the simulated skin: `aot-locate`'s 4 × 6 cells (seed 000 §4), their
//! eq. 4 labels and 3 × 3 Arrival-of-Time areas (§3) — the one copy, re-exported — placed in
//! millimetres for the physics, and the three sensors in an inverted triangle (§3, Figure 5).
//!
//! Coordinates are millimetres in the pad plane, x to the right along a row, y up, origin at
//! the pad centre. Row 1 is the top row, column 1 the left column, so cell `r.c` carries the
//! paper's unique area number `r.c` (`Arr_1 = 1.1`, `Arr_6 = 1.6`, `Arr_24 = 4.6`).
//!
//! The paper gives no dimensions. A 3 mm cell pitch (an 18 × 12 mm pad, [`PAD`]) is our
//! assumption, the size of a robot fingertip; the sensor positions ([`SENSORS_MM`]) are
//! [`super::LawParams::CALIBRATED`]'s. This module is their one owner: the Arrival-of-Time
//! evaluation, the scenes and the benches take the pad from here ([`aot_geometry`]), since
//! `aot-locate` holds no pad of its own.
//!
//! ```
//! use hand_sim::fingertip::{Cell, CellSet};
//! let square = CellSet::rect(1, 1, 2, 2).unwrap(); // areas 1.1, 1.2, 2.1, 2.2
//! assert!((square.average_area().value() - 1.65).abs() < 1e-6); // eq. 4
//! assert_eq!(square.aot_area(), Some(0)); // the top-left Arrival-of-Time area
//! assert_eq!(Cell::new(1, 1).unwrap().centre_mm(), [-7.5, 4.5]);
//! ```

use aot_locate::{AreaGrid, Geometry};

pub use aot_locate::{CELLS, COLS, CellSet, ROWS, SENSORS};

/// The simulated pad: 4 × 6 cells of 3 mm, 18 × 12 mm (see the module docs).
pub const PAD: AreaGrid = AreaGrid {
    width_mm: 18.0,
    height_mm: 12.0,
};
/// Pad width (x), mm.
pub const WIDTH_MM: f64 = PAD.width_mm as f64;
/// Pad height (y), mm.
pub const HEIGHT_MM: f64 = PAD.height_mm as f64;
/// Cell pitch, mm (assumed; see the module docs).
pub const PITCH_MM: f64 = WIDTH_MM / COLS as f64;

/// The three sensors, mm, in the paper's numbering, as `aot-locate` takes them (`f32`):
/// sensor 1 top right, sensor 2 bottom centre, sensor 3 top left (an inverted triangle; which
/// top corner is 1 follows from Table 2, where area 1.1 rises sensor 3 more and area 1.5
/// sensor 1 more).
pub const AOT_SENSORS_MM: [[f32; 2]; SENSORS] = [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]];

/// [`AOT_SENSORS_MM`] in `f64` for the physics (exact: whole and half millimetres).
pub const SENSORS_MM: [[f64; 2]; SENSORS] = {
    let s = AOT_SENSORS_MM;
    [
        [s[0][0] as f64, s[0][1] as f64],
        [s[1][0] as f64, s[1][1] as f64],
        [s[2][0] as f64, s[2][1] as f64],
    ]
};

/// The simulated pad for Arrival-of-Time: [`AOT_SENSORS_MM`] over [`PAD`]'s 3 × 3 areas.
///
/// ```
/// use hand_sim::fingertip::geometry::{AOT_SENSORS_MM, aot_geometry};
/// let pad = aot_geometry();
/// assert_eq!(pad.sensors_mm(), &AOT_SENSORS_MM);
/// // Area 7 (bottom centre, (0, −4) mm) is 0.5 mm from sensor 2.
/// assert!((pad.distance_mm(7, 1).unwrap() - 0.5).abs() < 1e-12);
/// ```
pub fn aot_geometry() -> Geometry {
    // Constants, all finite, no sensor on an area centre (a unit test holds it): never fails.
    Geometry::new(AOT_SENSORS_MM, PAD).expect("the simulated pad is a valid geometry")
}

/// One cell of the pad where the skin's physics sees it: `aot-locate`'s grid cell (row,
/// column, index, eq. 4 number and Arrival-of-Time area, through `Deref`) and its centre on
/// the simulated skin in `f64` millimetres.
///
/// ```
/// use hand_sim::fingertip::{Cell, CellSet};
/// let cell = Cell::new(2, 3).unwrap();
/// assert_eq!((cell.row(), cell.col(), cell.index()), (2, 3, 8));
/// assert_eq!(cell.centre_mm(), [-1.5, 1.5]);
/// assert_eq!(CellSet::EMPTY.with(cell).bits(), 1 << 8);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cell(aot_locate::Cell);

impl Cell {
    /// Cell at 1-based `row` (1…4) and `col` (1…6), if on the pad.
    pub fn new(row: u8, col: u8) -> Option<Cell> {
        aot_locate::Cell::new(row, col).map(Cell)
    }

    /// The cell with 0-based index `i` (row-major), if on the pad.
    pub fn from_index(i: usize) -> Option<Cell> {
        aot_locate::Cell::from_index(i).map(Cell)
    }

    /// Every cell, row-major.
    pub fn all() -> impl Iterator<Item = Cell> {
        aot_locate::Cell::all().map(Cell)
    }

    /// The grid cell.
    pub fn grid(self) -> aot_locate::Cell {
        self.0
    }

    /// The cell centre, mm: [`PAD`]'s, exact in `f64` (multiples of half the 3 mm pitch).
    pub fn centre_mm(self) -> [f64; 2] {
        PAD.cell_centre_mm(self.0).map(f64::from)
    }
}

impl core::ops::Deref for Cell {
    type Target = aot_locate::Cell;

    fn deref(&self) -> &aot_locate::Cell {
        &self.0
    }
}

impl From<aot_locate::Cell> for Cell {
    fn from(cell: aot_locate::Cell) -> Cell {
        Cell(cell)
    }
}

/// A skin cell adds to a [`CellSet`] as its grid cell.
impl From<Cell> for aot_locate::Cell {
    fn from(cell: Cell) -> aot_locate::Cell {
        cell.0
    }
}

/// The mean of the cells' centres on the skin, mm (the pad centre for an empty set): where a
/// contact's load is centred, for the law's arrival delays. `f64` and summed row-major as the
/// law was calibrated with; the eq. 4 and Arrival-of-Time labels come from the exact
/// [`CellSet::average_area`] and [`CellSet::aot_area`] instead.
///
/// ```
/// use hand_sim::fingertip::{CellSet, geometry::centroid_mm};
/// assert_eq!(centroid_mm(CellSet::rect(1, 1, 2, 2).unwrap()), [-6.0, 3.0]);
/// assert_eq!(centroid_mm(CellSet::EMPTY), [0.0, 0.0]);
/// ```
pub fn centroid_mm(cells: CellSet) -> [f64; 2] {
    let n = f64::from(cells.len().max(1));
    cells.iter().fold([0.0, 0.0], |acc, c| {
        let [x, y] = Cell(c).centre_mm();
        [acc[0] + x / n, acc[1] + y / n]
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_skin_is_the_3_mm_pad() {
        assert_eq!((WIDTH_MM, HEIGHT_MM, PITCH_MM), (18.0, 12.0, 3.0));
        // Corner cells sit half a pitch in from the pad's corners.
        let first = Cell::from_index(0).unwrap().centre_mm();
        let last = Cell::from_index(CELLS - 1).unwrap().centre_mm();
        assert_eq!(first, [-WIDTH_MM / 2.0 + 1.5, HEIGHT_MM / 2.0 - 1.5]);
        assert_eq!(last, [WIDTH_MM / 2.0 - 1.5, -HEIGHT_MM / 2.0 + 1.5]);
        for cell in Cell::all() {
            let [x, y] = cell.centre_mm();
            let grid = [f32::from(cell.row()), f32::from(cell.col())];
            assert_eq!([x as f32, y as f32], PAD.grid_point_mm(grid));
        }
    }

    #[test]
    fn sensors_are_the_aot_geometrys() {
        assert_eq!(SENSORS_MM, [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]]);
        assert!(Geometry::new(AOT_SENSORS_MM, PAD).is_ok());
        let g = aot_geometry();
        assert_eq!(g.centres_mm(), &PAD.centres_mm());
        for (k, s) in g.sensors_mm().iter().enumerate() {
            assert_eq!(s.map(f64::from), SENSORS_MM[k]);
        }
    }

    #[test]
    fn the_whole_pad_is_centred() {
        let all = Cell::all().fold(CellSet::EMPTY, CellSet::with);
        assert_eq!(all.len() as usize, CELLS);
        let [x, y] = centroid_mm(all);
        assert!(x.abs() < 1e-12 && y.abs() < 1e-12, "{x} {y}");
    }
}
