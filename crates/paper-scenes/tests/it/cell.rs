//! `fixtures/cells/tap-to-move.toml` across processes (feature `cell`): a Zenoh router in this
//! process, the pad and the UR3 nodes as `paper-scenes node` processes (the program the cell
//! file names, started as `handstack cell` starts it), the coordinator here.
//! The nine taps are located as the in-process tap-to-move locates the same taps (same pad
//! seed and schedule, same CNN, same window), every move arrives, nothing is lost; and a pad
//! node killed mid-run is seen going within a stated bound and ends the run with the arm told
//! to stop; a scene's whole stack runs as one `node` process. Needs `$HANDSTACK_PYTHON`
//! (ur-rtde). Everything on 127.0.0.x.
#![cfg(feature = "cell")]

use crate::common;

use common::root;
use hand_zenoh::config::SessionConfig;
use hand_zenoh::node::{Node, NodeOptions, Router};
use handstack::cell::coordinator::{self, TapToMoveCell};
use handstack::cell::launch::{self, start_nodes};
use handstack::cell::{CellError, CellFile, Stop};
use handstack::tap_to_move::RegionToGrid;
use paper_experiments::tap_run;
use paper_scenes::scene::PaperScene;
use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Instant;
use tactile_nets::contact_cnn::ContactCnn;

/// The arm node processes each start their simulator on 127.0.0.60: one cell at a time.
static ONE_CELL: Mutex<()> = Mutex::new(());

fn python_ok() -> bool {
    let ok = std::env::var_os("HANDSTACK_PYTHON").is_some();
    if !ok {
        eprintln!(
            "HANDSTACK_PYTHON unset: `cargo xtask test` sets it to the workspace venv; skipped"
        );
    }
    ok
}

fn program() -> PathBuf {
    PathBuf::from(env!("CARGO_BIN_EXE_paper-scenes"))
}

/// The committed cell file with its router on a free loopback port and its scenes absolute,
/// written to a fresh folder.
fn cell_file(name: &str) -> PathBuf {
    let endpoint = hand_zenoh::config::free_loopback_endpoint().expect("a free loopback port");
    let scenes = root().join("fixtures/scenes");
    let text = std::fs::read_to_string(root().join("fixtures/cells/tap-to-move.toml"))
        .expect("the cell file")
        .replace("tcp/127.0.0.1:7447", &endpoint)
        .replace("../scenes", &scenes.display().to_string());
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("tap-to-move.toml");
    std::fs::write(&path, text).unwrap();
    path
}

/// The regions the in-process tap-to-move locates for the first `n` taps of the scene.
fn in_process_located(n: usize) -> Vec<u16> {
    paper_scenes::devices::arm::sim_addresses_from(230);
    let scene = PaperScene::load(&root().join("fixtures/scenes/tap-to-ur3.toml")).unwrap();
    let schedule = paper_scenes::devices::pad::schedule(&scene, tap_run::TAPS_PER_REGION);
    let pad = paper_scenes::devices::pad::open(&scene, schedule[..n].to_vec()).unwrap();
    let mut arm = paper_scenes::devices::arm::open(&scene).unwrap();
    let model = tap_run::locator_path(&root());
    let mut cnn = ContactCnn::load(&model).unwrap();
    let rows = tap_run::run_on(
        &mut arm.arm,
        pad,
        tap_run::training_aligned(),
        &mut cnn,
        tap_run::cnn_window,
    )
    .expect("in-process run");
    rows.iter().map(|r| r.located).collect()
}

