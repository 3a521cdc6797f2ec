//! Pad geometry as data: the three sensor positions, the nine Arrival-of-Time area centres and
//! the distances `r_{n,k}` between them (Kim et al. 2020, "Artificial Intelligence-Based
//! Optimal Grasping Control", §3 and Figure 5). The user gives their pad's dimensions and
//! sensor positions; this crate assumes none.
//!
//! Coordinates are millimetres in the pad plane, x to the right, y up, origin at the pad
//! centre. Areas are numbered 0…8 row-major from the top-left (the paper's `Arr_1…Arr_9`
//! minus one); sensors 0…2 are the paper's sensors 1…3.

use crate::label::{COLS, Cell, ROWS};
use crate::trilateration::Trilateration;

/// Sensors on a fingertip (three barometers, in Kim et al. 2020 §3 an inverted triangle).
pub const SENSORS: usize = 3;
/// Areas of the 3 × 3 Arrival-of-Time grid.
pub const AREAS: usize = 9;

/// The pad rectangle the 3 × 3 areas divide into equal parts (§3: "nine equal-sized
/// rectangles"), centred on the origin.
///
/// ```
/// use aot_locate::AreaGrid;
/// // An 18 × 12 mm pad: 3 mm cells on the 4 × 6 grid, 6 × 4 mm areas on the 3 × 3 one.
/// let pad = AreaGrid { width_mm: 18.0, height_mm: 12.0 };
/// assert_eq!(pad.centres_mm()[0], [-6.0, 4.0]);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AreaGrid {
    /// Pad width along x, mm.
    pub width_mm: f32,
    /// Pad height along y, mm.
    pub height_mm: f32,
}

impl AreaGrid {
    /// The nine area centres, row-major from the top-left.
    pub fn centres_mm(&self) -> [[f32; 2]; AREAS] {
        let (w, h) = (self.width_mm / 3.0, self.height_mm / 3.0);
        core::array::from_fn(|n| {
            let (row, col) = ((n / 3) as f32, (n % 3) as f32);
            [(col - 1.0) * w, (1.0 - row) * h]
        })
    }

    /// A point given in 1-based (row, column) units of the 4 × 6 cells that tile this pad, cell
    /// centres at whole numbers (as [`crate::CellSet::centroid`] gives them), in pad mm.
    ///
    /// ```
    /// use aot_locate::AreaGrid;
    /// let pad = AreaGrid { width_mm: 18.0, height_mm: 12.0 }; // 3 mm cells
    /// assert_eq!(pad.grid_point_mm([1.0, 1.0]), [-7.5, 4.5]);
    /// assert_eq!(pad.grid_point_mm([2.5, 3.5]), [0.0, 0.0]);
    /// ```
    pub fn grid_point_mm(&self, [row, col]: [f32; 2]) -> [f32; 2] {
        let (pitch_x, pitch_y) = (
            self.width_mm / f32::from(COLS),
            self.height_mm / f32::from(ROWS),
        );
        [
            (col - 0.5) * pitch_x - self.width_mm / 2.0,
            self.height_mm / 2.0 - (row - 0.5) * pitch_y,
        ]
    }

    /// The inverse of [`grid_point_mm`](Self::grid_point_mm): the point `p_mm` (pad mm) in
    /// 1-based (row, column) units of the 4 × 6 cells, cell centres at whole numbers. Points off
    /// the pad map outside 0.5…4.5 × 0.5…6.5.
    ///
    /// ```
    /// use aot_locate::AreaGrid;
    /// let pad = AreaGrid { width_mm: 18.0, height_mm: 12.0 };
    /// assert_eq!(pad.grid_point_of([-7.5, 4.5]), [1.0, 1.0]);
    /// let [row, col] = pad.grid_point_of([0.6, -0.3]);
    /// assert!((row - 2.6).abs() < 1e-6 && (col - 3.7).abs() < 1e-6);
    /// assert_eq!(pad.grid_point_of(pad.grid_point_mm([2.5, 3.5])), [2.5, 3.5]);
    /// ```
    pub fn grid_point_of(&self, [x, y]: [f32; 2]) -> [f32; 2] {
        let (pitch_x, pitch_y) = (
            self.width_mm / f32::from(COLS),
            self.height_mm / f32::from(ROWS),
        );
        [
            (self.height_mm / 2.0 - y) / pitch_y + 0.5,
            (x + self.width_mm / 2.0) / pitch_x + 0.5,
        ]
    }

    /// The centre of `cell`, pad mm.
    ///
    /// ```
    /// use aot_locate::{AreaGrid, Cell};
    /// let pad = AreaGrid { width_mm: 18.0, height_mm: 12.0 };
    /// let cell = Cell::new(4, 6).unwrap();
    /// assert_eq!(pad.cell_centre_mm(cell), [7.5, -4.5]);
    /// ```
    pub fn cell_centre_mm(&self, cell: Cell) -> [f32; 2] {
        self.grid_point_mm([f32::from(cell.row()), f32::from(cell.col())])
    }

