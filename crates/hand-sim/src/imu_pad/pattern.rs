//! Where on the pad a tap is felt, and how: force fall-off towards the edges, coupling of the
//! deflection to the barometer, and the accelerometer / gyroscope patterns of Fig. 5.
//!
//! All functions take the tap's offset from the chip centre (`dx` across, `dy` along the pad,
//! mm) or its normalised place on the grid, so a jittered repeat moves smoothly between rows.

use crate::imu_pad::config::{Mechanics, PressureCoupling};
use crate::imu_pad::grid::COLUMN_STEP_MM;

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

/// Moment arm, mm, that tilts the pad as much about the across axis as a tap one column
/// (3.5 mm) off the chip tilts it about the along axis: the mean arm of the end rows (row 1 is
/// 12.5 mm, row 24 10.5 mm from the chip at row 13.5). Fig. 5 puts acc x of column 1 near zero at
/// row 24 and of column 3 near zero at row 1, i.e. one column's arm across balances an end
/// row's arm along; so, per mm, a tap tilts the 11.5 mm-wide pad 11.5 / 3.5 = 3.3 times more
/// about its long axis than about its short one (a plate on an elastic bed: 4.4 = (24 / 11.5)²;
/// the silicone walls and the PCB overhang make the measured pad stiffer across).
pub const ALONG_ARM_MM: f64 = 11.5;

/// The arm's share of the pad's tilt (the tilt is this times the tap's force), from a tap at offset (`dx`, `dy`) mm from the chip:
/// `[a, c]`, `a` about the across axis (set by the arm along the rows, −1.09 at row 1 … +0.91 at
/// row 24) and `c` about the along axis (set by the arm across, −1 at column 1 … +1 at
/// column 3). A lever, not a normalised grid place: the two arms have their own scales, so a
/// tap and its row / column mirror do not tilt the chip alike.
pub fn tilt(dx_mm: f64, dy_mm: f64) -> [f64; 2] {
    [
        (dy_mm / ALONG_ARM_MM).clamp(-1.5, 1.5),
        (dx_mm / COLUMN_STEP_MM).clamp(-1.5, 1.5),
    ]
}

/// Accelerometer x / y during the hold, per unit amplitude: gravity seen by the tilted chip,
/// whose axes sit at 45° to the pad's (§III-C, Fig. 5: acc x changes along the rows in the
/// centre column *and* shifts between columns, which an axis-aligned chip cannot show).
/// A tilt `θ'` in the chip frame reads `acc = g·(−θ'_y, θ'_x)`; with
/// `θ' = ((a − c), (a + c)) / 2`: acc x = `−(a + c) / 2` (col 1 + → ~0, col 2 + → −, col 3
/// ~0 → −, as Fig. 5) and acc y = `(a − c) / 2`, the same traces run from row 24 to row 1 —
/// Fig. 5's "opposite" (col 2 − → +; col 1 ~0 → +, col 3 − → ~0). A rigid tilt gives two
/// independent readings: a law with acc y = −acc x at every place would see one.
pub fn accel_pattern([a, c]: [f64; 2]) -> [f64; 2] {
    [-0.5 * (a + c), 0.5 * (a - c)]
}

/// Gyroscope x / y rate per unit amplitude and unit press rate: the rate of the same tilt
/// `θ'` (signed: the press tilts one way, the release back). |gyro x| = `|a − c| / 2` grows from
/// ~0 along the rows in column 1, runs between + and − in column 2 and falls to ~0 in column 3;
/// |gyro y| = `|a + c| / 2` does the opposite in columns 1 and 3 and the same in column 2
/// (Fig. 5).
pub fn gyro_pattern([a, c]: [f64; 2]) -> [f64; 2] {
    [0.5 * (a - c), 0.5 * (a + c)]
}
