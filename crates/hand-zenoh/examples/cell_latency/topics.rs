//! The cell's topics, their data keys and the synthetic messages on them, and the trailer the
//! bare floor appends to the CDR bytes in place of the attachment.

use hand_zenoh::HashMode;
use hand_zenoh::keys::topic_key;
use hand_zenoh::msg::Message;
use hand_zenoh::msg::builtin_interfaces::Time;
use hand_zenoh::msg::geometry_msgs::{Quaternion, Vector3};
use hand_zenoh::msg::handstack_msgs::PressureFrame;
use hand_zenoh::msg::sensor_msgs::Imu;
use hand_zenoh::msg::std_msgs::Header;
use hand_zenoh::node::now_ns;
use hand_zenoh::types::dds_type_name;

/// Fingertips per hand.
pub(crate) const FINGERTIPS: usize = 3;
/// Fingertip frames per second.
pub(crate) const HAND_HZ: f64 = 100.0;
/// Pad messages per second, each topic.
pub(crate) const PAD_HZ: f64 = 30.0;
/// The pad's IMU topic.
pub(crate) const PAD_IMU: &str = "/pad0/imu";
/// The pad's barometer topic (one sensor: the ICM-20789's).
pub(crate) const PAD_RAW: &str = "/pad0/tactile/raw";
/// Bytes the bare floor appends: the sequence number, then the send timestamp (ns since the
/// Unix epoch), both little-endian.
pub(crate) const TRAILER: usize = 16;

/// Hand `hand`'s fingertip topics, relative to its node (`tactile/raw0`…).
pub(crate) fn fingertip_names() -> [String; FINGERTIPS] {
    std::array::from_fn(|i| format!("tactile/raw{i}"))
}

/// Hand `hand`'s fingertip topics, fully qualified (`/hand3/tactile/raw0`…).
pub(crate) fn fingertip_topics(hand: usize) -> [String; FINGERTIPS] {
    fingertip_names().map(|n| format!("/hand{hand}/{n}"))
}

/// The data key of `M` on `topic` (rmw_zenoh's, type hash included): what both modes use.
pub(crate) fn key<M: Message>(topic: &str) -> String {
    topic_key(
        0,
        topic,
        &dds_type_name(M::NAME),
        &HashMode::Rihs01.key_text(&M::description()),
    )
}

fn header(frame_id: &str) -> Header {
    Header {
        stamp: Time::from_nanos(u64::try_from(now_ns()).unwrap_or(0)),
        frame_id: frame_id.to_owned(),
    }
}

/// Frame `n` of a fingertip: three barometers on a ramp of 10 Pa a frame, period 100.
pub(crate) fn fingertip_frame(frame_id: &str, tip: usize, n: u64) -> PressureFrame {
    let base = 101_325.0 + 10.0 * (n % 100) as f32;
    PressureFrame {
        header: header(frame_id),
        pressure_pa: (0..3)
            .map(|s| base + 100.0 * (tip * 3 + s) as f32)
            .collect(),
    }
}

/// Frame `n` of the pad's barometer.
pub(crate) fn pad_frame(n: u64) -> PressureFrame {
    PressureFrame {
        header: header("pad0"),
        pressure_pa: vec![101_325.0 + 10.0 * (n % 100) as f32],
    }
}

/// Sample `n` of the pad's IMU: a slow ramp on every axis.
pub(crate) fn imu(n: u64) -> Imu {
    let r = (n % 100) as f64 * 1e-3;
    let v = Vector3 {
        x: r,
        y: -r,
        z: 9.81 + r,
    };
    Imu {
        header: header("pad0"),
        orientation: Quaternion {
            x: 0.0,
            y: 0.0,
            z: 0.0,
            w: 1.0,
        },
        orientation_covariance: [-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        angular_velocity: Vector3 { x: r, y: r, z: r },
        angular_velocity_covariance: [0.0; 9],
        linear_acceleration: v,
        linear_acceleration_covariance: [0.0; 9],
    }
}

/// The bare floor's payload: `cdr`, then sequence number `seq`, then the send time, taken
/// last.
pub(crate) fn bare_payload(mut cdr: Vec<u8>, seq: u64) -> Vec<u8> {
    cdr.reserve(TRAILER);
    cdr.extend_from_slice(&seq.to_le_bytes());
    cdr.extend_from_slice(&now_ns().to_le_bytes());
    cdr
}

/// A bare payload's CDR bytes, sequence number and send time.
pub(crate) fn split_bare(bytes: &[u8]) -> Option<(&[u8], u64, i64)> {
    let cut = bytes.len().checked_sub(TRAILER)?;
    let (cdr, trailer) = bytes.split_at(cut);
    let seq = u64::from_le_bytes(trailer[..8].try_into().ok()?);
    let sent = i64::from_le_bytes(trailer[8..].try_into().ok()?);
    Some((cdr, seq, sent))
}
