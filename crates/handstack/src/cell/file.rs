//! Cell files: the router, the nodes (each one part of a scene, in its own process) and what
//! the coordinator runs.
//!
//! ```
//! use handstack::cell::{CellFile, Part};
//!
//! let cell = CellFile::parse("cell.toml", r#"
//!     title = "Tap to move across processes"
//!     router = "tcp/127.0.0.1:7447"
//!     [[node]]
//!     namespace = "/pad0"
//!     scene = "tap.toml"
//!     part = "pad"
//!     [[node]]
//!     namespace = "/arm0"
//!     scene = "tap.toml"
//!     part = "arm"
//!     [coordinator.tap_to_move]
//!     pad = "/pad0"
//!     arm = "/arm0"
//!     taps = 9
//! "#)?;
//! assert_eq!(cell.nodes[1].part, Part::Arm);
//! # Ok::<(), handstack::cell::CellError>(())
//! ```

use super::error::CellError;
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The part of a scene a node runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Part {
    /// The ICM-20789 pad: `imu`, `tactile/raw`, `tactile/contact`.
    Pad,
    /// The arm: `joint_states`, `tcp_pose`, `goal`, `stop`.
    Arm,
    /// The barometric fingertip: `tactile/{raw,touch,sensor_info}`, `tactile/tare`.
    Fingertip,
    /// The grasp hand (fingertip, controller, servos): `grasp/state`, `gripper/joint_states`,
    /// `gripper/command`, `grasp/{start,stop}`.
    Hand,
}

impl Part {
    /// The node's name.
    pub fn node_name(self) -> &'static str {
        match self {
            Part::Pad => "pad",
            Part::Arm => "arm",
            Part::Fingertip => "tactile",
            Part::Hand => "grasp",
        }
    }

    /// The namespace its node takes when none is given: `/hand0` for the hand and its
    /// fingertip, `/pad0`, `/arm0`.
    pub fn default_namespace(self) -> &'static str {
        match self {
            Part::Pad => "/pad0",
            Part::Arm => "/arm0",
            Part::Fingertip | Part::Hand => "/hand0",
        }
    }

    /// Its name on the command line.
    pub fn as_str(self) -> &'static str {
        match self {
            Part::Pad => "pad",
            Part::Arm => "arm",
            Part::Fingertip => "fingertip",
            Part::Hand => "hand",
        }
    }
}

impl core::str::FromStr for Part {
    type Err = String;
    fn from_str(s: &str) -> Result<Part, String> {
        match s {
            "pad" => Ok(Part::Pad),
            "arm" => Ok(Part::Arm),
            "fingertip" => Ok(Part::Fingertip),
            "hand" => Ok(Part::Hand),
            _ => Err(format!("`{s}` is not a part: pad, arm, fingertip or hand")),
        }
    }
}

/// One node of a cell.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeEntry {
    /// Its namespace (`/pad0`).
    pub namespace: String,
    /// The scene whose part it runs (relative to the cell file).
    pub scene: PathBuf,
    /// Which part.
    pub part: Part,
    /// Simulated devices only: read them this many times faster than real time.
    #[serde(default)]
    pub sim_speed: Option<f64>,
    /// The program whose `node` command runs it (default: the program running the cell). A
    /// bare name is looked for beside that program, then on `PATH`; a path is relative to the
    /// cell file. So `handstack cell` can start nodes of another program, such as a
    /// reproduction's simulated devices (`program = "paper-scenes"`).
    #[serde(default)]
    pub program: Option<PathBuf>,
}

impl NodeEntry {
    /// The program that runs this node when the cell runs under `default`.
    pub fn program_under(&self, default: &Path) -> PathBuf {
        match &self.program {
            None => default.to_owned(),
            Some(p) if p.components().count() > 1 => p.clone(),
            Some(name) => {
                let beside = default.with_file_name(name);
                if beside.is_file() {
                    beside
                } else {
                    name.clone()
                }
            }
        }
    }
}

/// The tap-to-move coordination.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TapToMoveEntry {
    /// The pad node's namespace.
    pub pad: String,
    /// The arm node's namespace.
    pub arm: String,
    /// Taps to handle.
    pub taps: usize,
}

/// What the coordinator runs.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CoordinatorEntry {
    /// Tap-to-move (Al & Martinez-Hernandez, §IV-B): a tap on the pad sends the arm to that
    /// region's grid pose.
    pub tap_to_move: TapToMoveEntry,
}

fn default_router() -> String {
    "tcp/127.0.0.1:7447".to_owned()
}

/// A cell file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CellFile {
    /// What the cell is.
    pub title: String,
    /// Where the router listens (and the nodes connect).
    #[serde(default = "default_router")]
    pub router: String,
    /// ROS domain id.
    #[serde(default)]
    pub domain_id: u32,
    /// The nodes, each its own process.
    #[serde(rename = "node")]
    pub nodes: Vec<NodeEntry>,
    /// What the coordinator runs.
    pub coordinator: CoordinatorEntry,
}

impl CellFile {
    /// Reads the cell file at `path`; node scenes are resolved against its folder.
    pub fn load(path: &Path) -> Result<CellFile, CellError> {
        let text = std::fs::read_to_string(path).map_err(|e| CellError::CellFile {
            path: path.display().to_string(),
            reason: e.to_string(),
        })?;
        let mut cell = CellFile::parse(&path.display().to_string(), &text)?;
        let dir = path.parent().unwrap_or(Path::new("."));
        for n in &mut cell.nodes {
            n.scene = dir.join(&n.scene);
            if let Some(p) = &mut n.program {
                if p.components().count() > 1 {
                    *p = dir.join(&*p);
                }
            }
        }
        Ok(cell)
    }

    /// Parses and checks cell text; `file` names it in errors.
    pub fn parse(file: &str, text: &str) -> Result<CellFile, CellError> {
        let fail = |reason: String| CellError::CellFile {
            path: file.to_owned(),
            reason,
        };
        let cell: CellFile = toml::from_str(text).map_err(|e| fail(e.to_string()))?;
        if !cell.router.starts_with("tcp/") {
            return Err(fail(format!(
                "router `{}`: nodes reach it over TCP only (`tcp/HOST:PORT`)",
                cell.router
            )));
        }
        let t = &cell.coordinator.tap_to_move;
        for (role, ns, part) in [("pad", &t.pad, Part::Pad), ("arm", &t.arm, Part::Arm)] {
            if !cell
                .nodes
                .iter()
                .any(|n| &n.namespace == ns && n.part == part)
            {
                return Err(fail(format!(
                    "coordinator.tap_to_move.{role} = `{ns}`: no [[node]] runs the {role} there"
                )));
            }
        }
        for n in &cell.nodes {
            if let Some(s) = n.sim_speed.filter(|s| !(s.is_finite() && *s > 0.0)) {
                return Err(fail(format!(
                    "node {}: sim_speed {s} is not > 0",
                    n.namespace
                )));
            }
        }
        Ok(cell)
    }
}
