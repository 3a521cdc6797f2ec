//! The grasp physics as the MX-28's load: the object between the pads, its friction, crushing
//! and sliding, and the patch it presses on the fingertip. It knows nothing of the motor: it is
//! a [`Plant`] the servo simulator steps, in process ([`super::GraspRig`]) or behind the
//! Protocol 2.0 bus (`dxl_sim::SimBus::set_plant`).

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};
use std::time::Duration;

use dxl_sim::{Load, Plant};

use super::contact::{self, PAD_SLIDE_LIMIT_M};
use super::object::{G, ObjectParams};
use super::persist::Persistence;
use super::rig::{CRUSH_TIME_S, RigParams};
use crate::fingertip::ContactPatch;

/// The object's state, stepped with the servo.
#[derive(Debug, Clone)]
pub struct GraspBody {
    object: ObjectParams,
    params: RigParams,
    /// Servo angle at which the pads are `approach_m` from the surface (the start), rad.
    origin_rad: f64,
    /// From this simulated time on the object is lifted, s (∞: on the table).
    lift_at_s: f64,
    slide_v: f64,
    slip_m: f64,
    crush: Persistence,
    dropped: bool,
    force_n: f64,
    peak_force_n: f64,
    ever_slipping: bool,
    patch: ContactPatch,
    /// Patch changes beyond this force step are logged for a fingertip (`None`: not logged).
    contact_dead_band_n: Option<f64>,
    contacts: Vec<(u64, ContactPatch)>,
}

impl GraspBody {
    /// `object` between open pads; the servo starts at `origin_rad`.
    pub fn new(object: ObjectParams, params: RigParams, origin_rad: f64) -> Self {
        GraspBody {
            object,
            params,
            origin_rad,
            lift_at_s: f64::INFINITY,
            slide_v: 0.0,
            slip_m: 0.0,
            crush: Persistence::default(),
            dropped: false,
            force_n: 0.0,
            peak_force_n: 0.0,
            ever_slipping: false,
            patch: ContactPatch::NONE,
            contact_dead_band_n: None,
            contacts: Vec::new(),
        }
    }

    /// Lifts the object from simulated time `t_s` on (∞: leave it on the table).
    pub fn lift_at(&mut self, t_s: f64) {
        self.lift_at_s = t_s;
    }

    /// Logs every patch change (new cells, or the force moving more than `dead_band_n`) for
    /// [`GraspBody::take_contacts`]: a fingertip fed from the log sees the squeeze at the
    /// physics' own steps, not only at a control loop's ticks.
    pub fn log_contacts(&mut self, dead_band_n: f64) {
        self.contact_dead_band_n = Some(dead_band_n);
    }

    /// The logged patch changes (simulated ns, patch) since the last call.
    pub fn take_contacts(&mut self) -> std::vec::Drain<'_, (u64, ContactPatch)> {
        self.contacts.drain(..)
    }

    /// The servo angle relative to the start, rad (positive closes).
    pub fn closing_rad(&self, position_rad: f64) -> f64 {
        position_rad - self.origin_rad
    }

    fn load_at(&self, position_rad: f64) -> Load {
        if self.dropped {
            Load::default()
        } else {
            contact::load(self.closing_rad(position_rad), &self.object, &self.params)
        }
    }

    /// Gravity against Coulomb friction on both pads (µ static = µ kinetic): the object sticks
    /// while `2 µ F ≥ m g`, else slides down with `a = g − 2 µ F / m` until it stops or leaves
    /// the pads.
    fn slide(&mut self, dt_s: f64, t_s: f64) {
        if t_s < self.lift_at_s || self.dropped {
            return;
        }
        let friction_n = 2.0 * self.object.material.friction * self.force_n;
        let weight_n = self.object.mass_kg * G;
        if self.slide_v == 0.0 && friction_n >= weight_n {
            return;
        }
        let a = G - friction_n / self.object.mass_kg;
        let v0 = self.slide_v;
        self.slide_v = (v0 + a * dt_s).max(0.0);
        self.slip_m += 0.5 * (v0 + self.slide_v) * dt_s;
        if self.slip_m >= PAD_SLIDE_LIMIT_M {
            self.dropped = true;
            self.slide_v = 0.0;
            self.force_n = 0.0;
        }
    }

    fn stepped(&mut self, position_rad: f64, velocity_rad_s: f64, dt_s: f64, t: Duration) {
        let t_s = t.as_secs_f64();
        let after = self.load_at(position_rad);
        self.force_n = contact::pad_force_n(&after, velocity_rad_s, &self.params);
        self.crush.update(
            self.force_n >= self.object.damage_force_n,
            dt_s,
            CRUSH_TIME_S,
        );
        self.slide(dt_s, t_s);
        self.peak_force_n = self.peak_force_n.max(self.force_n);
        self.ever_slipping |= self.slide_v > 0.0;
        if let Some(band) = self.contact_dead_band_n {
            let p = self.patch();
            if p.cells != self.patch.cells || (p.force_n - self.patch.force_n).abs() > band {
                self.contacts.push((t.as_nanos() as u64, p));
                self.patch = p;
            }
        }
    }

    /// Normal force of each pad on the object, N.
    pub fn grip_force_n(&self) -> f64 {
        self.force_n
    }

    /// Highest pad force so far, N.
    pub fn peak_force_n(&self) -> f64 {
        self.peak_force_n
    }

    /// Whether the object is sliding now.
    pub fn slipping(&self) -> bool {
        self.slide_v > 0.0
    }

    /// Whether it ever slid.
    pub fn ever_slipping(&self) -> bool {
        self.ever_slipping
    }

    /// Total slide along the pads since the lift, m.
    pub fn slip_m(&self) -> f64 {
        self.slip_m
    }

    /// Whether the object has been crushed.
    pub fn damaged(&self) -> bool {
        self.crush.tripped()
    }

    /// Whether the object has left the grasp.
    pub fn dropped(&self) -> bool {
        self.dropped
    }

    /// Where and how hard the object presses each fingertip pad now.
    pub fn patch(&self) -> ContactPatch {
        if self.dropped {
            ContactPatch::NONE
        } else {
            contact::patch(&self.object, self.force_n)
        }
    }

    /// The object.
    pub fn object(&self) -> &ObjectParams {
        &self.object
    }

    /// The hand's parameters.
    pub fn params(&self) -> &RigParams {
        &self.params
    }
}

/// A [`GraspBody`] shared between the servo that steps it and whoever reads it.
#[derive(Debug, Clone)]
pub struct GraspPlant(Arc<Mutex<GraspBody>>);

impl GraspPlant {
    /// Shares `body`.
    pub fn new(body: GraspBody) -> Self {
        GraspPlant(Arc::new(Mutex::new(body)))
    }

    /// The body (a panic elsewhere leaves it readable).
    pub fn body(&self) -> MutexGuard<'_, GraspBody> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl Plant for GraspPlant {
    fn load(&mut self, position_rad: f64, _velocity_rad_s: f64, _t: Duration) -> Load {
        self.body().load_at(position_rad)
    }

    fn stepped(&mut self, position_rad: f64, velocity_rad_s: f64, dt: Duration, t: Duration) {
        self.body()
            .stepped(position_rad, velocity_rad_s, dt.as_secs_f64(), t);
    }
}
