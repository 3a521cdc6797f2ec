//! Seed 001's underactuated hand behind a simulated Arduino: the device a user's real hand
//! would be. An Arduino Mega 2560 runs ConfigurableFirmata with AccelStepperFirmata
//! (firmata-sim's board on a pty); its stepper pulls the tendon that closes the four fingers of
//! hand-sim's underactuated hand on an object, and its analog pins read the four FSR dividers
//! and the four distal potentiometers from hand-sim's physics as the stepper moves. A Firmata
//! client (firmata-host, pyfirmata2, the paper's MATLAB) drives it as it would the real one.
//!
//! # Wiring (the one a real build of the hand would use)
//!
//! | Arduino pin | what | model |
//! |---|---|---|
//! | A0 … A3 | FSR divider of finger 1 … 4 (FSR from 5 V to the pin, 10 kΩ to ground) | [`hand_sim::underactuated::Fsr`] |
//! | A4 … A7 | distal potentiometer wiper of finger 1 … 4 (track across 5 V) | [`hand_sim::underactuated::Pot`] |
//! | D2, D3 | STEP, DIR of the stepper driver (AccelStepperFirmata device 0, `DRIVER`) | [`Drive`] |
//!
//! Eight analog inputs need more than an Uno's six (A0–A5): the board is a Mega 2560
//! (sixteen); a Nano's A0–A7 would take the same map. The paper names only "Arduino" and a
//! 10-bit read of each sensor as a voltage (§3.2); the Mega's ADC is that, against its 5 V
//! reference, the supply of both dividers.
//!
//! # Steps to tendon
//!
//! hand-sim's hand is driven by the tendon travel at the seesaw differential's input, in whole
//! steps of `stepper_resolution_mm` (0.01 mm by default). The paper gives no motor data, so
//! [`Drive`] assumes the common build: a 1.8° (200 full steps / rev) hybrid stepper on a
//! step/dir driver at 1/16 microstepping (3200 steps / rev), winding the tendon on a spool on
//! its shaft without a gearbox; one step is one `stepper_resolution_mm` of tendon, so a turn is
//! 32 mm and the spool's radius 32 mm / 2π ≈ 5.09 mm. Positive steps close the hand. The
//! board's stepper position therefore maps to the hand's input travel as
//! `travel = steps × stepper_resolution_mm`, and hand-sim's constant closing speed `v` mm/s is
//! `v / stepper_resolution_mm` steps/s on the board.
//!
//! The physics hears the motor's steps (firmata-sim's [`AnalogInputs::stepper_moved`]), not
//! AccelStepper's counter: zeroing the position or a reset of the board (each open of its port)
//! leaves the fingers where the tendon holds them, as on the real hand.

use std::path::Path;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::Duration;

use firmata_sim::{AnalogInputs, BoardKind, ChipBus, FirmwareKind, SimBoard, SimConfig};
use hand_sim::scene::Model;
use hand_sim::underactuated::{FingerState, Material, Underactuated, UnderactuatedConfig};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use underactuated_hand::Wiring;

use crate::Error;
use crate::error::device;

/// The board's wiring: the one a real hand's user states (underactuated-hand's default).
pub const WIRING: Wiring = Wiring::PAPER_BUILD;
/// The analog channels of the four FSR dividers, finger 1 … 4.
pub const FSR_CHANNELS: [u8; 4] = WIRING.fsr_channels;
/// The analog channels of the four distal potentiometers, finger 1 … 4.
pub const POT_CHANNELS: [u8; 4] = WIRING.pot_channels;
/// The AccelStepperFirmata device number of the hand's stepper.
pub const STEPPER_DEVICE: u8 = WIRING.stepper_device;
/// The stepper driver's STEP pin.
pub const STEP_PIN: u8 = WIRING.step_pin;
/// The stepper driver's DIR pin.
pub const DIR_PIN: u8 = WIRING.dir_pin;
/// The board: eight analog inputs need a Mega 2560 (an Uno has six).
pub const BOARD: BoardKind = BoardKind::Mega2560;

/// How the stepper's steps turn into tendon travel (see the module docs for the assumption).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Drive {
    /// Steps per motor revolution: 200 full steps × 16 microsteps.
    pub steps_per_rev: u32,
    /// Tendon travel per step, mm (hand-sim's `stepper_resolution_mm`).
    pub travel_per_step_mm: f64,
}

