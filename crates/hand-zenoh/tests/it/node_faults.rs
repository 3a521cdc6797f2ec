//! What a node does with bad input and a broken cell: malformed payloads, attachments and
//! service requests are counted and dropped; a node that goes is seen going by its liveliness
//! token; a router restart loses nothing silently (every sequence number is received or counted
//! lost); a force estimator's refusals are counted, not published; and nothing opens a UDP
//! socket. All on 127.0.0.1, multicast scouting off.

use crate::common::node;

use hand_zenoh::attachment::{Attachment, AttachmentError, Layout};
use hand_zenoh::keys::{self, EntityKind};
use hand_zenoh::msg::handstack_msgs::PressureFrame;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerRequest, TriggerResponse};
use hand_zenoh::msg::{Message as _, Service as _, service_description};
use hand_zenoh::node::{Node, Publisher, Router, Subscription};
use hand_zenoh::types::{dds_type_name, type_hash};
use std::time::{Duration, Instant};
use zenoh::Wait;

fn frame(p: f32) -> PressureFrame {
    PressureFrame {
        pressure_pa: vec![p; 3],
        ..Default::default()
    }
}

const WAIT: Duration = Duration::from_secs(10);

/// A writer node and a reader node of `/hand0/tactile/raw` (the reader holding `depth`), once
/// the reader has seen the writer.
fn talking(
    endpoint: &str,
    depth: usize,
) -> (
    Node,
    Node,
    Publisher<PressureFrame>,
    Subscription<PressureFrame>,
) {
    let a = node(endpoint, "/hand0", "tactile");
    let b = node(endpoint, "/hand0", "reader");
    let publisher = a.publisher::<PressureFrame>("tactile/raw").unwrap();
    let sub = b
        .subscription::<PressureFrame>("/hand0/tactile/raw", depth)
        .unwrap();
    assert!(
        b.wait_for(EntityKind::Publisher, "/hand0/tactile/raw", WAIT)
            .unwrap()
    );
    // And the writer knows the reader (its subscription travels through the router): without
    // this wait a first frame can go out before there is a route for it.
    assert!(publisher.wait_matched(WAIT).unwrap());
    (a, b, publisher, sub)
}

#[test]
fn malformed_samples_and_requests_are_counted_and_dropped() {
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let (a, b, mut publisher, mut sub) = talking(&endpoint, 64);
    let key = publisher.key().to_owned();
    let good = frame(101_325.0).to_cdr();
    let raw = a.session();
    // Wrong length, wrong encapsulation, a count far beyond the payload, a bad attachment.
    raw.put(&key, good[..good.len() - 3].to_vec())
        .wait()
        .unwrap();
    let mut big_endian = good.clone();
    big_endian[1] = 0x00;
    raw.put(&key, big_endian).wait().unwrap();
    let mut huge = good.clone();
    let n = huge.len();
    huge[n - 16..n - 12].copy_from_slice(&u32::MAX.to_le_bytes());
    raw.put(&key, huge).wait().unwrap();
    // Attachments no rmw_zenoh writes: 3 bytes; 33 with a GID length of 3; twice the first
    // kind (said once).
    raw.put(&key, good.clone())
        .attachment(vec![1, 2, 3])
        .wait()
        .unwrap();
    let mut gid3 = Attachment {
        sequence_number: 1,
        source_timestamp: 2,
        source_gid: [5; 16],
    }
    .encode();
    gid3[16] = 3;
    raw.put(&key, good.clone()).attachment(gid3).wait().unwrap();
    raw.put(&key, good.clone())
        .attachment(vec![9, 9, 9])
        .wait()
        .unwrap();
    // No attachment (a bare Zenoh writer), and the layout of rmw_zenoh ≤ 0.2.3: read, counted.
    raw.put(&key, good.clone()).wait().unwrap();
    let old = Attachment {
        sequence_number: 1,
        source_timestamp: 2,
        source_gid: [6; 16],
    };
    raw.put(&key, good.clone())
        .attachment(old.encode_legacy())
        .wait()
        .unwrap();
    // A writer's first sample is sequence number 1 (rmw_zenoh's publishers count from 1).
    assert_eq!(publisher.publish(&frame(7.0)).unwrap(), 1);
    let bare = sub.recv_timeout(WAIT).unwrap().expect("the bare frame");
    assert_eq!(bare.attachment, None);
    let legacy = sub
        .recv_timeout(WAIT)
        .unwrap()
        .expect("the older layout's frame");
    assert_eq!(legacy.attachment, Some(old));
    let got = sub.recv_timeout(WAIT).unwrap().expect("the good frame");
    assert_eq!(got.message, frame(7.0));
    assert_eq!(
        got.attachment.map(|a| (a.sequence_number, a.source_gid)),
        Some((1, publisher.gid()))
    );
    let stats = sub.stats();
    assert_eq!(
        (stats.malformed, stats.refused, stats.received),
        (3, 3, 3),
        "{stats:?}"
    );
    assert_eq!(
        (stats.missing_attachment, stats.legacy_attachment),
        (1, 1),
        "{stats:?}"
    );
    assert_eq!(
        sub.new_refusals(),
        [AttachmentError::Length(3), AttachmentError::GidLength(3)]
    );
    assert!(sub.new_refusals().is_empty(), "said twice");

    let server = a
        .service::<Trigger, _>("tactile/tare", |_| TriggerResponse {
            success: true,
            message: "ok".into(),
        })
        .unwrap();
    assert!(
        b.wait_for(EntityKind::Service, "/hand0/tactile/tare", WAIT)
            .unwrap()
    );
    let mut client = b.client::<Trigger>("/hand0/tactile/tare").unwrap();
    let ok = client.call(&TriggerRequest {}, WAIT).unwrap();
    assert!(ok.success);
    // A request that is not a Trigger request: an error reply, counted.
    let service_key = keys::topic_key(
        0,
        "/hand0/tactile/tare",
        &dds_type_name(Trigger::NAME),
        &type_hash(&service_description::<Trigger>()).to_string(),
    );
    let replies = raw
        .get(&service_key)
        .payload(vec![0u8; 2])
        .timeout(WAIT)
        .wait()
        .unwrap();
    let reply = replies.recv().expect("a reply");
    assert!(reply.result().is_err(), "garbage got a success reply");
    // A request without an attachment cannot be answered as a ROS 2 client expects (the reply
    // echoes its sequence number and GID): an error reply, counted.
    let replies = raw
        .get(&service_key)
        .payload(TriggerRequest {}.to_cdr())
        .timeout(WAIT)
        .wait()
        .unwrap();
    let reply = replies.recv().expect("a reply");
    assert!(reply.result().is_err(), "no attachment got a success reply");
    // One in the older layout is answered, echoing its sequence number and GID.
    let asked = Attachment {
        sequence_number: 41,
        source_timestamp: 3,
        source_gid: [7; 16],
    };
    let replies = raw
        .get(service_key)
        .payload(TriggerRequest {}.to_cdr())
        .attachment(asked.encode_legacy())
        .timeout(WAIT)
        .wait()
        .unwrap();
    let reply = replies.recv().expect("a reply");
    let sample = reply.result().expect("a success reply");
    let (echo, layout) =
        Attachment::read(&sample.attachment().expect("an attachment").to_bytes()).unwrap();
    assert_eq!(layout, Layout::Current);
    assert_eq!((echo.sequence_number, echo.source_gid), (41, [7; 16]));
    assert_eq!(server.handled(), 2);
    assert_eq!(server.malformed(), 1);
    assert_eq!(server.refused(), 1);
}

