//! Running the steps of a workflow: one announced, timed child process at a time.

use anyhow::{Context, Result, bail};
use std::ffi::OsStr;
use std::io::Write;
use std::path::Path;
use std::process::{Command, ExitStatus};
use std::time::Instant;

/// `cargo` as the running toolchain names it, started in the workspace root.
pub fn cargo(root: &Path) -> Command {
    let mut cmd = Command::new(std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into()));
    cmd.current_dir(root);
    cmd
}

/// Gives `cmd`, a cargo build of a manifest outside the workspace (a packaged crate being
/// verified, the consumer crate), the workspace's `[profile.dev]` and `[profile.test]` settings
/// (with their per-package ones) for its `dev` profile, read from the root `Cargo.toml`: such a
/// manifest does not read the workspace's profiles. With the same settings its third-party
/// crates hash as the test build's do and land in the same `target/debug`, so `cargo xtask
/// test` compiles each of them once, not once per profile; with cargo's defaults (full debug
/// info, incremental) those builds also wrote 3.8 GB and once filled CI's disk.
pub fn workspace_test_profile(cmd: &mut Command, root: &Path) -> Result<()> {
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).context("Cargo.toml")?;
    for setting in test_profile_as_dev(&manifest) {
        cmd.arg("--config").arg(setting);
    }
    cmd.env("CARGO_INCREMENTAL", "0");
    Ok(())
}

/// `[profile.dev]` and then `[profile.test]` settings of `manifest` (each with its
/// `.package.NAME` sections), as `profile.dev….KEY=VALUE` for `cargo --config`: what the test
/// profile is, said of `dev`.
fn test_profile_as_dev(manifest: &str) -> Vec<String> {
    let mut settings = Vec::new();
    for profile in ["dev", "test"] {
        let mut section: Option<String> = None;
        for line in manifest.lines().map(str::trim) {
            if line.starts_with('[') {
                let name = line.trim_matches(|c| c == '[' || c == ']');
                section = name
                    .strip_prefix(&format!("profile.{profile}"))
                    .filter(|rest| rest.is_empty() || rest.starts_with(".package."))
                    .map(str::to_owned);
                continue;
            }
            let (Some(suffix), Some((key, value))) = (&section, line.split_once('=')) else {
                continue;
            };
            if line.starts_with('#') {
                continue;
            }
            let key = key.trim();
            let value = value.split(" #").next().unwrap_or("").trim();
            let key = if suffix.is_empty() {
                key.to_owned()
            } else {
                // Package names with `-` need quoting in a dotted key.
                let package = &suffix[".package.".len()..];
                format!("package.\"{}\".{key}", package.trim_matches('"'))
            };
            settings.push(format!("profile.dev.{key}={value}"));
        }
    }
    settings
}

/// Runs `cmd` as the step `name`, printing its name and wall time; fails if it fails. In a
/// [`lane`](crate::lane), the name says so and the child's output goes to the lane's log.
pub fn step(name: &str, cmd: &mut Command) -> Result<()> {
    let name = match crate::lane::current()? {
        Some((lane, log)) => {
            cmd.stdout(log.try_clone()?).stderr(log);
            format!("{lane}: {name}")
        }
        None => name.to_owned(),
    };
    timed(&name, cmd, |cmd| cmd.status().map(|status| (status, ())))
}

/// [`step`] for a command whose standard output the caller reads: returned, and also written
/// to the lane's log or the terminal.
pub fn step_output(name: &str, cmd: &mut Command) -> Result<String> {
    let (name, mut sink): (String, Box<dyn Write>) = match crate::lane::current()? {
        Some((lane, log)) => {
            cmd.stderr(log.try_clone()?);
            (format!("{lane}: {name}"), Box::new(log))
        }
        None => (name.to_owned(), Box::new(std::io::stdout())),
    };
    timed(&name, cmd, |cmd| {
        let out = cmd.output()?;
        sink.write_all(&out.stdout)?;
        Ok((
            out.status,
            String::from_utf8_lossy(&out.stdout).into_owned(),
        ))
    })
}

