//! `cargo xtask test`: everything CI checks, in the order that fails fastest.

use crate::architecture::workspace_packages;
use crate::lane::Lane;
use crate::run::{PAPERS, cargo, step};
use crate::test_binaries::{self, Executable, find};
use crate::{bench, chromium, consumer, embedded, firmware, fixtures, msrv, package, venv};
use anyhow::Result;
use std::path::{Path, PathBuf};

/// fmt check, then the main steps: `.venv` and Chromium (the report render test), clippy `-D
/// warnings`, `cargo package` of every published crate ([`package::run`]) and the consumer
/// build and test of every README against the packages ([`consumer::run`]), the test build
/// with every feature; then the doctests and every test harness ([`test_binaries::run`])
/// alone; then the instruction-count gate (`bench --check`, on the test build's binary) and
/// the docs with warnings denied.
///
/// Beside them, in [`Lane`]s (idle priority: they take only the cores the main steps leave):
/// until the test build is done, the `no_std` builds for the Cortex-M3 target
/// ([`embedded::build`]), the fingertip firmware linked for its three boards and run on the
/// host ([`firmware::check`]) and the MSRV check ([`msrv::check`]), each in its own build
/// directory; after the tests, `fixtures --check` (again with numpy's widest SIMD kernels
/// off). Nothing runs beside the tests: their simulated devices and peer processes answer in
/// real time, and load beside them (even at idle priority) changes their timing.
pub fn run(root: &Path) -> Result<()> {
    step("fmt", cargo(root).args(["fmt", "--all", "--", "--check"]))?;
    let (env, executables) = std::thread::scope(|scope| {
        let builds = Lane::start(scope, root, "builds", || {
            embedded::build(root)?;
            firmware::check(root)?;
            msrv::check(root)
        })?;
        let main = build_steps(root);
        let lane = builds.finish();
        main.and_then(|built| lane.map(|()| built))
    })?;
    let env: Vec<(&str, &Path)> = env.iter().map(|(k, v)| (*k, v.as_path())).collect();
    all([
        test_binaries::doctests(root, &env),
        test_binaries::run(&executables, &env),
    ])?;
    let papers = find(&executables, PAPERS.package, PAPERS.name, false)?
        .path
        .clone();
    let instructions = find(
        &executables,
        bench::INSTRUCTIONS.0,
        bench::INSTRUCTIONS.1,
        true,
    )?;
    std::thread::scope(|scope| {
        let generated = Lane::start(scope, root, "generated", move || {
            fixtures::check_with(root, papers)?;
            println!("==> fixtures --check, numpy's widest SIMD kernels off");
            fixtures::check_with_numpy_narrowed(root)
        })?;
        let main = bench::instructions_of(instructions, "check").and_then(|()| doc(root));
        all([main, generated.finish()])
    })
}

/// Ok if every result is; else one error naming each failure.
fn all<const N: usize>(results: [Result<()>; N]) -> Result<()> {
    let failures: Vec<String> = results
        .into_iter()
        .filter_map(|r| r.err().map(|e| format!("{e:#}")))
        .collect();
    match failures.as_slice() {
        [] => Ok(()),
        [one] => Err(anyhow::anyhow!("{one}")),
        many => Err(anyhow::anyhow!(
            "{} steps failed:\n  {}",
            many.len(),
            many.join("\n  ")
        )),
    }
}

/// The variables the tests read (the venv's Python, Chromium, the fingertip on a pty) and the
/// test build's executables.
type Built = ([(&'static str, PathBuf); 3], Vec<Executable>);

/// The main steps after fmt, up to the test build.
fn build_steps(root: &Path) -> Result<Built> {
    let python = venv::ensure(root)?;
    let chromium = chromium::ensure()?;
    clippy(root)?;
    package::run(root)?;
    consumer::run(root, &python)?;
    let env = [
        ("HANDSTACK_PYTHON", python),
        ("HANDSTACK_CHROMIUM", chromium),
        // Built by the builds lane's firmware check, which ends before the tests start.
        ("HANDSTACK_FINGERTIP_MCU", root.join(firmware::HOST_UART)),
    ];
    let borrowed: Vec<(&str, &Path)> = env.iter().map(|(k, v)| (*k, v.as_path())).collect();
    let executables = test_binaries::build(root, &borrowed)?;
    Ok((env, executables))
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
/// among them). A binary named as its package's library is left out, as plain `cargo doc`
/// leaves it out: both would be written to the same `target/doc/NAME/`.
fn doc(root: &Path) -> Result<()> {
    let mut cmd = cargo(root);
    cmd.args(["doc", "--workspace", "--no-deps", "--all-features"])
        .args(["--lib", "--examples"])
        .env("RUSTDOCFLAGS", "-D warnings");
    for package in workspace_packages(root)? {
        let lib = package.name.replace('-', "_");
        for bin in package.bins.iter().filter(|b| b.replace('-', "_") != lib) {
            cmd.args(["--bin", bin]);
        }
    }
    step("doc", &mut cmd)
}
