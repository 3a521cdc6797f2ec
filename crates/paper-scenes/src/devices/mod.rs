//! The devices of a paper scene, opened here and nowhere else: each real when the scene names
//! its hardware (opened by `handstack::stack`, through the run's platform), else simulated at
//! its real interface — the MS5611 chip models under hand-sim's pad behind the real driver,
//! the Table 5 world's servo-bus simulator behind `ServoHand`, the ICM-20789 chip model behind
//! the real driver, ur-sim's UR controller simulator on loopback behind the real ur_rtde
//! client. The runners get handles and cannot tell which they hold.
//!
//! [`hand_board`] is a device for a user's own code rather than a scene's: seed 001's
//! underactuated hand behind a simulated Arduino running Firmata on a pty (`paper-scenes
//! hand-board` runs it as a process); so are [`grasp_board`] (seed 000's servo and fingertip,
//! `paper-scenes grasp-rig`), [`fingertip_board`] (the fingertip on a scale,
//! `paper-scenes fingertip-board`) and [`pad_board`] (seed 002's pad, tapped on command,
//! `paper-scenes pad-board`).

pub mod arm;
pub mod fingertip;
pub mod fingertip_board;
pub mod grasp;
pub mod grasp_board;
pub mod hand_board;
pub mod pad;
pub mod pad_board;
