//! Checked by code no one here wrote: rosbags (ROS 2 type hashes and CDR from the `.msg`
//! files and its Jazzy type store) and a Python subscriber on eclipse-zenoh that computes the
//! keys itself (`python/interop/ros_zenoh_client.py`). Needs `$HANDSTACK_PYTHON` (`cargo xtask
//! test` sets it to the workspace venv); skipped without it. Everything on 127.0.0.1, multicast
//! scouting off.

use crate::common::free_endpoint;
use crate::python::{client, client_text, hex, msgs_dir, python, root};

use hand_traits::{PressureFrame as Frame, TactileSource};
use hand_zenoh::HashMode;
use hand_zenoh::config::SessionConfig;
use hand_zenoh::msg::builtin_interfaces::Time;
use hand_zenoh::msg::geometry_msgs::{
    Point, Pose, PoseStamped, Quaternion, Vector3, Wrench, WrenchStamped,
};
use hand_zenoh::msg::handstack_msgs::{
    Contact, ContactArray, Fault, Figure, FingerFrame, FingertipFrame, GraspState, GripperCommand,
    Label, PressureFrame, SensorInfo, Softness,
};
use hand_zenoh::msg::sensor_msgs::{ChannelFloat32, Imu, JointState};
use hand_zenoh::msg::std_msgs::Header;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerRequest, TriggerResponse};
use hand_zenoh::msg::{Message, service_description};
use hand_zenoh::node::{Node, NodeOptions, Router};
use hand_zenoh::tactile::{TactileInfo, TactileNode};
use hand_zenoh::types::{TypeDescription, type_hash};
use serde_json::Value;

