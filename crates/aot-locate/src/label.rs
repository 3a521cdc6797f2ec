//! Eq. 4's "average area" labels on the 4 × 6 grid (Kim et al. 2020, "Artificial
//! Intelligence-Based Optimal Grasping Control", §4 and Table 2).
//!
//! Each cell has a unique number `row.col` (`Arr_1 = 1.1`, `Arr_6 = 1.6`, `Arr_24 = 4.6`); a
//! contact's label is the mean of its cells' numbers, `Σ Arr_i / n` (eq. 4), 0 for no contact.
//! Since a column never exceeds 6, the mean is `row̄ + col̄ / 10`: the label encodes the
//! patch's centroid, so two patches with the same centroid share a label (a 3 × 3 square and
//! the cell at its centre); [`decode_among`] returns every candidate of a vocabulary of
//! contact sets (the placements of a list of [`Shape`]s, for instance).

/// Rows of the fine grid.
pub const ROWS: u8 = 4;
/// Columns of the fine grid.
pub const COLS: u8 = 6;
/// Cells of the fine grid.
pub const CELLS: usize = ROWS as usize * COLS as usize;

/// One cell of the 4 × 6 grid: 1-based row (1…4, top first) and column (1…6, left first), so
/// cell `r.c` carries the paper's unique area number `r.c` (§4: `Arr_1 = 1.1`,
/// `Arr_24 = 4.6`). Ordered row-major, as its index.
///
/// ```
/// use aot_locate::Cell;
/// let cell = Cell::new(2, 3).unwrap();
/// assert_eq!(cell.index(), 8);
/// assert_eq!(Cell::from_index(8), Some(cell));
/// assert_eq!(cell.average_area().value(), 2.3);
/// // Row 2 of 4 has its centre in the middle third of the pad's height: the middle area.
/// assert_eq!(cell.aot_area(), 4);
/// assert_eq!(Cell::new(5, 1), None);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Cell {
    row: u8,
    col: u8,
}

impl Cell {
    /// The cell at 1-based `row` (1…4) and `col` (1…6), `None` off the grid.
    pub const fn new(row: u8, col: u8) -> Option<Cell> {
        if row >= 1 && row <= ROWS && col >= 1 && col <= COLS {
            Some(Cell { row, col })
        } else {
            None
        }
    }

    /// The cell of row-major index `i` (`0..24`), `None` off the grid.
    pub const fn from_index(i: usize) -> Option<Cell> {
        if i < CELLS {
            Some(Cell {
                row: (i / COLS as usize) as u8 + 1,
                col: (i % COLS as usize) as u8 + 1,
            })
        } else {
            None
        }
    }

    /// 1-based row.
    pub const fn row(self) -> u8 {
        self.row
    }

    /// 1-based column.
    pub const fn col(self) -> u8 {
        self.col
    }

    /// Row-major index, `0..24` (the cell's bit in a [`CellSet`]).
    pub const fn index(self) -> usize {
        (self.row as usize - 1) * COLS as usize + (self.col as usize - 1)
    }

    /// Every cell, row-major.
    pub fn all() -> impl Iterator<Item = Cell> {
        (0..CELLS).filter_map(Cell::from_index)
    }

    /// The cell's unique number `row.col` as an eq. 4 label of size 1.
    pub const fn average_area(self) -> AverageArea {
        AverageArea::of(CellSet(1 << self.index()))
    }

    /// The 3 × 3 Arrival-of-Time area (0…8, row-major) holding the cell's centre.
    pub const fn aot_area(self) -> usize {
        aot_area_of(self.row as u32, self.col as u32, 1)
    }
}

/// The 3 × 3 area holding the mean cell centre of `n` cells whose 1-based rows sum to `rows`
/// and columns to `cols`, in exact integers. The areas divide the rectangle the cells tile, so
/// in cell units a centre `(R/n − ½, C/n − ½)` lies in area band `⌊3 (2R − n) / (2 n ROWS)⌋`
/// (and likewise for columns); a centre on a border goes to the band after it, as
/// [`crate::AreaGrid::area_at`]'s floor does.
const fn aot_area_of(rows: u32, cols: u32, n: u32) -> usize {
    area_band(rows, n, ROWS as u32) * 3 + area_band(cols, n, COLS as u32)
}

