//! The region → grid map of tap-to-move ("the region recognised by the CNN is mapped to a
//! predefined robot position on a grid", §IV-B of the paper cited in the parent module): 9 pad regions →
//! 9 tool poses, each checked for a joint solution within the arm's reach and joint limits,
//! reached in a straight line from home.

use hand_traits::Pose;

use ur_bridge::kinematics::{self, Joints, KinematicsError, UrModel};

/// Regions of the pad, and positions on the grid.
pub const REGIONS: usize = 9;

/// Why a grid cannot be used, or a region has no pose.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GridError {
    /// A grid pose (or a point on the straight line to it from home) fails the arm's kinematics.
    #[error("grid position {region}: {source}")]
    Unreachable {
        /// The region whose pose fails, `0..9`.
        region: usize,
        /// Why.
        source: KinematicsError,
    },
    /// The home configuration itself is outside the joint limits.
    #[error("home: {0}")]
    Home(KinematicsError),
    /// A locator named a region the grid does not have.
    #[error("region {region} of {regions}: the grid has {REGIONS} positions")]
    NoSuchRegion {
        /// The region reported.
        region: u16,
        /// How many regions the locator distinguishes.
        regions: u16,
    },
    /// The grid spacing is not a positive finite length.
    #[error("grid spacing {0} m is not a positive finite length")]
    Spacing(f64),
}

/// Nine validated tool poses, one per pad region, and the home pose they are reached from.
#[derive(Debug, Clone, PartialEq)]
pub struct RegionToGrid {
    home: Pose,
    home_q: Joints,
    poses: [Pose; REGIONS],
    joints: [Joints; REGIONS],
}

/// Points checked along each straight line from home (the moveL path must stay reachable).
const LINE_CHECKS: usize = 20;

impl RegionToGrid {
    /// The home joint configuration: shoulder up, forearm level, tool pointing down
    /// ([`kinematics::HOME_Q`]).
    pub const HOME_Q: Joints = kinematics::HOME_Q;

    /// A grid from explicit poses, validated against `model` from `home_q`.
    pub fn new(model: &UrModel, home_q: Joints, poses: [Pose; REGIONS]) -> Result<Self, GridError> {
        model.check_limits(&home_q).map_err(GridError::Home)?;
        let home_iso = model.forward(&home_q);
        let mut joints = [home_q; REGIONS];
        for (region, pose) in poses.iter().enumerate() {
            let err = |source| GridError::Unreachable { region, source };
            let target = kinematics::to_isometry(pose);
            // Follow the moveL line from home so the solution is the one the arm will reach.
            let mut q = home_q;
            for k in 1..=LINE_CHECKS {
                let u = k as f64 / LINE_CHECKS as f64;
                let p = nalgebra::Isometry3::from_parts(
                    home_iso
                        .translation
                        .vector
                        .lerp(&target.translation.vector, u)
                        .into(),
                    home_iso.rotation.slerp(&target.rotation, u),
                );
                q = model.inverse_near(&p, &q).map_err(err)?;
                model.check_limits(&q).map_err(err)?;
            }
            joints[region] = q;
        }
        Ok(Self {
            home: kinematics::to_pose(&home_iso),
            home_q,
            poses,
            joints,
        })
    }