use std::path::Path;
use std::process::{Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

fn descriptions() -> Vec<TypeDescription> {
    vec![
        PressureFrame::description(),
        Contact::description(),
        ContactArray::description(),
        SensorInfo::description(),
        GraspState::description(),
        GripperCommand::description(),
        FingerFrame::description(),
        Softness::description(),
        Figure::description(),
        Fault::description(),
        Label::description(),
        FingertipFrame::description(),
        Imu::description(),
        JointState::description(),
        ChannelFloat32::description(),
        WrenchStamped::description(),
        PoseStamped::description(),
        Header::description(),
        Time::description(),
        service_description::<Trigger>(),
    ]
}

/// `std_srvs/srv/Trigger` on ROS 2 Jazzy, as rmw_zenoh puts it in the service's key: the value
/// several independent public ROS 2 / rmw_zenoh clients pin (rosbags has no service types, so
/// the Python side builds the service description from REP 2011; this pins it independently).
const TRIGGER_JAZZY: &str =
    "RIHS01_eeff2cd6fa5ad9d27cdf4dec64818317839b62f212a91e6b5304b634b2062c5f";

#[test]
fn the_trigger_service_hash_is_jazzys() {
    assert_eq!(
        type_hash(&service_description::<Trigger>()).to_string(),
        TRIGGER_JAZZY
    );
}

#[test]
fn type_hashes_match_rosbags() {
    let Some(py) = python() else { return };
    let theirs = client(&py, &["hashes", "--msgs", msgs_dir().to_str().unwrap()]);
    for d in descriptions() {
        let ours = type_hash(&d).to_string();
        assert_eq!(
            theirs[d.name].as_str(),
            Some(ours.as_str()),
            "{}: rosbags says {}",
            d.name,
            theirs[d.name]
        );
    }
}

fn header(frame: &str) -> Header {
    Header {
        stamp: Time {
            sec: 1_764_100_000,
            nanosec: 123_456_789,
        },
        frame_id: frame.to_owned(),
    }
}

/// One sample of each message, with values a float represents exactly.
fn samples() -> Vec<(&'static str, Vec<u8>)> {
    let v = |x, y, z| Vector3 { x, y, z };
    vec![
        (
            PressureFrame::NAME,
            PressureFrame {
                header: header("hand0/fingertip0"),
                pressure_pa: vec![101_325.0, 101_400.5, 99_999.25],
            }
            .to_cdr(),
        ),
        (
            ContactArray::NAME,
            ContactArray {
                header: header("pad0"),
                contacts: vec![
                    Contact {
                        region: 4,
                        regions: 9,
                        confidence: 0.75,
                    },
                    Contact {
                        region: 23,
                        regions: 24,
                        confidence: 0.5,
                    },
                ],
            }
            .to_cdr(),
        ),
        (
            SensorInfo::NAME,
            SensorInfo {
                header: header("hand0/fingertip0"),
                chip: "MS5611".into(),
                sensor_count: 3,
                rate_hz: 100.0,
                tare_pa: vec![101_325.0, 101_320.5, 101_330.0],
            }
            .to_cdr(),
        ),
        (
            GraspState::NAME,
            GraspState {
                header: header("hand0"),
                mode: 1,
                pressure_pa: 212.5,
                in_contact: true,
                effort: 0.375,
                position_rad: -0.25,
                load_fraction: 0.125,
                faults: 5,
            }
            .to_cdr(),
        ),
        (
            GripperCommand::NAME,
            GripperCommand {
                header: header("hand0"),
                position_rad: 1.5,
                effort: 0.5,
            }
            .to_cdr(),
        ),
        (
            Imu::NAME,
            Imu {
                header: header("pad0"),
                orientation: Quaternion {
                    w: 1.0,
                    ..Default::default()
                },
                orientation_covariance: [-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
                angular_velocity: v(0.5, -0.25, 0.125),
                angular_velocity_covariance: [0.0; 9],
                linear_acceleration: v(0.0, 0.0, 9.8125),
                linear_acceleration_covariance: [0.0; 9],
            }
            .to_cdr(),
        ),
        (
            Label::NAME,
            Label {
                header: header("sensors.fingertip"),
                experiment: "weight".into(),
                name: "weight_gf".into(),
                value: 120.5,
                start: Time {
                    sec: 1_700_000_001,
                    nanosec: 250_000_000,
                },
                end: Time {
                    sec: 1_700_000_002,
                    nanosec: 500,
                },
            }
            .to_cdr(),
        ),
        (
            FingertipFrame::NAME,
            FingertipFrame {
                header: header("hand0"),
                seq: 201,
                t_us: 4_000_123,
                pressure_pa: [101_325, 101_412, -7],
                tared: true,
                in_contact: true,
                fault: false,
                force_gf: 152.25,
                grid_cell: 4,
                pad_cell: 255,
                torque_raw: 612,
            }
            .to_cdr(),
        ),
        (
            JointState::NAME,
            JointState {
                header: header("arm0"),
                name: (1..=6).map(|i| format!("joint{i}")).collect(),
                position: vec![0.0, -1.5, 1.25, -1.25, -1.5, 0.0],
                velocity: vec![0.0; 6],
                effort: vec![],
            }
            .to_cdr(),
        ),
        (
            WrenchStamped::NAME,
            WrenchStamped {
                header: header("hand0/fingertip0"),
                wrench: Wrench {
                    force: v(0.0, 0.0, 12.5),
                    torque: v(0.0, 0.0, 0.0),
                },
            }
            .to_cdr(),
        ),
        (
            PoseStamped::NAME,
            PoseStamped {
                header: header("base"),
                pose: Pose {
                    position: Point {
                        x: 0.25,
                        y: -0.125,
                        z: 0.5,
                    },
                    orientation: Quaternion {
                        x: 1.0,
                        ..Default::default()
                    },
                },
            }
            .to_cdr(),
        ),
        ("std_srvs/srv/Trigger_Request", TriggerRequest {}.to_cdr()),
        (
            "std_srvs/srv/Trigger_Response",
            TriggerResponse {
                success: true,
                message: "tared".into(),
            }
            .to_cdr(),
        ),
    ]
}

#[test]
fn cdr_is_what_rosbags_reads_and_writes_byte_for_byte() {
    let Some(py) = python() else { return };
    for (name, bytes) in samples() {
        let got = client(&py, &["cdr", "--type", name, "--hex", &hex(&bytes)]);
        assert_eq!(got["roundtrip_identical"], true, "{name}: {got}");
        // And from rosbags' own encoding of the decoded fields: the same bytes as ours.
        let fields = got["fields"].to_string();
        let back = client_text(&py, &["encode", "--type", name, "--json", &fields]);
        assert_eq!(back.trim(), hex(&bytes), "{name}");
    }
}

/// A fingertip whose pressure rises by 1 Pa a frame.
struct Ramp(f32);

impl TactileSource for Ramp {
    type Frame = Frame<3>;
    type Error = core::convert::Infallible;
    fn read_frame(&mut self) -> Result<Frame<3>, Self::Error> {
        self.0 += 1.0;
        Ok(Frame {
            t_us: 0,
            pressure_pa: [self.0, self.0 + 100.0, self.0 + 200.0],
        })
    }
}

/// Runs a tactile node (100 Hz) against the router at `endpoint` while the Python client
/// subscribes to its raw frames and calls its tare service; returns the client's report.
fn python_sees_tactile_node(py: &Path, endpoint: &str, mode: HashMode) -> (Value, String) {
    let mut options = NodeOptions::new("/hand0", "tactile");
    options.session = SessionConfig::peer(endpoint);
    options.hash_mode = mode;
    let node = Node::open(options).expect("open the node");
    let info = TactileInfo {
        chip: "MS5611".into(),
        rate_hz: 100.0,
        frame_id: "hand0/fingertip0".into(),
    };
    let mut tactile = TactileNode::new(&node, Ramp(101_000.0), info).expect("tactile node");
    let key = tactile.raw().key().to_owned();
    let gid = tactile.raw().gid();
    let done = Arc::new(AtomicBool::new(false));
    let stop = Arc::clone(&done);
    let mut args = vec![
        "subscribe",
        "--connect",
        endpoint,
        "--domain",
        "0",
        "--msgs",
        msgs_dir().to_str().unwrap(),
    ]
    .into_iter()
    .map(str::to_owned)
    .collect::<Vec<_>>();
    args.extend(
        [
            "--topic",
            "/hand0/tactile/raw",
            "--type",
            PressureFrame::NAME,
            "--count",
            "20",
            "--timeout",
            "30",
            "--call-service",
            "/hand0/tactile/tare",
            "--service-type",
            "std_srvs/srv/Trigger",
        ]
        .map(str::to_owned),
    );
    if mode == HashMode::Humble {
        args.push("--humble".into());
    }
    let py = py.to_path_buf();
    let handle = std::thread::spawn(move || {
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let v = client(&py, &refs);
        stop.store(true, Ordering::Relaxed);
        v
    });
    // The node's own 100 Hz loop, bounded: at most 60 s of frames.
    let mut steps = 0;
    while !done.load(Ordering::Relaxed) && steps < 6000 {
        tactile.step().expect("step");
        steps += 1;
        std::thread::sleep(Duration::from_millis(10));
    }
    let report = handle.join().expect("client thread");
    assert!(tactile.tares() >= 1, "the tare service was not called");
    assert_eq!(
        report["gid_hex"].as_str(),
        Some(hex(&gid).as_str()),
        "{report}"
    );
    (report, key)
}

fn check_report(report: &Value, key: &str) {
    assert_eq!(report["key"].as_str(), Some(key), "{report}");
    assert_eq!(report["received"], 20, "{report}");
    assert_eq!(report["roundtrip_identical"], 20, "{report}");
    assert_eq!(report["gaps"], 0, "{report}");
    assert_eq!(report["timestamps_monotonic"], true, "{report}");
    // The current rmw_zenoh layout, and the GID rmw_zenoh derives from the publisher's token.
    assert_eq!(
        report["attachment_len"],
        hand_zenoh::attachment::LEN,
        "{report}"
    );
    assert_eq!(report["gid_matches_token"], true, "{report}");
    assert_eq!(report["service"]["seq_echoed"], true, "{report}");
    assert_eq!(report["service"]["gid_echoed"], true, "{report}");
    assert_eq!(report["service"]["success"], true, "{report}");
    assert_eq!(
        report["first_fields"]["header"]["frame_id"],
        "hand0/fingertip0"
    );
    assert_eq!(
        report["first_fields"]["pressure_pa"]
            .as_array()
            .map(Vec::len),
        Some(3)
    );
}

#[test]
fn python_subscriber_reads_frames_and_tares_over_hashed_keys() {
    let Some(py) = python() else { return };
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let (report, key) = python_sees_tactile_node(&py, &endpoint, HashMode::Rihs01);
    assert!(key.contains("/RIHS01_"), "{key}");
    check_report(&report, &key);
}

#[test]
fn python_subscriber_reads_frames_over_humble_keys() {
    let Some(py) = python() else { return };
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let (report, key) = python_sees_tactile_node(&py, &endpoint, HashMode::Humble);
    assert!(key.ends_with("/TypeHashNotSupported"), "{key}");
    check_report(&report, &key);
}

/// The router of the Zenoh version ROS 2 Humble / Jazzy's rmw_zenoh binaries bundle (1.6.x),
/// from eclipse-zenoh 1.6.2 installed beside the venv (`cargo xtask test` puts it there).
#[test]
fn works_through_the_zenoh_1_6_router_rmw_zenoh_bundles() {
    let Some(py) = python() else { return };
    let z16 = py
        .parent()
        .and_then(|bin| bin.parent())
        .map(|venv| venv.join("zenoh-1.6"))
        .expect("venv layout");
    assert!(
        z16.join("zenoh").exists(),
        "{} has no eclipse-zenoh 1.6: `cargo xtask test` installs it",
        z16.display()
    );
    let endpoint = free_endpoint();
    let mut router = Command::new(&py)
        .arg(root().join("python/interop/ros_zenoh_client.py"))
        .args(["router", "--listen", &endpoint, "--seconds", "120"])
        .env("PYTHONPATH", &z16)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("python router");
    let mut line = String::new();
    std::io::BufRead::read_line(
        &mut std::io::BufReader::new(router.stdout.as_mut().unwrap()),
        &mut line,
    )
    .unwrap();
    assert!(line.contains("ready"), "router said {line}");
    assert!(
        line.contains("\"zenoh\": \"1.6."),
        "not rmw_zenoh's Zenoh: {line}"
    );
    let (report, key) = python_sees_tactile_node(&py, &endpoint, HashMode::Rihs01);
    drop(router.stdin.take());
    let _ = router.wait();
    check_report(&report, &key);
}
