//! Both directions with an rmw_zenoh client written from rmw_zenoh's own specification, not
//! from this crate (`python/interop/ros_zenoh_client.py`: eclipse-zenoh's own serializer for
//! the attachment, the `xxhash` package for the GID): the attachment bytes, the GIDs, a
//! current-layout publisher commanding our subscription, a current-layout service client
//! calling our service and getting its sequence number and GID back, and our client calling a
//! current-layout service server (and refusing replies that do not echo).

use crate::common::node;
use crate::python::{Background, background, client, hex, msgs_dir, python, unhex};

use hand_zenoh::NodeError;
use hand_zenoh::attachment::{Attachment, LEN, Layout};
use hand_zenoh::keys::{self, EntityKind};
use hand_zenoh::msg::Message as _;
use hand_zenoh::msg::handstack_msgs::GripperCommand;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerRequest, TriggerResponse};
use hand_zenoh::node::Router;
use std::path::Path;
use std::time::Duration;

/// The attachments of the unit tests' vectors and the edges of each field, as the Python
/// client makes them with zenoh-ext's `z_serialize((Int64, Int64, bytes))` — the serializer
/// family zenoh-cpp's `ext::Serializer`, which rmw_zenoh's `attachment_helpers.cpp` uses, is
/// built to match — in the current layout and the older one, each read back by the client's
/// own parser.
#[test]
fn attachments_are_the_bytes_zenoh_ext_serializes() {
    let Some(py) = python() else { return };
    let gid: [u8; 16] = core::array::from_fn(|i| i as u8);
    let cases = [
        (1, 1_764_100_000_123_456_789, gid),
        (0, 0, [0; 16]),
        (i64::MAX, i64::MAX, [0xff; 16]),
        (-1, i64::MIN, [0x80; 16]),
        (16, 16, [16; 16]),
        // Read as the old keyed layout, these bytes ask zenoh-ext for an 853 GB string: the
        // client's parser must not hand them to that reader (it read every sample so, and aborted).
        (
            1,
            1_796_005_909_256_858_376,
            [
                0xde, 0x20, 0xf8, 0x8b, 0x85, 0xea, 0xb4, 0xd0, 0x6c, 0x26, 0x9b, 0xfd, 0x85, 0x35,
                0x37, 0x2a,
            ],
        ),
    ];
    for (seq, stamp, gid) in cases {
        let a = Attachment {
            sequence_number: seq,
            source_timestamp: stamp,
            source_gid: gid,
        };
        let (seq, stamp, gid) = (seq.to_string(), stamp.to_string(), hex(&gid));
        let args = [
            "attachment",
            "--seq",
            &seq,
            "--stamp",
            &stamp,
            "--gid",
            &gid,
        ];
        let current = client(&py, &args);
        assert_eq!(current["hex"], hex(&a.encode()), "{a:?}");
        let mut legacy_args = args.to_vec();
        legacy_args.push("--legacy");
        let legacy = client(&py, &legacy_args);
        assert_eq!(legacy["hex"], hex(&a.encode_legacy()), "{a:?}");
    }
}

/// GIDs as the `xxhash` package computes them from a token, by rmw_zenoh's rule
/// (`liveliness_utils.cpp`), for rmw_zenoh design.md's own `talker` token (the GIDs of our
/// publishers against their tokens: `ros_interop`'s subscriber checks them).
#[test]
fn gids_are_what_python_xxhash_makes_of_the_tokens() {
    let Some(py) = python() else { return };
    let talker = "@ros2_lv/2/8b20917502ee955ac4476e0266340d5c/0/10/MP/%/%/talker/%chatter/\
                  std_msgs::msg::dds_::String_/\
                  RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18/\
                  ::,7:,:,:,,";
    let theirs = client(&py, &["gid", "--token", talker]);
    assert_eq!(theirs["gid_hex"], hex(&keys::gid(talker)));
    // The value the Python client printed for design.md's token, kept as a vector.
    assert_eq!(hex(&keys::gid(talker)), "ac170f31eadcd9ff0cd86d7a17907d1c");
}

