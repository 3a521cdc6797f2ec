//! The arm node's safe state (feature `cell`): when the node commanding it leaves the graph in
//! the middle of a move, the arm is stopped (stopL) and does not arrive; a stop request stops
//! it too; a controller that dies mid-move ends `handstack node`, saying so. The workspace's
//! `ur-sim` binary as the UR controller (on 127.0.0.95 and 127.0.0.96) at real time, through the
//! real ur_rtde (needs `$HANDSTACK_PYTHON`); the router and the nodes on 127.0.0.1.

use hand_zenoh::config::SessionConfig;
use hand_zenoh::convert::{pose_from_msg, pose_to_msg};
use hand_zenoh::keys::EntityKind;
use hand_zenoh::msg::geometry_msgs::PoseStamped;
use hand_zenoh::node::{Node, NodeOptions, Router};
use handstack::cell::Stop;
use handstack::cell::arm::{self, ArmNodeConfig};
use std::time::{Duration, Instant};
use ur_bridge::{UrArm, UrConfig};

use crate::process::UrSim;

const WAIT: Duration = Duration::from_secs(20);

fn node(endpoint: &str, ns: &str, name: &str) -> Node {
    let mut o = NodeOptions::new(ns, name);
    o.session = SessionConfig::peer(endpoint);
    Node::open(o).expect("node")
}

/// A commander on `endpoint` that sends the arm node of `/arm0` 0.15 m down (0.6 s at
/// 0.25 m/s) and returns once the move is under way (1 cm): the commander, its `tcp_pose`
/// subscription and `goal` publisher, and the goal.
fn move_under_way(
    endpoint: &str,
) -> (
    Node,
    hand_zenoh::node::Subscription<PoseStamped>,
    hand_zenoh::node::Publisher<PoseStamped>,
    hand_traits::Pose,
) {
    let commander = node(endpoint, "/cell", "coordinator");
    let mut tcp = commander
        .subscription::<PoseStamped>("/arm0/tcp_pose", 256)
        .unwrap();
    let mut goal = commander.publisher::<PoseStamped>("/arm0/goal").unwrap();
    assert!(
        commander
            .wait_for(EntityKind::Subscription, "/arm0/goal", WAIT)
            .unwrap()
    );
    let start = pose_from_msg(
        &tcp.recv_timeout(WAIT)
            .unwrap()
            .expect("a pose")
            .message
            .pose,
    );
    let mut target = start;
    target.position_m[2] -= 0.15;
    // In the arm's base frame: a goal in any other is refused.
    goal.publish(&PoseStamped {
        header: hand_zenoh::convert::header(0, &handstack::cell::frames::base_frame("/arm0")),
        pose: pose_to_msg(&target),
    })
    .unwrap();
    let deadline = Instant::now() + WAIT;
    while tcp
        .recv_timeout(Duration::from_millis(100))
        .unwrap()
        .is_none_or(|p| pose_from_msg(&p.message.pose).distance_m(&start) <= 0.01)
    {
        assert!(Instant::now() < deadline, "the arm did not start moving");
    }
    (commander, tcp, goal, target)
}

/// Whether ur_rtde's Python is missing (the test is then skipped, saying so).
fn no_python() -> bool {
    let missing = std::env::var_os("HANDSTACK_PYTHON").is_none();
    if missing {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
    }
    missing
}

