//! The six grasp objects of seed 000 §7 (Figure 22, Table 5) and how their parameters follow
//! from Table 5.
//!
//! The paper names the objects and their torque range, nothing else. Each object gets a
//! physically plausible [`Material`] (size, curvature, friction against the silicone skin,
//! squeeze stiffness, contact modulus); the two parameters Table 5 pins down are *derived*, not
//! typed in ([`ObjectParams::calibrated`]):
//!
//! - mass, from "torque min" = the least limit that holds without slip: two opposing pads,
//!   `2 µ F(min − ½) = m g`, so `min` holds and `min − 1` slips;
//! - crush (damage) force, from "torque max" = the largest limit that neither damages nor
//!   releases in a 2 min hold: `F_crush = F(max + ½)` — unless `max` is the top of the scale
//!   (cone, paper cup), where Table 5 only says the object survives whatever the hand does; their
//!   crush force is then a material assumption, checked to exceed the hand's settled force.
//!
//! `F(count)` is the stalled pad force of [`super::linkage`]; the settled force is
//! [`super::statics::settled_force_n`] (it is below `F(count)` when a compliant object lets the
//! servo reach its goal first).

use serde::Serialize;
use std::sync::OnceLock;

use super::rig::RigParams;
use super::servo::{TORQUE_LIMIT_MAX, positive};
use super::statics::{HoldingRange, predicted_range, settled_force_n};
use crate::SimError;

/// Standard gravity, m/s².
pub const G: f64 = 9.806_65;

/// One row of Table 5: an object and its torque min / max, MX-28 counts.
type Table5Row = (ObjectKind, u16, u16);

/// Table 5 of seed 000, as `paper-fixtures` reads it, read once.
fn table5_rows() -> Result<&'static [Table5Row], SimError> {
    static ROWS: OnceLock<Result<Vec<Table5Row>, String>> = OnceLock::new();
    let rows = ROWS.get_or_init(|| {
        let fixture = paper_fixtures::seed000::table5_grasp_torque().map_err(|e| e.to_string())?;
        fixture
            .iter()
            .map(|row| {
                let kind = ObjectKind::from_name(&row.object)
                    .ok_or_else(|| format!("unknown object `{}`", row.object))?;
                let count =
                    |v: u32| u16::try_from(v).map_err(|_| format!("{v} is no torque limit"));
                Ok((kind, count(row.torque_min)?, count(row.torque_max)?))
            })
            .collect()
    });
    rows.as_deref()
        .map_err(|reason| SimError::config("Table 5 fixture", reason.clone()))
}

/// The objects of Table 5.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
pub enum ObjectKind {
    /// A thin-walled box (assumed material), flat faces.
    Cube,
    /// A thin-walled cylinder, axis vertical.
    Cylinder,
    /// A foam cone, grasped at mid-height.
    Cone,
    /// A thin-walled ellipsoid, long axis vertical.
    Ellipsoid,
    /// An empty-ish paper cup: a soft ring.
    PaperCup,
    /// A roll of tissue on a cardboard core.
    ScrollTissue,
}

impl ObjectKind {
    /// All six, in Table 5's order.
    pub const ALL: [ObjectKind; 6] = [
        ObjectKind::Cube,
        ObjectKind::Cylinder,
        ObjectKind::Cone,
        ObjectKind::Ellipsoid,
        ObjectKind::PaperCup,
        ObjectKind::ScrollTissue,
    ];

    /// The name used in Table 5's fixture and in scene files.
    pub fn name(self) -> &'static str {
        match self {
            ObjectKind::Cube => "cube",
            ObjectKind::Cylinder => "cylinder",
            ObjectKind::Cone => "cone",
            ObjectKind::Ellipsoid => "ellipsoid",
            ObjectKind::PaperCup => "paper_cup",
            ObjectKind::ScrollTissue => "scroll_tissue",
        }
    }

    /// The kind named `name`, if any.
    pub fn from_name(name: &str) -> Option<ObjectKind> {
        ObjectKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// Table 5's (min, max) for this object (`fixtures/paper/seed000_table5_grasp_torque.csv`
    /// through `paper-fixtures`); an error if the fixture cannot be read or lacks the object.
    pub fn table5(self) -> Result<(u16, u16), SimError> {
        table5_rows()?
            .iter()
            .find(|(k, _, _)| *k == self)
            .map(|&(_, lo, hi)| (lo, hi))
            .ok_or_else(|| {
                SimError::config("Table 5 fixture", format!("no row for `{}`", self.name()))
            })
    }

    /// The assumed material and shape (everything Table 5 does not fix).
    pub fn material(self) -> Material {
        const MM: f64 = 1e-3;
        match self {
            // A 50 mm thin-walled printed box: stiff, cracks at a few newton.
            ObjectKind::Cube => Material {
                width_m: 50.0 * MM,
                radius_m: [None, None],
                face_m: [50.0 * MM, 50.0 * MM],
                friction: 0.5,
                stiffness_n_per_m: 20_000.0,
                modulus_pa: 2.0e9,
                crush_force_n: None,
            },
            ObjectKind::Cylinder => Material {
                width_m: 60.0 * MM,
                radius_m: [Some(30.0 * MM), None],
                face_m: [60.0 * MM, 100.0 * MM],
                friction: 0.5,
                stiffness_n_per_m: 20_000.0,
                modulus_pa: 2.0e9,
                crush_force_n: None,
            },
            // 70 mm base, 100 mm high, held at mid-height (Ø 35 mm); a straight generator is
            // flat along y, the section radius over cos(half-angle) curves x. Polyurethane foam.
            ObjectKind::Cone => Material {
                width_m: 35.0 * MM,
                radius_m: [Some(18.5 * MM), None],
                face_m: [35.0 * MM, 106.0 * MM],
                friction: 0.6,
                stiffness_n_per_m: 300.0,
                modulus_pa: 5.0e4,
                crush_force_n: Some(30.0),
            },
            // Semi-axes 40 mm (vertical) × 30 × 30: R_x = 30 mm, R_y = 40²/30 mm.
            ObjectKind::Ellipsoid => Material {
                width_m: 60.0 * MM,
                radius_m: [Some(30.0 * MM), Some(53.3 * MM)],
                face_m: [60.0 * MM, 80.0 * MM],
                friction: 0.5,
                stiffness_n_per_m: 15_000.0,
                modulus_pa: 2.0e9,
                crush_force_n: None,
            },
            // Ø 66 mm at the grip; the wall ovalises as a soft ring (~150 N/m), buckles near 8 N.
            ObjectKind::PaperCup => Material {
                width_m: 66.0 * MM,
                radius_m: [Some(33.0 * MM), None],
                face_m: [66.0 * MM, 90.0 * MM],
                friction: 0.4,
                stiffness_n_per_m: 150.0,
                modulus_pa: 4.0e9,
                crush_force_n: Some(8.0),
            },
            // Ø 110 mm roll, 100 mm long: soft layers over a cardboard core.
            ObjectKind::ScrollTissue => Material {
                width_m: 110.0 * MM,
                radius_m: [Some(55.0 * MM), None],
                face_m: [110.0 * MM, 100.0 * MM],
                friction: 0.4,
                stiffness_n_per_m: 3_000.0,
                modulus_pa: 2.0e5,
                crush_force_n: None,
            },
        }
    }
}