    /// The area (0…8) holding the point `p_mm`; points off the pad fall in the nearest edge
    /// area, non-finite coordinates in the centre band of their axis.
    pub fn area_at(&self, p_mm: [f32; 2]) -> usize {
        // A non-finite or non-positive span would divide by zero: treat it as one band.
        let band = |v: f32, span: f32| {
            let b = libm::floorf(v / (span / 3.0));
            if b.is_nan() || span.is_nan() || span <= 0.0 {
                1
            } else {
                b.clamp(0.0, 2.0) as usize
            }
        };
        let row = band(self.height_mm / 2.0 - p_mm[1], self.height_mm);
        let col = band(p_mm[0] + self.width_mm / 2.0, self.width_mm);
        row * 3 + col
    }
}

/// Why a [`Geometry`] could not be built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum GeometryError {
    /// A sensor position, area centre or grid dimension is NaN or infinite.
    NonFinite,
    /// The grid's width or height is not positive.
    EmptyGrid,
    /// Sensor `sensor` sits on area `area`'s centre: `r_{n,k} = 0` and eq. 3 would divide by
    /// zero.
    ZeroDistance {
        /// The area, 0…8.
        area: usize,
        /// The sensor, 0…2.
        sensor: usize,
    },
}

impl core::fmt::Display for GeometryError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            GeometryError::NonFinite => f.write_str("non-finite pad geometry"),
            GeometryError::EmptyGrid => f.write_str("pad grid width or height not positive"),
            GeometryError::ZeroDistance { area, sensor } => {
                write!(f, "sensor {sensor} lies on the centre of area {area}")
            }
        }
    }
}

/// Sensor positions, area centres and the precomputed `1 / r_{n,k}` of eq. 3.
///
/// ```
/// use aot_locate::{AreaGrid, Geometry, GeometryError};
/// // Sensors in an inverted triangle under an 18 × 12 mm pad.
/// let sensors = [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]];
/// let pad = Geometry::new(sensors, AreaGrid { width_mm: 18.0, height_mm: 12.0 })?;
/// // Area 7 (bottom centre, (0, −4) mm) is 0.5 mm from sensor 2.
/// assert!((pad.distance_mm(7, 1).unwrap() - 0.5).abs() < 1e-12);
/// # Ok::<(), GeometryError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geometry {
    sensors_mm: [[f32; 2]; SENSORS],
    centres_mm: [[f32; 2]; AREAS],
    // Stored inverted and in f64: eq. 3 divides by r, and f64 keeps the products of any finite
    // f32 pressure, any r > 0 and any timing ratio finite.
    inv_r: [[f64; SENSORS]; AREAS],
    // The ranging scorer's pad-only work, done once here rather than per localisation.
    fix: Trilateration,
}

impl Geometry {
    /// Geometry from sensor positions and the pad rectangle divided 3 × 3.
    pub fn new(sensors_mm: [[f32; 2]; SENSORS], grid: AreaGrid) -> Result<Geometry, GeometryError> {
        if !(grid.width_mm.is_finite() && grid.height_mm.is_finite()) {
            return Err(GeometryError::NonFinite);
        }
        if grid.width_mm <= 0.0 || grid.height_mm <= 0.0 {
            return Err(GeometryError::EmptyGrid);
        }
        Geometry::from_centres(sensors_mm, grid.centres_mm())
    }

    /// Geometry from sensor positions and arbitrary area centres (a pad that is not a regular
    /// grid).
    pub fn from_centres(
        sensors_mm: [[f32; 2]; SENSORS],
        centres_mm: [[f32; 2]; AREAS],
    ) -> Result<Geometry, GeometryError> {
        let finite = |p: &[f32; 2]| p[0].is_finite() && p[1].is_finite();
        if !sensors_mm.iter().all(finite) || !centres_mm.iter().all(finite) {
            return Err(GeometryError::NonFinite);
        }
        let g = Geometry::compute(sensors_mm, centres_mm);
        for (area, row) in g.inv_r.iter().enumerate() {
            for (sensor, inv) in row.iter().enumerate() {
                if !inv.is_finite() {
                    return Err(GeometryError::ZeroDistance { area, sensor });
                }
            }
        }
        Ok(g)
    }

    fn compute(sensors_mm: [[f32; 2]; SENSORS], centres_mm: [[f32; 2]; AREAS]) -> Geometry {
        let inv_r = core::array::from_fn(|n| {
            core::array::from_fn(|k| 1.0 / distance(centres_mm[n], sensors_mm[k]))
        });
        Geometry {
            sensors_mm,
            centres_mm,
            inv_r,
            fix: Trilateration::new(&sensors_mm, &centres_mm),
        }
    }

    /// Sensor `k`'s position (0…2), mm.
    pub fn sensors_mm(&self) -> &[[f32; 2]; SENSORS] {
        &self.sensors_mm
    }

    /// The area centres (0…8), mm.
    pub fn centres_mm(&self) -> &[[f32; 2]; AREAS] {
        &self.centres_mm
    }

