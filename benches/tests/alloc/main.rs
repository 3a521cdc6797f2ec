//! Heap blocks counted by dhat's global allocator, one binary without the libtest harness: its
//! main thread allocates (the running-test table, the timeout queue) while a test thread runs,
//! and dhat counts every thread's blocks. Each module's check runs in turn.

mod grasp_loop_log;
mod zero_alloc;

#[global_allocator]
static ALLOC: dhat::Alloc = dhat::Alloc;

fn main() {
    // A child of zero_alloc's peak-heap report (this binary, run once per scene): that scene only.
    if std::env::var_os("HANDSTACK_PEAK_SCENE").is_some() {
        zero_alloc::run();
        return;
    }
    zero_alloc::run();
    grasp_loop_log::run();
}