/// One axis of [`aot_area_of`]: `sum` of `n` 1-based indices on an axis of `cells` cells.
const fn area_band(sum: u32, n: u32, cells: u32) -> usize {
    // n ≤ sum ≤ n·cells for real sets, so the band is 0…2 already; the saturation and the
    // clamp only keep the arithmetic total.
    let b = 3 * (2 * sum).saturating_sub(n) / (2 * n * cells);
    if b > 2 { 2 } else { b as usize }
}

/// A set of cells of the 4 × 6 grid as a 24-bit mask: bit `i` is the cell of row-major index
/// `i` (bit 0 is area 1.1, bit 23 area 4.6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct CellSet(u32);

impl CellSet {
    /// No cell (Table 2's size-0 rows).
    pub const EMPTY: CellSet = CellSet(0);

    /// The set of `mask`'s bits, `None` if a bit above 23 is set.
    pub const fn from_bits(mask: u32) -> Option<CellSet> {
        if mask >> CELLS == 0 {
            Some(CellSet(mask))
        } else {
            None
        }
    }

    /// A `rows` × `cols` rectangle with its top-left cell at 1-based (`row`, `col`), `None`
    /// unless it fits on the grid and is non-empty.
    pub const fn rect(row: u8, col: u8, rows: u8, cols: u8) -> Option<CellSet> {
        if row == 0 || col == 0 || rows == 0 || cols == 0 {
            return None;
        }
        if row as u16 + rows as u16 - 1 > ROWS as u16 || col as u16 + cols as u16 - 1 > COLS as u16
        {
            return None;
        }
        let line = ((1u32 << cols) - 1) << (col - 1);
        let mut mask = 0;
        let mut r = 0;
        while r < rows {
            mask |= line << ((row - 1 + r) as u32 * COLS as u32);
            r += 1;
        }
        Some(CellSet(mask))
    }

    /// The raw mask.
    pub const fn bits(self) -> u32 {
        self.0
    }

    /// How many cells (the paper's contact "size").
    pub const fn len(self) -> u32 {
        self.0.count_ones()
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// Whether the cell at 1-based (`row`, `col`) is in the set.
    pub const fn contains(self, row: u8, col: u8) -> bool {
        match Cell::new(row, col) {
            Some(cell) => self.0 & (1 << cell.index()) != 0,
            None => false,
        }
    }

    /// The mean 1-based (row, column) of the cells, `None` for the empty set.
    pub fn centroid(self) -> Option<[f32; 2]> {
        let n = self.len();
        if n == 0 {
            return None;
        }
        let (rs, cs) = self.index_sums();
        Some([rs as f32 / n as f32, cs as f32 / n as f32])
    }

    /// Eq. 4's label for this set.
    pub const fn average_area(self) -> AverageArea {
        AverageArea::of(self)
    }

    /// This set with `cell` added. Takes anything that names a grid cell, so a simulator's
    /// own cell type (one that also knows where the cell sits on its skin) adds directly.
    ///
    /// ```
    /// use aot_locate::{Cell, CellSet};
    /// let whole_pad = Cell::all().fold(CellSet::EMPTY, CellSet::with);
    /// assert_eq!(whole_pad, CellSet::rect(1, 1, 4, 6).unwrap());
    /// ```
    pub fn with(self, cell: impl Into<Cell>) -> CellSet {
        CellSet(self.0 | 1 << cell.into().index())
    }

    /// The cells, row-major.
    ///
    /// ```
    /// use aot_locate::{Cell, CellSet};
    /// let bar = CellSet::rect(3, 2, 1, 2).unwrap();
    /// assert!(bar.iter().eq([Cell::new(3, 2).unwrap(), Cell::new(3, 3).unwrap()]));
    /// ```
    pub fn iter(self) -> impl Iterator<Item = Cell> {
        Cell::all().filter(move |c| self.0 & (1 << c.index()) != 0)
    }

    /// The 3 × 3 Arrival-of-Time area (0…8, row-major) holding the set's centroid, `None` for
    /// the empty set: the area label of a tap. Exact (integer arithmetic), so a centroid on
    /// the border between two areas always goes to the one to its right or below.
    ///
    /// ```
    /// use aot_locate::CellSet;
    /// // A 2 × 2 square over columns 2–3: its centroid is on the border of columns 0 and 1.
    /// assert_eq!(CellSet::rect(1, 2, 2, 2).unwrap().aot_area(), Some(1));
    /// assert_eq!(CellSet::rect(4, 6, 1, 1).unwrap().aot_area(), Some(8));
    /// assert_eq!(CellSet::EMPTY.aot_area(), None);
    /// ```
    pub const fn aot_area(self) -> Option<usize> {
        let n = self.len();
        if n == 0 {
            return None;
        }
        let (rows, cols) = self.index_sums();
        Some(aot_area_of(rows, cols, n))
    }

    /// The sums of the cells' 1-based rows and columns.
    const fn index_sums(self) -> (u32, u32) {
        let (mut rows, mut cols) = (0u32, 0u32);
        let mut i = 0;
        while i < CELLS as u32 {
            if self.0 & (1 << i) != 0 {
                rows += i / COLS as u32 + 1;
                cols += i % COLS as u32 + 1;
            }
            i += 1;
        }
        (rows, cols)
    }
}

/// An eq. 4 value kept exact: the sum of the cells' numbers in tenths (`Σ (10·row + col)`)
/// over the contact size. Equality compares the values, so `2.2 = (1.1 + … + 3.3) / 9`.
#[derive(Debug, Clone, Copy)]
pub struct AverageArea {
    tenths_sum: u16,
    size: u8,
}

impl AverageArea {
    /// No contact: Table 2's label 0.
    pub const NONE: AverageArea = AverageArea {
        tenths_sum: 0,
        size: 0,
    };