#[test]
fn a_node_that_goes_is_seen_going() {
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let watcher = node(&endpoint, "/cell", "coordinator");
    let graph = watcher.graph().unwrap();
    let hand = node(&endpoint, "/hand0", "grasp");
    let publisher = hand.publisher::<PressureFrame>("tactile/raw").unwrap();
    assert!(
        watcher
            .wait_for(EntityKind::Publisher, "/hand0/tactile/raw", WAIT)
            .unwrap()
    );
    drop(publisher);
    let gone = Instant::now();
    // The node goes as a process that exits cleanly: its session closed (a dropped handle may
    // close in the background, and a vanished peer is only noticed at its lease, 10 s).
    hand.session().close().wait().unwrap();
    drop(hand);
    let deadline = gone + WAIT;
    let mut seen = None;
    while let Some(left) = deadline.checked_duration_since(Instant::now()) {
        match graph.recv_timeout(left).unwrap() {
            Some(c) if !c.alive && c.kind == Some(EntityKind::Node) && c.namespace == "%hand0" => {
                seen = Some(gone.elapsed());
                break;
            }
            Some(_) => {}
            None => break,
        }
    }
    let seen = seen.expect("the node's token did not go");
    // A closed session withdraws its tokens at once: well under a second on loopback.
    assert!(seen < Duration::from_secs(1), "{seen:?}");
}

#[test]
fn a_router_restart_loses_nothing_silently() {
    let (first, endpoint) = Router::open_on_loopback().unwrap();
    let (_a, _b, mut publisher, mut sub) = talking(&endpoint, 1024);
    let mut published = 0;
    let mut first_seq = None;
    let recv_one = |sub: &mut Subscription<PressureFrame>| {
        sub.recv_timeout(Duration::from_millis(50))
            .unwrap()
            .and_then(|r| r.attachment)
            .map(|a| a.sequence_number)
    };
    for i in 0..20 {
        published = publisher.publish(&frame(i as f32)).unwrap();
        if let Some(s) = recv_one(&mut sub) {
            first_seq.get_or_insert(s);
        }
    }
    first.close().unwrap();
    for i in 0..20 {
        published = publisher.publish(&frame(i as f32)).unwrap();
    }
    let _second = Router::open(&endpoint).unwrap();
    // Publish until the reader hears from the writer again (bounded), then drain.
    let deadline = Instant::now() + WAIT;
    let mut heard_again = false;
    while Instant::now() < deadline && !heard_again {
        published = publisher.publish(&frame(1.0)).unwrap();
        heard_again = recv_one(&mut sub).is_some_and(|s| s > 40);
    }
    assert!(heard_again, "no frame after the router came back");
    while recv_one(&mut sub).is_some() {}
    let s = sub.stats();
    let first_seq = first_seq.expect("frames before the restart") as u64;
    // Every sequence number from the first received on is either received or counted lost.
    assert_eq!(
        s.received + s.lost,
        published as u64 - first_seq + 1,
        "{s:?}, published {published}"
    );
}

