//! Shared by the scene tests: run a committed scene file, read committed metrics.
#![allow(dead_code, unreachable_pub)]

use handstack::Outcome;
use handstack::progress::Quiet;
use paper_scenes::runs::RunContext;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Output, Stdio};
use std::sync::mpsc::{Receiver, channel};
use std::sync::{Mutex, MutexGuard};
use std::time::{Duration, Instant};
use tactile_nets::metrics::MetricsFile;

/// The workspace root.
pub fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// `fixtures/scenes/NAME.toml`.
pub fn scene_path(name: &str) -> PathBuf {
    root().join("fixtures/scenes").join(format!("{name}.toml"))
}

/// Runs the committed scene `name` as `handstack run` does.
pub fn run_scene(name: &str) -> Outcome {
    let cx = RunContext::new(&Quiet);
    match paper_scenes::run_file(&scene_path(name), &cx) {
        Ok(o) => o,
        Err(e) => panic!("scene {name}: {e}"),
    }
}

/// The committed metrics file of model `dir` (`crates/tactile-nets/models/DIR/metrics.json`).
pub fn metrics(dir: &str) -> MetricsFile {
    metrics_in(dir, "metrics.json")
}

/// The committed metrics file `file` of the models in `dir`.
pub fn metrics_in(dir: &str, file: &str) -> MetricsFile {
    let path = root()
        .join("crates/tactile-nets/models")
        .join(dir)
        .join(file);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    MetricsFile::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The committed value `key` of row `row` of `file`.
pub fn committed(file: &MetricsFile, row: &str, key: &str) -> f64 {
    file.row(row)
        .and_then(|r| r.values.get(key))
        .copied()
        .unwrap_or_else(|| panic!("{}: no {row}/{key}", file.model))
}

/// The measured value of figure `name`.
pub fn value(o: &Outcome, name: &str) -> f64 {
    o.figure(name)
        .unwrap_or_else(|| panic!("{}: no figure {name}", o.scene))
        .value
}

/// The `handstack` binary the workspace's tests built beside this one.
pub fn handstack() -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary's path");
    let path = exe
        .parent()
        .and_then(Path::parent)
        .expect("target/<profile>")
        .join("handstack");
    assert!(
        path.exists(),
        "{} is not built: run the workspace's tests (`cargo xtask test`)",
        path.display()
    );
    path
}

/// Waits (bounded) for `child` to end, with what it printed.
pub fn finish(child: Child, within: Duration) -> Output {
    let pid = child.id();
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(child.wait_with_output());
    });
    match rx.recv_timeout(within) {
        Ok(out) => out.expect("output"),
        Err(_) => {
            signal(pid, "KILL");
            panic!("handstack did not end within {within:?}");
        }
    }
}

pub fn signal(pid: u32, name: &str) {
    let ok = Command::new("kill")
        .arg(format!("-{name}"))
        .arg(pid.to_string())
        .status()
        .expect("kill runs");
    assert!(ok.success(), "kill -{name} {pid}");
}

pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The message count of `topic` in a bag's `metadata.yaml` text.
pub fn bag_count(yaml: &str, topic: &str) -> u64 {
    let at = yaml
        .find(&format!("name: {topic}\n"))
        .unwrap_or_else(|| panic!("no {topic}: {yaml}"));
    yaml[at..]
        .lines()
        .find_map(|l| l.trim().strip_prefix("message_count: "))
        .and_then(|n| n.parse().ok())
        .expect("a count")
}

/// Scenes whose arm is ur-sim at 10 × real time measure its moves on the controller's clock,
/// where a wall-clock delay counts tenfold: one such scene at a time, so that two do not slow
/// each other's moves (the tap scene's 0.69–0.89 s bound).
static TIME_SCALED_ARM: Mutex<()> = Mutex::new(());

/// Holds the time-scaled arm for one scene run.
pub fn time_scaled_arm() -> MutexGuard<'static, ()> {
    TIME_SCALED_ARM
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// A new, empty directory for the test `name` of a user's own models (its sessions, weights
/// and scenes), kept after the test for a look at what it wrote.
pub fn own_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("handstack-own-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("test dir");
    d
}

