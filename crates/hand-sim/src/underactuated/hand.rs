//! The hand: one stepper at constant speed, a seesaw differential to four fingers, and the
//! sensors read through the ADC.
//!
//! The seesaw tree (seed 001 Fig. 1) gives every finger the same tendon tension `T` while the
//! input travel is the mean of the fingers' travels; so a finger that is blocked stops and the
//! others keep closing (underactuation). The stepper imposes the input travel `v·t` (whole
//! steps) until the tension reaches its torque limit; it then stalls, pushing at that limit,
//! and follows again wherever creep lets the fingers give.

use super::config::UnderactuatedConfig;
use super::finger::{FingerContact, FingerState};
use super::object::Pose;
use super::solve::increasing_root_near;
use crate::SimError;
use crate::scene::Model;
use hand_traits::{FingerFrame, TactileSource};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

/// Raw ADC codes of one read: four FSR dividers and four distal potentiometers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SensorCodes {
    /// FSR divider codes, per finger.
    pub force: [u16; 4],
    /// Distal potentiometer codes, per finger.
    pub angle: [u16; 4],
}

/// The eight sensor voltages at the ADC's inputs, before it converts them (no read noise):
/// what an Arduino's analog pins see.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorVolts {
    /// FSR divider outputs, per finger, V.
    pub force: [f64; 4],
    /// Distal potentiometer wipers, per finger, V.
    pub angle: [f64; 4],
}

/// The underactuated four-finger hand of seed 001 grasping one object.
///
/// ```
/// use hand_sim::scene::Model;
/// use hand_sim::underactuated::{Material, Underactuated, UnderactuatedConfig};
/// use hand_traits::TactileSource;
///
/// let mut config = UnderactuatedConfig::default();
/// config.object.material = Material::Wood;
/// let mut hand = Underactuated::new(&config, 7)?;
/// hand.step_to(60_000_000_000)?;
/// let frame = hand.read_frame()?;
/// assert!(hand.first_contact_ns().is_some());
/// assert!(frame.force_n.iter().all(|f| f.is_finite() && *f >= 0.0));
/// # Ok::<(), hand_sim::SimError>(())
/// ```
#[derive(Debug, Clone)]
pub struct Underactuated {
    config: UnderactuatedConfig,
    pose: Pose,
    contacts: [Option<FingerContact>; 4],
    fingers: [FingerState; 4],
    creep_m: [[f64; 2]; 4],
    tension_n: f64,
    stalled: bool,
    fsr_gain: [f64; 4],
    step_ns: u64,
    duration_ns: u64,
    approach_ns: u64,
    empty: bool,
    steps: u64,
    now_ns: u64,
    first_contact_ns: Option<u64>,
    rng: ChaCha8Rng,
}

impl Underactuated {
    /// Builds the hand for `config`, drawing the pose and this grasp's sensor spread from the
    /// stream `"underactuated"` of `seed`.
    pub fn new(config: &UnderactuatedConfig, seed: u64) -> Result<Underactuated, SimError> {
        config.validate()?;
        let mut rng = crate::seed::stream(seed, <Self as Model>::NAME);
        let pose = config.pose.draw(&mut rng);
        let sensors = &config.sensors;
        let fsr_gain = std::array::from_fn(|i| {
            let z: f64 = rng.sample(StandardNormal);
            sensors.fsr_gain[i] * (z * sensors.fsr_repeatability).exp()
        });
        let step_ns = (config.step_ms * 1e6).round() as u64;
        let contacts = config.object.finger_contacts(&pose, &config.finger);
        Ok(Underactuated {
            empty: contacts.iter().all(Option::is_none),
            contacts,
            config: config.clone(),
            pose,
            fingers: [FingerState::default(); 4],
            creep_m: [[0.0; 2]; 4],
            tension_n: 0.0,
            stalled: false,
            fsr_gain,
            step_ns,
            duration_ns: (config.duration_s * 1e9).round() as u64,
            approach_ns: (config.approach_timeout_s * 1e9).round() as u64,
            steps: 0,
            now_ns: 0,
            first_contact_ns: None,
            rng,
        })
    }

    /// The integration step, ns.
    pub fn step_ns(&self) -> u64 {
        self.step_ns
    }

