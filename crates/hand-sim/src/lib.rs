//! The physics each tactile-hand scene needs, calibrated to the papers, and seeded datasets.
//!
//! One module per physical model, each usable alone:
//!
//! - [`fingertip`]: the barometric fingertip of seed 000 — a silicone pad over three MS5611 in
//!   an inverted triangle, a 4 × 6 cell grid (3 × 3 for Arrival-of-Time), pressure rises that
//!   decay with distance, saturate with force and arrive later the farther the sensor;
//!   read through three MS5611 chip models by the real driver.
//! - [`grasp`]: the Table 5 objects between two MX-28 fingers (position control under a torque
//!   limit, load / current, overload shutdown, slip, crushing, the fingertip contact patch).
//! - [`imu_pad`]: the ICM-20789 pad of seed 002 — taps on a 3 × 24 grid under Ecoflex, force by
//!   the Yeoh law, pressure by the inverse of eq. 1, IMU patterns of Fig. 5, read at 30 Hz.
//! - [`underactuated`]: the four-finger underactuated hand of seed 001 — stepper, seesaw
//!   differentials, FSR and distal potentiometer per finger through a 10-bit ADC, objects of
//!   graded softness, and the seeded softness grasps.
//!
//! A [`Scene`](scene::Scene) builds only the models its [`SceneConfig`](scene::SceneConfig)
//! names, and steps only those. Every random source is seeded from the scene
//! ([`seed::stream`]). Sensor readings leave the simulator only through the chip models of
//! `baro-drivers` and `imu-icm20789`, decoded by the real drivers, so a dataset holds exactly
//! what a driver would have read.
//!
//! The datasets are written in one CSV dialect, each file through one serde record
//! ([`records`]) that paper-experiments' readers deserialize too.
//!
//! What is and is not modelled, and how each model compares with the papers' figures, is in
//! `docs/sim-calibration.md`.

pub mod error;
pub mod fingertip;
pub mod grasp;
pub mod imu_pad;
pub mod records;
pub mod scene;
pub mod seed;
pub mod underactuated;

pub use error::SimError;
