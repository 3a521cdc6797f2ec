//! The barometric fingertip of seed 000: three MS5611 under a silicone pad.

pub mod contact;
pub mod geometry;

pub use contact::{ContactEvent, ContactPatch, KGF_N};
pub use geometry::{Cell, CellSet};
