#![doc = include_str!("../README.md")]
#![no_std]
#![forbid(unsafe_code)]

mod arrival;
mod geometry;
mod label;
mod lag;
mod locator;
mod ranging;
mod score;
mod trilateration;

pub use arrival::{ArrivalDetector, ChannelDetector, DetectorConfig};
pub use geometry::{AREAS, AreaGrid, Geometry, GeometryError, SENSORS};
/// The `hand-traits` types of this crate's API (its locator is a [`ContactLocator`]), so that
/// a user needs no other crate.
pub use hand_traits::{Contact, ContactLocator};
pub use label::{
    AverageArea, CELLS, COLS, Candidates, Cell, CellSet, DECODE_TOLERANCE, LabelError,
    MAX_CANDIDATES, ROWS, Shape, decode_among,
};
pub use locator::{AotLocator, Scorer};
pub use ranging::{Ranging, RangingError, RangingFit};
pub use score::{AotError, ArrivalEvent, Scores, eq3};
