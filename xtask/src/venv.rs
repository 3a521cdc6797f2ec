//! The workspace's Python virtual environment: the real peers (ur_rtde, the ROBOTIS SDK,
//! scikit-fuzzy, pyfuzzylite) that simulators and reference fixtures are checked against.

use crate::run::step;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// Every module a test or generator imports, checked once the install is done.
const IMPORTS: &str =
    "import rtde_control, rtde_receive, dashboard_client, dynamixel_sdk, skfuzzy, fuzzylite";

/// The venv's python, creating `.venv` and installing `python/requirements.txt` when the venv
/// is missing or was made from other requirements. Uses `$PYTHON`, else `python3`.
pub fn ensure(root: &Path) -> Result<PathBuf> {
    let venv = root.join(".venv");
    let python = python_in(&venv);
    let requirements = root.join("python/requirements.txt");
    let wanted = std::fs::read(&requirements)
        .with_context(|| format!("reading {}", requirements.display()))?;
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
        Command::new(&python)
            .args([
                "-m",
                "pip",
                "install",
                "--disable-pip-version-check",
                "--quiet",
                "-r",
            ])
            .arg(&requirements),
    )?;
    step(
        "python imports",
        Command::new(&python).args(["-c", IMPORTS]),
    )?;
    std::fs::write(&stamp, wanted).with_context(|| format!("writing {}", stamp.display()))?;
    Ok(python)
}

/// The python executable inside a venv.
pub fn python_in(venv: &Path) -> PathBuf {
    venv.join("bin").join("python")
}