    /// Eq. 4 for `cells`.
    pub const fn of(cells: CellSet) -> AverageArea {
        // Σ (10·row + col) = 10·Σ row + Σ col; at most 24 · 46 = 1104, so u16 holds it.
        let (rows, cols) = cells.index_sums();
        AverageArea {
            tenths_sum: (10 * rows + cols) as u16,
            size: cells.len() as u8,
        }
    }

    /// The label as the paper writes it (`1.1`, `2.35`…; 0 for no contact).
    pub fn value(self) -> f32 {
        if self.size == 0 {
            0.0
        } else {
            f32::from(self.tenths_sum) / (10.0 * f32::from(self.size))
        }
    }

    /// The contact size `n` of eq. 4.
    pub const fn size(self) -> u8 {
        self.size
    }
}

impl PartialEq for AverageArea {
    fn eq(&self, other: &AverageArea) -> bool {
        // a/n = b/m ⇔ a·m = b·n; the empty label (0/0) equals only itself.
        u32::from(self.tenths_sum) * u32::from(other.size)
            == u32::from(other.tenths_sum) * u32::from(self.size)
            && (self.size == 0) == (other.size == 0)
    }
}

impl Eq for AverageArea {}

/// A rectangular contact shape: its name and the rows × columns it covers. Its
/// [`placements`](Shape::placements) are a label vocabulary for [`decode_among`].
///
/// ```
/// use aot_locate::{CellSet, DECODE_TOLERANCE, Shape, decode_among};
/// // A user's contact shapes: one cell, a 2 × 2 square and a 3 × 3 square.
/// let shapes = [
///     Shape { name: "1", rows: 1, cols: 1 },
///     Shape { name: "4", rows: 2, cols: 2 },
///     Shape { name: "9", rows: 3, cols: 3 },
/// ];
/// assert_eq!(shapes[1].placements().count(), 15); // 3 rows × 5 columns of positions
/// let vocabulary = || shapes.into_iter().flat_map(Shape::placements);
/// // 2.2 is cell 2.2 alone and the 3 × 3 square around it: both are candidates.
/// let both = decode_among(2.2, DECODE_TOLERANCE, vocabulary()).unwrap();
/// let (cell, square) = (CellSet::rect(2, 2, 1, 1), CellSet::rect(1, 1, 3, 3));
/// assert_eq!(both.as_slice(), [cell.unwrap(), square.unwrap()]);
/// // 1.65 is only the 2 × 2 square at the top left.
/// let square = decode_among(1.65, DECODE_TOLERANCE, vocabulary()).unwrap();
/// assert_eq!(square.unique(), CellSet::rect(1, 1, 2, 2));
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shape {
    /// The shape's name, for reports.
    pub name: &'static str,
    /// Rows it covers.
    pub rows: u8,
    /// Columns it covers.
    pub cols: u8,
}

impl Shape {
    /// Every placement on the grid, moved right one cell at a time, then down (as Kim et al.
    /// 2020 §4 move their contacts), as cell sets.
    pub fn placements(self) -> impl Iterator<Item = CellSet> {
        (1..=ROWS).flat_map(move |r| {
            (1..=COLS).filter_map(move |c| CellSet::rect(r, c, self.rows, self.cols))
        })
    }
}

/// Most cell sets [`decode_among`] returns for one label. Rectangles share a label when they
/// share a centroid, so a vocabulary of shapes nested around one centre (a cell and the
/// 3 × 3 square around it) gives more than one candidate; four leaves room.
pub const MAX_CANDIDATES: usize = 4;

/// The cell sets a label decodes to, in vocabulary order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Candidates {
    sets: [CellSet; MAX_CANDIDATES],
    len: usize,
}

