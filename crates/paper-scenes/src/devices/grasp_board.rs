//! Seed 000's grasp rig as two devices a user's `handstack` opens, in real time: the hand's
//! MX-28 on a Protocol 2.0 servo bus (dxl-sim's servo on a pty, at wall-clock pace) and the
//! fingertip's three MS5611 behind a TCA9548A on a simulated Arduino Mega running
//! ConfigurableFirmata (firmata-sim's board on another pty). One physics joins them: the servo
//! closes hand-sim's grasp linkage on a Table 5 object, and the pad force it makes presses
//! hand-sim's fingertip, whose pressures the three chips measure. A client sees only the two
//! ports, as it would a real hand on a USB RS-485 adapter and a fingertip on an Arduino.
//!
//! The physics is the Table 5 world of `paper_experiments::grasp_rig` (the same object
//! calibration, servo tuning and contact dead band), run at wall-clock pace instead of
//! simulated time: the object is lifted [`LIFT_AT_S`] after the pads first touch it, as
//! Table 5's arm lifts it 3 s into the grasp.

use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use baro_drivers::sim::Conditions;
use dxl_sim::{Pace, SimBus, SimConfig};
use firmata_sim::{BaroEnv, SimBoard};
use hand_control::control_table::MX_28;
use hand_sim::fingertip::{FingertipConfig, FingertipPhysics, LawParams};
use hand_sim::grasp::rig::SERVO_ID;
use hand_sim::grasp::{GraspBody, GraspPlant, GraspState, ObjectKind, ObjectParams, RigParams};
use paper_experiments::grasp_rig::{CONTACT_DEAD_BAND_N, DT_S, LIFT_AT_S};

use super::fingertip_board::{sensor_baselines, spawn_mega};
use crate::Error;
use crate::error::device;

/// Where the open fingers are, rad: 0, so the rig's closing goal (15 mm past first contact,
/// 0.2 rad) and its range (0…0.5 rad) are the grasp loop's defaults, which a scene then need
/// not state (Table 5's in-process rig opens at π instead).
pub const OPEN_RAD: f64 = 0.0;

/// What to build.
#[derive(Debug, Clone)]
pub struct GraspBoardConfig {
    /// The Table 5 object between the fingers.
    pub object: ObjectKind,
    /// The seed of the fingertip sensors' baselines and noise.
    pub seed: u64,
    /// The fingertip board's baud rate (its sketch's).
    pub baud: u32,
    /// From the board's port opening to its version report.
    pub boot_delay: Duration,
}

impl GraspBoardConfig {
    /// `object`, seed 1, 115 200 baud, the real board's 1.6 s boot.
    pub fn new(object: ObjectKind) -> GraspBoardConfig {
        GraspBoardConfig {
            object,
            seed: 1,
            baud: 115_200,
            boot_delay: Duration::from_millis(1600),
        }
    }
}

/// The pad and the object, shared by the servo's plant (which logs each change of the contact)
/// and the fingertip's chips (which read the pressures it makes).
struct Pad {
    physics: FingertipPhysics,
    last_ns: u64,
    lifted: bool,
    error: Option<String>,
}

pub(crate) fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The rig: its two ports until dropped.
pub struct GraspBoard {
    bus: SimBus,
    board: SimBoard,
    plant: GraspPlant,
    pad: Arc<Mutex<Pad>>,
}