impl Drive {
    /// A 200-step motor at 1/16 microstepping on a spool, one step being `config`'s
    /// `stepper_resolution_mm` of tendon.
    ///
    /// ```
    /// use hand_sim::underactuated::UnderactuatedConfig;
    /// use paper_scenes::devices::hand_board::Drive;
    /// let drive = Drive::of(&UnderactuatedConfig::default());
    /// assert_eq!(drive.steps_per_rev, 3200);
    /// assert!((drive.spool_radius_mm() - 5.093).abs() < 1e-3);
    /// assert_eq!(drive.steps_per_s(1.5), 150.0); // the paper-speed close
    /// assert!((drive.travel_m(150) - 1.5e-3).abs() < 1e-15);
    /// ```
    pub fn of(config: &UnderactuatedConfig) -> Drive {
        Drive {
            steps_per_rev: 200 * 16,
            travel_per_step_mm: config.stepper_resolution_mm,
        }
    }

    /// The tendon pulled after `steps` steps from open, m.
    pub fn travel_m(&self, steps: i64) -> f64 {
        steps as f64 * self.travel_per_step_mm * 1e-3
    }

    /// The motor's angle after `steps` steps, degrees.
    pub fn motor_angle_deg(&self, steps: i64) -> f64 {
        steps as f64 * 360.0 / f64::from(self.steps_per_rev)
    }

    /// The spool's radius the two figures imply, mm.
    pub fn spool_radius_mm(&self) -> f64 {
        self.travel_per_step_mm * f64::from(self.steps_per_rev) / std::f64::consts::TAU
    }

    /// The step rate of a tendon speed of `mm_s`, steps/s.
    pub fn steps_per_s(&self, mm_s: f64) -> f64 {
        mm_s / self.travel_per_step_mm
    }
}

/// What to build: the hand and its object, the seed of its pose and sensor spread, the board.
#[derive(Debug, Clone)]
pub struct HandBoardConfig {
    /// hand-sim's hand and object (`closing_speed_mm_s` and `duration_s` play no part: the
    /// board's stepper closes it); `sensors.noise_lsb` is the read noise at the pins.
    pub hand: UnderactuatedConfig,
    /// The seed of the pose and the sensors' spread, as hand-sim's own grasps draw them.
    pub seed: u64,
    /// From the port opening to the version report.
    pub boot_delay: Duration,
}

impl HandBoardConfig {
    /// hand-sim's default hand (its 80 mm cylinder) of `material`, stepped every 10 ms (finer
    /// than the board's 19 ms analog sampling, where hand-sim's recorded grasps use 50 ms),
    /// seed 1, the real board's 1.6 s boot.
    pub fn new(material: Material) -> HandBoardConfig {
        let mut hand = UnderactuatedConfig::default();
        hand.object.material = material;
        hand.step_ms = 10.0;
        HandBoardConfig {
            hand,
            seed: 1,
            boot_delay: Duration::from_millis(1600),
        }
    }
}

/// What the simulated hand is doing (the ground truth no Firmata client sees).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truth {
    /// The motor's steps from open (what it turned, whatever AccelStepper's counter says).
    pub shaft_steps: i64,
    /// The tendon pulled, m.
    pub travel_m: f64,
    /// Each finger's state.
    pub fingers: [FingerState; 4],
    /// The tendon tension per finger, N.
    pub tension_n: f64,
    /// Whether the stepper is at its torque limit (its steps are then lost on the real one).
    pub stalled: bool,
    /// The hand's clock, ns: the board's time since it first started, across its resets.
    pub now_ns: u64,
}

/// The hand seen from the board: its physics, the steps it heard, its clock.
struct World {
    hand: Underactuated,
    drive: Drive,
    shaft_steps: i64,
    /// The board's clock restarts with each reset; the hand's goes on: `offset + now`.
    offset: Duration,
    last: Duration,
    rng: ChaCha8Rng,
    error: Option<hand_sim::SimError>,
    /// The seed of the first object's pose, and how many were put in the hand since.
    seed: u64,
    placed: u64,
}

impl World {
    fn at(&mut self, now: Duration) {
        if now < self.last {
            // The sketch restarted: its clock began again at 0.
            self.offset += self.last;
        }
        self.last = now;
        let t_ns = u64::try_from((self.offset + now).as_nanos()).unwrap_or(u64::MAX);
        let travel = self.drive.travel_m(self.shaft_steps);
        if let Err(e) = self.hand.drive_to(t_ns, travel) {
            self.error.get_or_insert(e);
        }
    }

    fn volts(&mut self, channel: u8) -> f32 {
        let v = self.hand.sensor_volts();
        let volts = match channel {
            0..=3 => v.force[usize::from(channel)],
            4..=7 => v.angle[usize::from(channel - 4)],
            _ => return 0.0,
        };
        let sensors = &self.hand.config().sensors;
        let lsb = sensors.adc.vref_v / 1024.0;
        let sigma = sensors.noise_lsb * lsb;
        let noise = if sigma > 0.0 {
            let z: f64 = self.rng.sample(StandardNormal);
            z * sigma
        } else {
            0.0
        };
        (volts + noise) as f32
    }
}

fn lock(world: &Mutex<World>) -> MutexGuard<'_, World> {
    world.lock().unwrap_or_else(|p| p.into_inner())
}