/// How long a line a [`Session`] waits for may take to come.
const SESSION_WAIT: Duration = Duration::from_secs(30);
/// How long a [`Session`]'s whole run may take.
const SESSION_RUN: Duration = Duration::from_secs(150);

/// A `handstack run SCENE --json` whose stderr the test reads line by line and whose stdin it
/// answers on.
pub struct Session {
    /// The `handstack` process.
    pub child: Child,
    stdin: Option<ChildStdin>,
    stderr: Receiver<String>,
    said: Vec<String>,
}

impl Session {
    pub fn start(scene: &Path) -> Session {
        Session::start_with(scene, &[])
    }

    /// `handstack run SCENE --json ARGS…`.
    pub fn start_with(scene: &Path, args: &[&std::ffi::OsStr]) -> Session {
        let mut all = vec!["run".as_ref(), scene.as_os_str(), "--json".as_ref()];
        all.extend_from_slice(args);
        Session::command(&all)
    }

    /// `handstack ARGS…`.
    pub fn command(args: &[&std::ffi::OsStr]) -> Session {
        let mut child = Command::new(handstack())
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("handstack starts");
        let stdin = child.stdin.take();
        let stderr = child.stderr.take().expect("stderr");
        let (tx, rx) = channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if tx.send(line).is_err() {
                    break;
                }
            }
        });
        Session {
            child,
            stdin,
            stderr: rx,
            said: Vec::new(),
        }
    }

    /// The next line on stderr that starts with `start` (bounded wait).
    pub fn wait_for(&mut self, start: &str) -> String {
        let deadline = Instant::now() + SESSION_WAIT;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match self.stderr.recv_timeout(left) {
                Ok(line) => {
                    self.said.push(line.clone());
                    if line.trim_start().starts_with(start) {
                        return line;
                    }
                }
                Err(_) => panic!(
                    "no \"{start}…\" within {SESSION_WAIT:?}; said:\n{}",
                    self.said.join("\n")
                ),
            }
        }
    }

    pub fn answer(&mut self, line: &str) {
        let stdin = self.stdin.as_mut().expect("stdin open");
        writeln!(stdin, "{line}").expect("answer written");
        stdin.flush().expect("answer sent");
    }

    /// Closes its stdin, as a script that runs out of answers does.
    pub fn close_stdin(&mut self) {
        drop(self.stdin.take());
    }

    /// Waits (bounded) for the run to end; its exit status, stdout and everything on stderr.
    pub fn finish(mut self) -> (Option<i32>, String, String) {
        let out = finish(self.child, SESSION_RUN);
        self.said.extend(self.stderr.try_iter());
        (out.status.code(), text(&out.stdout), self.said.join("\n"))
    }
}

/// The figures of the run's outcome printed by `--json`, by name.
pub fn figures(stdout: &str) -> impl Fn(&str) -> serde_json::Value {
    let outcomes: serde_json::Value = serde_json::from_str(stdout).expect("the outcomes as JSON");
    let stdout = stdout.to_owned();
    move |name: &str| {
        outcomes[0]["figures"]
            .as_array()
            .and_then(|fs| fs.iter().find(|f| f["name"] == name))
            .cloned()
            .unwrap_or_else(|| panic!("no figure {name}: {stdout}"))
    }
}

/// What a `paper-scenes` device process printed, run as a user runs it: its first line (the
/// port, as a scene names it), the rest of stdout once its stdin (`commands`) closed, stderr and
/// its exit status.
pub struct DeviceRun {
    /// The first line.
    pub port_line: String,
    /// The rest of stdout.
    pub rest: String,
    /// Everything on stderr.
    pub stderr: String,
    /// The exit status.
    pub code: Option<i32>,
}

