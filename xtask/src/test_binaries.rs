//! The test build and its test binaries: `cargo test --workspace --all-features` split into its
//! build (`--no-run`, whose JSON messages list every executable) and the runs, which xtask
//! makes itself, one binary after another in cargo's order, each in its package's directory
//! with the variables cargo gives it. So every binary runs even after one fails (the step
//! names each that failed), and the steps after the tests take the executables they run (the
//! `papers` binary, the instruction counter) from the same list, without another cargo call.

use crate::run::{cargo, step};
use anyhow::{Context, Result, bail};
use serde_json::Value;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::Instant;

/// An executable the test build made.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Executable {
    /// Its package's name.
    pub package: String,
    /// The target's name (`it`, the crate name of a library's unit tests, a `[[bin]]` name).
    pub target: String,
    /// The target's first kind (`lib`, `bin`, `test`, `bench`, `example`).
    pub kind: String,
    /// A test harness (`cargo test` runs it), not a plain binary that tests start.
    pub test: bool,
    /// The target's root source file, relative to its package's directory where it lies
    /// inside it.
    pub src: PathBuf,
    /// The executable.
    pub path: PathBuf,
    /// Its package's `Cargo.toml`.
    pub manifest: PathBuf,
}

impl Executable {
    /// A command that runs the executable as `cargo test` does: in its package's directory,
    /// with `CARGO_MANIFEST_DIR`, `CARGO_MANIFEST_PATH` and `CARGO_PKG_NAME` set.
    pub fn command(&self) -> Command {
        let dir = self.manifest.parent().unwrap_or(Path::new("."));
        let mut cmd = Command::new(&self.path);
        cmd.current_dir(dir)
            .env("CARGO_MANIFEST_DIR", dir)
            .env("CARGO_MANIFEST_PATH", &self.manifest)
            .env("CARGO_PKG_NAME", &self.package);
        cmd
    }
}

/// The test build's `cargo test --workspace --all-features` command, with `env` (what the test
/// step sets: build scripts may read it, so it is part of what the build is).
pub fn test_build(root: &Path, env: &[(&str, &Path)]) -> Command {
    let mut cmd = cargo(root);
    cmd.args(["test", "--workspace", "--all-features"]);
    for (key, value) in env {
        cmd.env(key, value);
    }
    cmd
}

/// Test binaries whose tests mostly wait on simulated devices answering in real time (taps,
/// grasps, weights placed by the test as a user would), run with more test threads than the
/// machine's cores: measured on 2 cores, paper-scenes' 68 tests take 415 s with 2 threads and
/// 218 s with 4, the load average staying under 1.
const WAITING: [(&str, &str); 1] = [("paper-scenes", "4")];

/// The examples that tests run (`target/<profile>/examples/NAME`), by package. `cargo test`
/// builds every example by default; the test build builds these only: clippy's and the docs'
/// builds check that every example compiles, and the others took 40 CPU-s of the test build
/// to compile and link at its optimisation. (`cargo test --example NAME` would build one as a
/// test harness, not as the program a test starts: they are built with `cargo build
/// --profile test`.) A test that starts an example missing here fails to find it.
const EXAMPLES_TESTS_RUN: [&str; 3] = [
    "grasp_on_port", // dxl-sim
    "cell_latency",  // hand-zenoh
    "bench_rig",     // handstack
];

/// Builds every test target (the step `test build`; cargo's progress and diagnostics on the
/// terminal) and lists the executables it made, in cargo's order: the targets `cargo test`
/// runs (`--tests`) and the binaries that integration tests start; then the examples that
/// tests run.
pub fn build(root: &Path, env: &[(&str, &Path)]) -> Result<Vec<Executable>> {
    let executables = build_tests(root, env)?;
    let mut examples = cargo(root);
    examples.args([
        "build",
        "--profile",
        "test",
        "--workspace",
        "--all-features",
    ]);
    for example in EXAMPLES_TESTS_RUN {
        examples.args(["--example", example]);
    }
    for (key, value) in env {
        examples.env(key, value);
    }
    step("the examples tests run", &mut examples)?;
    Ok(executables)
}

/// The test build proper: `cargo test --no-run --tests`, its executables from its messages.
fn build_tests(root: &Path, env: &[(&str, &Path)]) -> Result<Vec<Executable>> {
    println!("==> test build");
    let start = Instant::now();
    let mut child = test_build(root, env)
        .args([
            "--tests",
            "--no-run",
            "--message-format=json-render-diagnostics",
        ])
        .stdout(Stdio::piped())
        .spawn()
        .context("could not start the test build")?;
    let stdout = child.stdout.take().context("the test build's output")?;
    let mut executables = Vec::new();
    for line in BufReader::new(stdout).lines() {
        let line = line.context("reading the test build's messages")?;
        match serde_json::from_str::<Value>(&line) {
            Ok(message) => executables.extend(executable(&message)),
            // Build scripts may print to cargo's stdout: not ours to parse.
            Err(_) => println!("{line}"),
        }
    }
    let status = child.wait().context("the test build")?;
    let secs = start.elapsed().as_secs_f64();
    if !status.success() {
        bail!("test build failed after {secs:.1} s ({status})");
    }
    println!("    test build: ok in {secs:.1} s");
    Ok(executables)
}

