//! `cell CELL.toml`: a router (a Zenoh session in router mode in this process; `zenohd` need
//! not be installed), each `[[node]]` as a separate process (`<its program, else this one> node
//! SCENE --part P --namespace NS --connect ROUTER`), and the coordinator as a node of this
//! process. The node
//! processes are stopped by closing their stdin (then killed if they have not ended within
//! 5 s) when the run ends, however it ends.

use super::coordinator::{self, CellReport, CellRow, TapToMoveCell};
use super::error::CellError;
use super::file::CellFile;
use crate::stop::Stop;
use crate::tap_to_move::RegionToGrid;
use hand_zenoh::config::SessionConfig;
use hand_zenoh::node::{Node, NodeOptions, Router};
use std::io::{BufRead as _, BufReader};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// One node process: its namespace, the child, and what it wrote on stderr so far.
#[derive(Debug)]
struct NodeProcess {
    namespace: String,
    child: Child,
    log: Arc<Mutex<String>>,
}

/// The node processes of a run; dropping it stops them. Each one's stderr is shown on this
/// process's stderr, each line prefixed with its namespace, and kept.
#[derive(Debug, Default)]
pub struct Nodes(Vec<NodeProcess>);

impl Nodes {
    /// Stops the nodes (stdin closed, killed after 5 s) and returns each namespace with what
    /// it wrote on stderr.
    pub fn finish(mut self) -> Vec<(String, String)> {
        self.stop();
        self.0
            .iter()
            .map(|p| {
                let log = p.log.lock().map(|l| l.clone()).unwrap_or_default();
                (p.namespace.clone(), log)
            })
            .collect()
    }

    fn stop(&mut self) {
        for p in &mut self.0 {
            drop(p.child.stdin.take());
        }
        let deadline = Instant::now() + Duration::from_secs(5);
        for p in &mut self.0 {
            while Instant::now() < deadline && matches!(p.child.try_wait(), Ok(None)) {
                std::thread::sleep(Duration::from_millis(20));
            }
            let _ = p.child.kill();
            let _ = p.child.wait();
        }
        // The readers end with their pipes; give them a moment to store the last lines.
        let deadline = Instant::now() + Duration::from_secs(1);
        while Instant::now() < deadline && self.0.iter().any(|p| Arc::strong_count(&p.log) > 1) {
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    /// The process of the node in `namespace`.
    pub fn child_mut(&mut self, namespace: &str) -> Option<&mut Child> {
        self.0
            .iter_mut()
            .find(|p| p.namespace == namespace)
            .map(|p| &mut p.child)
    }
}

impl Drop for Nodes {
    fn drop(&mut self) {
        self.stop();
    }
}

/// Starts the node processes of `cell`, each with its own `program` or else with `program`
/// (a binary with the `node` command for these scenes).
pub fn start_nodes(cell: &CellFile, program: &Path) -> Result<Nodes, CellError> {
    let mut nodes = Nodes::default();
    for n in &cell.nodes {
        let program = n.program_under(program);
        let mut cmd = Command::new(&program);
        cmd.arg("node")
            .arg(&n.scene)
            .args(["--part", n.part.as_str()])
            .args(["--namespace", &n.namespace])
            .args(["--connect", &cell.router])
            .args(["--domain", &cell.domain_id.to_string()]);
        if let Some(s) = n.sim_speed {
            cmd.args(["--sim-speed", &s.to_string()]);
        }
        let mut child = cmd
            .stdin(Stdio::piped())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|e| CellError::Process {
                node: n.namespace.clone(),
                reason: format!("{}: {e}", program.display()),
            })?;
        let log = Arc::new(Mutex::new(String::new()));
        if let Some(err) = child.stderr.take() {
            let (keep, ns) = (Arc::clone(&log), n.namespace.clone());
            std::thread::spawn(move || {
                for line in BufReader::new(err).lines().map_while(Result::ok) {
                    eprintln!("[{ns}] {line}");
                    if let Ok(mut l) = keep.lock() {
                        l.push_str(&line);
                        l.push('\n');
                    }
                }
            });
        }
        nodes.0.push(NodeProcess {
            namespace: n.namespace.clone(),
            child,
            log,
        });
    }
    Ok(nodes)
}

/// What a cell run gives.
#[derive(Debug)]
pub struct CellRun {
    /// The cell file.
    pub cell: CellFile,
    /// The coordinator's report.
    pub report: CellReport,
    /// Wall time of the whole run, s.
    pub wall_s: f64,
}

/// Runs the cell file at `path`: router, node processes of `program`, coordinator;
/// `on_tap` is told of each tap.
pub fn run(
    path: &Path,
    program: &Path,
    stop: &Stop,
    on_tap: impl FnMut(&CellRow),
) -> Result<CellRun, CellError> {
    let t0 = Instant::now();
    let cell = CellFile::load(path)?;
    let _router = Router::open(&cell.router)?;
    let _nodes = start_nodes(&cell, program)?;
    let mut options = NodeOptions::new("/cell", "coordinator");
    options.domain_id = cell.domain_id;
    options.session = SessionConfig::peer(&cell.router);
    let node = Node::open(options)?;
    let t = &cell.coordinator.tap_to_move;
    let mut settings = TapToMoveCell::new(t.taps);
    settings.pad = t.pad.clone();
    settings.arm = t.arm.clone();
    let grid = RegionToGrid::ur3_default().map_err(|e| CellError::device("grid", e))?;
    let report = coordinator::run(&node, &settings, &grid, stop, on_tap)?;
    Ok(CellRun {
        cell,
        report,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}
