//! The 4 × 6 pad of the barometric fingertip (seed 000 §4): cells, eq. 4 labels, cell sets.
//!
//! Cell `i` (0–23) is row `i / 6 + 1`, column `i % 6 + 1`, row-major from the top left; its
//! unique number is `row + column / 10` (area 1.1 … 4.6). A contact is a cell set, a 24-bit
//! mask with bit `i` for cell `i`.

/// Rows of the pad.
pub const ROWS: usize = 4;
/// Columns of the pad.
pub const COLS: usize = 6;
/// Cells of the pad.
pub const CELLS: usize = ROWS * COLS;

/// Eq. 4's unique number of cell `cell` (1.1 … 4.6).
pub fn cell_label(cell: usize) -> f32 {
    (cell / COLS + 1) as f32 + (cell % COLS + 1) as f32 / 10.0
}

/// Cells of a mask, in order.
pub fn cells(mask: u32) -> impl Iterator<Item = usize> {
    (0..CELLS).filter(move |&i| mask & (1 << i) != 0)
}

/// Eq. 4: the mean of the unique numbers of the touched cells (0 for no cell, as Table 2).
pub fn average_area(mask: u32) -> f32 {
    let n = cells(mask).count();
    if n == 0 {
        return 0.0;
    }
    cells(mask).map(cell_label).sum::<f32>() / n as f32
}

/// Centroid of a mask as (row, column) in cell units, 0-based; `None` for no cell.
pub fn centroid(mask: u32) -> Option<(f32, f32)> {
    let n = cells(mask).count();
    if n == 0 {
        return None;
    }
    let (r, c) = cells(mask).fold((0.0, 0.0), |(r, c), i| {
        (r + (i / COLS) as f32, c + (i % COLS) as f32)
    });
    Some((r / n as f32, c / n as f32))
}

/// Cells in one mask but not the other: `|a ∆ b|`.
pub fn cell_difference(a: u32, b: u32) -> u32 {
    ((a ^ b) & ((1 << CELLS) - 1)).count_ones()
}

/// Distance between two masks' centroids, cells; `None` if either is empty.
pub fn centroid_distance(a: u32, b: u32) -> Option<f32> {
    let ((ra, ca), (rb, cb)) = (centroid(a)?, centroid(b)?);
    Some(((ra - rb).powi(2) + (ca - cb).powi(2)).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_and_sets() {
        assert_eq!(cell_label(0), 1.1);
        assert_eq!(cell_label(23), 4.6);
        // A 2 × 2 square at the top left: cells 1.1, 1.2, 2.1, 2.2 -> 1.65.
        let square = 0b11 | (0b11 << COLS);
        assert!((average_area(square) - 1.65).abs() < 1e-6);
        assert_eq!(centroid(square), Some((0.5, 0.5)));
        assert_eq!(cell_difference(square, 1), 3);
        assert_eq!(centroid_distance(1, 1 << 23), Some((9.0f32 + 25.0).sqrt()));
        assert_eq!(average_area(0), 0.0);
    }
}
