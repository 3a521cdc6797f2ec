//! Grasped objects: shape × size × material (seed 001 §2.4, Table 1), per-finger local
//! stiffness for irregular household objects, and where each finger meets them.

use super::contact::ContactLaw;
use super::finger::{FingerContact, FingerParams};
use crate::SimError;
use hand_traits::Softness;
use rand::Rng;
use rand_distr::StandardNormal;
use serde::Deserialize;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

/// The model objects' cross-section sizes, mm: small, medium, big (seed 001 Table 1: 65, 80, 90
/// for the rectangle's side and the cylinder's and sphere's diameter).
pub const MODEL_SIZES_MM: [f64; 3] = [65.0, 80.0, 90.0];

/// Model-object shapes (seed 001 §2.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Shape {
    /// A square-section block, grasped around its 80 mm height.
    Rectangular,
    /// An upright cylinder.
    Cylinder,
    /// A sphere.
    Sphere,
}

impl Shape {
    /// Every shape, in Table 1's order.
    pub const ALL: [Shape; 3] = [Shape::Rectangular, Shape::Cylinder, Shape::Sphere];

    /// The name used in scene files and datasets.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Rectangular => "rectangular",
            Shape::Cylinder => "cylinder",
            Shape::Sphere => "sphere",
        }
    }

    /// Contact patch relative to a flat face: a curved surface meets the flat pad over less.
    fn area_factor(self) -> f64 {
        match self {
            Shape::Rectangular => 1.0,
            Shape::Cylinder => 0.6,
            Shape::Sphere => 0.35,
        }
    }

    /// Distal angle at which the distal phalanx reaches the surface once the proximal touches,
    /// rad, for local half-width `w_m`: phenomenological — a flat face needs a fixed small
    /// wrap, a curved one more the smaller its radius.
    fn distal_wrap_rad(self, w_m: f64) -> f64 {
        let r = w_m.max(1e-3);
        match self {
            Shape::Rectangular => 0.25,
            Shape::Cylinder => 0.5 * 0.03 / r,
            Shape::Sphere => 0.6 * 0.03 / r,
        }
    }
}

/// Model-object materials and their softness class (seed 001 §2.4 and §3.1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Material {
    /// Sponge: soft.
    Sponge,
    /// Silicone rubber: moderate.
    SiliconeRubber,
    /// Wood: hard.
    Wood,
}

impl Material {
    /// Every material, soft to hard.
    pub const ALL: [Material; 3] = [Material::Sponge, Material::SiliconeRubber, Material::Wood];

    /// The class the paper labels it with.
    pub fn softness(self) -> Softness {
        match self {
            Material::Sponge => Softness::Soft,
            Material::SiliconeRubber => Softness::Moderate,
            Material::Wood => Softness::Hard,
        }
    }

    /// The model material of a class.
    pub fn of(softness: Softness) -> Material {
        match softness {
            Softness::Soft => Material::Sponge,
            Softness::Moderate => Material::SiliconeRubber,
            Softness::Hard => Material::Wood,
        }
    }

    /// Nominal effective Young's modulus, Pa: open-cell PU foam ≈ 25 kPa, a soft casting
    /// silicone ≈ 0.25 MPa, wood across the grain ≈ 10 GPa (handbook orders of magnitude; the
    /// paper gives none).
    pub fn nominal_modulus_pa(self) -> f64 {
        match self {
            Material::Sponge => 25e3,
            Material::SiliconeRubber => 0.12e6,
            Material::Wood => 10e9,
        }
    }
}

/// An object to grasp. `size_mm = 0` is an empty grasp (no finger ever touches).
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ObjectConfig {
    /// Shape.
    pub shape: Shape,
    /// Cross-section size, mm: the rectangle's side, the cylinder's or sphere's diameter.
    pub size_mm: f64,
    /// Material, and so the class label.
    pub material: Material,
    /// Effective modulus, Pa, when not the material's nominal one (another batch, a household
    /// object's overall stiffness).
    pub modulus_pa: Option<f64>,
    /// Per-finger multiplier of the modulus where that finger touches (1 = uniform).
    pub local_modulus_factor: [f64; 4],
    /// Per-finger multiplier of the local half-width (1 = the ideal shape).
    pub local_width_factor: [f64; 4],
}

impl Default for ObjectConfig {
    fn default() -> Self {
        ObjectConfig {
            shape: Shape::Cylinder,
            size_mm: 80.0,
            material: Material::Sponge,
            modulus_pa: None,
            local_modulus_factor: [1.0; 4],
            local_width_factor: [1.0; 4],
        }
    }
}

fn non_negative(field: &'static str, x: f64) -> Result<(), SimError> {
    if x.is_finite() && x >= 0.0 {
        Ok(())
    } else {
        Err(SimError::config(
            field,
            format!("must be finite and ≥ 0, got {x}"),
        ))
    }
}

