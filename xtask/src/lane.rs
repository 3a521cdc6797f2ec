//! Lanes: a workflow's independent steps on a thread of their own, beside the main steps.
//!
//! A 2-core machine spends part of a sequential `cargo xtask test` with a core idle (pip
//! downloading, a build ending on one crate). Steps that need none of the main steps' results
//! meanwhile run in a lane, at idle priority (Linux's `SCHED_IDLE`, inherited by every process
//! the lane starts): a lane gets only the CPU time the main steps leave, so those keep their
//! pace and the lane soaks up the idle cores. A lane's children write
//! to its log file, not the terminal, so the two do not interleave; [`step`](crate::run::step)
//! still announces each step and its time, and a failing lane prints the end of its log.

use anyhow::{Context, Result, anyhow};
use std::cell::RefCell;
use std::fs::File;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
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
    /// Starts `steps` on a thread of `scope` at idle priority, its children's output going to
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
            idle_priority(&lane_name);
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

/// Puts the calling thread, and so every process it starts from now on, in Linux's
/// `SCHED_IDLE` class: it runs only on a core that nothing else wants. Through `chrt`
/// (util-linux) on the thread's own ID, which `/proc/thread-self` names: xtask forbids
/// `unsafe`, so it makes no system call itself. Where that fails the lane says so and runs at
/// normal priority.
fn idle_priority(lane: &str) {
    let tid = std::fs::read_link("/proc/thread-self")
        .ok()
        .and_then(|p| p.file_name().map(|n| n.to_string_lossy().into_owned()));
    let lowered = tid.is_some_and(|tid| {
        Command::new("chrt")
            .args(["--idle", "--pid", "0", &tid])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .is_ok_and(|s| s.success())
    });
    if !lowered {
        println!(
            "==> lane {lane}: could not lower its priority (`chrt --idle` on its thread); it runs \
             at normal priority"
        );
    }
}

#[cfg(test)]
mod tests {
    use super::Lane;
    use std::process::Command;

    /// Field 41 of `/proc/PID/stat` is the scheduling policy (proc(5)); 5 is `SCHED_IDLE`.
    #[test]
    fn what_a_lane_starts_runs_at_idle_priority() {
        let root = std::env::temp_dir().join(format!("xtask-lane-{}", std::process::id()));
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::scope(|scope| {
            let lane = Lane::start(scope, &root, "idle", move || {
                let out = Command::new("cut")
                    .args(["-d", " ", "-f", "41", "/proc/self/stat"])
                    .output()?;
                tx.send(String::from_utf8(out.stdout)?.trim().to_owned())?;
                Ok(())
            })
            .unwrap();
            lane.finish().unwrap();
        });
        assert_eq!(rx.recv().unwrap(), "5");
        std::fs::remove_dir_all(root).unwrap();
    }
}
