//! hand-control's integration tests, one binary: the Protocol 2.0 parser under arbitrary
//! bytes. (`tests/goals_alloc.rs` is apart: it installs a counting global allocator. The driver
//! against a simulated bus is tested in `dxl-sim`, which depends on this crate.)

mod parser_fuzz;
