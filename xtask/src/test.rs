//! `cargo xtask test`: everything CI checks, in the order that fails fastest.

use crate::lane::Lane;
use crate::run::{PAPERS, cargo, step};
use crate::test_binaries::{self, find_binary, find_test};
use crate::{bench, chromium, consumer, embedded, firmware, fixtures, msrv, package, venv};
use anyhow::Result;
use std::path::Path;
use std::thread::Scope;

/// fmt check, then the main steps: `.venv` and Chromium (the report render test), clippy `-D
/// warnings`, `cargo package` of every published crate ([`package::run`]) and the consumer
/// build and test of every README against the packages ([`consumer::run`]), the test build and
/// every test with every feature ([`test_binaries`]).
///
/// Beside them, in [`Lane`]s (idle priority: they take only the cores the main steps leave,
/// so the real-time tests run as they would alone): from the start, the `no_std` builds for the
/// thumb targets ([`embedded::build`]), the fingertip firmware linked for both and run on the
/// host ([`firmware::check`]) and the MSRV check ([`msrv::check`]), each in its own build
/// directory; once the test build is done, the instruction-count gate (`bench --check`, on
/// the test build's binary), `fixtures --check` (again with numpy's widest SIMD kernels off)
/// and the docs with warnings denied.
pub fn run(root: &Path) -> Result<()> {
    step("fmt", cargo(root).args(["fmt", "--all", "--", "--check"]))?;
    std::thread::scope(|scope| {
        let builds = Lane::start(scope, root, "builds", || {
            embedded::build(root)?;
            firmware::check(root)?;
            msrv::check(root)
        })?;
        let main = main_steps(root, scope);
        let lane = builds.finish();
        main.and(lane)
    })
}

/// The steps after fmt, the `generated` lane started beside the test run.
fn main_steps<'scope>(root: &'scope Path, scope: &'scope Scope<'scope, '_>) -> Result<()> {
    let python = venv::ensure(root)?;
    let chromium = chromium::ensure()?;
    clippy(root)?;
    package::run(root)?;
    consumer::run(root, &python)?;
    let env = [
        ("HANDSTACK_PYTHON", python.as_path()),
        ("HANDSTACK_CHROMIUM", chromium.as_path()),
    ];
    let executables = test_binaries::build(root, &env)?;
    let papers = find_binary(&executables, PAPERS.package, PAPERS.name)?
        .path
        .clone();
    let instructions =
        find_test(&executables, bench::INSTRUCTIONS.0, bench::INSTRUCTIONS.1)?.clone();
    let generated = Lane::start(scope, root, "generated", move || {
        bench::instructions_of(&instructions, "check")?;
        fixtures::check_with(root, papers)?;
        println!("==> fixtures --check, numpy's widest SIMD kernels off");
        fixtures::check_with_numpy_narrowed(root)?;
        doc(root)
    })?;
    let tests = test_binaries::run(root, &executables, &env);
    tests.and(generated.finish())
}

/// clippy on every target and feature, warnings denied.
fn clippy(root: &Path) -> Result<()> {
    step(
        "clippy",
        cargo(root).args([
            "clippy",
            "--workspace",
            "--all-targets",
            "--all-features",
            "--",
            "-D",
            "warnings",
        ]),
    )
}

/// The docs of every workspace crate, warnings denied: libraries, binaries and examples. With
/// the examples, whose dev-dependencies turn on the features clippy's build has, the docs
/// reuse clippy's checked third-party crates (without them, 19 were checked again, Zenoh's
/// among them).
fn doc(root: &Path) -> Result<()> {
    step(
        "doc",
        cargo(root)
            .args(["doc", "--workspace", "--no-deps", "--all-features"])
            .args(["--lib", "--bins", "--examples"])
            .env("RUSTDOCFLAGS", "-D warnings"),
    )
}
