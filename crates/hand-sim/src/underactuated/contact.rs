//! One phalanx pressing into an object: the fingertip pad in series with the object's local
//! material, stiffening as the material densifies, with creep for soft materials.
//!
//! Stated model (the paper gives no material data): the object's local material is described by
//! one effective Young's modulus `E`. Over a contact patch of area `A` (a phalanx pad, reduced
//! for curved shapes) and a compressible depth `h` (the object's local half-width), its
//! stiffness is `E·A/h`; the soft fingertip pad (seed 001 §2.1 prefers one) is in series. The
//! force is `k·u / (1 − u/u_max)`, `u` the indentation minus creep, `u_max` the depth at which
//! the material densifies; past 90 % of `u_max` the law continues as a steep line so it stays
//! finite. Creep is a Zener-like relaxation: a fraction `ρ(E)` of the indentation flows away
//! with time constant `τ` (sponge ρ ≈ 0.35, silicone ≈ 0.15, wood 0).

use serde::Deserialize;

/// The soft fingertip pad every contact goes through.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Pad {
    /// Pad modulus, Pa (a soft silicone, Shore A ≈ 10).
    pub modulus_pa: f64,
    /// Pad thickness, m.
    pub thickness_m: f64,
    /// Contact area of one phalanx on a flat face, m² (the 10 mm wide FSR strip × 30 mm).
    pub area_m2: f64,
    /// Creep time constant of every material, s.
    pub creep_tau_s: f64,
}

impl Default for Pad {
    fn default() -> Self {
        Pad {
            modulus_pa: 0.3e6,
            thickness_m: 0.004,
            area_m2: 3.0e-4,
            creep_tau_s: 2.5,
        }
    }
}

/// (log10 E, relaxing fraction ρ, densification strain) anchors: sponge, silicone rubber, wood.
/// Between anchors the two properties are interpolated linearly in log10 E.
const ANCHORS: [(f64, f64, f64); 3] = [(4.4, 0.35, 0.8), (5.4, 0.15, 0.5), (10.0, 0.0, 0.02)];

/// `(ρ, densification strain)` of a material of modulus `modulus_pa`.
pub fn material_properties(modulus_pa: f64) -> (f64, f64) {
    let x = modulus_pa.max(1e-30).log10();
    let first = ANCHORS[0];
    let last = ANCHORS[ANCHORS.len() - 1];
    if x <= first.0 {
        return (first.1, first.2);
    }
    for w in ANCHORS.windows(2) {
        let (a, b) = (w[0], w[1]);
        if x <= b.0 {
            let s = (x - a.0) / (b.0 - a.0);
            return (a.1 + s * (b.1 - a.1), a.2 + s * (b.2 - a.2));
        }
    }
    (last.1, last.2)
}

/// A phalanx–object contact law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// Small-indentation stiffness, N/m (pad and object in series).
    pub stiffness_n_per_m: f64,
    /// Indentation at which the pad and material are fully densified, m.
    pub max_depth_m: f64,
    /// Fraction of a held indentation that creeps away.
    pub relax_fraction: f64,
    /// Creep time constant, s.
    pub tau_s: f64,
}

impl ContactLaw {
    /// The law for material `modulus_pa`, compressible depth `depth_m`, patch area
    /// `area_factor · pad.area_m2`.
    pub fn new(modulus_pa: f64, depth_m: f64, area_factor: f64, pad: &Pad) -> ContactLaw {
        let area = pad.area_m2 * area_factor;
        let k_pad = pad.modulus_pa * area / pad.thickness_m;
        // A 1 mm floor on the depth keeps E·A/h finite for vanishing objects.
        let depth = depth_m.max(1e-3);
        let k_obj = modulus_pa * area / depth;
        // 1/(1/a + 1/b), written so that k_obj = 0 gives 0 and k_obj = ∞ gives k_pad.
        let stiffness = if k_obj.is_infinite() {
            k_pad
        } else {
            k_pad * k_obj / (k_pad + k_obj)
        };
        let share = if k_obj.is_infinite() {
            0.0
        } else {
            k_pad / (k_pad + k_obj)
        };
        let (rho, strain) = material_properties(modulus_pa);
        ContactLaw {
            stiffness_n_per_m: if stiffness.is_finite() {
                stiffness
            } else {
                0.0
            },
            max_depth_m: 0.6 * pad.thickness_m + strain * depth,
            relax_fraction: rho * share,
            tau_s: pad.creep_tau_s,
        }
    }

    /// Normal force, N, at indentation `depth_m` with `creep_m` of it relaxed away.
    pub fn force(&self, depth_m: f64, creep_m: f64) -> f64 {
        let u = depth_m - creep_m;
        if u.is_nan() || u <= 0.0 {
            return 0.0;
        }
        let knee = 0.9 * self.max_depth_m;
        let shape = if u < knee {
            u / (1.0 - u / self.max_depth_m)
        } else {
            // Value and slope of u/(1 − u/u_max) at 0.9·u_max are 10·knee and 100.
            10.0 * knee + 100.0 * (u - knee)
        };
        self.stiffness_n_per_m * shape
    }

    /// The creep after `dt_s` more at indentation `depth_m` (implicit Euler: stable for any step).
    pub fn creep_after(&self, creep_m: f64, depth_m: f64, dt_s: f64) -> f64 {
        let target = self.relax_fraction * depth_m.max(0.0);
        let a = dt_s / (self.tau_s + dt_s);
        creep_m + a * (target - creep_m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wood_is_pad_limited_and_sponge_is_object_limited() {
        let pad = Pad::default();
        let k_pad = pad.modulus_pa * pad.area_m2 / pad.thickness_m;
        let wood = ContactLaw::new(10e9, 0.04, 1.0, &pad);
        let sponge = ContactLaw::new(25e3, 0.04, 1.0, &pad);
        assert!((wood.stiffness_n_per_m / k_pad - 1.0).abs() < 1e-3);
        assert!(sponge.stiffness_n_per_m < 0.01 * k_pad);
        assert!(sponge.relax_fraction > 0.3 && wood.relax_fraction < 1e-3);
        assert_eq!(ContactLaw::new(0.0, 0.04, 1.0, &pad).force(0.01, 0.0), 0.0);
    }
}
