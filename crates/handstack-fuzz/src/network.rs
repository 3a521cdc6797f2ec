//! Payloads from the network: CDR messages and rmw_zenoh attachments.

use hand_zenoh::attachment::Attachment;
use hand_zenoh::msg::Message;
use hand_zenoh::msg::geometry_msgs::{PoseStamped, WrenchStamped};
use hand_zenoh::msg::handstack_msgs::{
    ContactArray, GraspState, GripperCommand, PressureFrame, SensorInfo,
};
use hand_zenoh::msg::sensor_msgs::{Imu, JointState};
use hand_zenoh::msg::std_srvs::{TriggerRequest, TriggerResponse};

/// Decodes `payload` as `M`.
///
/// Oracle: what decodes re-encodes to bytes that decode and re-encode to the same bytes.
fn message<M: Message>(payload: &[u8]) {
    let Ok(m) = M::from_cdr(payload) else {
        return;
    };
    let once = m.to_cdr();
    let again = M::from_cdr(&once)
        .unwrap_or_else(|e| panic!("{}: re-encoded payload refused: {e}", M::NAME))
        .to_cdr();
    assert_eq!(once, again, "{}", M::NAME);
}

/// A payload of the message type the first byte picks (every type a node decodes), or an
/// attachment.
///
/// Oracle (attachments): what decodes re-encodes to the same bytes.
pub fn cdr(data: &[u8]) {
    let data = crate::bounded(data);
    let [kind, payload @ ..] = data else {
        return;
    };
    match kind % 12 {
        0 => message::<PressureFrame>(payload),
        1 => message::<ContactArray>(payload),
        2 => message::<SensorInfo>(payload),
        3 => message::<GraspState>(payload),
        4 => message::<GripperCommand>(payload),
        5 => message::<WrenchStamped>(payload),
        6 => message::<Imu>(payload),
        7 => message::<JointState>(payload),
        8 => message::<PoseStamped>(payload),
        9 => message::<TriggerRequest>(payload),
        10 => message::<TriggerResponse>(payload),
        _ => {
            // Either layout reads back as written; a read never panics.
            if let Ok((a, _)) = Attachment::read(payload) {
                assert_eq!(Attachment::decode(&a.encode()), Ok(a));
                assert_eq!(
                    Attachment::read(&a.encode_legacy()),
                    Ok((a, hand_zenoh::attachment::Layout::Legacy))
                );
            }
        }
    }
}