/// What an object is made of and shaped like, apart from mass and crush force.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Material {
    /// Width between the two pads at first contact, m.
    pub width_m: f64,
    /// Radius of curvature at the contact along the pad's x (row) and y (column), m; `None`: flat.
    pub radius_m: [Option<f64>; 2],
    /// Extent of the contact face along pad x and y, m (bounds the contact patch).
    pub face_m: [f64; 2],
    /// Coulomb friction coefficient against the silicone skin.
    pub friction: f64,
    /// Squeeze stiffness between the two pads (force per total compression), N/m.
    pub stiffness_n_per_m: f64,
    /// Young's modulus at the contact, Pa (sets the Hertz contact size).
    pub modulus_pa: f64,
    /// Crush force when Table 5 does not bound it (its max is 1023), N.
    pub crush_force_n: Option<f64>,
}

/// Everything the grasp model needs to know about one object.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ObjectParams {
    /// A name for reports.
    pub name: String,
    /// Shape and material.
    pub material: Material,
    /// Mass, kg.
    pub mass_kg: f64,
    /// Pad force held 0.5 s or longer that crushes (damages) it, N.
    pub damage_force_n: f64,
}

impl ObjectParams {
    /// The Table 5 object `kind`, calibrated to its row of Table 5 ([`ObjectKind::table5`]) for
    /// `rig`.
    pub fn table5(kind: ObjectKind, rig: &RigParams) -> Result<ObjectParams, SimError> {
        let (lo, hi) = kind.table5()?;
        ObjectParams::calibrated(kind, lo, hi, rig)
    }

    /// `kind`'s material with mass and crush force derived from a holding range
    /// `torque_min…torque_max` (see the module docs); errors if the range is not reachable with
    /// this material and rig (checked by recomputing it from the statics).
    pub fn calibrated(
        kind: ObjectKind,
        torque_min: u16,
        torque_max: u16,
        rig: &RigParams,
    ) -> Result<ObjectParams, SimError> {
        if !(1..=TORQUE_LIMIT_MAX).contains(&torque_min)
            || torque_max > TORQUE_LIMIT_MAX
            || torque_min > torque_max
        {
            return Err(SimError::config(
                "torque range",
                format!("need 1 ≤ min ≤ max ≤ 1023, got {torque_min}…{torque_max}"),
            ));
        }
        let m = kind.material();
        let f = |count: f64| rig.linkage.force_at_limit(count);
        let mass_kg = 2.0 * m.friction * f(f64::from(torque_min) - 0.5) / G;
        let damage_force_n = match (torque_max < TORQUE_LIMIT_MAX, m.crush_force_n) {
            (true, _) => f(f64::from(torque_max) + 0.5),
            (false, Some(crush)) => crush,
            (false, None) => {
                return Err(SimError::config(
                    "torque max",
                    format!("{} has no crush force for an unbounded max", kind.name()),
                ));
            }
        };
        let obj = ObjectParams {
            name: kind.name().to_string(),
            material: m,
            mass_kg,
            damage_force_n,
        };
        obj.validate()?;
        let want = HoldingRange {
            min: torque_min,
            max: torque_max,
        };
        match predicted_range(&obj, rig) {
            Some(got) if got == want => Ok(obj),
            got => Err(SimError::config(
                "material",
                format!(
                    "{}: material + rig give {got:?}, not {want:?} (settled force at goal {:.2} N)",
                    kind.name(),
                    settled_force_n(f64::from(TORQUE_LIMIT_MAX), &obj, rig)
                ),
            )),
        }
    }

    /// Checks every value is finite and in range.
    pub fn validate(&self) -> Result<(), SimError> {
        let m = &self.material;
        positive("mass_kg", self.mass_kg)?;
        positive("damage_force_n", self.damage_force_n)?;
        positive("width_m", m.width_m)?;
        positive("friction", m.friction)?;
        positive("stiffness_n_per_m", m.stiffness_n_per_m)?;
        positive("modulus_pa", m.modulus_pa)?;
        positive("face_m", m.face_m[0])?;
        positive("face_m", m.face_m[1])?;
        for r in m.radius_m.iter().flatten() {
            positive("radius_m", *r)?;
        }
        Ok(())
    }
}