/// `handstack node SCENE --part arm` as `/arm0` for a UR3 at `host`, on the router at
/// `endpoint`: the process, its stdin held open (a closed stdin is the node's normal stop, not
/// what these tests are about) and the directory of its scene file (`name` tells it apart).
fn arm_node(
    host: &str,
    endpoint: &str,
    name: &str,
) -> (
    std::process::Child,
    Option<std::process::ChildStdin>,
    std::path::PathBuf,
) {
    let dir = std::env::temp_dir().join(format!("handstack-arm-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let scene = dir.join("arm.toml");
    std::fs::write(
        &scene,
        format!("title = \"arm\"\n[arm]\nmodel = \"ur3\"\nhost = \"{host}\"\n"),
    )
    .expect("scene");
    let mut node = crate::process::start_node(&scene, "arm", "/arm0", endpoint);
    let stdin = node.stdin.take();
    (node, stdin, dir)
}

#[test]
fn the_arm_stops_when_its_commander_leaves_mid_move() {
    if no_python() {
        return;
    }
    let address = "127.0.0.95";
    let sim = UrSim::start(address);
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let stop = Stop::new();
    let arm_thread = {
        let (endpoint, stop) = (endpoint.clone(), stop.clone());
        std::thread::spawn(move || {
            let mut ur = UrArm::connect(UrConfig::new(address)).expect("ur_rtde");
            let n = node(&endpoint, "/arm0", "arm");
            arm::run(&n, &mut ur, &ArmNodeConfig::default(), &stop)
        })
    };
    let (commander, tcp, goal, target) = move_under_way(&endpoint);
    drop((tcp, goal, commander));
    // Watch the arm from a second node until it has stood still for 0.5 s.
    let watcher = node(&endpoint, "/cell", "watcher");
    let mut tcp = watcher
        .subscription::<PoseStamped>("/arm0/tcp_pose", 256)
        .unwrap();
    let mut last = None::<(hand_traits::Pose, Instant)>;
    let deadline = Instant::now() + WAIT;
    let rest = loop {
        assert!(Instant::now() < deadline, "the arm never came to rest");
        let Some(p) = tcp.recv_timeout(Duration::from_millis(100)).unwrap() else {
            continue;
        };
        let pose = pose_from_msg(&p.message.pose);
        match last {
            Some((prev, since)) if prev.distance_m(&pose) < 1e-6 => {
                if since.elapsed() > Duration::from_millis(500) {
                    break pose;
                }
            }
            _ => last = Some((pose, Instant::now())),
        }
    };
    assert!(
        rest.distance_m(&target) > 0.01,
        "the arm went on to its goal: {:.4} m from it",
        rest.distance_m(&target)
    );
    stop.set();
    let report = arm_thread.join().unwrap().expect("the arm node");
    assert_eq!(report.goals, 1);
    assert_eq!(report.safe_stops, 1, "{report:?}");
    assert_eq!(report.moves_done, 0, "{report:?}");
    drop(watcher);
    sim.kill();
}

#[test]
fn a_controller_that_dies_mid_move_ends_the_arm_node_saying_so() {
    use crate::process::{finish, text};
    if no_python() {
        return;
    }
    let host = "127.0.0.96";
    let ur = UrSim::start(host);
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let (arm_node, _stdin, dir) = arm_node(host, &endpoint, "dies");
    let _moving = move_under_way(&endpoint);
    let killed = Instant::now();
    ur.kill();
    let out = finish(arm_node);
    let after = killed.elapsed();
    let err = text(&out.stderr);
    assert!(
        after < Duration::from_secs(5),
        "ended {after:?} after the kill: {err}"
    );
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(
        err.contains(&format!("error: /arm0 arm: arm: controller at {host}: "))
            && err.contains("the arm's stop (stopL) could not be sent"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// SIGTERM to `handstack node --part arm` mid-move: the arm is stopped (stopL) short of its
/// goal, and the node exits with the signal's status (143).
#[test]
fn sigterm_mid_move_stops_the_arm_and_ends_the_node_with_its_status() {
    use crate::process::{finish, signal, text};
    if no_python() {
        return;
    }
    let host = "127.0.0.97";
    let ur = UrSim::start(host);
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let (arm_node, _stdin, dir) = arm_node(host, &endpoint, "term");
    let (_commander, _tcp, _goal, target) = move_under_way(&endpoint);
    signal(arm_node.id(), "TERM");
    let out = finish(arm_node);
    let err = text(&out.stderr);
    assert_eq!(out.status.code(), Some(143), "{err}");
    assert!(err.contains("/arm0 arm: "), "{err}");
    // Read back from the controller: at rest, short of the goal.
    let arm = UrArm::connect(UrConfig::new(host)).expect("ur_rtde");
    let deadline = Instant::now() + WAIT;
    let mut last = arm.tool_pose().expect("pose");
    let rest = loop {
        std::thread::sleep(Duration::from_millis(200));
        let pose = arm.tool_pose().expect("pose");
        if pose.distance_m(&last) < 1e-6 {
            break pose;
        }
        assert!(Instant::now() < deadline, "the arm never came to rest");
        last = pose;
    };
    assert!(
        rest.distance_m(&target) > 0.01,
        "the arm went on to its goal: {:.4} m from it",
        rest.distance_m(&target)
    );
    drop(arm);
    ur.kill();
    let _ = std::fs::remove_dir_all(&dir);
}