/// Announces the step `name`, runs `cmd` through `run` (its exit status and what the caller
/// keeps of it) and prints its wall time; fails if the command does.
fn timed<T>(
    name: &str,
    cmd: &mut Command,
    run: impl FnOnce(&mut Command) -> std::io::Result<(ExitStatus, T)>,
) -> Result<T> {
    println!("==> {name}");
    let start = Instant::now();
    let program = cmd.get_program().to_string_lossy().into_owned();
    let (status, value) = run(cmd).with_context(|| format!("{name}: could not run {program}"))?;
    let secs = start.elapsed().as_secs_f64();
    if !status.success() {
        bail!("{name} failed after {secs:.1} s ({status})");
    }
    println!("    {name}: ok in {secs:.1} s");
    Ok(value)
}

/// The lines `rustup ARGS` prints (what is installed), trimmed; `why` says what needs rustup.
pub fn rustup_lines(args: &[&str], why: &str) -> Result<Vec<String>> {
    let out = Command::new("rustup")
        .args(args)
        .output()
        .with_context(|| format!("rustup is needed for {why}"))?;
    if !out.status.success() {
        bail!(
            "rustup {} failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    Ok(String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| l.trim().to_owned())
        .collect())
}

/// A workspace binary that a workflow runs through `cargo run`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Binary {
    /// The package that holds it.
    pub package: &'static str,
    /// The `[[bin]]` name.
    pub name: &'static str,
    /// Build the package with its default features.
    pub default_features: bool,
}

/// The reproduction's writers: training (`train MODEL`: weights and metrics), a model's plots
/// and docs, the simulated datasets, the speed / accuracy trade. Without the default `arm`
/// feature: they need no Python, so the binary embeds none.
pub const PAPERS: Binary = Binary {
    package: "paper-experiments",
    name: "papers",
    default_features: false,
};

impl Binary {
    /// `cargo run --quiet --profile test -p PACKAGE [--no-default-features] --bin NAME -- ARGS
    /// --root ROOT`, under the optimised `test` profile: the profile the tests build, so nothing
    /// is compiled twice, and numeric code runs several times faster than at `opt-level = 0`.
    pub fn command<S: AsRef<OsStr>>(&self, root: &Path, args: &[S]) -> Command {
        let mut cmd = cargo(root);
        cmd.args(["run", "--quiet", "--profile", "test", "-p", self.package]);
        if !self.default_features {
            cmd.arg("--no-default-features");
        }
        cmd.args(["--bin", self.name, "--"])
            .args(args)
            .arg("--root")
            .arg(root);
        cmd
    }

    /// Runs `self ARGS --root ROOT` ([`Binary::command`]) as the step `name`.
    pub fn run<S: AsRef<OsStr>>(&self, root: &Path, name: &str, args: &[S]) -> Result<()> {
        step(name, &mut self.command(root, args))
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_test_profile_is_said_of_dev() {
        let manifest = "[profile.dev]\ndebug = \"line-tables-only\"\n\n[profile.bench]\ndebug = false\n\n\
                        [profile.test]\n# why\nopt-level = 2 # fast\nincremental = false\n\n\
                        [profile.test.package.zenoh-config]\nopt-level = 0\n";
        assert_eq!(
            super::test_profile_as_dev(manifest),
            [
                "profile.dev.debug=\"line-tables-only\"",
                "profile.dev.opt-level=2",
                "profile.dev.incremental=false",
                "profile.dev.package.\"zenoh-config\".opt-level=0",
            ]
        );
    }

    /// The workspace's own profiles say what the outside builds copy.
    #[test]
    fn the_workspace_sets_a_test_profile() {
        let manifest = std::fs::read_to_string(crate::workspace_root().join("Cargo.toml")).unwrap();
        let settings = super::test_profile_as_dev(&manifest);
        assert!(
            settings.contains(&"profile.dev.opt-level=2".to_owned()),
            "{settings:?}"
        );
        assert!(
            settings.contains(&"profile.dev.incremental=false".to_owned()),
            "{settings:?}"
        );
    }
}
