//! The barometric fingertip of seed 000: three MS5611 under a silicone pad.
//!
//! - [`geometry`]: `aot-locate`'s 4 × 6 cells, eq. 4 labels and 3 × 3 Arrival-of-Time areas,
//!   placed on the skin in millimetres;
//! - [`contact`]: which cells are pressed, how hard, when;
//! - [`law`]: contact → each sensor's steady rise and arrival delay (calibrated to Tables 1–2);
//! - [`physics`]: true pressures over time (baseline, drift, re-zero, first-order response);
//! - [`model`]: the three chip models read through the real driver, as a scene model;
//! - [`dataset`]: the seeded tap and weight datasets the learned models train on.

pub mod contact;
pub mod dataset;
pub mod geometry;
pub mod law;
mod law_calibrated;
pub mod model;
pub mod physics;
pub mod skin;

pub use contact::{ContactEvent, ContactPatch, KGF_N};
pub use geometry::{Cell, CellSet};
pub use law::LawParams;
pub use model::{Fingertip, FingertipConfig, TapConfig};
pub use physics::FingertipPhysics;