impl ObjectConfig {
    /// The modulus away from any local feature, Pa.
    pub fn modulus(&self) -> f64 {
        self.modulus_pa
            .unwrap_or(self.material.nominal_modulus_pa())
    }

    /// The modulus each finger meets, Pa: [`modulus`](Self::modulus) × its local factor.
    pub fn local_moduli(&self) -> [f64; 4] {
        self.local_modulus_factor.map(|f| self.modulus() * f)
    }

    /// Checks every value; `palm_radius_m` bounds the size that fits the open hand.
    pub fn validate(&self, palm_radius_m: f64) -> Result<(), SimError> {
        non_negative("object.size_mm", self.size_mm)?;
        let max = 2000.0 * palm_radius_m;
        if self.size_mm > max {
            let why = format!(
                "{} mm does not fit between the open fingers (≤ {max} mm)",
                self.size_mm
            );
            return Err(SimError::config("object.size_mm", why));
        }
        non_negative("object.modulus_pa", self.modulus())?;
        for f in self.local_modulus_factor {
            non_negative("object.local_modulus_factor", f)?;
        }
        for f in self.local_width_factor {
            non_negative("object.local_width_factor", f)?;
        }
        Ok(())
    }

    /// Where each finger meets the object in `pose`, or `None` for a finger that never does.
    pub fn finger_contacts(
        &self,
        pose: &Pose,
        finger: &FingerParams,
    ) -> [Option<FingerContact>; 4] {
        std::array::from_fn(|i| {
            // Fingers sit at 45°, 135°, 225°, 315° around the hand's axis.
            let psi = FRAC_PI_4 + FRAC_PI_2 * i as f64;
            let half = self.size_mm * 5e-4;
            let w_ideal = match self.shape {
                Shape::Rectangular => {
                    let a = psi - pose.yaw_rad;
                    half / a.cos().abs().max(a.sin().abs())
                }
                Shape::Cylinder | Shape::Sphere => half,
            };
            let toward = pose.offset_m[0] * psi.cos() + pose.offset_m[1] * psi.sin();
            let w = w_ideal * self.local_width_factor[i] + toward;
            let gap = finger.palm_radius_m - w;
            if self.size_mm <= 0.0 || w <= 0.0 || gap > finger.proximal_contact_m {
                return None;
            }
            let law = ContactLaw::new(
                self.local_moduli()[i],
                w,
                self.shape.area_factor(),
                &finger.pad,
            );
            let wrap = self.shape.distal_wrap_rad(w) + pose.wrap_jitter_rad[i];
            Some(FingerContact {
                proximal_touch_rad: (gap / finger.proximal_contact_m).clamp(0.0, 1.0).asin(),
                distal_touch_rad: wrap.clamp(0.0, 1.2),
                proximal: law,
                distal: law,
            })
        })
    }
}

/// How an object sits in the hand for one grasp ("arbitrary pose", seed 001 §3.1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Pose {
    /// Object centre off the hand's axis, m.
    pub offset_m: [f64; 2],
    /// Rotation about the hand's axis, rad.
    pub yaw_rad: f64,
    /// Per-finger change of where the distal meets the surface, rad.
    pub wrap_jitter_rad: [f64; 4],
}

/// How poses vary between repeats.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PoseConfig {
    /// Standard deviation of the centre offset along each axis, mm.
    pub offset_sd_mm: f64,
    /// Whether the yaw is uniform over a full turn (else 0).
    pub random_yaw: bool,
    /// Standard deviation of the distal touch angle, degrees.
    pub wrap_jitter_sd_deg: f64,
}

impl Default for PoseConfig {
    fn default() -> Self {
        PoseConfig {
            offset_sd_mm: 2.0,
            random_yaw: true,
            wrap_jitter_sd_deg: 4.0,
        }
    }
}

impl PoseConfig {
    /// Checks every value.
    pub fn validate(&self) -> Result<(), SimError> {
        non_negative("pose.offset_sd_mm", self.offset_sd_mm)?;
        non_negative("pose.wrap_jitter_sd_deg", self.wrap_jitter_sd_deg)
    }

    /// Draws a pose (validated configs only: the deviations are finite and ≥ 0).
    pub fn draw(&self, rng: &mut impl Rng) -> Pose {
        let mut n = || -> f64 { rng.sample(StandardNormal) };
        let offset_m = [
            n() * self.offset_sd_mm * 1e-3,
            n() * self.offset_sd_mm * 1e-3,
        ];
        let wrap_jitter_rad = std::array::from_fn(|_| n() * self.wrap_jitter_sd_deg.to_radians());
        let yaw_rad = if self.random_yaw {
            rng.random_range(0.0..std::f64::consts::TAU)
        } else {
            0.0
        };
        Pose {
            offset_m,
            yaw_rad,
            wrap_jitter_rad,
        }
    }
}
