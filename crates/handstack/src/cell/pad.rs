//! An ICM-20789 pad as a node (`/pad0`): `imu` (`sensor_msgs/Imu`, every frame),
//! `tactile/raw` (the barometer, every frame) and `tactile/contact` (one `ContactArray` per
//! tap: the pressure trigger of Al & Martinez-Hernandez, §IV-B, the window around it, the
//! contact locator, when the node has one).

use super::error::CellError;
use crate::pace::Pacer;
use crate::stop::Stop;
use crate::tap_to_move::{TapToMoveConfig, TapTrigger};
use hand_traits::{Contact, ContactLocator, ImuFrame, TactileSource};
use hand_zenoh::convert::{contact_to_msg, header, imu_to_msg};
use hand_zenoh::msg::handstack_msgs::{ContactArray, PressureFrame};
use hand_zenoh::msg::sensor_msgs::Imu;
use hand_zenoh::node::{Node, now_ns};
use tactile_nets::contact_cnn::{self, ContactCnn};

/// How the pad node runs.
#[derive(Debug, Clone)]
pub struct PadNodeConfig {
    /// Frames read per second.
    pub rate_hz: f64,
    /// The frame id of its messages (`pad0`).
    pub frame_id: String,
    /// The trigger and the window.
    pub trigger: TapToMoveConfig,
    /// Stop after this many frames (`None`: until stopped).
    pub max_frames: Option<u64>,
}

/// What the pad node did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PadNodeReport {
    /// Frames read and published.
    pub frames: u64,
    /// Contacts located and published.
    pub contacts: u64,
    /// Of those, the ones located from a window outside the locator's range
    /// ([`Contact::in_range`]): extrapolations, published as located.
    pub contacts_outside_range: u64,
}

impl core::fmt::Display for PadNodeReport {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(
            f,
            "{} frames, {} contacts ({} outside the locator's range)",
            self.frames, self.contacts, self.contacts_outside_range
        )
    }
}

/// Locates the tap in a window of frames: the contact locator behind the pad node.
pub type Locate<'a> = &'a mut dyn FnMut(&[ImuFrame]) -> Result<Contact, CellError>;

/// The contact CNN (Al & Martinez-Hernandez, §IV-A) as a pad node's locator: each window of
/// [`contact_cnn::WINDOW`] frames (the trigger's `frames_before + frames_after`) → one of the
/// pad's 9 regions. An error names the CNN and what was wrong.
pub fn cnn_locator(
    cnn: &mut ContactCnn,
) -> impl FnMut(&[ImuFrame]) -> Result<Contact, CellError> + '_ {
    move |frames| {
        contact_cnn::window(frames)
            .and_then(|w| cnn.locate(&w))
            .map_err(|e| CellError::Device {
                device: "estimators.contact",
                reason: format!("the contact CNN: {e}"),
            })
    }
}

/// Runs the pad node on `node` until `stop` (or `max_frames`): reads `source` at the configured
/// rate and publishes each frame; with `locate`, also cuts the window around each tap's trigger
/// and publishes where `locate` puts it (without, no `tactile/contact` topic).
pub fn run<S>(
    node: &Node,
    source: &mut S,
    mut locate: Option<Locate<'_>>,
    config: &PadNodeConfig,
    stop: &Stop,
) -> Result<PadNodeReport, CellError>
where
    S: TactileSource<Frame = ImuFrame>,
    S::Error: core::fmt::Display,
{
    let mut imu = node.publisher::<Imu>("imu")?;
    let mut raw = node.publisher::<PressureFrame>("tactile/raw")?;
    let mut contact = match locate {
        Some(_) => Some(node.publisher::<ContactArray>("tactile/contact")?),
        None => None,
    };
    let mut trigger = TapTrigger::new(config.trigger);
    let mut pacer = Pacer::new(config.rate_hz);
    let mut report = PadNodeReport::default();
    while !stop.is_set() && config.max_frames.is_none_or(|m| report.frames < m) {
        let frame = source
            .read_frame()
            .map_err(|e| CellError::device("pad", e))?;
        let h = header(now_ns(), &config.frame_id);
        imu.publish(&imu_to_msg(&frame, h.clone()))?;
        if let Some(p) = frame.pressure_pa {
            raw.publish(&PressureFrame {
                header: h.clone(),
                pressure_pa: vec![p],
            })?;
        }
        report.frames += 1;
        if let (Some(locate), Some(contact)) = (&mut locate, &mut contact) {
            if let Some((window, _trigger_t_us)) = trigger.push(frame) {
                let c = locate(window)?;
                contact.publish(&ContactArray {
                    header: h,
                    contacts: vec![contact_to_msg(&c)],
                })?;
                report.contacts += 1;
                report.contacts_outside_range += u64::from(!c.in_range);
            }
        }
        pacer.wait();
    }
    Ok(report)
}
