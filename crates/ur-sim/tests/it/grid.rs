//! Where the tests send the arm: the home configuration and nine tool poses on a 3 × 3 grid
//! 60 mm apart, 0.2 m above the base plane under the home pose, tool oriented as at home — each
//! with a joint solution inside a UR3's reach and limits.

use ur_bridge::Pose;
use ur_bridge::kinematics::{self, HOME_Q, Joints, UrModel};

/// The home pose and the nine grid poses, region order (row along y, column along x).
pub(crate) struct Grid {
    home: Pose,
    poses: [Pose; 9],
}

impl Grid {
    /// The grid of a UR3 at [`HOME_Q`]; panics if a pose has no joint solution near home.
    pub(crate) fn ur3() -> Grid {
        const CENTRE_M: [f64; 3] = [-0.30, -0.11, 0.20];
        const SPACING_M: f64 = 0.06;
        let model = UrModel::ur3();
        let home = kinematics::to_pose(&model.forward(&HOME_Q));
        let poses = core::array::from_fn(|r| {
            let (row, col) = ((r / 3) as f64 - 1.0, (r % 3) as f64 - 1.0);
            Pose {
                position_m: [
                    CENTRE_M[0] + col * SPACING_M,
                    CENTRE_M[1] + row * SPACING_M,
                    CENTRE_M[2],
                ],
                rotation_vec_rad: home.rotation_vec_rad,
            }
        });
        for (r, pose) in poses.iter().enumerate() {
            let q = model
                .inverse_near(&kinematics::to_isometry(pose), &HOME_Q)
                .unwrap_or_else(|e| panic!("grid pose {r}: {e}"));
            model
                .check_limits(&q)
                .unwrap_or_else(|e| panic!("grid pose {r}: {e}"));
        }
        Grid { home, poses }
    }

    /// The home tool pose.
    pub(crate) fn home(&self) -> &Pose {
        &self.home
    }

    /// The home joint configuration.
    pub(crate) fn home_joints(&self) -> &Joints {
        &HOME_Q
    }

    /// The pose of region `r` (`0..9`).
    pub(crate) fn pose(&self, r: u16) -> &Pose {
        &self.poses[usize::from(r)]
    }
}