/// A publisher of the Python client (current layout, sequence numbers from 1, its GID from
/// its token) commands a subscription of ours: every command received in order, none refused.
#[test]
fn a_current_layout_publisher_commands_our_subscription() {
    let Some(py) = python() else { return };
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let hand = node(&endpoint, "/hand0", "grasp");
    let mut commands = hand
        .subscription::<GripperCommand>("gripper/command", 64)
        .unwrap();
    let msgs = msgs_dir();
    let report = client(
        &py,
        &[
            "publish",
            "--connect",
            &endpoint,
            "--msgs",
            msgs.to_str().unwrap(),
            "--topic",
            "/hand0/gripper/command",
            "--type",
            GripperCommand::NAME,
            "--json",
            r#"{"header": {"frame_id": "hand0"}, "position_rad": 1.25, "effort": 0.5}"#,
            "--count",
            "8",
            "--rate",
            "50",
            "--timeout",
            "30",
        ],
    );
    assert_eq!(report["published"], 8, "{report}");
    let mut seqs = Vec::new();
    while seqs.len() < 8 {
        let Some(m) = commands.recv_timeout(Duration::from_secs(10)).unwrap() else {
            panic!(
                "{} of 8 commands arrived: {:?}",
                seqs.len(),
                commands.stats()
            );
        };
        assert_eq!((m.message.position_rad, m.message.effort), (1.25, 0.5));
        assert_eq!(m.message.header.frame_id, "hand0");
        let a = m.attachment.expect("an attachment");
        assert_eq!(
            Some(hex(&a.source_gid).as_str()),
            report["gid_hex"].as_str()
        );
        seqs.push(a.sequence_number);
    }
    assert_eq!(seqs, (1..=8).collect::<Vec<i64>>());
    let stats = commands.stats();
    assert_eq!(
        (
            stats.refused,
            stats.malformed,
            stats.legacy_attachment,
            stats.lost
        ),
        (0, 0, 0, 0),
        "{stats:?}"
    );
    let first = report["first_attachment_hex"].as_str().unwrap();
    assert_eq!(first.len(), 2 * LEN, "{first}");
}

/// A service client of the Python client calls our service: answered, and the reply's
/// attachment (33 bytes) carries the request's sequence number and the client's GID.
#[test]
fn a_current_layout_client_gets_its_sequence_number_and_gid_back() {
    let Some(py) = python() else { return };
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let tactile = node(&endpoint, "/hand0", "tactile");
    let server = tactile
        .service::<Trigger, _>("tactile/tare", |_| TriggerResponse {
            success: true,
            message: "tared".into(),
        })
        .unwrap();
    let msgs = msgs_dir();
    let report = client(
        &py,
        &[
            "call",
            "--connect",
            &endpoint,
            "--msgs",
            msgs.to_str().unwrap(),
            "--service",
            "/hand0/tactile/tare",
            "--seq",
            "41",
            "--timeout",
            "30",
        ],
    );
    assert_eq!(report["response"]["success"], true, "{report}");
    assert_eq!(report["response"]["message"], "tared", "{report}");
    assert_eq!(report["reply_attachment_len"], LEN, "{report}");
    assert_eq!(report["reply_seq"], 41, "{report}");
    assert_eq!(report["seq_echoed"], true, "{report}");
    assert_eq!(report["gid_echoed"], true, "{report}");
    assert_eq!((server.handled(), server.refused()), (1, 0));
}

/// The Python client's `serve` of `std_srvs/srv/Trigger` on `/hand0/<service>`, answering
/// `count` requests with `{success: true, message: "tared by python"}` and a reply attachment
/// made as `mode` says (`echo`: design.md's; the others are faults).
fn python_server(py: &Path, endpoint: &str, service: &str, mode: &str, count: u32) -> Background {
    let msgs = msgs_dir();
    let (service, count) = (format!("/hand0/{service}"), count.to_string());
    background(
        py,
        &[
            "serve",
            "--connect",
            endpoint,
            "--msgs",
            msgs.to_str().unwrap(),
            "--service",
            &service,
            "--json",
            r#"{"success": true, "message": "tared by python"}"#,
            "--count",
            &count,
            "--reply-attachment",
            mode,
            "--timeout",
            "60",
        ],
    )
}

