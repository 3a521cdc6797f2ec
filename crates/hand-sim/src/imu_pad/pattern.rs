//! Where on the pad a tap is felt, and how: force fall-off towards the edges, coupling of the
//! deflection to the barometer, and the accelerometer / gyroscope patterns of Fig. 5.
//!
//! All functions take the tap's offset from the chip centre (`dx` across, `dy` along the pad,
//! mm) or its normalised place on the grid, so a jittered repeat moves smoothly between rows.

use crate::imu_pad::config::{Mechanics, PressureCoupling};
use crate::imu_pad::grid::{COLUMN_STEP_MM, ROW_STEP_MM, ROWS};

/// Distance along the pad at which [`Mechanics::edge_force_drop`] is reached, mm.
const EDGE_REACH_MM: f64 = 12.0;

/// Force at offset (`dx`, `dy`) relative to the same depth on the chip (Fig. 4B / 4D: centre
/// column and centre rows push back hardest, the bending edges least). In 0…1.
pub fn force_factor(mech: &Mechanics, dx_mm: f64, dy_mm: f64) -> f64 {
    let along = (dy_mm / EDGE_REACH_MM).clamp(-1.5, 1.5);
    let across = (dx_mm.abs() / COLUMN_STEP_MM).min(1.5);
    let along_factor = 1.0 - mech.edge_force_drop * along * along;
    let across_factor = 1.0 - (1.0 - mech.side_column_force) * across;
    (along_factor * across_factor).clamp(0.0, 1.0)
}

/// The share `k` (0…1) of the tap's depth that reaches the silicone over the chip.
pub fn chip_coupling(p: &PressureCoupling, dx_mm: f64, dy_mm: f64) -> f64 {
    let r = dx_mm.hypot(dy_mm);
    let spread = if dy_mm < 0.0 {
        p.spread_low_mm
    } else {
        p.spread_high_mm
    };
    let beyond = ((r - p.plateau_mm).max(0.0) / spread).min(1e3);
    (-beyond * beyond).exp()
}

/// Peak pressure counts of a tap of depth `depth_mm` with coupling `k` and force `force_n`.
///
/// No counts unless the deflection over the chip `depth · k` closes the gap; then the inverse
/// of eq. 1 at the tap force, scaled by how far past the gap the chip is pushed relative to a
/// tap on the chip itself (1 on the chip, falling to 0 where contact is lost).
pub fn pressure_counts(p: &PressureCoupling, depth_mm: f64, k: f64, force_n: f64) -> f64 {
    let excess = depth_mm * k - p.gap_mm;
    if !(excess > 0.0 && depth_mm > p.gap_mm) {
        return 0.0;
    }
    let contact = (excess / (depth_mm - p.gap_mm)).clamp(0.0, 1.0);
    p.eq1.counts(force_n) * contact
}

/// Place along the rows, −1 at row 1 … +1 at row 24, from the offset along the pad from row 1.
pub fn along(y_mm: f64) -> f64 {
    let half = 0.5 * f64::from(ROWS - 1) * ROW_STEP_MM;
    ((y_mm - half) / half).clamp(-1.5, 1.5)
}

/// Place across the columns, −1 at column 1 … +1 at column 3.
pub fn across(x_mm: f64) -> f64 {
    (x_mm / COLUMN_STEP_MM).clamp(-1.5, 1.5)
}

/// Accelerometer x / y during the hold, per unit amplitude (§III-C, Fig. 5):
/// x goes positive → ~0 along the rows in column 1, positive → negative in column 2, ~0 →
/// negative in column 3; y is the opposite. Both are `∓(u + v) / 2`: the chip tilts about the
/// pad diagonal, more the farther the tap from the column-3/row-1 … column-1/row-24 line.
pub fn accel_pattern(u: f64, v: f64) -> [f64; 2] {
    let s = 0.5 * (u + v);
    [-s, s]
}

/// Gyroscope x / y rate magnitude, per unit amplitude (§III-C, Fig. 5): x grows from zero
/// along the rows in column 1, stays mid-size in column 2 and falls to zero in column 3;
/// y is the opposite in columns 1 and 3 and the same in column 2. The sign comes from the
/// motion: positive while pressing, negative while releasing ("positive and negative values").
pub fn gyro_pattern(u: f64, v: f64) -> [f64; 2] {
    [
        (0.5 * (1.0 - u * v)).max(0.0),
        (0.5 * (1.0 + u * v)).max(0.0),
    ]
}
