//! Debian's Chromium for the report render test (`crates/paper-scenes/tests/it/report_render.rs`)
//! and the demo screenshot: found, or installed with apt-get when we are root.

use crate::run::step;
use anyhow::{Result, bail};
use std::path::PathBuf;
use std::process::{Command, Stdio};

/// Where Debian's `chromium` package puts the browser.
const DEBIAN: &str = "/usr/bin/chromium";

/// The Chromium to hand to tests as `HANDSTACK_CHROMIUM`: `$HANDSTACK_CHROMIUM` if set,
/// `/usr/bin/chromium`, `chromium` on `PATH`; else, as root, `apt-get install chromium`
/// (with an `apt-get update` first if the install fails on stale lists); else an error saying
/// what to install.
pub fn ensure() -> Result<PathBuf> {
    if let Some(p) = std::env::var_os("HANDSTACK_CHROMIUM").filter(|p| !p.is_empty()) {
        return Ok(p.into());
    }
    if let Some(found) = found() {
        return Ok(found);
    }
    if !is_root() {
        bail!(
            "Chromium is needed by the report render test and `demo --screenshot`: install \
             Debian's package (`sudo apt-get install --no-install-recommends chromium`) or set \
             HANDSTACK_CHROMIUM to a Chromium executable"
        );
    }
    let install = || {
        let mut cmd = Command::new("apt-get");
        cmd.args(["install", "-y", "--no-install-recommends", "chromium"])
            .env("DEBIAN_FRONTEND", "noninteractive");
        cmd
    };
    if step("apt-get install chromium", &mut install()).is_err() {
        step(
            "apt-get update",
            Command::new("apt-get")
                .arg("update")
                .env("DEBIAN_FRONTEND", "noninteractive"),
        )?;
        step("apt-get install chromium (after update)", &mut install())?;
    }
    found().ok_or_else(|| anyhow::anyhow!("apt-get installed chromium but {DEBIAN} is missing"))
}

/// Debian's path if it exists, else `chromium` if it runs from `PATH`.
fn found() -> Option<PathBuf> {
    if std::path::Path::new(DEBIAN).exists() {
        return Some(DEBIAN.into());
    }
    Command::new("chromium")
        .arg("--version")
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .ok()
        .filter(|s| s.success())
        .map(|_| "chromium".into())
}

fn is_root() -> bool {
    Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0")
}