/// Our client calls a service server of the Python client (design.md "Service Servers"): three
/// calls answered; each reply carried that request's sequence number (1, 2, 3) and our
/// client's GID, which our client checks; and the server saw those sequence numbers and our
/// client's GID, the XXH3-128 of our client's `SC` token.
#[test]
fn our_client_calls_a_current_layout_server() {
    let Some(py) = python() else { return };
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let server = python_server(&py, &endpoint, "tactile/tare", "echo", 3);
    let grasp = node(&endpoint, "/hand0", "grasp");
    let found = grasp
        .wait_for(EntityKind::Service, "tactile/tare", Duration::from_secs(30))
        .unwrap();
    assert!(found, "no service-server token for /hand0/tactile/tare");
    let mut tare = grasp.client::<Trigger>("tactile/tare").unwrap();
    assert_eq!(tare.name(), "/hand0/tactile/tare");
    for _ in 0..3 {
        let response = tare
            .call(&TriggerRequest::default(), Duration::from_secs(10))
            .unwrap();
        assert!(response.success);
        assert_eq!(response.message, "tared by python");
    }
    let report = server.finish();
    assert_eq!(report["served"], 3, "{report}");
    assert_eq!(report["refused"], serde_json::json!([]), "{report}");
    assert_eq!(report["extra"], 0, "{report}");
    let gid = hex(&tare.gid());
    let requests = report["requests"].as_array().unwrap();
    for (r, seq) in requests.iter().zip(1..) {
        assert_eq!(r["seq"], seq, "{report}");
        assert_eq!(r["client_gid_hex"], gid.as_str(), "{report}");
        assert_eq!(r["client_gid_matches_token"], true, "{report}");
        assert_eq!(r["request_roundtrip_identical"], true, "{report}");
        // What our client received and accepted: the 33-byte layout, the request's sequence
        // number and our GID.
        let sent = unhex(r["reply_attachment_hex"].as_str().unwrap());
        let (a, layout) = Attachment::read(&sent).unwrap();
        assert_eq!(layout, Layout::Current);
        assert_eq!((a.sequence_number, a.source_gid), (seq, tare.gid()));
    }
    assert_eq!(requests.len(), 3);
}

/// A server whose reply does not echo the request — no attachment, the next sequence number,
/// another GID — is answered by our client with [`NodeError::NotEchoed`] saying which, not the
/// response.
#[test]
fn our_client_refuses_a_reply_that_does_not_echo() {
    let Some(py) = python() else { return };
    let (_router, endpoint) = Router::open_on_loopback().unwrap();
    let grasp = node(&endpoint, "/hand0", "grasp");
    // A service of its own for each server: the last one's token may not be gone yet.
    for (mode, name) in [
        ("none", "tare_no_attachment"),
        ("next-seq", "tare_next_seq"),
        ("other-gid", "tare_other_gid"),
    ] {
        let server = python_server(&py, &endpoint, name, mode, 1);
        let found = grasp
            .wait_for(EntityKind::Service, name, Duration::from_secs(30))
            .unwrap();
        assert!(found, "{mode}: no service-server token");
        let mut tare = grasp.client::<Trigger>(name).unwrap();
        let err = tare
            .call(&TriggerRequest::default(), Duration::from_secs(10))
            .unwrap_err();
        match &err {
            NodeError::NotEchoed { service, reason } => {
                assert_eq!(service, &format!("/hand0/{name}"));
                let said = match mode {
                    "none" => "no attachment",
                    "next-seq" => "sequence number 2, not this request's 1",
                    _ => "another client's GID",
                };
                assert_eq!(reason, said, "{mode}: {err}");
            }
            other => panic!("{mode}: {other:?}"),
        }
        let report = server.finish();
        assert_eq!(report["served"], 1, "{mode}: {report}");
        assert_eq!(report["requests"][0]["seq"], 1, "{mode}: {report}");
        assert_eq!(
            report["requests"][0]["client_gid_hex"],
            hex(&tare.gid()).as_str(),
            "{mode}: {report}"
        );
    }
}