#[test]
fn tap_to_move_across_processes_locates_as_in_process() {
    if !python_ok() {
        return;
    }
    let _one = ONE_CELL.lock().unwrap_or_else(|e| e.into_inner());
    let path = cell_file("across");
    // As `handstack cell` runs it from beside paper-scenes (target/debug): the cell file's
    // nodes name their program, `paper-scenes`, found beside the running one.
    let handstack = program().with_file_name("handstack");
    let run = launch::run(&path, &handstack, &Stop::new(), |_| {}).expect("the cell run");
    let r = &run.report;
    assert_eq!(r.rows.len(), 9, "{r:?}");
    assert_eq!(r.lost_contacts, 0);
    assert_eq!(r.malformed, 0);
    for row in &r.rows {
        assert!(row.tcp_error_m < 1e-4, "{row:?}");
        assert!(
            row.contact_latency_s.is_finite() && row.contact_latency_s < 1.0,
            "{row:?}"
        );
    }
    let seqs: Vec<i64> = r.rows.iter().map(|x| x.seq).collect();
    let first = seqs[0];
    assert_eq!(
        seqs,
        (first..first + 9).collect::<Vec<_>>(),
        "contacts in order"
    );
    let reference = in_process_located(first as usize + 8);
    for row in &r.rows {
        assert_eq!(
            row.region,
            reference[row.seq as usize - 1],
            "tap {}: across processes vs in process",
            row.seq
        );
    }
    let outcome = paper_scenes::cell::outcome(&path, &run);
    let tapped = paper_scenes::cell::tapped_regions(&run.cell).unwrap();
    let right = r
        .rows
        .iter()
        .filter(|x| tapped[x.seq as usize - 1] == x.region)
        .count();
    let acc = outcome.figure("tap_accuracy_pct").unwrap().value;
    assert!((acc - 100.0 * right as f64 / 9.0).abs() < 1e-9);
}

#[test]
fn a_pad_node_killed_mid_run_is_seen_going_and_the_arm_is_stopped() {
    if !python_ok() {
        return;
    }
    let _one = ONE_CELL.lock().unwrap_or_else(|e| e.into_inner());
    let path = cell_file("killed");
    let cell = CellFile::load(&path).unwrap();
    let _router = Router::open(&cell.router).unwrap();
    let nodes = Mutex::new(start_nodes(&cell, &program()).unwrap());
    let mut options = NodeOptions::new("/cell", "coordinator");
    options.session = SessionConfig::peer(&cell.router);
    let node = Node::open(options).unwrap();
    let grid = RegionToGrid::ur3_default().unwrap();
    let mut killed_at = None;
    let mut udp = Vec::new();
    let result = coordinator::run(&node, &TapToMoveCell::new(9), &grid, &Stop::new(), |_| {
        if killed_at.is_none() {
            let mut n = nodes.lock().unwrap();
            // Nothing may leave the loopback: no node process holds a UDP socket.
            for ns in ["/pad0", "/arm0"] {
                let pid = n.child_mut(ns).unwrap().id();
                udp.extend(hand_zenoh::config::udp_sockets(Some(pid)));
            }
            n.child_mut("/pad0").unwrap().kill().unwrap();
            killed_at = Some(Instant::now());
        }
    });
    let seen_after = killed_at.expect("a tap before the kill").elapsed();
    eprintln!("the killed pad node was seen leaving {seen_after:?} after the kill");
    assert_eq!(
        udp,
        Vec::<String>::new(),
        "UDP sockets in the node processes"
    );
    match result {
        Err(CellError::Graph { node, what }) => {
            assert_eq!(node, "/pad0");
            assert!(what.contains("left the graph after 1 taps"), "{what}");
        }
        other => panic!("expected the pad node's loss, got {other:?}"),
    }
    // The bound the docs state: a killed node's TCP link closes at once on loopback, the router
    // withdraws its tokens; seen well within 2 s (the coordinator polls every 50 ms).
    assert!(seen_after.as_secs_f64() < 2.0, "{seen_after:?}");
    let logs = nodes.into_inner().unwrap().finish();
    let arm = logs
        .iter()
        .find(|(ns, _)| ns == "/arm0")
        .map(|(_, l)| l.as_str());
    assert!(
        arm.is_some_and(|l| l.contains(" 1 stops asked")),
        "the arm node was not told to stop: {arm:?}"
    );
}

