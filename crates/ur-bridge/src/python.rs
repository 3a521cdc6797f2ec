//! Finding ur_rtde: the venv whose site-packages the embedded interpreter loads it from.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use pyo3::prelude::*;
use pyo3::sync::MutexExt;

use crate::UrError;

/// Environment variable naming the venv directory that holds ur_rtde.
pub const VENV_ENV: &str = "HANDSTACK_VENV";
/// Environment variable naming a venv's python executable (`<venv>/bin/python`), as
/// `cargo xtask test` sets it.
pub const PYTHON_ENV: &str = "HANDSTACK_PYTHON";

/// Where ur_rtde is installed: a Python virtual environment.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Venv {
    /// The venv's root directory (the one holding `pyvenv.cfg`).
    pub root: PathBuf,
}

impl Venv {
    /// A venv at `root`.
    pub fn at(root: impl Into<PathBuf>) -> Self {
        Self { root: root.into() }
    }

    /// `$HANDSTACK_VENV`, else the venv of `$HANDSTACK_PYTHON`, else the activated venv
    /// (`$VIRTUAL_ENV`), else the nearest `.venv` at or above the current directory (as uv and
    /// Poetry find a project's venv), else `.venv` in the current directory.
    ///
    /// ```
    /// let venv = ur_bridge::Venv::from_env();
    /// assert!(venv.root.is_absolute());
    /// ```
    pub fn from_env() -> Self {
        if let Some(dir) = std::env::var_os(VENV_ENV) {
            return Self::at(dir);
        }
        if let Some(python) = std::env::var_os(PYTHON_ENV) {
            // <venv>/bin/python → <venv>
            if let Some(root) = Path::new(&python).parent().and_then(Path::parent) {
                return Self::at(root);
            }
        }
        if let Some(dir) = std::env::var_os("VIRTUAL_ENV") {
            return Self::at(dir);
        }
        let here = std::env::current_dir().unwrap_or_default();
        let nearest = here
            .ancestors()
            .map(|d| d.join(".venv"))
            .find(|v| v.join("pyvenv.cfg").is_file());
        Self::at(nearest.unwrap_or_else(|| here.join(".venv")))
    }

    /// Puts the venv's site-packages on the embedded interpreter's `sys.path` (once per venv)
    /// and checks that the interpreter's version matches the venv's.
    pub(crate) fn activate(&self, py: Python<'_>) -> Result<(), UrError> {
        static DONE: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);
        // Wait for the lock detached from the interpreter: the holder runs Python
        // (`addsitedir`), which may release the GIL and need it back.
        let mut done = DONE.lock_py_attached(py).unwrap_or_else(|e| e.into_inner());
        let done = done.get_or_insert_with(HashSet::new);
        if done.contains(&self.root) {
            return Ok(());
        }
        let info = py.version_info();
        let site = self
            .root
            .join("lib")
            .join(format!("python{}.{}", info.major, info.minor))
            .join("site-packages");
        if !site.is_dir() {
            return Err(UrError::Python(format!(
                "no {} (set ${VENV_ENV} or ${PYTHON_ENV} to a Python {}.{} venv with ur-rtde)",
                site.display(),
                info.major,
                info.minor
            )));
        }
        // site.addsitedir also runs the .pth files, as the venv's own interpreter would.
        py.import("site")
            .and_then(|site_mod| {
                site_mod.call_method1("addsitedir", (site.to_string_lossy().as_ref(),))
            })
            .map_err(|e| UrError::Python(e.to_string()))?;
        done.insert(self.root.clone());
        Ok(())
    }
}
