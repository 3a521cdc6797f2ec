//! The closed grasp loop of the grasping paper (§5–7): tactile pressures → contact estimate →
//! fuzzy grasp policy → torque-limited position command, at a fixed rate, with a defined safe
//! state.
//!
//! - [`estimate`]: tare, mean contact pressure, low-pass-filtered rate, contact flag;
//! - [`config`]: rate, target, per-object [`TorqueBand`] (Table 5), safe action, [`Recovery`];
//! - [`end`]: what the hand is left doing when the loop ends ([`EndAction`], [`GraspLoop::end`]);
//! - [`clock`]: the [`LoopClock`] (wall or simulated) and the [`FixedRate`] scheduler;
//! - [`fault`]: typed faults per part and the [`RebootableActuator`] trait;
//! - [`log`]: one [`Sample`] per cycle, faulted or not, and [`settling`];
//! - [`runner`]: the [`GraspLoop`] itself.
//!
//! The loop is generic over the `hand-traits` parts, so the same code drives the simulated
//! hand of `hand-sim` in the tests and a Dynamixel hand on a serial port.
//!
//! ```
//! use hand_control::grasp_loop::{GraspLoop, LoopClock, LoopConfig, Mode, RebootableActuator};
//! use hand_traits::*;
//! use core::convert::Infallible;
//!
//! /// A pad whose pressure rises with the effort last sent (a shared cell stands in for physics).
//! struct Pad(std::rc::Rc<std::cell::Cell<f32>>, u64);
//! impl TactileSource for Pad {
//!     type Frame = PressureFrame<1>;
//!     type Error = Infallible;
//!     fn read_frame(&mut self) -> Result<PressureFrame<1>, Infallible> {
//!         self.1 += 10_000;
//!         Ok(PressureFrame { t_us: self.1, pressure_pa: [101_000.0 + 1_000.0 * self.0.get()] })
//!     }
//! }
//! struct Hand(std::rc::Rc<std::cell::Cell<f32>>);
//! impl GripperActuator for Hand {
//!     type Error = Infallible;
//!     fn command(&mut self, c: &GripperCommand) -> Result<(), Infallible> {
//!         self.0.set(c.effort.fraction());
//!         Ok(())
//!     }
//!     fn state(&mut self) -> Result<GripperState, Infallible> {
//!         Ok(GripperState { position_rad: 0.1, velocity_rad_per_s: 0.0,
//!             load_fraction: self.0.get(), faults: Faults::NONE })
//!     }
//!     fn safe_stop(&mut self, _: SafeAction) -> Result<(), Infallible> { Ok(()) }
//! }
//! impl RebootableActuator for Hand {
//!     fn reboot(&mut self) -> Result<(), Infallible> { Ok(()) }
//!     fn enable_torque(&mut self) -> Result<(), Infallible> { Ok(()) }
//! }
//! struct Sim(u64);
//! impl LoopClock for Sim {
//!     fn now_us(&mut self) -> u64 { self.0 }
//!     fn wait_until_us(&mut self, t: u64) { self.0 = self.0.max(t); }
//! }
//!
//! let effort = std::rc::Rc::new(std::cell::Cell::new(0.0));
//! let mut grasp = GraspLoop::new(
//!     Pad(effort.clone(), 0), fuzzy_mamdani::grasp_controller(), Hand(effort), Sim(0),
//!     LoopConfig { target_pressure_pa: 600.0, ..LoopConfig::new() },
//! )?;
//! grasp.run_until(2_000_000);
//! assert_eq!(grasp.mode(), Mode::Grasp);
//! assert_eq!(grasp.log().len(), 200); // every 10 ms cycle logged
//! let last = grasp.log().last().unwrap().estimate.unwrap();
//! // The fuzzy map is P-like: effort ≈ ½ + ½·e, so p = 1000·(½ + (600 − p)/4000) settles at 520.
//! assert!((last.pressure_pa - 520.0).abs() < 20.0, "{last:?}");
//! # Ok::<(), hand_control::grasp_loop::ConfigError>(())
//! ```

pub mod clock;
pub mod config;
pub mod end;
/// The contact estimate, `hand-traits`' (a fingertip's firmware estimates alike).
pub mod estimate {
    pub use hand_traits::{ContactEstimate, EstimateError, PressureEstimator};
}
pub mod fault;
pub mod log;
pub mod runner;
mod servo_hand;

pub use clock::{FixedRate, LoopClock, StdClock};
pub use config::{ConfigError, LoopConfig, Recovery, TorqueBand};
pub use end::{EndAction, EndReport, EndState, RELEASE_TOLERANCE_RAD};
pub use estimate::{ContactEstimate, EstimateError, PressureEstimator};
pub use fault::{FaultEvent, FaultKind, LoopFault, RebootableActuator};
pub use log::{Mode, SETTLE_TOL_RAW, SETTLE_WINDOW_US, Sample, Settling, settling};
pub use runner::{FaultOf, GraspLoop};
