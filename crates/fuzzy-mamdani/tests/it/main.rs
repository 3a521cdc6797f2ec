//! fuzzy-mamdani's integration tests, one binary: MATLAB's and scikit-fuzzy's golden values, the
//! scikit-fuzzy / pyfuzzylite reference rows, fuzzylite's own examples, the grasp preset, and properties over any input.
//! (`tests/zero_alloc.rs` is apart: it installs a counting global allocator.)

// Also included by the zero-allocation test and the benchmarks, so it stays in `tests/common/`.
#[path = "../common/mod.rs"]
mod common;
mod fuzzylite_examples;
mod golden;
mod preset;
mod properties;
mod reference_fixtures;