    /// `r_{n,k}`: the distance from area `n`'s centre to sensor `k`, mm (`None` off range).
    pub fn distance_mm(&self, area: usize, sensor: usize) -> Option<f64> {
        self.inv_r.get(area)?.get(sensor).map(|inv| 1.0 / inv)
    }

    /// The ranging scorer's precomputed, pad-only part of the position fix.
    pub(crate) fn trilateration(&self) -> &Trilateration {
        &self.fix
    }

    /// `1 / r_{n,k}` for every area and sensor, as eq. 3 uses it.
    pub fn inverse_distances(&self) -> &[[f64; SENSORS]; AREAS] {
        &self.inv_r
    }

    /// The same pad with its sensors renumbered: new sensor `i` is old sensor `order[i]`.
    /// `None` unless `order` is a permutation of 0…2.
    pub fn permuted(&self, order: [usize; SENSORS]) -> Option<Geometry> {
        let mut seen = [false; SENSORS];
        for &o in &order {
            *seen.get_mut(o)? = true;
        }
        if !seen.iter().all(|&s| s) {
            return None;
        }
        let sensors_mm = core::array::from_fn(|i| self.sensors_mm[order[i]]);
        Some(Geometry {
            sensors_mm,
            centres_mm: self.centres_mm,
            inv_r: core::array::from_fn(|n| core::array::from_fn(|i| self.inv_r[n][order[i]])),
            fix: Trilateration::new(&sensors_mm, &self.centres_mm),
        })
    }
}

fn distance(a: [f32; 2], b: [f32; 2]) -> f64 {
    let dx = f64::from(a[0]) - f64::from(b[0]);
    let dy = f64::from(a[1]) - f64::from(b[1]);
    libm::sqrt(dx * dx + dy * dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A test pad: 18 × 12 mm (3 mm cells on the 4 × 6 grid).
    const PAD: AreaGrid = AreaGrid {
        width_mm: 18.0,
        height_mm: 12.0,
    };
    /// Its sensors: an inverted triangle, none on an area centre.
    const SENSORS_MM: [[f32; 2]; SENSORS] = [[4.5, 1.5], [0.0, -4.5], [-4.5, 1.5]];

    fn pad() -> Geometry {
        Geometry::new(SENSORS_MM, PAD).unwrap()
    }

    #[test]
    fn centres_are_the_3x3_rectangles_of_an_18_by_12_pad() {
        let c = PAD.centres_mm();
        assert_eq!(c[0], [-6.0, 4.0]);
        assert_eq!(c[4], [0.0, 0.0]);
        assert_eq!(c[8], [6.0, -4.0]);
        for (n, p) in c.iter().enumerate() {
            assert_eq!(PAD.area_at(*p), n);
        }
    }

    #[test]
    fn distances_follow_pythagoras() {
        let g = pad();
        // Area 7 (bottom centre, (0, −4)) to sensor 2 (0, −4.5): 0.5 mm.
        assert!((g.distance_mm(7, 1).unwrap() - 0.5).abs() < 1e-12);
        // Area 2 (top right, (6, 4)) to sensor 1 (4.5, 1.5): √(1.5² + 2.5²).
        assert!((g.distance_mm(2, 0).unwrap() - 8.5f64.sqrt()).abs() < 1e-12);
        assert_eq!(g.distance_mm(9, 0), None);
    }

    #[test]
    fn a_sensor_on_an_area_centre_is_a_typed_error() {
        let sensors = [[0.0, 0.0], [0.0, -4.5], [-4.5, 1.5]];
        assert_eq!(
            Geometry::new(sensors, PAD),
            Err(GeometryError::ZeroDistance { area: 4, sensor: 0 })
        );
        let bad = [[f32::NAN, 0.0], [0.0, -4.5], [-4.5, 1.5]];
        assert_eq!(Geometry::new(bad, PAD), Err(GeometryError::NonFinite));
        let flat = AreaGrid {
            width_mm: 0.0,
            height_mm: 12.0,
        };
        assert_eq!(
            Geometry::new(SENSORS_MM, flat),
            Err(GeometryError::EmptyGrid)
        );
    }

    #[test]
    fn points_off_the_pad_fall_in_edge_areas() {
        let g = PAD;
        assert_eq!(g.area_at([-100.0, 100.0]), 0);
        assert_eq!(g.area_at([100.0, -100.0]), 8);
        assert_eq!(g.area_at([f32::NAN, f32::NAN]), 4);
    }

    #[test]
    fn permutation_must_be_a_permutation() {
        let g = pad();
        assert!(g.permuted([0, 0, 1]).is_none());
        assert!(g.permuted([0, 1, 3]).is_none());
        let p = g.permuted([2, 0, 1]).unwrap();
        assert_eq!(p.sensors_mm()[0], g.sensors_mm()[2]);
        assert_eq!(p.inverse_distances()[5][1], g.inverse_distances()[5][0]);
    }
}
