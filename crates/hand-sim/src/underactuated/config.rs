//! The `[underactuated]` table of a scene file.

use super::finger::FingerParams;
use super::object::{ObjectConfig, PoseConfig};
use super::{Adc, Fsr, Pot};
use crate::SimError;
use serde::Deserialize;

/// Everything the underactuated-hand model needs; every field has a default.
///
/// ```
/// use hand_sim::underactuated::{Material, Shape, UnderactuatedConfig};
/// let c: UnderactuatedConfig = toml::from_str(
///     "closing_speed_mm_s = 2.0\n[object]\nshape = \"sphere\"\nsize_mm = 65\nmaterial = \"wood\"",
/// )?;
/// assert_eq!((c.object.shape, c.object.material), (Shape::Sphere, Material::Wood));
/// assert_eq!(c.duration_s, 14.0);
/// assert!(toml::from_str::<UnderactuatedConfig>("speed = 1").is_err());
/// # Ok::<(), toml::de::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UnderactuatedConfig {
    /// Quasi-static integration step, ms (0.1…1000).
    pub step_ms: f64,
    /// Length of the recorded grasp after first contact, s; the actuator holds after it
    /// (seed 001 §3.1: t₂ = 14 s, read as 14 s after t₁ — see the calibration report).
    pub duration_s: f64,
    /// Longest approach before first contact, s; a grasp that has not touched by then ends.
    pub approach_timeout_s: f64,
    /// Constant, open-loop closing speed of the stepper at the differential's input, mm/s.
    pub closing_speed_mm_s: f64,
    /// Tendon travel per (micro)step, mm: positions are whole steps.
    pub stepper_resolution_mm: f64,
    /// Tendon tension per finger at which the stepper stalls (its torque limit), N.
    pub stall_tension_n: f64,
    /// The object grasped.
    pub object: ObjectConfig,
    /// How its pose varies.
    pub pose: PoseConfig,
    /// Each finger's geometry.
    pub finger: FingerParams,
    /// The sensors and their ADC.
    pub sensors: SensorConfig,
}

impl Default for UnderactuatedConfig {
    fn default() -> Self {
        UnderactuatedConfig {
            step_ms: 50.0,
            duration_s: 14.0,
            approach_timeout_s: 120.0,
            closing_speed_mm_s: 1.5,
            stepper_resolution_mm: 0.01,
            stall_tension_n: 200.0,
            object: ObjectConfig::default(),
            pose: PoseConfig::default(),
            finger: FingerParams::default(),
            sensors: SensorConfig::default(),
        }
    }
}

/// The FSRs, potentiometers and the ADC that reads them.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SensorConfig {
    /// The Arduino's ADC.
    pub adc: Adc,
    /// The FSR law and divider.
    pub fsr: Fsr,
    /// The potentiometer.
    pub pot: Pot,
    /// Gaussian read noise at the ADC input, in LSB (σ).
    pub noise_lsb: f64,
    /// Each finger's FSR sensitivity relative to nominal (unit-to-unit spread).
    pub fsr_gain: [f64; 4],
    /// Grasp-to-grasp FSR repeatability, σ of a log-normal gain.
    pub fsr_repeatability: f64,
    /// Each potentiometer's mounting error, degrees.
    pub pot_offset_deg: [f64; 4],
}

impl Default for SensorConfig {
    fn default() -> Self {
        SensorConfig {
            adc: Adc::default(),
            fsr: Fsr::default(),
            pot: Pot::default(),
            noise_lsb: 0.5,
            fsr_gain: [1.0; 4],
            fsr_repeatability: 0.05,
            pot_offset_deg: [0.0; 4],
        }
    }
}

fn check(field: &'static str, x: f64, lo: f64, hi: f64) -> Result<(), SimError> {
    if x.is_finite() && x >= lo && x <= hi {
        Ok(())
    } else {
        Err(SimError::config(
            field,
            format!("must be in {lo}…{hi}, got {x}"),
        ))
    }
}

impl UnderactuatedConfig {
    /// Checks every value, naming the first one out of range.
    pub fn validate(&self) -> Result<(), SimError> {
        check("step_ms", self.step_ms, 0.1, 1000.0)?;
        check("duration_s", self.duration_s, 0.0, 3600.0)?;
        check("approach_timeout_s", self.approach_timeout_s, 0.0, 3600.0)?;
        check("closing_speed_mm_s", self.closing_speed_mm_s, 0.0, 1e3)?;
        check(
            "stepper_resolution_mm",
            self.stepper_resolution_mm,
            0.0,
            10.0,
        )?;
        check("stall_tension_n", self.stall_tension_n, 1e-3, 1e5)?;
        let f = &self.finger;
        for (name, x) in [
            ("finger.proximal_length_m", f.proximal_length_m),
            ("finger.proximal_contact_m", f.proximal_contact_m),
            ("finger.distal_contact_m", f.distal_contact_m),
            ("finger.proximal_pulley_m", f.proximal_pulley_m),
            ("finger.distal_pulley_m", f.distal_pulley_m),
            ("finger.palm_radius_m", f.palm_radius_m),
            ("finger.pad.thickness_m", f.pad.thickness_m),
            ("finger.pad.area_m2", f.pad.area_m2),
        ] {
            check(name, x, 1e-6, 1.0)?;
        }
        for (name, x) in [
            (
                "finger.proximal_spring_nm_per_rad",
                f.proximal_spring_nm_per_rad,
            ),
            (
                "finger.distal_spring_nm_per_rad",
                f.distal_spring_nm_per_rad,
            ),
            ("finger.proximal_preload_nm", f.proximal_preload_nm),
            ("finger.distal_preload_nm", f.distal_preload_nm),
        ] {
            check(name, x, 0.0, 1e3)?;
        }
        check("finger.joint_limit_deg", f.joint_limit_deg, 1.0, 180.0)?;
        check("finger.pad.modulus_pa", f.pad.modulus_pa, 1.0, 1e12)?;
        check("finger.pad.creep_tau_s", f.pad.creep_tau_s, 1e-3, 1e4)?;
        let s = &self.sensors;
        check("sensors.adc.vref_v", s.adc.vref_v, 0.1, 100.0)?;
        check("sensors.fsr.r_1kgf_ohm", s.fsr.r_1kgf_ohm, 1.0, 1e9)?;
        check("sensors.fsr.exponent", s.fsr.exponent, 0.05, 10.0)?;
        check("sensors.fsr.r_open_ohm", s.fsr.r_open_ohm, 1.0, 1e12)?;
        check("sensors.fsr.min_force_n", s.fsr.min_force_n, 1e-6, 1e4)?;
        check(
            "sensors.fsr.max_force_n",
            s.fsr.max_force_n,
            s.fsr.min_force_n,
            1e5,
        )?;
        check("sensors.fsr.divider_ohm", s.fsr.divider_ohm, 1.0, 1e9)?;
        check("sensors.pot.travel_deg", s.pot.travel_deg, 1.0, 3600.0)?;
        check("sensors.pot.zero_deg", s.pot.zero_deg, -3600.0, 3600.0)?;
        check("sensors.noise_lsb", s.noise_lsb, 0.0, 1023.0)?;
        check("sensors.fsr_repeatability", s.fsr_repeatability, 0.0, 5.0)?;
        for g in s.fsr_gain {
            check("sensors.fsr_gain", g, 1e-3, 1e3)?;
        }
        for o in s.pot_offset_deg {
            check("sensors.pot_offset_deg", o, -360.0, 360.0)?;
        }
        self.pose.validate()?;
        self.object.validate(self.finger.palm_radius_m)
    }
}
