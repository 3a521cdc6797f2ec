//! What the training examples share.

use std::path::PathBuf;

/// The workspace root: the first argument unless it is a `--flag`, else this crate's `../..`
/// (`cargo xtask train …` passes it).
pub(crate) fn workspace_root(args: &[String]) -> PathBuf {
    args.first()
        .filter(|a| !a.starts_with("--"))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../.."))
}
