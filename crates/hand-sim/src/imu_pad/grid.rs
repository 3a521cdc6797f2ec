//! The 3 × 24 tap grid of seed 002 §III-C (1 mm row step along y, 3.5 mm column step along x)
//! and the 9 contact regions of §IV-A (3 columns × 3 groups of 8 rows).

use crate::SimError;

/// Columns on the grid.
pub const COLUMNS: u8 = 3;
/// Rows on the grid.
pub const ROWS: u8 = 24;
/// Row pitch along the pad, mm.
pub const ROW_STEP_MM: f64 = 1.0;
/// Column pitch across the pad, mm.
pub const COLUMN_STEP_MM: f64 = 3.5;
/// Rows per region group (§IV-A: "3 groups of 8 rows").
pub const ROWS_PER_GROUP: u8 = 8;
/// Number of contact regions.
pub const REGIONS: u8 = 9;

/// A grid position, 1-based as in the paper: column 1…3, row 1…24.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct TapPosition {
    column: u8,
    row: u8,
}

impl TapPosition {
    /// A checked position; anything off the grid is a [`SimError::Config`].
    ///
    /// ```
    /// use hand_sim::imu_pad::TapPosition;
    /// assert!(TapPosition::new(2, 13).is_ok());
    /// assert!(TapPosition::new(4, 1).is_err());
    /// assert!(TapPosition::new(1, 0).is_err());
    /// ```
    pub fn new(column: u8, row: u8) -> Result<Self, SimError> {
        if !(1..=COLUMNS).contains(&column) {
            return Err(SimError::config(
                "column",
                format!("1…{COLUMNS}, got {column}"),
            ));
        }
        if !(1..=ROWS).contains(&row) {
            return Err(SimError::config("row", format!("1…{ROWS}, got {row}")));
        }
        Ok(TapPosition { column, row })
    }

    /// All 72 positions, column by column, rows 1…24 (the order the UR3 tapped them).
    pub fn all() -> impl Iterator<Item = TapPosition> {
        (1..=COLUMNS).flat_map(|column| (1..=ROWS).map(move |row| TapPosition { column, row }))
    }

    /// Column, 1…3.
    pub fn column(&self) -> u8 {
        self.column
    }

    /// Row, 1…24.
    pub fn row(&self) -> u8 {
        self.row
    }

    /// Offset from the centre column across the pad, mm (column 1 at −3.5).
    pub fn x_mm(&self) -> f64 {
        (f64::from(self.column) - 2.0) * COLUMN_STEP_MM
    }

    /// Position along the pad, mm from row 1.
    pub fn y_mm(&self) -> f64 {
        (f64::from(self.row) - 1.0) * ROW_STEP_MM
    }

    /// The §IV-A contact region, 0…8: `3 · group + (column − 1)` with group 0 for rows 1–8,
    /// 1 for rows 9–16, 2 for rows 17–24. (Fig. 8A's own numbering is not in the text.)
    ///
    /// ```
    /// use hand_sim::imu_pad::TapPosition;
    /// assert_eq!(TapPosition::new(1, 1)?.region(), 0);
    /// assert_eq!(TapPosition::new(3, 8)?.region(), 2);
    /// assert_eq!(TapPosition::new(2, 9)?.region(), 4);
    /// assert_eq!(TapPosition::new(3, 24)?.region(), 8);
    /// # Ok::<(), hand_sim::SimError>(())
    /// ```
    pub fn region(&self) -> u8 {
        3 * ((self.row - 1) / ROWS_PER_GROUP) + (self.column - 1)
    }
}
