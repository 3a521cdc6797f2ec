//! The ICM-20789 tactile pad of seed 002 (Al & Martinez-Hernandez): a 24 × 11.5 × 4.5 mm
//! Ecoflex 00-30 case over the chip, tapped by a UR3 with a 10 mm sphere on a 3 × 24 grid.
//!
//! * [`force`]: depth → force by the Yeoh law (eq. 2) fitted through the published points
//!   (0.8 mm 3.5 N, 1.3 mm 8 N, 1.7 mm 13 N), and force → counts by the inverse of eq. 1.
//! * [`pattern`]: where a tap is felt — force fall-off to the edges, coupling to the barometer
//!   (pressure only where §III-C sees it), the accelerometer and gyroscope patterns of Fig. 5.
//! * [`tap`]: the press / hold / release profile, the seeded realisation of each tap, and the
//!   pad's truth over time.
//! * [`ImuPad`]: the truth fed to `imu_icm20789::sim::ChipModel` and read back at 30 Hz by
//!   the real driver; frames are [`hand_traits::ImuFrame`]s, so they hold what a driver read.
//! * [`TapWindow`]: the 4 × 38 window of §IV-A; [`TapPosition::region`]: its 9-region label.
//! * [`dataset`]: the seeded tap dataset for the contact CNN, and its CSV format.
//!
//! # What a "count" is
//!
//! The paper's pressure output is in "counts" (263…969 for 3.53…13 N, eq. 1) and never
//! converted. We take **one count = 1 Pa of pressure above the pre-tap baseline**, as the
//! driver reports it: the truth fed to the chip model is `ambient_pa + counts · pa_per_count`
//! (default 1 Pa per count), and a tap's peak in counts is the driver-read pressure's peak
//! minus its mean at rest. Raw 24-bit barometer codes cannot be meant: at ~140 codes per Pa,
//! 263 codes would be 2 Pa, within the Low Noise mode's 0.8 Pa rms noise, not a clear signal.

pub mod config;
pub mod dataset;
pub mod force;
pub mod grid;
mod model;
mod other;
pub mod pattern;
pub mod tap;
mod window;

pub use config::{ImuPadConfig, TapSpec, TapTiming};
pub use grid::TapPosition;
pub use model::{IMU_SETTINGS, ImuPad};
pub use other::{CHIP_SHIFT_MAX_ROWS, CHIP_SHIFT_MIN_ROWS, MOTION_SPREAD};
pub use window::{TapWindow, WINDOW_SAMPLES, WINDOW_SIGNALS, pressure_peak_pa};