impl Candidates {
    /// The candidates.
    pub fn as_slice(&self) -> &[CellSet] {
        &self.sets[..self.len]
    }

    /// The only candidate, `None` when the label is ambiguous.
    pub fn unique(&self) -> Option<CellSet> {
        (self.len == 1).then_some(self.sets[0])
    }
}

/// Why a label did not decode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum LabelError {
    /// The label is NaN or infinite.
    NonFinite,
    /// No set of the vocabulary has this label.
    NoMatch,
    /// More than [`MAX_CANDIDATES`] sets share the label.
    TooManyCandidates,
}

impl core::fmt::Display for LabelError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            LabelError::NonFinite => "label is not finite",
            LabelError::NoMatch => "no contact shape has this label",
            LabelError::TooManyCandidates => "more candidate shapes than fit",
        })
    }
}

/// Half the spacing of rectangles' labels: a rectangle's mean row and column are whole or
/// half, so its eq. 4 value is a multiple of 0.05, and a value within 0.025 of a rectangle's
/// label is that label.
pub const DECODE_TOLERANCE: f32 = 0.025;

/// Every set of `vocabulary` whose eq. 4 label is strictly within `tolerance` of `value`
/// (include [`CellSet::EMPTY`] in the vocabulary to decode 0 as no contact).
pub fn decode_among(
    value: f32,
    tolerance: f32,
    vocabulary: impl IntoIterator<Item = CellSet>,
) -> Result<Candidates, LabelError> {
    if !value.is_finite() {
        return Err(LabelError::NonFinite);
    }
    let mut out = Candidates {
        sets: [CellSet::EMPTY; MAX_CANDIDATES],
        len: 0,
    };
    for set in vocabulary {
        if (set.average_area().value() - value).abs() < tolerance {
            *out.sets
                .get_mut(out.len)
                .ok_or(LabelError::TooManyCandidates)? = set;
            out.len += 1;
        }
    }
    if out.len == 0 {
        Err(LabelError::NoMatch)
    } else {
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The test's vocabulary: six rectangles (Kim et al. 2020's Figure 7 contact shapes, read
    /// as 1 × 1, 2 × 2, 3 × 3, 4 × 4, 3 × 4 and 1 × 4) at every position, and the empty set.
    fn placements() -> impl Iterator<Item = CellSet> {
        let shape = |name, rows, cols| Shape { name, rows, cols };
        let shapes = [
            shape("1", 1, 1),
            shape("4-1", 2, 2),
            shape("9", 3, 3),
            shape("16", 4, 4),
            shape("12", 3, 4),
            shape("4-2", 1, 4),
        ];
        core::iter::once(CellSet::EMPTY).chain(shapes.into_iter().flat_map(Shape::placements))
    }

    fn decode(value: f32) -> Result<Candidates, LabelError> {
        decode_among(value, DECODE_TOLERANCE, placements())
    }

    #[test]
    fn unique_numbers_match_the_paper() {
        // §4: Arr_1 = 1.1, Arr_6 = 1.6, Arr_24 = 4.6.
        let cell = |i: u32| CellSet::from_bits(1 << i).unwrap().average_area().value();
        assert_eq!(cell(0), 1.1);
        assert_eq!(cell(5), 1.6);
        assert_eq!(cell(23), 4.6);
        assert_eq!(CellSet::EMPTY.average_area().value(), 0.0);
        assert_eq!(CellSet::from_bits(1 << 24), None);
    }

    #[test]
    fn rect_masks() {
        assert_eq!(CellSet::rect(1, 1, 2, 2).unwrap().bits(), 0b11 | 0b11 << 6);
        assert_eq!(CellSet::rect(4, 3, 1, 4).unwrap().len(), 4);
        assert!(CellSet::rect(4, 4, 1, 4).is_none());
        assert!(CellSet::rect(0, 1, 1, 1).is_none());
        assert!(CellSet::rect(2, 2, 3, 3).unwrap().contains(4, 4));
        assert!(!CellSet::rect(2, 2, 3, 3).unwrap().contains(1, 2));
    }

    #[test]
    fn eq4_by_hand() {
        // A 2 × 2 square at 1.1: (1.1 + 1.2 + 2.1 + 2.2) / 4 = 1.65.
        let sq = CellSet::rect(1, 1, 2, 2).unwrap().average_area();
        assert!((sq.value() - 1.65).abs() < 1e-6);
        assert_eq!(sq.size(), 4);
        // A 1 × 4 bar at 3.2: (3.2 + 3.3 + 3.4 + 3.5) / 4 = 3.35.
        let bar = CellSet::rect(3, 2, 1, 4).unwrap().average_area();
        assert!((bar.value() - 3.35).abs() < 1e-6);
    }

    #[test]
    fn labels_compare_by_value() {
        let nine = CellSet::rect(1, 1, 3, 3).unwrap().average_area();
        let one = CellSet::rect(2, 2, 1, 1).unwrap().average_area();
        assert_eq!(nine, one);
        assert_ne!(AverageArea::NONE, one);
        assert_eq!(AverageArea::NONE, CellSet::EMPTY.average_area());
    }

    #[test]
    fn cells_index_row_major_and_sets_iterate_them() {
        for (i, cell) in Cell::all().enumerate() {
            assert_eq!(cell.index(), i);
            assert_eq!(Cell::new(cell.row(), cell.col()), Some(cell));
            let one = CellSet::EMPTY.with(cell);
            assert_eq!(one.bits(), 1 << i);
            assert!(one.contains(cell.row(), cell.col()));
            assert_eq!(cell.average_area(), one.average_area());
            assert!(one.iter().eq([cell]));
        }
        assert_eq!(Cell::all().count(), CELLS);
        assert_eq!(Cell::from_index(CELLS), None);
        assert_eq!(Cell::new(0, 1), None);
        assert_eq!(Cell::new(1, 7), None);
        let bar = CellSet::rect(2, 3, 1, 4).unwrap();
        assert_eq!(bar.iter().fold(CellSet::EMPTY, CellSet::with), bar);
        assert!(bar.iter().map(Cell::col).eq(3..=6));
    }

    #[test]
    fn aot_areas_are_the_grids_areas_of_the_centroid() {
        // An 18 × 12 mm pad of 3 mm cells.
        let pad = crate::AreaGrid {
            width_mm: 18.0,
            height_mm: 12.0,
        };
        // Every placement: centroids on area borders included (a 2 × 2 square over columns
        // 2–3 sits on the border of area columns 0 and 1; f32 holds those exactly).
        for set in placements().skip(1) {
            let centroid = set.centroid().map(|c| pad.grid_point_mm(c));
            assert_eq!(set.aot_area(), centroid.map(|c| pad.area_at(c)), "{set:?}");
        }
        for cell in Cell::all() {
            assert_eq!(cell.aot_area(), pad.area_at(pad.cell_centre_mm(cell)));
        }
        let whole = CellSet::rect(1, 1, ROWS, COLS).unwrap();
        assert_eq!(whole.aot_area(), Some(4));
        assert_eq!(CellSet::rect(1, 1, 2, 2).unwrap().aot_area(), Some(0));
        assert_eq!(CellSet::rect(1, 2, 2, 2).unwrap().aot_area(), Some(1));
        assert_eq!(CellSet::rect(3, 4, 2, 2).unwrap().aot_area(), Some(8));
    }

    #[test]
    fn decode_errors() {
        assert_eq!(decode(f32::NAN), Err(LabelError::NonFinite));
        // 1.15 would be row 1, column 1.5: no shape of the vocabulary is centred there.
        assert_eq!(decode(1.15), Err(LabelError::NoMatch));
        assert_eq!(decode(-1.0), Err(LabelError::NoMatch));
        assert_eq!(decode(0.0).unwrap().unique(), Some(CellSet::EMPTY));
        let all = [CellSet::rect(2, 2, 1, 1).unwrap(); 5];
        assert_eq!(
            decode_among(2.2, 0.01, all),
            Err(LabelError::TooManyCandidates)
        );
    }
}
