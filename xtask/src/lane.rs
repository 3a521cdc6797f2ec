//! Lanes: a workflow's independent steps on a thread of their own, beside the main steps.
//!
//! A 2-core machine spends much of a sequential `cargo xtask test` with one core idle (a build
//! ending on one crate, a test binary waiting on a simulated device). Steps that share no
//! build directory with the main steps (the MSRV and firmware builds have their own) run in a
//! lane meanwhile. A lane's children write to its log file, not the terminal, so the two do not
//! interleave; [`step`](crate::run::step) still announces each step and its time, and a failing
//! lane prints the end of its log.

use anyhow::{Context, Result, anyhow};
use std::cell::RefCell;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::thread::{Scope, ScopedJoinHandle};

/// The lines of a failed lane's log printed with its error.
const SHOWN_LINES: usize = 200;

thread_local! {
    /// The lane this thread runs (its name and log), if any.
    static CURRENT: RefCell<Option<(String, File)>> = const { RefCell::new(None) };
}

/// A lane started by [`Lane::start`].
pub struct Lane<'scope> {
    name: String,
    log: PathBuf,
    handle: ScopedJoinHandle<'scope, Result<()>>,
}

impl<'scope> Lane<'scope> {
    /// Starts `steps` on a thread of `scope`, its children's output going to
    /// `root/target/xtask/NAME.log`.
    pub fn start<'env, F>(
        scope: &'scope Scope<'scope, 'env>,
        root: &Path,
        name: &str,
        steps: F,
    ) -> Result<Lane<'scope>>
    where
        F: FnOnce() -> Result<()> + Send + 'scope,
    {
        let dir = root.join("target/xtask");
        std::fs::create_dir_all(&dir).with_context(|| format!("create {}", dir.display()))?;
        let log = dir.join(format!("{name}.log"));
        let file = File::create(&log).with_context(|| format!("create {}", log.display()))?;
        println!("==> lane {name} started (output: {})", log.display());
        let lane_name = name.to_owned();
        let handle = scope.spawn(move || {
            CURRENT.set(Some((lane_name, file)));
            steps()
        });
        Ok(Lane {
            name: name.to_owned(),
            log,
            handle,
        })
    }

    /// Waits for the lane; its error, after the end of its log, if it failed.
    pub fn finish(self) -> Result<()> {
        let outcome = self
            .handle
            .join()
            .map_err(|_| anyhow!("lane {} panicked", self.name))
            .and_then(|r| r);
        match outcome {
            Ok(()) => {
                println!("==> lane {}: ok", self.name);
                Ok(())
            }
            Err(e) => {
                let text = std::fs::read_to_string(&self.log).unwrap_or_default();
                let lines: Vec<&str> = text.lines().collect();
                eprintln!(
                    "==> lane {} failed; the last lines of {}:",
                    self.name,
                    self.log.display()
                );
                for line in &lines[lines.len().saturating_sub(SHOWN_LINES)..] {
                    eprintln!("    {line}");
                }
                Err(e.context(format!("lane {}", self.name)))
            }
        }
    }
}

/// The current thread's lane name and a handle on its log, if it runs a lane.
pub fn current() -> Result<Option<(String, File)>> {
    CURRENT.with_borrow(|lane| {
        lane.as_ref()
            .map(|(name, file)| Ok((name.clone(), file.try_clone()?)))
            .transpose()
    })
}
