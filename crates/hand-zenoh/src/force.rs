//! A force estimate as a topic: `force` (`geometry_msgs/WrenchStamped`) under the device's
//! namespace, from any [`ForceEstimator`] over the tared pressure rises of a fingertip (hPa,
//! the unit of the force DNN of Kim et al. 2020, §2.2).
//!
//! The wrench is the load pressing on the pad along its normal, the fingertip frame's `z`
//! (positive into the pad, as the weight in that paper's Table 1); a barometric fingertip
//! measures neither shear nor torque, so those stay zero.
//!
//! ```no_run
//! use hand_traits::{ForceEstimate, ForceEstimator};
//! use hand_zenoh::force::ForceTopic;
//! use hand_zenoh::node::{Node, NodeOptions};
//!
//! /// 1 N per hPa of summed rise.
//! struct Linear;
//! impl ForceEstimator for Linear {
//!     type Input = [f32];
//!     type Error = core::convert::Infallible;
//!     fn estimate_force(&mut self, rise_hpa: &[f32]) -> Result<ForceEstimate, Self::Error> {
//!         Ok(ForceEstimate { force_n: rise_hpa.iter().sum(), in_range: true })
//!     }
//! }
//!
//! let node = Node::open(NodeOptions::new("/hand0", "force"))?;
//! let mut force = ForceTopic::new(&node, Linear)?;
//! let header = hand_zenoh::convert::header(0, "hand0");
//! assert!(force.publish(header, &[0.7, 0.5, 0.6])?); // /hand0/force, z = 1.8 N
//! # Ok::<(), hand_zenoh::NodeError>(())
//! ```

use crate::NodeError;
use crate::convert::force_to_msg;
use crate::msg::geometry_msgs::WrenchStamped;
use crate::msg::std_msgs::Header;
use crate::node::{Node, Publisher};
use hand_traits::{ForceEstimate, ForceEstimator};

/// The estimator behind a [`ForceTopic`], its error as text (it is counted, not propagated:
/// a frame the estimator refuses must not stop the node's other topics).
type Estimate = Box<dyn FnMut(&[f32]) -> Result<ForceEstimate, String> + Send>;

/// The `force` topic of a device and the estimator that feeds it.
pub struct ForceTopic {
    publisher: Publisher<WrenchStamped>,
    estimate: Estimate,
    refused: u64,
    last_refusal: Option<String>,
    beyond_range: u64,
}

impl ForceTopic {
    /// Declares `force` on `node`, published from `estimator`.
    pub fn new<F>(node: &Node, mut estimator: F) -> Result<Self, NodeError>
    where
        F: ForceEstimator<Input = [f32]> + Send + 'static,
        F::Error: core::fmt::Display,
    {
        Ok(ForceTopic {
            publisher: node.publisher("force")?,
            estimate: Box::new(move |rise| {
                estimator.estimate_force(rise).map_err(|e| e.to_string())
            }),
            refused: 0,
            last_refusal: None,
            beyond_range: 0,
        })
    }

    /// Estimates the force from `rise_hpa` (each sensor's rise over its zero, hPa) and
    /// publishes it stamped with `header`. `Ok(false)`: the estimator refused the input or
    /// gave a force that is not finite, which is counted ([`ForceTopic::refused`]) and not
    /// published. An estimate outside the estimator's range ([`ForceEstimate::in_range`]) is
    /// published as it is and counted ([`ForceTopic::beyond_range`]).
    pub fn publish(&mut self, header: Header, rise_hpa: &[f32]) -> Result<bool, NodeError> {
        match (self.estimate)(rise_hpa) {
            Ok(f) if f.force_n.is_finite() => {
                self.publisher.publish(&force_to_msg(f, header))?;
                self.beyond_range += u64::from(!f.in_range);
                Ok(true)
            }
            Ok(f) => Ok(self.refuse(format!("a force of {} N", f.force_n))),
            Err(e) => Ok(self.refuse(e)),
        }
    }

    fn refuse(&mut self, why: String) -> bool {
        self.refused += 1;
        self.last_refusal = Some(why);
        false
    }

    /// Inputs the estimator refused (or answered with a force that is not finite).
    pub fn refused(&self) -> u64 {
        self.refused
    }

    /// Published estimates outside the estimator's range (a force DNN pressed past its rated
    /// weights: its saturated output).
    pub fn beyond_range(&self) -> u64 {
        self.beyond_range
    }

    /// Why the latest refused input was refused.
    pub fn last_refusal(&self) -> Option<&str> {
        self.last_refusal.as_deref()
    }

    /// The `force` publisher (its key and GID).
    pub fn publisher(&self) -> &Publisher<WrenchStamped> {
        &self.publisher
    }
}

/// Each sensor's rise over `zero_pa`, in hPa (the unit of the force DNN of Kim et al. 2020,
/// §2.2).
pub fn rise_hpa<const N: usize>(pressure_pa: &[f32; N], zero_pa: &[f32]) -> [f32; N] {
    core::array::from_fn(|k| (pressure_pa[k] - zero_pa.get(k).copied().unwrap_or(0.0)) / 100.0)
}
