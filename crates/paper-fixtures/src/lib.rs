//! Typed access to the figures the three source papers publish.
//!
//! The numbers live once, in `fixtures/paper/*.csv`, each file opening with `#` lines that cite
//! the seed, table, equation or section it transcribes. Tests and reports read them through this
//! crate instead of retyping them.
//!
//! ```
//! let rows = paper_fixtures::seed000::table1_weight()?;
//! assert_eq!(rows.len(), 13);
//! assert_eq!(rows[2].weight_gf, 100.0);
//! # Ok::<(), paper_fixtures::FixtureError>(())
//! ```
//!
//! The fixture tree is found at `$HANDSTACK_FIXTURES` if set, else at the workspace's
//! `fixtures/`; every loader also has a `*_in(root)` form for a tree elsewhere.

mod constants;
mod error;
mod table;

pub mod seed000;
pub mod seed001;
pub mod seed002;

pub use constants::{Constant, Constants};
pub use error::FixtureError;
pub use table::{Record, Table};

use std::path::PathBuf;

/// The fixture tree: `$HANDSTACK_FIXTURES`, or the workspace's `fixtures/` folder.
pub fn fixtures_dir() -> PathBuf {
    std::env::var_os("HANDSTACK_FIXTURES")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures")))
}
