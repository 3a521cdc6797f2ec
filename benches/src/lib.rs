//! Criterion benchmarks that span several handstack crates live in `benches/` of this package.