    /// When the grasp ends and the actuator holds (t₂), ns since the actuator started:
    /// `duration_s` after first contact; for an empty grasp `duration_s` after the start; while
    /// no finger has touched yet, the approach timeout.
    pub fn end_ns(&self) -> u64 {
        match self.first_contact_ns {
            Some(t1) => t1.saturating_add(self.duration_ns),
            None if self.empty => self.duration_ns,
            None => self.approach_ns,
        }
    }

    /// The pose drawn for this grasp.
    pub fn pose(&self) -> &Pose {
        &self.pose
    }

    /// Each finger's state (ground truth, not a sensor reading).
    pub fn fingers(&self) -> &[FingerState; 4] {
        &self.fingers
    }

    /// Tendon tension per finger, N.
    pub fn tension_n(&self) -> f64 {
        self.tension_n
    }

    /// Whether the stepper is at its torque limit.
    pub fn stalled(&self) -> bool {
        self.stalled
    }

    /// When a finger first touched the object (t₁ of seed 001 §3.1), ns; `None` before that
    /// and for an empty grasp.
    pub fn first_contact_ns(&self) -> Option<u64> {
        self.first_contact_ns
    }

    /// The stepper's commanded input travel at `t_s`, m: constant speed, whole steps.
    fn commanded_travel_m(&self, t_s: f64) -> f64 {
        let x_mm = self.config.closing_speed_mm_s * t_s;
        let res = self.config.stepper_resolution_mm;
        let x_mm = if res > 0.0 {
            (x_mm / res).floor() * res
        } else {
            x_mm
        };
        x_mm * 1e-3
    }

    fn equilibria(&self, tension_n: f64) -> [FingerState; 4] {
        std::array::from_fn(|i| {
            self.config.finger.equilibrium(
                tension_n,
                self.contacts[i].as_ref(),
                self.creep_m[i],
                &self.fingers[i],
            )
        })
    }

    fn mean_travel(&self, states: &[FingerState; 4]) -> f64 {
        states
            .iter()
            .map(|s| self.config.finger.tendon_travel(s))
            .sum::<f64>()
            / 4.0
    }

    /// One quasi-static step to `(steps + 1) · step` with the stepper's own constant-speed
    /// travel.
    fn advance(&mut self) {
        let t_s = ((self.steps + 1) * self.step_ns) as f64 * 1e-9;
        self.advance_toward(self.commanded_travel_m(t_s));
    }

    /// One quasi-static step to `(steps + 1) · step` with the differential's input at `target`
    /// (m of tendon pulled).
    fn advance_toward(&mut self, target: f64) {
        let t_ns = (self.steps + 1) * self.step_ns;
        let stall = self.config.stall_tension_n;
        let tension = increasing_root_near(
            |t| self.mean_travel(&self.equilibria(t)) - target,
            self.tension_n,
            0.5,
            0.0,
            stall,
            1e-4,
        );
        let states = self.equilibria(tension);
        self.stalled = tension >= stall;
        self.tension_n = tension;
        let dt_s = self.step_ns as f64 * 1e-9;
        for (i, state) in states.iter().enumerate() {
            if let Some(c) = &self.contacts[i] {
                let creep = &mut self.creep_m[i];
                creep[0] = c.proximal.creep_after(creep[0], state.depth_m[0], dt_s);
                creep[1] = c.distal.creep_after(creep[1], state.depth_m[1], dt_s);
            }
        }
        self.fingers = states;
        let touching = states
            .iter()
            .any(|s| s.proximal_force_n > 0.0 || s.distal_force_n > 0.0);
        if touching && self.first_contact_ns.is_none() {
            self.first_contact_ns = Some(t_ns);
        }
        self.steps += 1;
    }

    fn noisy_code(&mut self, volts: f64) -> u16 {
        let adc = self.config.sensors.adc;
        let z: f64 = self.rng.sample(StandardNormal);
        adc.code(volts + z * self.config.sensors.noise_lsb * adc.vref_v / 1024.0)
    }

