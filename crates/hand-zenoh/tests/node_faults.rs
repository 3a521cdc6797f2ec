//! What a node does with bad input and a broken cell: malformed payloads, attachments and
//! service requests are counted and dropped; a node that goes is seen going by its liveliness
//! token; a router restart loses nothing silently (every sequence number is received or counted
//! lost); and nothing opens a UDP socket. All on 127.0.0.1, multicast scouting off.

mod common;

use common::{free_endpoint, node};

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
    let endpoint = free_endpoint();
    let _router = Router::open(&endpoint).unwrap();
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
    raw.put(&key, good.clone())
        .attachment(vec![1, 2, 3])
        .wait()
        .unwrap();
    publisher.publish(&frame(7.0)).unwrap();
    let got = sub.recv_timeout(WAIT).unwrap().expect("the good frame");
    assert_eq!(got.message, frame(7.0));
    assert_eq!(got.attachment.map(|a| a.source_gid), Some(publisher.gid()));
    assert_eq!(sub.stats().malformed, 4, "{:?}", sub.stats());
    assert_eq!(sub.stats().received, 1);

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
        .get(service_key)
        .payload(vec![0u8; 2])
        .timeout(WAIT)
        .wait()
        .unwrap();
    let reply = replies.recv().expect("a reply");
    assert!(reply.result().is_err(), "garbage got a success reply");
    assert_eq!(server.handled(), 1);
    assert_eq!(server.malformed(), 1);
}

#[test]
fn a_node_that_goes_is_seen_going() {
    let endpoint = free_endpoint();
    let _router = Router::open(&endpoint).unwrap();
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
    let endpoint = free_endpoint();
    let first = Router::open(&endpoint).unwrap();
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
    let endpoint = free_endpoint();
    let _router = Router::open(&endpoint).unwrap();
    let (_a, _b, mut publisher, mut sub) = talking(&endpoint, 8);
    publisher.publish(&frame(1.0)).unwrap();
    assert!(sub.recv_timeout(WAIT).unwrap().is_some());
    assert!(std::path::Path::new("/proc/net/udp").exists());
    assert_eq!(hand_zenoh::config::udp_sockets(None), Vec::<String>::new());
}
