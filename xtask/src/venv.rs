//! The workspace's Python virtual environment: the real peers (ur_rtde, the ROBOTIS SDK,
//! scikit-fuzzy, pyfuzzylite) that simulators and reference fixtures are checked against.

use crate::run::step;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Every module a test or generator imports, checked once the install is done.
const IMPORTS: &str = "import rtde_control, rtde_receive, dashboard_client, dynamixel_sdk, \
     skfuzzy, fuzzylite, zenoh, rosbags, mcap, mcap_ros2, xxhash, pyfirmata2";

/// A second Zenoh (rmw_zenoh's 1.6.x) for hand-zenoh's interop test, beside the venv's own.
const ZENOH_16: &str = "python/requirements-zenoh-1.6.txt";

/// The venv's python, creating `.venv` and installing `python/requirements.txt` when the venv
/// is missing or was made from other requirements. Uses `$PYTHON`, else `python3`.
pub fn ensure(root: &Path) -> Result<PathBuf> {
    let venv = root.join(".venv");
    let python = python_in(&venv);
    let requirements = root.join("python/requirements.txt");
    let mut wanted = std::fs::read(&requirements)
        .with_context(|| format!("reading {}", requirements.display()))?;
    wanted.extend(std::fs::read(root.join(ZENOH_16)).with_context(|| ZENOH_16.to_owned())?);
    // The stamp is the requirements file the venv was built from: a change re-installs.
    let stamp = venv.join("handstack-requirements.txt");
    if python.exists() && std::fs::read(&stamp).is_ok_and(|s| s == wanted) {
        return Ok(python);
    }
    if !python.exists() {
        let base = std::env::var_os("PYTHON").unwrap_or_else(|| "python3".into());
        step(
            "python venv",
            Command::new(base).arg("-m").arg("venv").arg(&venv),
        )?;
    }
    step(
        "pip install python/requirements.txt",
        pip_install(&python).arg("-r").arg(&requirements),
    )?;
    step(
        "pip install --target .venv/zenoh-1.6 (rmw_zenoh's Zenoh)",
        pip_install(&python)
            .arg("--upgrade")
            .arg("--target")
            .arg(venv.join("zenoh-1.6"))
            .arg("-r")
            .arg(root.join(ZENOH_16)),
    )?;
    step(
        "python imports",
        Command::new(&python).args(["-c", IMPORTS]),
    )?;
    std::fs::write(&stamp, wanted).with_context(|| format!("writing {}", stamp.display()))?;
    Ok(python)
}

/// `python -m pip install`, quietly.
fn pip_install(python: &Path) -> Command {
    let mut cmd = Command::new(python);
    cmd.args([
        "-m",
        "pip",
        "install",
        "--disable-pip-version-check",
        "--quiet",
    ]);
    cmd
}

/// The python executable inside a venv.
pub fn python_in(venv: &Path) -> PathBuf {
    venv.join("bin").join("python")
}
