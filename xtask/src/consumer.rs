//! The consumer test: a scratch crate outside the workspace (`target/consumer/`) that depends
//! only on the `.crate` files `cargo package` wrote, unpacked afresh. It builds every published
//! crate's library and binaries from those files (cargo's package verify, for all of them in one
//! build) and runs every published crate's README (product crates and simulators) as its own
//! doctests — what a user who added the crates from crates.io would run. Third-party versions
//! come from the workspace's `Cargo.lock`, copied in.

use crate::package::published_crates;
use crate::run::{cargo, step, workspace_test_profile};
use anyhow::{Context, Result, bail};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

/// The features each README's examples use beyond the defaults (the chip models and simulators
/// stand in for hardware), and the crates a README's example uses besides its own.
const README_NEEDS: [(&str, &[&str]); 2] = [("baro-drivers", &["sim"]), ("imu-icm20789", &["sim"])];

/// Crates the README examples use that are not ours: a driver user has embedded-hal.
const EXTRA_DEPENDENCIES: [(&str, &str); 1] = [("embedded-hal", "1.0.0")];

/// Third-party crates the consumer builds with fewer features than the workspace's test build
/// turns on (its dev-dependencies and unpublished crates add them), with those features: asked
/// for here too, they hash as the test build's do, so that neither they nor what is built on
/// them (`serde_core` and `rand` are under nearly everything) is compiled twice. Found by
/// comparing `cargo tree -e features` of the two builds; a crate missing here costs build time
/// only.
const TEST_BUILD_FEATURES: [(&str, &str, &[&str]); 14] = [
    ("anyhow", "1", &["default"]),
    ("bytemuck", "1", &["extern_crate_alloc"]),
    ("cast", "0.3", &["default"]),
    ("crc32fast", "1", &["default"]),
    ("embedded-hal-nb", "1", &["default"]),
    ("filetime", "0.2", &["default"]),
    ("getrandom", "0.4", &["sys_rng"]),
    ("linux-embedded-hal", "0.5", &["spi", "spidev"]),
    ("matrixmultiply", "0.3", &["cgemm"]),
    ("rand", "0.10", &["sys_rng"]),
    ("regex-automata", "0.4", &["meta", "nfa-pikevm"]),
    ("regex-syntax", "0.8", &["default"]),
    ("serde_core", "1", &["default"]),
    ("simd-adler32", "0.3", &["default", "const-generics"]),
];

/// One packaged crate: its name, version and the directory its `.crate` was unpacked to.
struct Packaged {
    name: String,
    version: String,
    dir: PathBuf,
}

/// Builds the consumer crate over the packages in `target/package/` and runs its doctests
/// (every README example) with `python` as the venv the arm's examples load ur_rtde from.
pub fn run(root: &Path, python: &Path) -> Result<()> {
    let consumer = root.join("target/consumer");
    if consumer.exists() {
        std::fs::remove_dir_all(&consumer).context("clear target/consumer")?;
    }
    let unpacked = consumer.join("crates");
    std::fs::create_dir_all(consumer.join("src")).context("create target/consumer")?;
    std::fs::create_dir_all(&unpacked).context("create target/consumer/crates")?;
    let mut packages = Vec::new();
    for name in published_crates(root)? {
        packages.push(unpack(root, &name, &unpacked)?);
    }
    std::fs::write(consumer.join("Cargo.toml"), manifest(&packages)?)?;
    std::fs::write(consumer.join("src/lib.rs"), readmes(&packages)?)?;
    std::fs::copy(root.join("Cargo.lock"), consumer.join("Cargo.lock"))
        .context("copy Cargo.lock")?;
    let mut build = consumer_cargo(root, &consumer, &packages, &["build", "--lib", "--bins"])?;
    for p in &packages {
        build.args(["-p", &p.name]);
    }
    step(
        "consumer build: every package's library and binaries from its packaged files",
        &mut build,
    )?;
    let mut test = consumer_cargo(root, &consumer, &packages, &["test", "--doc"])?;
    test.env("HANDSTACK_PYTHON", python);
    step(
        "consumer test: every README against the packaged crates",
        &mut test,
    )
}

