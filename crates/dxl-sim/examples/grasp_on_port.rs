//! Your tactile sensor, the paper's fuzzy grasp controller and a Dynamixel hand on a serial
//! port, in one fixed-rate grasp loop.
//!
//! `cargo run --example grasp_on_port -- PORT PRESSURE_FILE`: PORT is the RS-485 adapter
//! (`/dev/ttyUSB0`) or the pty `dxl-sim --servo mx28:1 --servo mx28:2` prints; PRESSURE_FILE is
//! where Linux's IIO driver puts the fingertip barometer's reading, in kPa
//! (`/sys/bus/iio/devices/iio:device0/in_pressure_input`), or any file holding one.
use std::path::PathBuf;
use std::time::Instant;

use hand_control::ServoHand;
use hand_control::grasp_loop::{GraspLoop, LoopConfig, StdClock};
use hand_traits::{PressureFrame, TactileSource};

/// Your sensor: a barometer under the fingertip's silicone, read through Linux IIO.
struct Fingertip {
    reading: PathBuf,
    start: Instant,
}

impl TactileSource for Fingertip {
    type Frame = PressureFrame<1>;
    type Error = std::io::Error;

    fn read_frame(&mut self) -> Result<PressureFrame<1>, std::io::Error> {
        let text = std::fs::read_to_string(&self.reading)?;
        let kpa: f32 = text.trim().parse().map_err(std::io::Error::other)?;
        let t_us = self.start.elapsed().as_micros() as u64;
        Ok(PressureFrame {
            t_us,
            pressure_pa: [kpa * 1000.0],
        })
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let (Some(port), Some(reading)) = (args.next(), args.next()) else {
        return Err("usage: grasp_on_port PORT PRESSURE_FILE".into());
    };
    // Two MX-28s at 1 Mbps (the grasping paper's hand), in position mode under a torque limit.
    let mut hand = ServoHand::open(&port, 1_000_000, &[1, 2])?;
    // A USB adapter, or a simulator on a busy machine, can answer later than a servo's 34 ms.
    hand.set_reply_latency(dxl_sim::REPLY_LATENCY);
    hand.set_torque(false)?;
    hand.set_position_mode()?;
    hand.set_torque(true)?;

    let fingertip = Fingertip {
        reading: reading.into(),
        start: Instant::now(),
    };
    let config = LoopConfig {
        goal_rad: 2.6, // your hand's closed pose
        goal_limits_rad: (1.5, 3.2),
        ..LoopConfig::new() // 100 Hz, 500 Pa target, tare, hold the last safe effort on a fault
    };
    let policy = fuzzy_mamdani::grasp_controller();
    let mut grasp = GraspLoop::new(fingertip, policy, hand, StdClock::new(), config)?;
    grasp.run_until(1_000_000); // 1 s

    let last = grasp.log().last().ok_or("no cycle ran")?;
    println!(
        "mode {} after {} cycles, {} faults",
        grasp.mode(),
        grasp.log().len(),
        grasp.events().len()
    );
    if let (Some(torque), Some(state)) = (last.torque_raw, last.state) {
        println!("torque limit {torque} of 1023");
        println!(
            "hand at {:.3} rad, load {:.2}",
            state.position_rad, state.load_fraction
        );
    }
    for event in grasp.events() {
        println!("fault at cycle {}: {}", event.cycle, event.fault);
    }
    // However the loop ends, the hand is left as the configuration says (release: open to
    // where the loop found it, then torque off).
    let end = grasp.end();
    match (end.state, end.error) {
        (Some(state), _) => println!("hand {state}"),
        (None, Some(e)) => println!("hand: the end action did not reach it: {e}"),
        (None, None) => println!("hand: the end action did not reach it"),
    }
    Ok(())
}