#[test]
fn no_udp_socket_is_opened() {
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let (_a, _b, mut publisher, mut sub) = talking(&endpoint, 8);
    publisher.publish(&frame(1.0)).unwrap();
    assert!(sub.recv_timeout(WAIT).unwrap().is_some());
    assert!(std::path::Path::new("/proc/net/udp").exists());
    assert_eq!(hand_zenoh::config::udp_sockets(None), Vec::<String>::new());
}

/// Seed 000's fingertip with a load that comes and goes: three frames at rest, then the frames
/// `loads_pa` above rest, one per step.
struct Loaded {
    rest_pa: [f32; 3],
    loads_pa: Vec<[f32; 3]>,
    read: usize,
}

impl hand_traits::TactileSource for Loaded {
    type Frame = hand_traits::PressureFrame<3>;
    type Error = core::convert::Infallible;
    fn read_frame(&mut self) -> Result<Self::Frame, Self::Error> {
        let load = self
            .read
            .checked_sub(3)
            .map_or([0.0; 3], |i| self.loads_pa[i]);
        self.read += 1;
        Ok(hand_traits::PressureFrame {
            t_us: 0,
            pressure_pa: std::array::from_fn(|k| self.rest_pa[k] + load[k]),
        })
    }
}

/// 1 N per hPa of summed rise; out of its range above 20 hPa, refuses more than 50 hPa (an
/// estimator's typed error).
struct Linear;

impl hand_traits::ForceEstimator for Linear {
    type Input = [f32];
    type Error = &'static str;
    fn estimate_force(
        &mut self,
        rise_hpa: &[f32],
    ) -> Result<hand_traits::ForceEstimate, Self::Error> {
        let sum: f32 = rise_hpa.iter().sum();
        if sum > 50.0 {
            return Err("beyond the rated range");
        }
        Ok(hand_traits::ForceEstimate {
            force_n: sum,
            in_range: sum <= 20.0,
        })
    }
}

#[test]
fn a_force_estimate_is_published_once_tared_and_a_refusal_is_counted() {
    use hand_zenoh::msg::geometry_msgs::WrenchStamped;
    use hand_zenoh::tactile::{TactileInfo, TactileNode};
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let a = node(&endpoint, "/hand0", "tactile");
    let b = node(&endpoint, "/hand0", "reader");
    let source = Loaded {
        rest_pa: [119_125.0, 119_902.0, 101_804.0],
        // 6 hPa in all; 60 hPa (refused); 0.5 hPa; 30 hPa (beyond the range).
        loads_pa: vec![
            [100.0, 200.0, 300.0],
            [2000.0, 2000.0, 2000.0],
            [50.0, 0.0, 0.0],
            [1000.0, 1000.0, 1000.0],
        ],
        read: 0,
    };
    let info = TactileInfo {
        chip: "MS5611".into(),
        rate_hz: 100.0,
        frame_id: "hand0/fingertip0".into(),
    };
    let mut tactile = TactileNode::new(&a, source, info)
        .unwrap()
        .with_force(&a, Linear, 3)
        .unwrap();
    let mut sub = b.subscription::<WrenchStamped>("/hand0/force", 16).unwrap();
    assert!(
        b.wait_for(EntityKind::Publisher, "/hand0/force", WAIT)
            .unwrap()
    );
    assert!(
        tactile
            .force()
            .unwrap()
            .publisher()
            .wait_matched(WAIT)
            .unwrap()
    );
    for _ in 0..7 {
        tactile.step().unwrap();
    }
    // Nothing before the start-up tare's third frame; that frame itself is the zero (0 N).
    let mut got = Vec::new();
    while got.len() < 4 {
        let m = sub.recv_timeout(WAIT).unwrap().expect("a force message");
        got.push(m.message);
    }
    let z: Vec<f64> = got.iter().map(|m| m.wrench.force.z).collect();
    assert_eq!(got[0].header.frame_id, "hand0/fingertip0");
    assert!(z[0].abs() < 1e-6, "{z:?}");
    assert!((z[1] - 6.0).abs() < 1e-3, "{z:?}");
    // The refused 60 hPa frame published nothing: the next message is the 0.5 hPa frame.
    assert!((z[2] - 0.5).abs() < 1e-3, "{z:?}");
    // Beyond the range: published as estimated, and counted.
    assert!((z[3] - 30.0).abs() < 1e-3, "{z:?}");
    let force = tactile.force().unwrap();
    assert_eq!(force.beyond_range(), 1);
    assert_eq!(force.refused(), 1);
    assert_eq!(force.last_refusal(), Some("beyond the rated range"));
    for m in &got {
        let w = &m.wrench;
        assert_eq!(
            [w.force.x, w.force.y, w.torque.x, w.torque.y, w.torque.z],
            [0.0; 5]
        );
    }
}
