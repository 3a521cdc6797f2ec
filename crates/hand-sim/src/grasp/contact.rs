//! The contact between one pad and the object: the squeeze force law the servo drives against,
//! and the fingertip cells it presses ([`ContactPatch`]).

use super::object::ObjectParams;
use super::rig::RigParams;
use dxl_sim::Load;

use crate::fingertip::ContactPatch;
use crate::fingertip::geometry::{Cell, CellSet, HEIGHT_MM};

/// Poisson's ratio assumed for skin and objects (rubber-like 0.5 for the skin; the term barely
/// matters for stiff objects).
const POISSON: f64 = 0.5;
/// Young's modulus of the fingertip skin, Pa: seed 000 §2's 1:1 liquid/solid silicone "similar to
/// a solid jelly" — a Shore 00 silicone, about 0.1 MPa (assumed).
pub const SKIN_MODULUS_PA: f64 = 1.0e5;

/// The pad's penetration into the object, m, at servo position `theta` (0 at the start, the pads
/// `approach_m` away from the surface).
pub fn penetration_m(theta_rad: f64, rig: &RigParams) -> f64 {
    theta_rad * rig.linkage.lever_m - rig.approach_m
}

/// The object's squeeze reaction, seen at the servo: spring torque, stiffness and damping at the
/// present state (zero out of contact). The object is a spring `k` between the two pads (it is
/// compressed by twice each pad's penetration) with damping for a contact damping ratio `ζ`.
pub fn load(theta_rad: f64, obj: &ObjectParams, rig: &RigParams) -> Load {
    let x = penetration_m(theta_rad, rig);
    if x <= 0.0 {
        return Load::default();
    }
    let lever = rig.linkage.lever_m / rig.linkage.efficiency;
    let k_pad = 2.0 * obj.material.stiffness_n_per_m;
    let stiffness = k_pad * rig.linkage.lever_m * lever;
    Load {
        torque_nm: k_pad * x * lever,
        stiffness_nm_per_rad: stiffness,
        damping_nm_s_per_rad: 2.0
            * rig.contact_damping_ratio
            * (stiffness * rig.servo.inertia_kg_m2).sqrt(),
    }
}

/// The pad force, N, for servo torque `load` state at velocity `omega`: spring plus damping,
/// never pulling.
pub fn pad_force_n(lin: &Load, omega_rad_s: f64, rig: &RigParams) -> f64 {
    let torque = lin.torque_nm + lin.damping_nm_s_per_rad * omega_rad_s;
    (torque * rig.linkage.force_per_torque()).max(0.0)
}

/// The cells the object presses with `force_n`. Along each pad axis the contact half-width is
/// Hertz's `a = (3 F R / 4 E*)^⅓` for a curved object (a per-axis approximation of the
/// elliptical contact), or half the face for a flat one; cells whose centres lie in the ellipse
/// are pressed, and the cells nearest the pad centre when it holds none.
pub fn patch(obj: &ObjectParams, force_n: f64) -> ContactPatch {
    if !(force_n.is_finite() && force_n > 0.0) {
        return ContactPatch::NONE;
    }
    let m = &obj.material;
    let e_star = 1.0 / ((1.0 - POISSON * POISSON) * (1.0 / SKIN_MODULUS_PA + 1.0 / m.modulus_pa));
    let half_mm = |axis: usize| match m.radius_m[axis] {
        Some(r) => (3.0 * force_n * r / (4.0 * e_star)).cbrt() * 1e3,
        None => m.face_m[axis] * 1e3 / 2.0,
    };
    let (ax, ay) = (half_mm(0), half_mm(1));
    let inside = |c: &Cell| {
        let [x, y] = c.centre_mm();
        (x / ax).powi(2) + (y / ay).powi(2) <= 1.0
    };
    let mut cells = Cell::all()
        .filter(inside)
        .fold(CellSet::EMPTY, CellSet::with);
    if cells.is_empty() {
        let dist = |c: &Cell| {
            let [x, y] = c.centre_mm();
            x.hypot(y)
        };
        let nearest = Cell::all().map(|c| dist(&c)).fold(f64::INFINITY, f64::min);
        cells = Cell::all()
            .filter(|c| dist(c) <= nearest + 1e-9)
            .fold(CellSet::EMPTY, CellSet::with);
    }
    ContactPatch {
        cells,
        force_n,
        offset_mm: [0.0, 0.0],
    }
}

/// How far the object can slide along the pad before it leaves it, m: the pad height.
pub const PAD_SLIDE_LIMIT_M: f64 = HEIGHT_MM * 1e-3;
