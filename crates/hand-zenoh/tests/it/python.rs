//! The workspace's Python, for the checks by code no one here wrote: `$HANDSTACK_PYTHON`
//! (`cargo xtask test` sets it to the workspace venv); a test without it is skipped, saying so.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::Command;

pub(crate) fn python() -> Option<PathBuf> {
    let p = std::env::var_os("HANDSTACK_PYTHON").map(PathBuf::from);
    if p.is_none() {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
    }
    p
}

pub(crate) fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub(crate) fn msgs_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("ros/handstack_msgs")
}

/// Runs the client with `args`, returns its JSON (fails the test on a non-zero exit).
pub(crate) fn client(python: &Path, args: &[&str]) -> Value {
    let text = client_text(python, args);
    serde_json::from_str(text.trim()).unwrap_or_else(|e| panic!("client JSON {text}: {e}"))
}

pub(crate) fn client_text(python: &Path, args: &[&str]) -> String {
    let mut cmd = Command::new(python);
    cmd.arg(root().join("python/interop/ros_zenoh_client.py"))
        .args(args);
    let out = cmd.output().expect("run the python client");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "client {args:?} failed: {text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text.into_owned()
}

pub(crate) fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}