#[test]
fn a_hand_node_goes_to_its_safe_state_when_its_command_stream_stops() {
    use hand_zenoh::keys::EntityKind;
    use hand_zenoh::msg::geometry_msgs::WrenchStamped;
    use hand_zenoh::msg::handstack_msgs::{GraspState, GripperCommand};
    use hand_zenoh::msg::std_srvs::{Trigger, TriggerRequest};
    use handstack::cell::{NodeArgs, Part};
    use std::time::Duration;

    let wait = Duration::from_secs(20);
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let stop = Stop::new();
    // The Table 5 world (its first object, the cube) behind the real driver and Protocol 2.0,
    // paced at 5 × real time, with the built-in force DNN; the world is single-threaded, so it
    // is made in the node's thread.
    let hand = {
        let (endpoint, stop) = (endpoint.clone(), stop.clone());
        std::thread::spawn(move || {
            let path = root().join("fixtures/scenes/grasp-table5.toml");
            let text = std::fs::read_to_string(&path).expect("the scene")
                + "\n[estimators.force]\nmodel = \"sim\"\n";
            let scene = PaperScene::parse("grasp-table5-with-force.toml", &text)?;
            let progress = handstack::progress::Quiet;
            let cx = paper_scenes::runs::RunContext::new(&progress);
            let args = NodeArgs {
                part: Part::Hand,
                namespace: "/hand0".into(),
                connect: endpoint,
                domain_id: 0,
                humble: false,
            };
            paper_scenes::cell::run_node(&scene, &args, 5.0, &cx, &stop)
        })
    };
    let mut options = NodeOptions::new("/cell", "commander");
    options.session = SessionConfig::peer(&endpoint);
    let commander = Node::open(options).unwrap();
    for (kind, name) in [
        (EntityKind::Service, "/hand0/grasp/start"),
        (EntityKind::Subscription, "/hand0/gripper/command"),
        (EntityKind::Publisher, "/hand0/force"),
    ] {
        assert!(commander.wait_for(kind, name, wait).unwrap(), "{name}");
    }
    let mut state = commander
        .subscription::<GraspState>("/hand0/grasp/state", 4096)
        .unwrap();
    let mut force = commander
        .subscription::<WrenchStamped>("/hand0/force", 4096)
        .unwrap();
    let mut joints = commander
        .subscription::<hand_zenoh::msg::sensor_msgs::JointState>(
            "/hand0/gripper/joint_states",
            4096,
        )
        .unwrap();
    let mut command = commander
        .publisher::<GripperCommand>("/hand0/gripper/command")
        .unwrap();
    assert!(command.wait_matched(wait).unwrap());
    let mut start = commander.client::<Trigger>("/hand0/grasp/start").unwrap();
    assert!(start.call(&TriggerRequest {}, wait).unwrap().success);
    let first = state.recv_timeout(wait).unwrap().expect("a state").message;
    // Goals whose attachment no rmw_zenoh writes (3 bytes; 33 with a GID length of 3): counted
    // as unreadable, never acted on.
    {
        use hand_zenoh::msg::Message as _;
        use zenoh::Wait as _;
        let goal = GripperCommand {
            position_rad: first.position_rad + 0.3,
            ..Default::default()
        }
        .to_cdr();
        let mut gid3 = hand_zenoh::attachment::Attachment {
            sequence_number: 1,
            source_timestamp: 2,
            source_gid: [5; 16],
        }
        .encode();
        gid3[16] = 3;
        for attachment in [vec![1, 2, 3], gid3.to_vec()] {
            commander
                .session()
                .put(command.key(), goal.clone())
                .attachment(attachment)
                .wait()
                .unwrap();
        }
    }
    // A goal 0.3 rad past the servo's start (inside the rig's limits), and one far outside
    // them: taken, and refused.
    for position_rad in [first.position_rad + 0.3, first.position_rad + 3.0] {
        command
            .publish(&GripperCommand {
                position_rad,
                ..Default::default()
            })
            .unwrap();
    }
    // Grasping (mode 1, in contact), then the command stream's publisher goes.
    let deadline = Instant::now() + wait;
    loop {
        assert!(Instant::now() < deadline, "the hand never grasped");
        let s = state.recv_timeout(Duration::from_millis(100)).unwrap();
        if s.is_some_and(|s| s.message.mode == 1 && s.message.in_contact) {
            break;
        }
    }
    drop(command);
    // The loop stops: no state for half a second (bounded).
    let deadline = Instant::now() + wait;
    let mut last = Instant::now();
    while last.elapsed() < Duration::from_millis(500) {
        assert!(Instant::now() < deadline, "the hand kept grasping");
        if state
            .recv_timeout(Duration::from_millis(50))
            .unwrap()
            .is_some()
        {
            last = Instant::now();
        }
    }
    stop.set();
    let report = hand.join().unwrap().expect("the hand node");
    // `force` from the loop's frames once it had tared: near zero on the open fingertip, then
    // the grasp's load (the cube's Table 5 grip rises the pad by tens of gf at least).
    let mut z = Vec::new();
    while let Some(m) = force.recv_timeout(Duration::from_millis(200)).unwrap() {
        assert_eq!(m.message.header.frame_id, "hand0");
        z.push(m.message.wrench.force.z);
    }
    assert!(z.len() > 10 && z.iter().all(|f| f.is_finite()), "{z:?}");
    // `joint_states`: one joint's position and velocity; no effort, which JointState defines in
    // N·m or N and the servo reports only as a load fraction (that is in `grasp/state`).
    let joint = joints
        .recv_timeout(Duration::from_millis(200))
        .unwrap()
        .expect("a joint state")
        .message;
    assert_eq!(
        (
            joint.position.len(),
            joint.velocity.len(),
            joint.effort.len()
        ),
        (1, 1, 0),
        "{joint:?}"
    );
    let (first, peak) = (z[0], z.iter().copied().fold(f64::MIN, f64::max));
    assert!(
        first.abs() < 0.2,
        "tared, the open fingertip reads {first} N"
    );
    assert!(
        peak > first + 0.2,
        "the grasp never loaded the pad: {first} → {peak} N"
    );
    // The full-hand scene's force DNN (`sim`): what it published beyond its rated range is
    // counted as such.
    let [lo, hi] =
        tactile_nets::force_dnn::valid_range_gf(tactile_nets::pretrained::FORCE_DNN_SIM.range_gf())
            .map(|gf| f64::from(gf * hand_traits::GRAM_FORCE_N));
    let beyond = z.iter().filter(|&&f| !(lo..=hi).contains(&f)).count();
    assert!(
        report.contains(&format!(
            "forces: {} published ({beyond} beyond the model's range), 0 frames refused",
            z.len()
        )),
        "{report}"
    );
    assert!(report.contains(" 1 safe stops;"), "{report}");
    assert!(
        report.contains("goals: 1 taken, 1 refused, 2 unreadable"),
        "{report}"
    );
    assert!(report.contains("; 1 starts,"), "{report}");
    // However the node ends, the hand gets its end action (release, then torque off).
    assert!(report.ends_with("then torque off (cube)"), "{report}");
}

