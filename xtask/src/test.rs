//! `cargo xtask test`: everything CI checks, in the order that fails fastest.

use crate::run::{cargo, step};
use crate::{chromium, consumer, embedded, firmware, fixtures, msrv, package, venv};
use anyhow::Result;
use std::path::Path;

/// Sets up `.venv` and Chromium (the report render test), then runs fmt check, clippy `-D warnings`,
/// the `no_std` builds for the thumb targets ([`embedded::build`]), the fingertip firmware
/// linked for both and run on the host ([`firmware::check`]), the MSRV check ([`msrv::check`]),
/// `cargo package` of every
/// published crate ([`package::run`]) and every README against the packages ([`consumer::run`]),
/// every test with every feature, the instruction-count gate (`bench --check`),
/// the docs with warnings denied, and `fixtures --check` (again with numpy's widest SIMD kernels off).
pub fn run(root: &Path) -> Result<()> {
    let python = venv::ensure(root)?;
    let chromium = chromium::ensure()?;
    step("fmt", cargo(root).args(["fmt", "--all", "--", "--check"]))?;
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
    )?;
    embedded::build(root)?;
    firmware::check(root)?;
    msrv::check(root)?;
    package::run(root)?;
    consumer::run(root, &python)?;
    step(
        "test",
        cargo(root)
            .args(["test", "--workspace", "--all-features"])
            .env("HANDSTACK_PYTHON", &python)
            .env("HANDSTACK_CHROMIUM", &chromium),
    )?;
    crate::bench::instructions(root, "check")?;
    step(
        "doc",
        cargo(root)
            .args(["doc", "--workspace", "--no-deps", "--all-features"])
            .env("RUSTDOCFLAGS", "-D warnings"),
    )?;
    println!("==> fixtures --check");
    fixtures::run(root, fixtures::Mode::Check)?;
    println!("==> fixtures --check, numpy's widest SIMD kernels off");
    fixtures::check_with_numpy_narrowed(root)
}
