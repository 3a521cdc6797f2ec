//! Tap-to-move (Al & Martinez-Hernandez, §IV-B) across processes: the pad node locates a tap
//! and publishes the contact; the
//! coordinator names the region's grid pose as the arm node's goal, waits until the arm's
//! `tcp_pose` is there, sends it home again, and waits for the next contact.
//!
//! The coordinator watches the graph: when the pad or the arm node leaves (its liveliness token
//! goes), it calls the arm's `stop` (while the arm node is there), and ends the run with a
//! [`CellError::Graph`] saying who left, after how many taps, and how long after its last
//! message the loss was seen.

use super::error::CellError;
use crate::stop::Stop;
use crate::tap_to_move::RegionToGrid;
use hand_traits::Pose;
use hand_zenoh::convert::{header, pose_from_msg, pose_to_msg};
use hand_zenoh::keys::{EntityKind, mangle};
use hand_zenoh::msg::geometry_msgs::PoseStamped;
use hand_zenoh::msg::handstack_msgs::ContactArray;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerRequest};
use hand_zenoh::node::{Graph, Node, Subscription, now_ns};
use std::time::{Duration, Instant};

/// The coordinator's settings.
#[derive(Debug, Clone)]
pub struct TapToMoveCell {
    /// The pad node's namespace (`/pad0`).
    pub pad: String,
    /// The arm node's namespace (`/arm0`).
    pub arm: String,
    /// Taps to handle before the run ends.
    pub taps: usize,
    /// How long the nodes may take to appear.
    pub discovery_timeout: Duration,
    /// How long a move may take to arrive.
    pub move_timeout: Duration,
    /// How long to wait for the next contact.
    pub contact_timeout: Duration,
    /// When the tool counts as arrived, m.
    pub tolerance_m: f64,
}

impl TapToMoveCell {
    /// `taps` taps between the pad `/pad0` and the arm `/arm0`, with bounds that a loaded
    /// 2-core machine meets: 20 s to appear, 20 s a move, 60 s a contact; arrived within 0.1 mm.
    pub fn new(taps: usize) -> TapToMoveCell {
        TapToMoveCell {
            pad: "/pad0".to_owned(),
            arm: "/arm0".to_owned(),
            taps,
            discovery_timeout: Duration::from_secs(20),
            move_timeout: Duration::from_secs(20),
            contact_timeout: Duration::from_secs(60),
            tolerance_m: 1e-4,
        }
    }
}

/// One tap across the cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellRow {
    /// The contact's sequence number on the pad node (1 for its first contact): which tap.
    pub seq: i64,
    /// The region the pad node located.
    pub region: u16,
    /// Its confidence.
    pub confidence: f32,
    /// Contact published on the pad node → received here, s (one machine clock).
    pub contact_latency_s: f64,
    /// Goal published → the arm's tcp_pose within tolerance, s (wall).
    pub move_s: f64,
    /// The arm's distance from the region's pose when it counted as arrived, m.
    pub tcp_error_m: f64,
}

/// What the coordinator saw.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CellReport {
    /// One row per tap, in order.
    pub rows: Vec<CellRow>,
    /// Contacts missing by the pad's sequence numbers.
    pub lost_contacts: u64,
    /// Contacts and poses that did not decode (counted, dropped).
    pub malformed: u64,
    /// From opening to all nodes seen, s.
    pub discovery_s: f64,
}

struct Watch<'a> {
    graph: Graph,
    cell: &'a TapToMoveCell,
    last_heard: Instant,
}

impl Watch<'_> {
    /// Fails when the pad or the arm node has left the graph.
    fn check(&mut self, done: usize) -> Result<(), CellError> {
        while let Some(c) = self.graph.try_recv()? {
            let left = !c.alive && c.kind == Some(EntityKind::Node);
            for ns in [&self.cell.pad, &self.cell.arm] {
                if left && c.namespace == mangle(ns) {
                    return Err(CellError::Graph {
                        node: ns.clone(),
                        what: format!(
                            "left the graph after {done} taps (seen {:.0} ms after the last \
                             message heard)",
                            self.last_heard.elapsed().as_secs_f64() * 1e3
                        ),
                    });
                }
            }
        }
        Ok(())
    }
}