#[test]
fn a_scenes_whole_stack_runs_as_one_node_process() {
    use hand_zenoh::keys::EntityKind;
    use std::io::Read as _;
    use std::process::{Command, Stdio};
    use std::time::Duration;
    if !python_ok() {
        return;
    }
    let _one = ONE_CELL.lock().unwrap_or_else(|e| e.into_inner());
    let wait = Duration::from_secs(30);
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    // The full hand, no --part: its hand (with the fingertip and the force DNN), its pad and
    // its arm, each a node in its default namespace.
    let mut child = Command::new(program())
        .arg("node")
        .arg(root().join("fixtures/scenes/full-hand.toml"))
        .args(["--connect", &endpoint])
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("paper-scenes node");
    let mut stderr = child.stderr.take().unwrap();
    let log = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = stderr.read_to_string(&mut s);
        s
    });
    let mut options = NodeOptions::new("/cell", "watcher");
    options.session = SessionConfig::peer(&endpoint);
    let watcher = Node::open(options).unwrap();
    for (kind, name) in [
        (EntityKind::Service, "/hand0/grasp/start"),
        (EntityKind::Publisher, "/hand0/force"),
        (EntityKind::Publisher, "/pad0/imu"),
        (EntityKind::Publisher, "/pad0/tactile/contact"),
        (EntityKind::Publisher, "/arm0/joint_states"),
    ] {
        let seen = watcher.wait_for(kind, name, wait).unwrap();
        if !seen {
            let _ = child.kill();
            panic!("{name} never appeared; node log:\n{}", log.join().unwrap());
        }
    }
    // A current ROS 2 node (the independent rmw_zenoh client, current attachments) starts
    // the grasp, commands the hand and sends the arm a goal; the nodes act on them.
    commanded_by_a_ros2_client(&endpoint, &watcher);
    // Closing stdin stops every part; the process ends on its own, successfully.
    drop(child.stdin.take());
    let deadline = Instant::now() + wait;
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("the node process did not end after stdin closed");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    let log = log.join().unwrap();
    assert!(status.success(), "{status}: {log}");
    for part in ["/hand0 hand: ", "/pad0 pad: ", "/arm0 arm: "] {
        assert!(log.contains(part), "no {part:?} in {log}");
    }
    // The hand took the five goals inside its limits and refused the one outside; the arm
    // refused the goal in a frame it does not publish in and moved to the one in its own.
    assert!(
        log.contains("goals: 5 taken, 1 refused, 0 unreadable; 1 starts,"),
        "{log}"
    );
    assert!(
        log.contains("/arm0 arm: 1 goals, 1 refused (another frame), 0 unreadable, 1 moves done"),
        "{log}"
    );
}

