//! `cargo xtask test`: everything CI checks, in the order that fails fastest.

use crate::lane::Lane;
use crate::run::{cargo, step, test_build};
use crate::{chromium, consumer, embedded, firmware, fixtures, msrv, package, venv};
use anyhow::Result;
use std::path::Path;

/// Sets up `.venv` and Chromium (the report render test), then runs fmt check, clippy `-D warnings`,
/// `cargo package` of every published crate ([`package::run`]) and the consumer build and test of
/// every README against the packages ([`consumer::run`]), every test with every feature, the
/// instruction-count gate (`bench --check`), the docs with warnings denied, and `fixtures
/// --check` (again with numpy's widest SIMD kernels off).
///
/// Beside clippy, the packages and the consumer test, in a [`Lane`] (their own build
/// directories): the `no_std` builds for the thumb targets ([`embedded::build`]), the fingertip
/// firmware linked for both and run on the host ([`firmware::check`]) and the MSRV check
/// ([`msrv::check`]). The tests run alone; then the fixtures (Python and the tested `papers`
/// binary, no build) run in a lane beside the instruction-count gate and the docs.
pub fn run(root: &Path) -> Result<()> {
    let python = venv::ensure(root)?;
    let chromium = chromium::ensure()?;
    step("fmt", cargo(root).args(["fmt", "--all", "--", "--check"]))?;
    std::thread::scope(|scope| {
        let builds = Lane::start(scope, root, "builds", || {
            embedded::build(root)?;
            firmware::check(root)?;
            msrv::check(root)
        })?;
        let main = clippy(root)
            .and_then(|()| package::run(root))
            .and_then(|()| consumer::run(root, &python));
        let lane = builds.finish();
        main.and(lane)
    })?;
    let env = [
        ("HANDSTACK_PYTHON", python.as_path()),
        ("HANDSTACK_CHROMIUM", chromium.as_path()),
    ];
    // Alone: the tests' simulated devices answer in real time, and a loaded machine made a
    // servo bus miss its reply timeout.
    step("test", &mut test_build(root, &env))?;
    let papers = fixtures::tested_papers(root, &env)?;
    std::thread::scope(|scope| {
        let fixtures = Lane::start(scope, root, "generated", || {
            fixtures::check_with(root, papers)?;
            println!("==> fixtures --check, numpy's widest SIMD kernels off");
            fixtures::check_with_numpy_narrowed(root)
        })?;
        let main = crate::bench::instructions(root, "check").and_then(|()| doc(root));
        main.and(fixtures.finish())
    })
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

/// The docs of every workspace crate, warnings denied.
fn doc(root: &Path) -> Result<()> {
    step(
        "doc",
        cargo(root)
            .args(["doc", "--workspace", "--no-deps", "--all-features"])
            .env("RUSTDOCFLAGS", "-D warnings"),
    )
}