/// `cargo ARGS` (a subcommand and its options) for the consumer crate at `consumer`: the workspace's test profile, so that
/// third-party crates are the test build's own (same settings, same `target/`), with the
/// packaged crates themselves unoptimised — they are built here only to be compiled and to run
/// the READMEs' short examples, and their code differs from the workspace's anyway.
fn consumer_cargo(
    root: &Path,
    consumer: &Path,
    packages: &[Packaged],
    args: &[&str],
) -> Result<Command> {
    let mut cmd = cargo(root);
    workspace_test_profile(&mut cmd, root)?;
    for p in packages {
        cmd.arg("--config")
            .arg(format!("profile.dev.package.\"{}\".opt-level=0", p.name));
    }
    cmd.args(args)
        .arg("--manifest-path")
        .arg(consumer.join("Cargo.toml"))
        .env("CARGO_TARGET_DIR", root.join("target"));
    Ok(cmd)
}

/// Unpacks `target/package/NAME-VERSION.crate` (the newest of NAME's) into `into`.
fn unpack(root: &Path, name: &str, into: &Path) -> Result<Packaged> {
    let dir = root.join("target/package");
    let prefix = format!("{name}-");
    let mut found = None;
    for entry in std::fs::read_dir(&dir).context("target/package: run `cargo package` first")? {
        let file = entry?.file_name().to_string_lossy().into_owned();
        let version = file
            .strip_prefix(&prefix)
            .and_then(|v| v.strip_suffix(".crate"))
            .filter(|v| v.starts_with(|c: char| c.is_ascii_digit()));
        if let Some(v) = version {
            found = Some(v.to_owned());
        }
    }
    let Some(version) = found else {
        bail!("no {name}-*.crate in {}", dir.display());
    };
    // `-m`: the files get the time of unpacking, not the package's fixed 2006 stamp, which
    // would leave a previous consumer build's fingerprints looking fresh.
    let status = Command::new("tar")
        .arg("-xzmf")
        .arg(dir.join(format!("{name}-{version}.crate")))
        .arg("-C")
        .arg(into)
        .status()
        .context("tar is needed to unpack the .crate files")?;
    if !status.success() {
        bail!("could not unpack {name}-{version}.crate ({status})");
    }
    Ok(Packaged {
        dir: into.join(format!("{name}-{version}")),
        name: name.to_owned(),
        version,
    })
}

/// The consumer's manifest: each package at its exact version, patched to the unpacked files.
fn manifest(packages: &[Packaged]) -> Result<String> {
    let mut deps = String::new();
    let mut patch = String::new();
    for p in packages {
        let features = README_NEEDS
            .iter()
            .find(|(n, _)| *n == p.name)
            .map_or(&[][..], |(_, f)| *f);
        writeln!(
            deps,
            "{} = {{ version = \"={}\", features = {features:?} }}",
            p.name, p.version
        )?;
        writeln!(patch, "{} = {{ path = {:?} }}", p.name, path_str(&p.dir)?)?;
    }
    for (name, version) in EXTRA_DEPENDENCIES {
        writeln!(deps, "{name} = \"{version}\"")?;
    }
    for (name, version, features) in TEST_BUILD_FEATURES {
        // `default` as `cargo tree` shows it: the default features asked for (declared or not).
        let default = features.contains(&"default");
        let features: Vec<&str> = features
            .iter()
            .copied()
            .filter(|f| *f != "default")
            .collect();
        writeln!(
            deps,
            "{name} = {{ version = \"{version}\", default-features = {default}, features = {features:?} }}"
        )?;
    }
    Ok(format!(
        "[package]\nname = \"handstack-consumer\"\nversion = \"0.0.0\"\nedition = \"2024\"\n\
         publish = false\n\n[dependencies]\n{deps}\n[patch.crates-io]\n{patch}\n[workspace]\n"
    ))
}

/// The consumer's library: one empty module per package, documented by its README, so that
/// `cargo test --doc` runs every README example against the packages.
fn readmes(packages: &[Packaged]) -> Result<String> {
    let mut lib = String::from("//! Every handstack README, run as doctests.\n\n");
    for p in packages {
        let readme = p.dir.join("README.md");
        if !readme.is_file() {
            bail!("{}: the package holds no README.md", p.name);
        }
        writeln!(
            lib,
            "#[doc = include_str!({:?})]\npub mod {} {{}}\n",
            path_str(&readme)?,
            p.name.replace('-', "_")
        )?;
    }
    Ok(lib)
}

fn path_str(path: &Path) -> Result<&str> {
    path.to_str()
        .with_context(|| format!("{}: not UTF-8", path.display()))
}