impl GraspBoard {
    /// Builds the object, the servo bus and the fingertip board, and starts both.
    pub fn spawn(config: &GraspBoardConfig) -> Result<GraspBoard, Error> {
        let rig = RigParams::default();
        let object = ObjectParams::table5(config.object, &rig)?;
        let mut body = GraspBody::new(object, rig, OPEN_RAD);
        // Lifted `LIFT_AT_S` after the pads first touch it (below): a client's grasp starts
        // whenever it starts, where Table 5's in-process rig starts with the servo bus.
        body.log_contacts(CONTACT_DEAD_BAND_N);
        let plant = GraspPlant::new(body);
        let (bus, client) = SimBus::spawn(SimConfig {
            params: rig.servo.params(),
            step: Duration::from_secs_f64(DT_S),
            initial_position_rad: OPEN_RAD,
            pace: Pace::WallClock,
            ..SimConfig::with_ids(&[SERVO_ID])
        })
        .map_err(|e| device("servo bus", e.to_string()))?;
        // The pty lives while one end of each side is open: the client end stays here.
        std::mem::forget(client);
        bus.set_plant(SERVO_ID, plant.clone());
        // The rig's servo tuning, as Table 5's hand has it (RAM: a reboot loses it, as there).
        for (name, value) in rig.servo.registers() {
            let r = MX_28
                .register(name)
                .ok_or_else(|| device("servo bus", format!("no MX-28 register {name}")))?;
            let bytes = value.to_le_bytes();
            bus.with_servo(SERVO_ID, |s| {
                s.write(r.address, &bytes[..usize::from(r.width)])
            })
            .ok_or_else(|| device("servo bus", "the grasp servo is not on the bus"))?
            .map_err(|e| device("servo bus", e.to_string()))?;
        }
        let defaults = FingertipConfig::default();
        let baseline = sensor_baselines(config.seed, "grasp-board fingertip");
        let physics = FingertipPhysics::new(LawParams::CALIBRATED, baseline, 0.0)?;
        let pad = Arc::new(Mutex::new(Pad {
            physics,
            last_ns: 0,
            lifted: false,
            error: None,
        }));
        let epoch = Instant::now();
        let envs: [BaroEnv; 3] = core::array::from_fn(|k| {
            let (pad, plant) = (pad.clone(), plant.clone());
            let temperature = defaults.temperature_c;
            Box::new(move |_board_ns: u64| {
                // The servo bus's clock follows the wall clock from its start: the same epoch.
                let now_ns = u64::try_from(epoch.elapsed().as_nanos()).unwrap_or(u64::MAX);
                let mut p = lock(&pad);
                let mut body = plant.body();
                let mut touched_at = None;
                for (at_ns, patch) in body.take_contacts() {
                    let at = at_ns.max(p.last_ns);
                    p.last_ns = at;
                    if patch.force_n > 0.0 {
                        touched_at.get_or_insert(at);
                    }
                    if let Err(e) = p.physics.set_contact(at, patch) {
                        p.error.get_or_insert(e.to_string());
                    }
                }
                if let (Some(at), false) = (touched_at, p.lifted) {
                    body.lift_at(at as f64 * 1e-9 + LIFT_AT_S);
                    p.lifted = true;
                }
                drop(body);
                let t_ns = now_ns.max(p.last_ns);
                Conditions {
                    pressure_mbar: p.physics.pressure_hpa(k, t_ns),
                    temperature_celsius: temperature,
                }
            }) as BaroEnv
        });
        let board = spawn_mega(envs, config.seed, config.baud, config.boot_delay)?;
        Ok(GraspBoard {
            bus,
            board,
            plant,
            pad,
        })
    }

    /// The servo bus's port (a scene's `[hand] serial_port`).
    pub fn servo_path(&self) -> &Path {
        self.bus.client_path()
    }

    /// The fingertip board's port (a scene's `[sensors.fingertip] firmata_port`).
    pub fn board_path(&self) -> &Path {
        self.board.path()
    }

    /// The servo and the object now (ground truth no client sees).
    pub fn state(&self) -> Option<GraspState> {
        // The bus's world first, then the body, as the bus's own thread takes them (it steps
        // the plant holding its world): the other order deadlocks against it.
        self.bus
            .with_servo(SERVO_ID, |s| GraspState::of(s, &self.plant.body()))
    }

    /// Waits until the servo bus has handled every byte a client sent so far: call it after a
    /// client ends, before reading what it left the servo doing (its torque off is a
    /// broadcast, which nothing answers, so the client may exit before the bus reads it).
    ///
    /// # Errors
    /// A device error when the bus does not acknowledge within 10 s.
    pub fn sync(&mut self) -> Result<(), Error> {
        self.bus
            .sync()
            .map_err(|e| device("servo bus", e.to_string()))
    }

    /// Whether the servo's torque is on.
    pub fn torque_enabled(&self) -> Option<bool> {
        self.bus.with_servo(SERVO_ID, |s| s.torque_enabled())
    }

    /// The first error of the pad's physics, if any.
    pub fn error(&self) -> Option<String> {
        lock(&self.pad).error.clone()
    }
}
