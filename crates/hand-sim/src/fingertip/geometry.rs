//! The fingertip pad's geometry: the 4 × 6 cell grid of seed 000 §4, its 3 × 3 Arrival-of-Time
//! partition (§3), and the three sensors in an inverted triangle (§3, Figure 5).
//!
//! Coordinates are millimetres in the pad plane, x to the right along a row, y up, origin at
//! the pad centre. Row 1 is the top row, column 1 the left column, so cell `r.c` carries the
//! paper's unique area number `r.c` (`Arr_1 = 1.1`, `Arr_6 = 1.6`, `Arr_24 = 4.6`).
//!
//! The paper gives no dimensions. A 3 mm cell pitch (an 18 × 12 mm pad) is our assumption,
//! the size of a robot fingertip; the sensor positions are [`super::LawParams::CALIBRATED`]'s.

/// Rows of the fine grid.
pub const ROWS: u8 = 4;
/// Columns of the fine grid.
pub const COLS: u8 = 6;
/// Cells of the fine grid.
pub const CELLS: usize = (ROWS as usize) * (COLS as usize);
/// Cell pitch, mm (assumed; see the module docs).
pub const PITCH_MM: f64 = 3.0;
/// Pad width (x), mm.
pub const WIDTH_MM: f64 = PITCH_MM * COLS as f64;
/// Pad height (y), mm.
pub const HEIGHT_MM: f64 = PITCH_MM * ROWS as f64;

/// One cell of the 4 × 6 grid.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cell {
    row: u8,
    col: u8,
}

impl Cell {
    /// Cell at 1-based `row` (1…4) and `col` (1…6), if on the pad.
    pub fn new(row: u8, col: u8) -> Option<Cell> {
        ((1..=ROWS).contains(&row) && (1..=COLS).contains(&col)).then_some(Cell { row, col })
    }

    /// The cell with 0-based index `i` (row-major), if on the pad.
    pub fn from_index(i: usize) -> Option<Cell> {
        (i < CELLS).then(|| Cell {
            row: (i / COLS as usize) as u8 + 1,
            col: (i % COLS as usize) as u8 + 1,
        })
    }

    /// 1-based row.
    pub fn row(self) -> u8 {
        self.row
    }

    /// 1-based column.
    pub fn col(self) -> u8 {
        self.col
    }

    /// 0-based row-major index, `0..24`.
    pub fn index(self) -> usize {
        usize::from(self.row - 1) * usize::from(COLS) + usize::from(self.col - 1)
    }

    /// The paper's unique area number `row.col` (§4: `Arr_1 = 1.1`, `Arr_24 = 4.6`).
    ///
    /// ```
    /// use hand_sim::fingertip::geometry::Cell;
    /// assert_eq!(Cell::new(1, 1).unwrap().label(), 1.1);
    /// assert_eq!(Cell::from_index(23).unwrap().label(), 4.6);
    /// ```
    pub fn label(self) -> f64 {
        f64::from(self.row) + f64::from(self.col) / 10.0
    }

    /// The cell centre, mm.
    pub fn centre_mm(self) -> [f64; 2] {
        [
            (f64::from(self.col) - 0.5) * PITCH_MM - WIDTH_MM / 2.0,
            HEIGHT_MM / 2.0 - (f64::from(self.row) - 0.5) * PITCH_MM,
        ]
    }

    /// The 3 × 3 Arrival-of-Time region (0-based, row-major) holding this cell's centre.
    pub fn aot_region(self) -> usize {
        aot_region_at(self.centre_mm())
    }

    /// Every cell, row-major.
    pub fn all() -> impl Iterator<Item = Cell> {
        (0..CELLS).filter_map(Cell::from_index)
    }
}

/// A set of cells, as a 24-bit mask (bit `i` is the cell of index `i`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CellSet(u32);

impl CellSet {
    /// No cell.
    pub const EMPTY: CellSet = CellSet(0);

    /// The cells of a `rows` × `cols` rectangle whose top-left cell is `top_left`, if it fits.
    ///
    /// ```
    /// use hand_sim::fingertip::geometry::{Cell, CellSet};
    /// let square = CellSet::rect(Cell::new(1, 1).unwrap(), 2, 2).unwrap();
    /// assert_eq!(square.len(), 4);
    /// assert!(CellSet::rect(Cell::new(4, 6).unwrap(), 2, 1).is_none());
    /// ```
    pub fn rect(top_left: Cell, rows: u8, cols: u8) -> Option<CellSet> {
        let mut set = CellSet::EMPTY;
        for r in 0..rows {
            for c in 0..cols {
                set = set.with(Cell::new(top_left.row + r, top_left.col + c)?);
            }
        }
        Some(set)
    }

    /// This set with `cell` added.
    pub fn with(self, cell: Cell) -> CellSet {
        CellSet(self.0 | 1 << cell.index())
    }

    /// Whether `cell` is in the set.
    pub fn contains(self, cell: Cell) -> bool {
        self.0 & (1 << cell.index()) != 0
    }

    /// How many cells the set holds (the paper's contact "size").
    pub fn len(self) -> usize {
        self.0.count_ones() as usize
    }

    /// Whether the set is empty.
    pub fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The cells, row-major.
    pub fn iter(self) -> impl Iterator<Item = Cell> {
        Cell::all().filter(move |c| self.contains(*c))
    }

    /// The raw mask.
    pub fn bits(self) -> u32 {
        self.0
    }

    /// The mean of the cells' centres, mm (the pad centre for an empty set).
    pub fn centroid_mm(self) -> [f64; 2] {
        let n = self.len().max(1) as f64;
        self.iter().fold([0.0, 0.0], |acc, c| {
            let [x, y] = c.centre_mm();
            [acc[0] + x / n, acc[1] + y / n]
        })
    }

    /// Eq. 4's average-area label: the mean of the cells' unique numbers (0 for no contact).
    pub fn average_area(self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            self.iter().map(Cell::label).sum::<f64>() / self.len() as f64
        }
    }
}

/// `aot-locate` numbers the same 4 × 6 cells the same way (row-major, bit 0 = area 1.1).
impl From<aot_locate::CellSet> for CellSet {
    fn from(cells: aot_locate::CellSet) -> CellSet {
        CellSet(cells.bits())
    }
}

/// The 3 × 3 Arrival-of-Time region (0-based, row-major) holding the pad point `p` (mm);
/// points off the pad fall in the nearest edge region.
pub fn aot_region_at(p: [f64; 2]) -> usize {
    let [x, y] = p;
    let band = |v: f64, span: f64| ((v / (span / 3.0)).max(0.0) as usize).min(2);
    band(HEIGHT_MM / 2.0 - y, HEIGHT_MM) * 3 + band(x + WIDTH_MM / 2.0, WIDTH_MM)
}

/// The three sensors, in the paper's numbering: sensor 1 top right, sensor 2 bottom centre,
/// sensor 3 top left (an inverted triangle; which top corner is 1 follows from Table 2, where
/// area 1.1 rises sensor 3 more and area 1.5 sensor 1 more).
pub const SENSORS: usize = 3;
