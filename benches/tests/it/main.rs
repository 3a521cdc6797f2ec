//! handstack-benches' integration tests, one binary: each scene's cycle checked against its
//! parts. (`tests/alloc/` counts heap blocks under a global allocator, and `tests/instructions.rs`
//! counts instructions under callgrind: each its own binary without the libtest harness.)

mod cycles;
