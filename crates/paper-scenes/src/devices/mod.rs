//! The devices of a paper scene: each real when the scene names its hardware (opened by
//! `handstack::stack`, through the run's platform), else simulated at its real interface — the
//! MS5611 chip models under hand-sim's pad behind the real driver, ur-bridge's UR controller
//! simulator on loopback behind the real ur_rtde client.

pub mod arm;
pub mod fingertip;