    /// A 3 × 3 grid in the horizontal plane through `centre_m`, `spacing_m` apart, tool
    /// orientation as at home. Region `r` is row `r / 3` (along y), column `r % 3` (along x).
    ///
    /// ```
    /// use handstack::tap_to_move::RegionToGrid;
    /// use ur_bridge::kinematics::UrModel;
    /// let grid = RegionToGrid::square(&UrModel::ur3(), RegionToGrid::HOME_Q, [-0.30, -0.11, 0.20], 0.06)?;
    /// let p4 = grid.pose(4)?; // the centre
    /// assert!((p4.position_m[0] + 0.30).abs() < 1e-12);
    /// // 0.9 m from the base is beyond a UR3's 0.5 m reach:
    /// assert!(RegionToGrid::square(&UrModel::ur3(), RegionToGrid::HOME_Q, [-0.9, 0.0, 0.2], 0.06).is_err());
    /// # Ok::<(), handstack::tap_to_move::GridError>(())
    /// ```
    pub fn square(
        model: &UrModel,
        home_q: Joints,
        centre_m: [f64; 3],
        spacing_m: f64,
    ) -> Result<Self, GridError> {
        if !(spacing_m.is_finite() && spacing_m > 0.0) {
            return Err(GridError::Spacing(spacing_m));
        }
        let rot = kinematics::to_pose(&model.forward(&home_q)).rotation_vec_rad;
        let poses = core::array::from_fn(|r| {
            let (row, col) = ((r / 3) as f64 - 1.0, (r % 3) as f64 - 1.0);
            Pose {
                position_m: [
                    centre_m[0] + col * spacing_m,
                    centre_m[1] + row * spacing_m,
                    centre_m[2],
                ],
                rotation_vec_rad: rot,
            }
        });
        Self::new(model, home_q, poses)
    }

    /// The grid the tests and docs use: 60 mm pitch, centred 0.2 m above the base plane under
    /// the home pose of a UR3.
    pub fn ur3_default() -> Result<Self, GridError> {
        Self::square(&UrModel::ur3(), Self::HOME_Q, [-0.30, -0.11, 0.20], 0.06)
    }

    /// The home tool pose.
    pub fn home(&self) -> &Pose {
        &self.home
    }

    /// The home joint configuration.
    pub fn home_joints(&self) -> &Joints {
        &self.home_q
    }

    /// The pose for `region`.
    pub fn pose(&self, region: u16) -> Result<&Pose, GridError> {
        self.poses
            .get(usize::from(region))
            .ok_or(GridError::NoSuchRegion {
                region,
                regions: REGIONS as u16,
            })
    }

    /// The joint solution the validation found for `region` (reached by moveL from home).
    pub fn joints(&self, region: u16) -> Result<&Joints, GridError> {
        self.joints
            .get(usize::from(region))
            .ok_or(GridError::NoSuchRegion {
                region,
                regions: REGIONS as u16,
            })
    }

    /// All nine poses, region order.
    pub fn poses(&self) -> &[Pose; REGIONS] {
        &self.poses
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_grid_is_valid_and_regular() {
        let g = RegionToGrid::ur3_default().expect("default grid");
        let m = UrModel::ur3();
        for r in 0..9u16 {
            let fk = kinematics::to_pose(&m.forward(g.joints(r).unwrap()));
            assert!(fk.distance_m(g.pose(r).unwrap()) < 1e-9);
        }
        let d = g.pose(0).unwrap().distance_m(g.pose(1).unwrap());
        assert!((d - 0.06).abs() < 1e-12);
        assert!(matches!(
            g.pose(9),
            Err(GridError::NoSuchRegion { region: 9, .. })
        ));
    }

    #[test]
    fn joint_limits_reject_a_grid() {
        let mut m = UrModel::ur3();
        // A base joint limited to ±0.1 rad cannot swing to a grid 0.3 m to the side.
        m.q_min_rad[0] = -0.1;
        m.q_max_rad[0] = 0.1;
        let e =
            RegionToGrid::square(&m, RegionToGrid::HOME_Q, [-0.10, -0.35, 0.20], 0.06).unwrap_err();
        assert!(
            matches!(
                e,
                GridError::Unreachable {
                    source: KinematicsError::JointLimit { joint: 0, .. },
                    ..
                }
            ),
            "{e}"
        );
        assert!(matches!(
            RegionToGrid::square(&m, RegionToGrid::HOME_Q, [0.0; 3], f64::NAN),
            Err(GridError::Spacing(_))
        ));
    }
}