/// Runs `paper-scenes ARGS…`, waits for its first line, writes `commands` to its stdin, closes
/// it and waits (bounded) for the process to end.
pub fn device_process(args: &[&str], commands: &str) -> DeviceRun {
    let mut child = Command::new(env!("CARGO_BIN_EXE_paper-scenes"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("paper-scenes starts");
    let mut stdin = child.stdin.take().expect("stdin");
    let mut stdout = BufReader::new(child.stdout.take().expect("stdout"));
    let mut port_line = String::new();
    stdout.read_line(&mut port_line).expect("the port line");
    stdin.write_all(commands.as_bytes()).expect("commands");
    drop(stdin);
    // The rest of stdout, to its end when the process ends (bounded by `finish` below).
    let reader = std::thread::spawn(move || {
        let mut rest = String::new();
        std::io::Read::read_to_string(&mut stdout, &mut rest).map(|_| rest)
    });
    let out = finish(child, SESSION_WAIT);
    DeviceRun {
        port_line,
        rest: reader.join().expect("reader").expect("stdout read"),
        stderr: text(&out.stderr),
        code: out.status.code(),
    }
}

/// The run connected to the arm once: the device check's connection moved it, so ur_rtde's
/// control script was uploaded once (a second connection would race the controller's release
/// of the first one's input registers).
pub fn script_uploaded_once(sim: &ur_sim::UrSim) {
    let log = sim.log();
    let uploads = log
        .iter()
        .filter(|l| *l == "RTDE Control Script Loaded")
        .count();
    assert_eq!(uploads, 1, "{log:?}");
}

/// A fingertip run's bag in `dir`: at least `frames_at_least` raw pressure frames, each with its
/// `tactile_msgs/TactileState`, and `figures` figures.
pub fn check_fingertip_bag(dir: &Path, frames_at_least: u64, figures: u64) {
    let yaml = std::fs::read_to_string(dir.join("metadata.yaml")).expect("metadata.yaml");
    let raw = bag_count(&yaml, "/hand0/tactile/raw");
    assert!(raw >= frames_at_least, "{raw} frames: {yaml}");
    assert_eq!(bag_count(&yaml, "/handstack/figures"), figures, "{yaml}");
    assert_eq!(bag_count(&yaml, "/hand0/tactile_states"), raw, "{yaml}");
}

/// Writes to `path` a weight scene on the fingertip board at `port` (OSR 4096, 115 200 baud)
/// whose `[estimators.force]` holds `force` (`model = "sim"`), weighing `weights`, with `extra`
/// lines under `[experiment.weight]`.
pub fn weight_scene(path: &Path, port: &Path, force: &str, weights: &[f64], extra: &str) {
    std::fs::write(
        path,
        format!(
            "title = \"Weights on my fingertip\"\n\
             [sensors.fingertip]\nosr = 4096\nfirmata_port = \"{}\"\nfirmata_baud = 115200\n\
             [estimators.force]\n{force}\n\
             [experiment.weight]\nweights_gf = {weights:?}\n{extra}",
            port.display()
        ),
    )
    .expect("scene written");
}

/// `handstack collect SCENE --into SESSIONS`'s arguments.
pub fn collect_args<'a>(scene: &'a Path, sessions: &'a Path) -> Vec<&'a std::ffi::OsStr> {
    vec![
        "collect".as_ref(),
        scene.as_os_str(),
        "--into".as_ref(),
        sessions.as_os_str(),
    ]
}

/// What `handstack train MODEL SESSIONS --out FILE --json` printed.
pub struct Trained {
    /// The outcome.
    pub outcome: serde_json::Value,
    stdout: String,
}

impl Trained {
    /// The value of the figure `name`.
    pub fn figure(&self, name: &str) -> f64 {
        self.outcome["figures"]
            .as_array()
            .and_then(|fs| fs.iter().find(|f| f["name"] == name))
            .and_then(|f| f["value"].as_f64())
            .unwrap_or_else(|| panic!("no {name}: {}", self.stdout))
    }
}

/// Runs `handstack train MODEL SESSIONS --out FILE --json`, which must succeed.
pub fn train_json(model: &str, sessions: &Path, out: &Path) -> Trained {
    let run = Command::new(handstack())
        .args(["train", model])
        .arg(sessions)
        .arg("--out")
        .arg(out)
        .arg("--json")
        .output()
        .expect("handstack train runs");
    let (stdout, stderr) = (text(&run.stdout), text(&run.stderr));
    assert_eq!(run.status.code(), Some(0), "{stdout}\n{stderr}");
    Trained {
        outcome: serde_json::from_str(&stdout).expect("JSON"),
        stdout,
    }
}

/// Collects `asked` in two sessions of `args`, as a user stopped half-way does: the first answers
/// `first` questions (`answer` answers the next one and returns what it asked for), is stopped by
/// Ctrl-C at the next `question`, and exits 130; the second asks only for the rest (in any
/// order) and exits 0; a third asks nothing and says to train `model`. Returns what the first
/// said on stderr.
pub fn collect_in_two<T: Ord + Clone + std::fmt::Debug>(
    args: &[&std::ffi::OsStr],
    asked: &[T],
    first: usize,
    question: &str,
    model: &str,
    mut answer: impl FnMut(&mut Session) -> T,
) -> String {
    let mut one = Session::command(args);
    let got: Vec<T> = (0..first).map(|_| answer(&mut one)).collect();
    assert_eq!(got, asked[..first], "{got:?}");
    one.wait_for(question);
    signal(one.child.id(), "INT");
    let (code, _, first_said) = one.finish();
    assert_eq!(code, Some(130), "{first_said}");
    let mut two = Session::command(args);
    let mut got: Vec<T> = (first..asked.len()).map(|_| answer(&mut two)).collect();
    let (code, stdout, stderr) = two.finish();
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let mut want = asked[first..].to_vec();
    want.sort_unstable();
    got.sort_unstable();
    assert_eq!(got, want);
    nothing_left(args, model);
    first_said
}

/// A collect session (`args`) after every step is recorded: it asks nothing, exits 0 and
/// says to train `model`.
pub fn nothing_left(args: &[&std::ffi::OsStr], model: &str) {
    let (code, _, stderr) = Session::command(args).finish();
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stderr.contains("everything ")
            && stderr.contains(&format!("train with `handstack train {model} ")),
        "{stderr}"
    );
}

/// The fingertip firmware on a pty: its process, its stdin, the port.
pub struct Mcu {
    child: Child,
    stdin: ChildStdin,
    /// The pty's path.
    pub port: String,
}

impl Mcu {
    /// Starts `host_uart` with `args` (`--skin N`, `--speed X`).
    pub fn start(args: &[&str]) -> Mcu {
        let exe = std::env::var_os("HANDSTACK_FINGERTIP_MCU")
            .map(PathBuf::from)
            .unwrap_or_else(|| {
                crate::common::root().join("target/firmware/host-check/examples/host_uart")
            });
        assert!(
            exe.exists(),
            "{} is not built: `cargo xtask test` builds it (or, in firmware/fingertip, \
             `cargo build --profile host-check --example host_uart` with \
             CARGO_TARGET_DIR=../../target/firmware)",
            exe.display()
        );
        let mut child = Command::new(&exe)
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("the fingertip starts");
        let stdin = child.stdin.take().expect("stdin");
        let mut port = String::new();
        BufReader::new(child.stdout.take().expect("stdout"))
            .read_line(&mut port)
            .expect("the pty's path");
        Mcu {
            child,
            stdin,
            port: port.trim().to_owned(),
        }
    }

    /// Writes the contact scene `path` on this fingertip for `cells` (row, column from 1),
    /// with `estimators` before its experiment (an `[estimators.contact]` table, or nothing).
    pub fn scene(&self, path: &Path, cells: &[(u8, u8)], estimators: &str) -> PathBuf {
        let cells: Vec<String> = cells.iter().map(|(r, c)| format!("[{r}, {c}]")).collect();
        std::fs::write(
            path,
            format!(
                "title = \"Where my fingertip is touched\"\n\
                 [sensors.fingertip]\nosr = 1024\nserial_port = \"{}\"\n{estimators}\
                 [experiment.contact]\ncells = [{}]\nwait_s = 20\n",
                self.port,
                cells.join(", ")
            ),
        )
        .expect("scene written");
        path.to_owned()
    }

    /// Writes `line` to the fingertip's stdin (`tap ROW COL`).
    pub fn say(&mut self, line: &str) {
        writeln!(self.stdin, "{line}").expect("a line to the fingertip");
        self.stdin.flush().expect("sent");
    }
}

impl Drop for Mcu {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// The cell a "Tap the fingertip at row R, column C" question asks for.
pub fn asked_cell(line: &str) -> (u8, u8) {
    let words: Vec<&str> = line.split_whitespace().collect();
    let n = |w: &str| w.trim_end_matches(',').parse::<u8>().expect("a number");
    (n(words[5]), n(words[7]))
}