    /// Drives the differential's input from outside — a stepper on a board, whose steps give
    /// the tendon pulled — instead of at `closing_speed_mm_s`: integrates whole steps up to
    /// `t_ns` with the input at `travel_m` (m; 0 = open, clamped there), whatever the grasp's
    /// end. The same quasi-static physics as [`Model::step_to`], which it must not be mixed
    /// with on one hand.
    ///
    /// ```
    /// use hand_sim::underactuated::{Underactuated, UnderactuatedConfig};
    /// let mut hand = Underactuated::new(&UnderactuatedConfig::default(), 1)?;
    /// hand.drive_to(1_000_000_000, 0.004)?; // 4 mm of tendon after 1 s: closing, not touching
    /// let closed = hand.fingers()[0].proximal_rad;
    /// assert!(closed > 0.1);
    /// hand.drive_to(2_000_000_000, 0.004)?; // held: the fingers stay
    /// assert_eq!(hand.fingers()[0].proximal_rad, closed);
    /// assert!(hand.drive_to(3_000_000_000, f64::NAN).is_err());
    /// # Ok::<(), hand_sim::SimError>(())
    /// ```
    pub fn drive_to(&mut self, t_ns: u64, travel_m: f64) -> Result<(), SimError> {
        if !travel_m.is_finite() {
            let why = format!("must be finite, got {travel_m}");
            return Err(SimError::config("travel_m", why));
        }
        let target = travel_m.max(0.0);
        while (self.steps + 1).saturating_mul(self.step_ns) <= t_ns {
            self.advance_toward(target);
        }
        self.now_ns = self.now_ns.max(t_ns);
        Ok(())
    }

    /// The eight channels' voltages at the ADC's inputs now (each FSR's unit gain and each
    /// potentiometer's mounting error included, no read noise).
    pub fn sensor_volts(&self) -> SensorVolts {
        let s = &self.config.sensors;
        let mut volts = SensorVolts {
            force: [0.0; 4],
            angle: [0.0; 4],
        };
        for (i, f) in self.fingers.iter().enumerate() {
            volts.force[i] = s
                .fsr
                .volts(f.distal_force_n, self.fsr_gain[i], s.adc.vref_v);
            volts.angle[i] = s.pot.volts(f.distal_rad, s.pot_offset_deg[i], s.adc.vref_v);
        }
        volts
    }

    /// Reads all eight channels through the ADC, with read noise.
    pub fn read_codes(&mut self) -> SensorCodes {
        let volts = self.sensor_volts();
        let mut codes = SensorCodes {
            force: [0; 4],
            angle: [0; 4],
        };
        // Finger by finger, force then angle: the order the noise is drawn in.
        for i in 0..4 {
            codes.force[i] = self.noisy_code(volts.force[i]);
            codes.angle[i] = self.noisy_code(volts.angle[i]);
        }
        codes
    }

    /// The configuration the hand was built with.
    pub fn config(&self) -> &UnderactuatedConfig {
        &self.config
    }

    /// Decodes codes by the nominal sensor laws (the Arduino-side calibration) into a frame
    /// stamped with the current simulated time.
    pub fn decode(&self, codes: &SensorCodes) -> FingerFrame<4> {
        let s = &self.config.sensors;
        FingerFrame {
            t_us: self.now_ns / 1000,
            force_n: codes.force.map(|c| s.fsr.decode(&s.adc, c) as f32),
            distal_angle_rad: codes.angle.map(|c| s.pot.decode(&s.adc, c) as f32),
        }
    }
}

impl Model for Underactuated {
    const NAME: &'static str = "underactuated";

    /// Integrates whole steps up to `t_ns`; after the grasp's end ([`Underactuated::end_ns`])
    /// the actuator holds and only the clock moves.
    fn step_to(&mut self, t_ns: u64) -> Result<(), SimError> {
        while (self.steps + 1).saturating_mul(self.step_ns) <= t_ns.min(self.end_ns()) {
            self.advance();
        }
        self.now_ns = self.now_ns.max(t_ns);
        Ok(())
    }

    fn steps(&self) -> u64 {
        self.steps
    }
}

impl TactileSource for Underactuated {
    type Frame = FingerFrame<4>;
    type Error = SimError;

    /// Reads forces (N) and distal angles (rad) as an Arduino would: ADC codes, then the
    /// nominal calibration.
    fn read_frame(&mut self) -> Result<FingerFrame<4>, SimError> {
        let codes = self.read_codes();
        Ok(self.decode(&codes))
    }
}