/// Runs `python/interop/ros_zenoh_client.py` with `args`; its JSON report.
fn ros_client(args: &[&str]) -> serde_json::Value {
    let py = std::env::var_os("HANDSTACK_PYTHON").expect("HANDSTACK_PYTHON");
    let (command, rest) = args.split_first().expect("a subcommand");
    let out = std::process::Command::new(py)
        .arg(root().join("python/interop/ros_zenoh_client.py"))
        .arg(command)
        .arg("--msgs")
        .arg(root().join("crates/hand-zenoh/ros/handstack_msgs"))
        .args(rest)
        .output()
        .expect("run the python client");
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success(), "client {args:?}: {text}");
    serde_json::from_str(text.trim()).unwrap_or_else(|e| panic!("{e}: {text}"))
}

/// The full hand's nodes, commanded as a ROS 2 node on a current rmw_zenoh would: `grasp/start`
/// called, six `GripperCommand`s (five inside the rig's goal limits, one 3 rad outside), an
/// arm goal in frame `base` (refused) and one in the arm's `arm0_base` at the UR3 grid's
/// region 5, which the arm reaches (its `tcp_pose` read back here).
fn commanded_by_a_ros2_client(endpoint: &str, watcher: &Node) {
    use hand_zenoh::convert::{pose_from_msg, pose_to_msg};
    use hand_zenoh::msg::geometry_msgs::PoseStamped;
    use std::time::Duration;

    let common = ["--connect", endpoint, "--timeout", "30"];
    let call = [
        &["call", "--service", "/hand0/grasp/start", "--seq", "3"],
        &common[..],
    ]
    .concat();
    let started = ros_client(&call);
    assert_eq!(started["response"]["success"], true, "{started}");
    assert_eq!(started["seq_echoed"], true, "{started}");
    let origin = hand_sim::grasp::rig::ORIGIN_RAD;
    for (position, count) in [(origin + 0.3, "5"), (origin + 3.0, "1")] {
        let json = format!(r#"{{"header": {{"frame_id": "hand0"}}, "position_rad": {position}}}"#);
        let publish = [
            &[
                "publish",
                "--topic",
                "/hand0/gripper/command",
                "--type",
                "handstack_msgs/msg/GripperCommand",
                "--json",
                &json,
                "--count",
                count,
                "--rate",
                "50",
            ],
            &common[..],
        ]
        .concat();
        let sent = ros_client(&publish);
        assert_eq!(sent["published"].to_string(), count, "{sent}");
    }
    let mut tcp = watcher
        .subscription::<PoseStamped>("/arm0/tcp_pose", 64)
        .unwrap();
    let grid = RegionToGrid::ur3_default().unwrap();
    let target = *grid.pose(5).unwrap();
    let m = pose_to_msg(&target);
    let (p, q) = (m.position, m.orientation);
    for frame in ["base", "arm0_base"] {
        let json = format!(
            r#"{{"header": {{"frame_id": "{frame}"}}, "pose": {{"position": {{"x": {}, "y": {}, "z": {}}}, "orientation": {{"x": {}, "y": {}, "z": {}, "w": {}}}}}}}"#,
            p.x, p.y, p.z, q.x, q.y, q.z, q.w
        );
        // The goal's writer stays in the graph for the move (a writer that leaves mid-move
        // stops the arm: its safe state).
        let publish = [
            &[
                "publish",
                "--topic",
                "/arm0/goal",
                "--type",
                "geometry_msgs/msg/PoseStamped",
                "--json",
                &json,
                "--count",
                "1",
                "--linger",
                if frame == "base" { "0" } else { "10" },
            ],
            &common[..],
        ]
        .concat();
        if frame == "base" {
            ros_client(&publish);
            continue;
        }
        let publish: Vec<String> = publish.iter().map(ToString::to_string).collect();
        let mover = std::thread::spawn(move || {
            ros_client(&publish.iter().map(String::as_str).collect::<Vec<_>>())
        });
        let deadline = Instant::now() + Duration::from_secs(10);
        let mut last = f64::INFINITY;
        while last > 1e-4 {
            assert!(
                Instant::now() < deadline,
                "the arm never reached the goal: {last} m away"
            );
            if let Some(s) = tcp.recv_timeout(Duration::from_millis(100)).unwrap() {
                last = pose_from_msg(&s.message.pose).distance_m(&target);
                assert_eq!(s.message.header.frame_id, "arm0_base");
            }
        }
        let sent = mover.join().unwrap();
        assert_eq!(sent["published"], 1, "{sent}");
    }
}

/// The node processes `pid` started (its children).
fn children(pid: u32) -> Vec<u32> {
    std::fs::read_to_string(format!("/proc/{pid}/task/{pid}/children"))
        .unwrap_or_default()
        .split_whitespace()
        .filter_map(|p| p.parse().ok())
        .collect()
}

/// `handstack cell` as a user runs it, stopped by Ctrl-C mid-run: the nodes are stopped through
/// their own shutdown (each prints its report), none is left running, and the status is 130.
#[test]
fn handstack_cell_stopped_by_sigint_stops_its_nodes_and_says_so() {
    use std::process::{Command, Stdio};
    use std::time::Duration;
    if !python_ok() {
        return;
    }
    let _one = ONE_CELL.lock().unwrap_or_else(|e| e.into_inner());
    let path = cell_file("sigint");
    let handstack = program().with_file_name("handstack");
    let cell = Command::new(&handstack)
        .arg("cell")
        .arg(&path)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("handstack cell starts");
    // Mid-run: both node processes started (the coordinator then waits for them, then taps).
    let deadline = Instant::now() + Duration::from_secs(30);
    let nodes = loop {
        let nodes = children(cell.id());
        if nodes.len() >= 2 {
            break nodes;
        }
        assert!(Instant::now() < deadline, "the cell started no nodes");
        std::thread::sleep(Duration::from_millis(10));
    };
    let ok = Command::new("kill")
        .args(["-INT", &cell.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(ok.success());
    let (tx, rx) = std::sync::mpsc::channel();
    let waiter = std::thread::spawn(move || {
        let out = cell.wait_with_output();
        let _ = tx.send(());
        out
    });
    rx.recv_timeout(Duration::from_secs(30))
        .expect("the cell ended within 30 s of SIGINT");
    let out = waiter.join().unwrap().expect("output");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(130), "{stderr}");
    assert!(stderr.contains("stopped by SIGINT"), "{stderr}");
    // Each node ended through its shutdown path (stdin closed): its last report line.
    for ns in ["/pad0", "/arm0"] {
        assert!(
            stderr.contains(&format!("[{ns}] {ns} ")),
            "no report from {ns}: {stderr}"
        );
    }
    for pid in nodes {
        assert!(
            !std::path::Path::new(&format!("/proc/{pid}")).exists()
                || std::fs::read_to_string(format!("/proc/{pid}/stat"))
                    .is_ok_and(|s| s.contains(") Z ")),
            "node process {pid} still running"
        );
    }
}
