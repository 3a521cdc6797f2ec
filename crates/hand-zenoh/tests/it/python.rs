//! The workspace's Python, for the checks by code no one here wrote: `$HANDSTACK_PYTHON`
//! (`cargo xtask test` sets it to the workspace venv); a test without it is skipped, saying so.

use serde_json::Value;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

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

/// The client running in the background (`serve`), its JSON read by [`Background::finish`];
/// killed if dropped before (a failed test does not leave it waiting out its `--timeout`).
pub(crate) struct Background {
    child: Option<Child>,
    args: Vec<String>,
}

/// Starts the client with `args`, its stdout piped.
pub(crate) fn background(python: &Path, args: &[&str]) -> Background {
    let child = Command::new(python)
        .arg(root().join("python/interop/ros_zenoh_client.py"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run the python client");
    Background {
        child: Some(child),
        args: args.iter().map(|a| (*a).to_owned()).collect(),
    }
}

impl Background {
    /// Waits for it to exit; its JSON (fails the test on a non-zero exit).
    pub(crate) fn finish(mut self) -> Value {
        let child = self.child.take().expect("running");
        let out = child
            .wait_with_output()
            .expect("wait for the python client");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "client {:?} failed: {text}\n{}",
            self.args,
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_str(text.trim()).unwrap_or_else(|e| panic!("client JSON {text}: {e}"))
    }
}

impl Drop for Background {
    fn drop(&mut self) {
        if let Some(mut child) = self.child.take() {
            let _ = child.kill();
            let _ = child.wait();
        }
    }
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

/// The bytes of a hex string the client printed.
pub(crate) fn unhex(text: &str) -> Vec<u8> {
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).expect("hex"))
        .collect()
}
