//! Other processes, as a user runs them: binaries the workspace built, their output read line
//! by line as it comes, real signals, bounded waits.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::sync::{Arc, Condvar, Mutex};
use std::time::{Duration, Instant};

/// Longest any wait here takes (a bound, not a delay: each returns at its event).
pub(crate) const WAIT: Duration = Duration::from_secs(30);

/// The reply allowance for the `dxl-sim` process's servos: its `REPLY_LATENCY` (a simulator
/// on a loaded machine answers later than a real servo's 34 ms).
pub(crate) const SIM_REPLY_TIMEOUT_MS: u64 = 1000;

/// A binary the workspace's `cargo test` built beside this test (`dxl-sim`, `ur-sim`,
/// `firmata-sim`), or one of this package's examples (`examples/bench_rig`).
pub(crate) fn built(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    // target/<profile>/deps/<this test> → target/<profile>/<name>
    let dir = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>");
    let path = dir.join(name);
    assert!(
        path.exists(),
        "{} is not built: run the workspace's tests (`cargo xtask test`, or `cargo test \
         --workspace --all-features`), which build dxl-sim, ur-sim, firmata-sim and this \
         package's examples",
        path.display()
    );
    path
}

/// Lines a child process printed, shared with the thread reading them.
#[derive(Default)]
pub(crate) struct Lines {
    /// The lines so far, and whether the output has ended.
    lines: Mutex<(Vec<String>, bool)>,
    more: Condvar,
}

impl Lines {
    /// Reads `from` line by line into a new `Lines`.
    pub(crate) fn read(from: impl std::io::Read + Send + 'static) -> Arc<Lines> {
        let lines = Arc::new(Lines::default());
        let keep = Arc::clone(&lines);
        std::thread::spawn(move || {
            for line in BufReader::new(from).lines().map_while(Result::ok) {
                keep.lines.lock().expect("lines").0.push(line);
                keep.more.notify_all();
            }
            keep.lines.lock().expect("lines").1 = true;
            keep.more.notify_all();
        });
        lines
    }

    /// Waits until `done` holds for the lines so far; returns how many there were then, or
    /// `None` when the output ended first or [`WAIT`] passed.
    pub(crate) fn wait_until(&self, done: impl Fn(&[String]) -> bool) -> Option<usize> {
        let deadline = Instant::now() + WAIT;
        let mut lines = self.lines.lock().expect("lines");
        while !done(&lines.0) {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() || lines.1 {
                return None;
            }
            lines = self.more.wait_timeout(lines, left).expect("lines").0;
        }
        Some(lines.0.len())
    }

    /// Waits until `done` holds for the lines so far; returns how many there were then.
    pub(crate) fn wait_for(&self, what: &str, done: impl Fn(&[String]) -> bool) -> usize {
        self.wait_until(done).unwrap_or_else(|| {
            let lines = self.lines.lock().expect("lines");
            let why = if lines.1 {
                "before the output ended"
            } else {
                "within the wait"
            };
            panic!("no {what} {why} ({WAIT:?}): {:?}", lines.0.last())
        })
    }

    /// Waits (bounded) for the output to end; the lines then.
    pub(crate) fn all(&self) -> Vec<String> {
        let _ = self.wait_until(|_| false);
        self.snapshot()
    }

    pub(crate) fn snapshot(&self) -> Vec<String> {
        self.lines.lock().expect("lines").0.clone()
    }
}

/// The workspace's `ur-sim` binary (a simulated UR controller, as a user runs it in CI) on
/// `host`, listening; SIGTERM and reaped when dropped.
pub(crate) struct UrSim {
    child: Child,
}

impl UrSim {
    /// Starts `ur-sim --host HOST` and waits for its `rtde` line (its last port listening).
    pub(crate) fn start(host: &str) -> UrSim {
        let mut child = Command::new(built("ur-sim"))
            .args(["--host", host])
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("ur-sim starts");
        let services = Lines::read(child.stdout.take().expect("stdout"));
        services.wait_for("ur-sim's RTDE", |l| {
            l.iter().any(|l| l.starts_with("rtde "))
        });
        UrSim { child }
    }

    /// Kills it at once (SIGKILL: every socket closes, no goodbye) and reaps it.
    #[cfg(feature = "cell")]
    pub(crate) fn kill(mut self) {
        signal(self.child.id(), "KILL");
        let _ = self.child.wait();
    }
}

impl Drop for UrSim {
    fn drop(&mut self) {
        if let Ok(None) = self.child.try_wait() {
            let _ = Command::new("kill")
                .arg("-TERM")
                .arg(self.child.id().to_string())
                .status();
            let _ = self.child.wait();
        }
    }
}

/// Two simulated MX-28s (IDs 1 and 2) on a pty: the workspace's `dxl-sim` as its own process, as
/// a user runs it. A scene opens the pty by its path, as it would /dev/ttyUSB0; `lines` is what
/// the simulator prints after the path (its bus trace, with `--trace`).
pub(crate) struct DxlSim {
    pub(crate) child: Child,
    pub(crate) path: String,
    pub(crate) lines: Arc<Lines>,
}

