//! Both directions with an rmw_zenoh client written from rmw_zenoh's own specification, not
//! from this crate (`python/interop/ros_zenoh_client.py`: eclipse-zenoh's own serializer for
//! the attachment, the `xxhash` package for the GID): the attachment bytes, the GIDs, a
//! current-layout publisher commanding our subscription, and a current-layout service client
//! calling our service and getting its sequence number and GID back.

use crate::common::{free_endpoint, node};
use crate::python::{client, hex, msgs_dir, python};

use hand_zenoh::attachment::{Attachment, LEN};
use hand_zenoh::keys;
use hand_zenoh::msg::Message as _;
use hand_zenoh::msg::handstack_msgs::GripperCommand;
use hand_zenoh::msg::std_srvs::{Trigger, TriggerResponse};
use hand_zenoh::node::Router;
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
    let endpoint = free_endpoint();
    let _router = Router::open(&endpoint).unwrap();
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
    let endpoint = free_endpoint();
    let _router = Router::open(&endpoint).unwrap();
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