/// The board's analog pins on the hand: firmata-sim's extension point, hand-sim's physics.
struct HandPins(Arc<Mutex<World>>);

impl AnalogInputs for HandPins {
    fn volts(&mut self, channel: u8, now: Duration) -> f32 {
        let mut w = lock(&self.0);
        w.at(now);
        w.volts(channel)
    }

    fn stepper_moved(&mut self, device: u8, steps: i32, now: Duration) {
        if device != STEPPER_DEVICE {
            return;
        }
        let mut w = lock(&self.0);
        // Up to now the tendon was where the last steps left it; the new steps count from here.
        w.at(now);
        w.shaft_steps += i64::from(steps);
    }
}

/// The simulated Arduino with the hand on its pins, running on a pty until dropped.
///
/// ```no_run
/// use firmata_host::{Board, Options, StepperConfig};
/// use hand_sim::underactuated::Material;
/// use paper_scenes::devices::hand_board::{HandBoard, HandBoardConfig};
///
/// let sim = HandBoard::spawn(HandBoardConfig::new(Material::Wood))?;
/// let mut board = Board::open(sim.path(), &Options::default())?;
/// board.stepper_config(0, &StepperConfig::driver(2, 3))?;
/// board.stepper_set_speed(0, 150.0)?; // 1.5 mm/s of tendon
/// board.stepper_to(0, 3000)?;
/// let a0 = board.enable_analog(0)?; // finger 1's FSR divider
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct HandBoard {
    sim: SimBoard,
    world: Arc<Mutex<World>>,
}

impl HandBoard {
    /// Builds the hand (hand-sim refuses a bad configuration) and starts its board.
    pub fn spawn(config: HandBoardConfig) -> Result<HandBoard, Error> {
        let hand = Underactuated::new(&config.hand, config.seed)?;
        let world = Arc::new(Mutex::new(World {
            drive: Drive::of(&config.hand),
            hand,
            shaft_steps: 0,
            offset: Duration::ZERO,
            last: Duration::ZERO,
            rng: hand_sim::seed::stream(config.seed, "hand-board adc"),
            error: None,
            seed: config.seed,
            placed: 0,
        }));
        let board = SimConfig::default()
            .board(BOARD)
            .firmware(FirmwareKind::Configurable)
            .bus(ChipBus::empty())
            .boot_delay(config.boot_delay)
            .analog(HandPins(world.clone()));
        let sim = SimBoard::spawn(board).map_err(|e| device("hand board", e.to_string()))?;
        Ok(HandBoard { sim, world })
    }

    /// The port a client opens.
    pub fn path(&self) -> &Path {
        self.sim.path()
    }

    /// The board (its counters, its stepper's position as AccelStepper counts it).
    pub fn board(&self) -> &SimBoard {
        &self.sim
    }

    /// How steps map to tendon.
    pub fn drive(&self) -> Drive {
        lock(&self.world).drive
    }

    /// The hand now, as of the board's last pass.
    pub fn truth(&self) -> Truth {
        let w = lock(&self.world);
        Truth {
            shaft_steps: w.shaft_steps,
            travel_m: w.drive.travel_m(w.shaft_steps),
            fingers: *w.hand.fingers(),
            tension_n: w.hand.tension_n(),
            stalled: w.hand.stalled(),
            now_ns: w.hand.steps() * w.hand.step_ns(),
        }
    }

    /// Puts an object of `material` in the hand in place of the one it holds, its shape and
    /// size kept and its pose drawn again (an object placed by hand never sits the same way
    /// twice). The hand must be open — its tendon let out, as a run's release leaves it — or
    /// the object could not be taken out.
    ///
    /// Errors: the tendon is pulled (the hand holds its object).
    pub fn hold(&self, material: Material) -> Result<(), Error> {
        let mut w = lock(&self.world);
        if w.shaft_steps != 0 {
            return Err(device(
                "hand board",
                format!(
                    "the hand is closed ({} steps of tendon pulled): open it before another \
                     object is put in",
                    w.shaft_steps
                ),
            ));
        }
        let mut config = w.hand.config().clone();
        config.object.material = material;
        w.placed += 1;
        let mut hand = Underactuated::new(&config, w.seed.wrapping_add(w.placed))?;
        // The new hand's clock starts where the old one's was: the board's time goes on.
        hand.drive_to(w.hand.steps() * w.hand.step_ns(), 0.0)?;
        w.hand = hand;
        Ok(())
    }

    /// What the hand holds now.
    pub fn material(&self) -> Material {
        lock(&self.world).hand.config().object.material
    }

    /// The first error the physics gave, if any (it then holds the hand where it was).
    pub fn error(&self) -> Option<String> {
        lock(&self.world).error.as_ref().map(ToString::to_string)
    }
}