impl DxlSim {
    /// Starts `dxl-sim --servo mx28:1 --servo mx28:2 EXTRA…` and waits for its pty path.
    pub(crate) fn start(extra: &[&str]) -> DxlSim {
        let mut child = Command::new(built("dxl-sim"))
            .args(["--servo", "mx28:1", "--servo", "mx28:2"])
            .args(extra)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("dxl-sim starts");
        let lines = Lines::read(child.stdout.take().expect("stdout"));
        lines.wait_for("pty path", |l| !l.is_empty());
        let path = lines.snapshot()[0].clone();
        assert!(path.starts_with("/dev/"), "{path}");
        DxlSim { child, path, lines }
    }

    /// Registers `a` and `b` (control-table addresses) of each servo, read back over Protocol
    /// 2.0: after every byte sent before, a broadcast included.
    pub(crate) fn read_back(&self, a: u16, b: u16) -> Vec<(i32, i32)> {
        let port = serial2::SerialPort::open(&self.path, 1_000_000).expect("pty");
        let mut hand = hand_control::ServoHand::with_reply_latency(
            port,
            &[1, 2],
            Duration::from_millis(SIM_REPLY_TIMEOUT_MS),
        )
        .expect("both servos answer");
        [1, 2]
            .iter()
            .map(|&id| {
                let first = hand.read_register(id, a).expect("register a");
                (first, hand.read_register(id, b).expect("register b"))
            })
            .collect()
    }
}

impl Drop for DxlSim {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A simulated Arduino Mega 2560 running ConfigurableFirmata on a pty, with an ICM-20789 on its
/// I2C (at rest: 1 g on z, 1013.25 hPa) and, as asked, three fingertip MS5611 behind a
/// TCA9548A at 0x70: the workspace's `firmata-sim` as its own process, as a user runs it. A
/// scene names the pty as it would /dev/ttyACM0.
pub(crate) struct FirmataSim {
    child: Child,
    pub(crate) path: String,
}

impl FirmataSim {
    /// Starts `firmata-sim --board mega2560 --boot-ms 200 --no-fingertips EXTRA…` (the pad's
    /// board) and waits for its pty path.
    pub(crate) fn start(extra: &[&str]) -> FirmataSim {
        let mut args = vec!["--no-fingertips"];
        args.extend_from_slice(extra);
        FirmataSim::with_args(&args)
    }

    /// Starts `firmata-sim --board mega2560 --boot-ms 200 ARGS…` and waits for its pty path.
    pub(crate) fn with_args(args: &[&str]) -> FirmataSim {
        let mut child = Command::new(built("firmata-sim"))
            .args(["--board", "mega2560", "--boot-ms", "200"])
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("firmata-sim starts");
        let lines = Lines::read(child.stdout.take().expect("stdout"));
        let errors = Lines::read(child.stderr.take().expect("stderr"));
        if lines.wait_until(|l| !l.is_empty()).is_none() {
            let _ = child.kill();
            let _ = child.wait();
            panic!(
                "firmata-sim {args:?} printed no pty path; its stderr:\n{}",
                errors.all().join("\n")
            );
        }
        let path = lines.snapshot()[0].clone();
        assert!(path.starts_with("/dev/"), "{path}");
        FirmataSim { child, path }
    }
}

impl Drop for FirmataSim {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Waits for `child` to end (bounded), with what it printed.
pub(crate) fn finish(child: Child) -> Output {
    let pid = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(child.wait_with_output());
    });
    match rx.recv_timeout(WAIT) {
        Ok(out) => out.expect("output"),
        Err(_) => {
            signal(pid, "KILL");
            let said = rx
                .recv_timeout(Duration::from_secs(5))
                .ok()
                .and_then(Result::ok)
                .map_or_else(String::new, |o| text(&o.stderr));
            panic!("the process did not end within {WAIT:?}; its stderr:\n{said}");
        }
    }
}

/// Sends `signal` (`INT`, `TERM`, `KILL`) to process `pid`, as a shell's `kill` does.
pub(crate) fn signal(pid: u32, signal: &str) {
    let ok = Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(pid.to_string())
        .status()
        .expect("kill runs");
    assert!(ok.success(), "kill -{signal} {pid}");
}

pub(crate) fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

/// `handstack node SCENE --part PART --namespace NS --connect ENDPOINT` as its own process, its
/// stdin and stderr piped (closing stdin is a node's normal stop).
#[cfg(feature = "cell")]
pub(crate) fn start_node(scene: &Path, part: &str, namespace: &str, endpoint: &str) -> Child {
    Command::new(env!("CARGO_BIN_EXE_handstack"))
        .arg("node")
        .arg(scene)
        .args([
            "--part",
            part,
            "--namespace",
            namespace,
            "--connect",
            endpoint,
        ])
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("handstack node starts")
}