/// Runs the tap-to-move coordination on `node` over `grid`; `on_tap` is told of each tap.
pub fn run(
    node: &Node,
    cell: &TapToMoveCell,
    grid: &RegionToGrid,
    stop: &Stop,
    mut on_tap: impl FnMut(&CellRow),
) -> Result<CellReport, CellError> {
    let opened = Instant::now();
    let contact_topic = format!("{}/tactile/contact", cell.pad);
    let mut contacts = node.subscription::<ContactArray>(&contact_topic, 64)?;
    let mut tcp = node.subscription::<PoseStamped>(&format!("{}/tcp_pose", cell.arm), 256)?;
    let mut goal = node.publisher::<PoseStamped>(&format!("{}/goal", cell.arm))?;
    let mut stop_arm = node.client::<Trigger>(&format!("{}/stop", cell.arm))?;
    let mut watch = Watch {
        graph: node.graph()?,
        cell,
        last_heard: Instant::now(),
    };
    for (kind, name) in [
        (EntityKind::Publisher, contact_topic.clone()),
        (EntityKind::Subscription, format!("{}/goal", cell.arm)),
        (EntityKind::Publisher, format!("{}/tcp_pose", cell.arm)),
        (EntityKind::Service, format!("{}/stop", cell.arm)),
    ] {
        if !node.wait_for(kind, &name, cell.discovery_timeout)? {
            return Err(CellError::Graph {
                node: name,
                what: format!(
                    "not in the graph within {} s",
                    cell.discovery_timeout.as_secs_f64()
                ),
            });
        }
    }
    let mut report = CellReport {
        discovery_s: opened.elapsed().as_secs_f64(),
        ..CellReport::default()
    };
    let mut go = |target: &Pose, watch: &mut Watch<'_>, done: usize| {
        move_to(&mut goal, &mut tcp, target, cell, watch, done)
    };
    let outcome = (|| {
        go(grid.home(), &mut watch, 0)?;
        while report.rows.len() < cell.taps && !stop.is_set() {
            let done = report.rows.len();
            let deadline = Instant::now() + cell.contact_timeout;
            let got = loop {
                watch.check(done)?;
                if let Some(c) = contacts.recv_timeout(Duration::from_millis(50))? {
                    break c;
                }
                if stop.is_set() {
                    return Ok(());
                }
                if Instant::now() > deadline {
                    return Err(CellError::Graph {
                        node: cell.pad.clone(),
                        what: format!("no contact within {} s", cell.contact_timeout.as_secs_f64()),
                    });
                }
            };
            watch.last_heard = Instant::now();
            let latency = got.attachment.map_or(f64::NAN, |a| {
                (got.received_ns - a.source_timestamp) as f64 * 1e-9
            });
            let Some(c) = got.message.contacts.first().cloned() else {
                continue;
            };
            let target = *grid
                .pose(c.region)
                .map_err(|e| CellError::device("grid", e))?;
            let (move_s, tcp_error_m) = go(&target, &mut watch, done)?;
            go(grid.home(), &mut watch, done)?;
            let row = CellRow {
                seq: got.attachment.map_or(0, |a| a.sequence_number),
                region: c.region,
                confidence: c.confidence,
                contact_latency_s: latency,
                move_s,
                tcp_error_m,
            };
            on_tap(&row);
            report.rows.push(row);
        }
        Ok(())
    })();
    if outcome.is_err() {
        // Whatever went wrong, the arm does not go on moving for a run that ended.
        let _ = stop_arm.call(&TriggerRequest {}, Duration::from_secs(2));
    }
    outcome?;
    report.lost_contacts = contacts.stats().lost;
    report.malformed = contacts.stats().malformed + tcp.stats().malformed;
    Ok(report)
}

/// Publishes `target` as the arm's goal and waits until its tcp_pose is within tolerance;
/// returns the wall time and the final distance.
fn move_to(
    goal: &mut hand_zenoh::node::Publisher<PoseStamped>,
    tcp: &mut Subscription<PoseStamped>,
    target: &Pose,
    cell: &TapToMoveCell,
    watch: &mut Watch<'_>,
    done: usize,
) -> Result<(f64, f64), CellError> {
    // Poses from before this goal say nothing about it.
    while tcp.try_recv()?.is_some() {}
    let t0 = Instant::now();
    goal.publish(&PoseStamped {
        header: header(now_ns(), &super::frames::base_frame(&cell.arm)),
        pose: pose_to_msg(target),
    })?;
    while t0.elapsed() < cell.move_timeout {
        watch.check(done)?;
        if let Some(p) = tcp.recv_timeout(Duration::from_millis(50))? {
            watch.last_heard = Instant::now();
            let d = pose_from_msg(&p.message.pose).distance_m(target);
            if d < cell.tolerance_m {
                return Ok((t0.elapsed().as_secs_f64(), d));
            }
        }
    }
    Err(CellError::Graph {
        node: cell.arm.clone(),
        what: format!(
            "did not reach its goal within {} s",
            cell.move_timeout.as_secs_f64()
        ),
    })
}