/// The executable a `compiler-artifact` message names, if it names one.
fn executable(message: &Value) -> Option<Executable> {
    if message["reason"] != "compiler-artifact" {
        return None;
    }
    let path = PathBuf::from(message["executable"].as_str()?);
    let manifest = PathBuf::from(message["manifest_path"].as_str()?);
    let src = PathBuf::from(message["target"]["src_path"].as_str()?);
    let src = manifest
        .parent()
        .and_then(|dir| src.strip_prefix(dir).ok())
        .map_or(src.clone(), Path::to_path_buf);
    Some(Executable {
        package: package_name(message["package_id"].as_str()?)?.to_owned(),
        target: message["target"]["name"].as_str()?.to_owned(),
        kind: message["target"]["kind"][0].as_str()?.to_owned(),
        test: message["profile"]["test"].as_bool()?,
        src,
        path,
        manifest,
    })
}

/// The package name in a cargo package ID: `path+file:///…/NAME#VERSION` or
/// `path+file:///…/DIR#NAME@VERSION`.
fn package_name(id: &str) -> Option<&str> {
    let (url, fragment) = id.rsplit_once('#')?;
    match fragment.split_once('@') {
        Some((name, _)) => Some(name),
        None => url.rsplit('/').next(),
    }
}

/// The executable `name` of `package` among `executables`: its test harness (`test`) or, for
/// a `[[bin]]`, the binary itself (not its unit tests, also a `bin` target).
pub fn find<'a>(
    executables: &'a [Executable],
    package: &str,
    name: &str,
    test: bool,
) -> Result<&'a Executable> {
    let what = if test { "test" } else { "binary" };
    executables
        .iter()
        .find(|e| {
            e.package == package && e.target == name && e.test == test && (test || e.kind == "bin")
        })
        .with_context(|| format!("the test build made no {what} `{name}` of {package}"))
}

/// Runs the doctests (`cargo test --doc`, which holds the build directory's lock while they
/// run).
pub fn doctests(root: &Path, env: &[(&str, &Path)]) -> Result<()> {
    step(
        "doctests",
        test_build(root, env).args(["--doc", "--no-fail-fast"]),
    )
}

/// Runs every test harness among `executables` with `env`, one after
/// another (as `cargo test` does: the tests' simulated devices answer in real time, so the
/// binaries do not share the machine with one another). All of them run; the step fails at
/// the end, naming each that failed. No cargo command: the build directory stays free for
/// others.
pub fn run(executables: &[Executable], env: &[(&str, &Path)]) -> Result<()> {
    println!("==> test run");
    let start = Instant::now();
    let mut failed = Vec::new();
    for exe in executables.iter().filter(|e| e.test) {
        println!(
            "     Running {} {} ({})",
            exe.package,
            exe.src.display(),
            exe.path.display()
        );
        let mut cmd = exe.command();
        for (key, value) in env {
            cmd.env(key, value);
        }
        if let Some(&(_, threads)) = WAITING.iter().find(|(p, _)| *p == exe.package) {
            cmd.args(["--test-threads", threads]);
        }
        let status = cmd
            .status()
            .with_context(|| format!("could not start {}", exe.path.display()))?;
        if !status.success() {
            failed.push(format!("{} {} ({status})", exe.package, exe.src.display()));
        }
    }
    let secs = start.elapsed().as_secs_f64();
    if !failed.is_empty() {
        bail!(
            "test run failed after {secs:.1} s: {} of them failed:\n  {}",
            failed.len(),
            failed.join("\n  ")
        );
    }
    println!("    test run: ok in {secs:.1} s");
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn package_ids_name_their_package() {
        assert_eq!(
            package_name("path+file:///w/crates/hand-sim#0.1.0"),
            Some("hand-sim")
        );
        assert_eq!(
            package_name("path+file:///w/benches#handstack-benches@0.1.0"),
            Some("handstack-benches")
        );
        assert_eq!(
            package_name("registry+https://x/index#serde@1.0.0"),
            Some("serde")
        );
        assert_eq!(package_name("no fragment"), None);
    }

    #[test]
    fn an_artifact_message_names_its_executable() {
        let message: Value = serde_json::from_str(
            r#"{"reason":"compiler-artifact",
                "package_id":"path+file:///w/crates/ur-sim#0.1.0",
                "manifest_path":"/w/crates/ur-sim/Cargo.toml",
                "target":{"kind":["test"],"name":"it","src_path":"/w/crates/ur-sim/tests/it/main.rs"},
                "profile":{"test":true},
                "executable":"/w/target/debug/deps/it-0123"}"#,
        )
        .unwrap();
        let exe = executable(&message).expect("an executable");
        assert_eq!(exe.package, "ur-sim");
        assert_eq!(exe.target, "it");
        assert_eq!(exe.kind, "test");
        assert!(exe.test);
        assert_eq!(exe.src, Path::new("tests/it/main.rs"));
        assert_eq!(exe.path, Path::new("/w/target/debug/deps/it-0123"));
        let executables = [exe];
        assert!(find(&executables, "ur-sim", "it", true).is_ok());
        assert!(find(&executables, "ur-sim", "it", false).is_err());
    }

    #[test]
    fn a_library_without_an_executable_is_not_listed() {
        let message: Value = serde_json::from_str(
            r#"{"reason":"compiler-artifact","package_id":"path+file:///w/crates/a#0.1.0",
                "manifest_path":"/w/crates/a/Cargo.toml",
                "target":{"kind":["lib"],"name":"a","src_path":"/w/crates/a/src/lib.rs"},
                "profile":{"test":false},"executable":null}"#,
        )
        .unwrap();
        assert_eq!(executable(&message), None);
        let other: Value =
            serde_json::from_str(r#"{"reason":"build-finished","success":true}"#).unwrap();
        assert_eq!(executable(&other), None);
    }
}
