//! A kinematic UR3: Denavit–Hartenberg forward kinematics, the geometric Jacobian, a damped
//! least-squares inverse kinematics seeded near a joint configuration, and the arm's limits.
//!
//! Parameters are Universal Robots' published UR3 (CB3) DH table ("DH parameters for calculations
//! of kinematics and dynamics", universal-robots.com) and the UR3 datasheet (reach 500 mm, joint
//! range ±360°, wrist 3 infinite, joint speeds 180 °/s base/shoulder/elbow and 360 °/s wrists).

use core::f64::consts::{FRAC_PI_2, PI};

use hand_traits::Pose;
use nalgebra::{Isometry3, Matrix6, Rotation3, Translation3, UnitQuaternion, Vector3, Vector6};

/// Why a pose or a joint configuration is not usable.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum KinematicsError {
    /// A coordinate or angle is NaN or infinite.
    #[error("non-finite value in {0}")]
    NonFinite(&'static str),
    /// The position is farther from the shoulder than the arm reaches.
    #[error("pose is {distance_m:.4} m from the shoulder, beyond the {reach_m:.3} m reach")]
    OutOfReach {
        /// Distance from the shoulder joint to the wrist centre, in metres.
        distance_m: f64,
        /// The arm's reach, in metres.
        reach_m: f64,
    },
    /// No joint configuration near the seed reaches the pose.
    #[error("no inverse-kinematics solution (residual {residual:.3e})")]
    NoSolution {
        /// The remaining position + orientation error norm.
        residual: f64,
    },
    /// A joint would be outside its position limit.
    #[error("joint {joint} at {angle_rad:.4} rad is outside [{min_rad:.4}, {max_rad:.4}]")]
    JointLimit {
        /// Joint index, 0 = base … 5 = wrist 3.
        joint: usize,
        /// The offending angle.
        angle_rad: f64,
        /// The joint's lower limit.
        min_rad: f64,
        /// The joint's upper limit.
        max_rad: f64,
    },
}

/// Six joint angles, base first, in radians.
pub type Joints = [f64; 6];

/// A home joint configuration: shoulder up, forearm level, tool pointing down.
pub const HOME_Q: Joints = [0.0, -FRAC_PI_2, FRAC_PI_2, -FRAC_PI_2, -FRAC_PI_2, 0.0];

/// A UR arm's geometry and limits.
#[derive(Debug, Clone, PartialEq)]
pub struct UrModel {
    /// DH link offsets `d_i`, in metres.
    pub d_m: [f64; 6],
    /// DH link lengths `a_i`, in metres.
    pub a_m: [f64; 6],
    /// DH twists `alpha_i`, in radians.
    pub alpha_rad: [f64; 6],
    /// Lower joint position limits, in radians.
    pub q_min_rad: Joints,
    /// Upper joint position limits, in radians.
    pub q_max_rad: Joints,
    /// Joint speed limits, in radians per second.
    pub qd_max_rad_per_s: Joints,
    /// The datasheet reach (shoulder axis to wrist), in metres.
    pub reach_m: f64,
}

impl UrModel {
    /// The UR3 (CB3): DH table and datasheet limits.
    ///
    /// ```
    /// use ur_bridge::kinematics::UrModel;
    /// let ur3 = UrModel::ur3();
    /// // All joints at zero: the arm lies stretched along -x.
    /// let tcp = ur3.forward(&[0.0; 6]);
    /// assert!((tcp.translation.x - (-0.24365 - 0.21325)).abs() < 1e-12);
    /// ```
    pub fn ur3() -> Self {
        let big = 1e9; // wrist 3 turns without limit on a UR3
        Self {
            d_m: [0.1519, 0.0, 0.0, 0.11235, 0.08535, 0.0819],
            a_m: [0.0, -0.24365, -0.21325, 0.0, 0.0, 0.0],
            alpha_rad: [PI / 2.0, 0.0, 0.0, PI / 2.0, -PI / 2.0, 0.0],
            q_min_rad: [-2.0 * PI, -2.0 * PI, -2.0 * PI, -2.0 * PI, -2.0 * PI, -big],
            q_max_rad: [2.0 * PI, 2.0 * PI, 2.0 * PI, 2.0 * PI, 2.0 * PI, big],
            qd_max_rad_per_s: [PI, PI, PI, 2.0 * PI, 2.0 * PI, 2.0 * PI],
            reach_m: 0.5,
        }
    }

    /// The frame of every joint axis: `frames[i]` is the base-to-frame-`i` transform, `frames[0]`
    /// the base and `frames[6]` the flange (the TCP, with no tool offset).
    pub fn frames(&self, q: &Joints) -> [Isometry3<f64>; 7] {
        let mut frames = [Isometry3::identity(); 7];
        for i in 0..6 {
            let link = Isometry3::from_parts(
                Translation3::new(0.0, 0.0, self.d_m[i]),
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), q[i]),
            ) * Isometry3::from_parts(
                Translation3::new(self.a_m[i], 0.0, 0.0),
                UnitQuaternion::from_axis_angle(&Vector3::x_axis(), self.alpha_rad[i]),
            );
            frames[i + 1] = frames[i] * link;
        }
        frames
    }

    /// The tool flange pose for joint angles `q`.
    pub fn forward(&self, q: &Joints) -> Isometry3<f64> {
        self.frames(q)[6]
    }

    /// The geometric Jacobian (rows: linear x y z, angular x y z in the base frame).
    pub fn jacobian(&self, q: &Joints) -> Matrix6<f64> {
        let frames = self.frames(q);
        let tip = frames[6].translation.vector;
        let mut j = Matrix6::zeros();
        for i in 0..6 {
            let z = frames[i].rotation * Vector3::z();
            let o = frames[i].translation.vector;
            let lin = z.cross(&(tip - o));
            for r in 0..3 {
                j[(r, i)] = lin[r];
                j[(r + 3, i)] = z[r];
            }
        }
        j
    }

    /// Distance from the shoulder joint to the wrist centre (flange minus the last link), the
    /// quantity the datasheet reach bounds.
    pub fn shoulder_distance_m(&self, target: &Isometry3<f64>) -> f64 {
        let wrist =
            target.translation.vector - target.rotation * Vector3::new(0.0, 0.0, self.d_m[5]);
        (wrist - Vector3::new(0.0, 0.0, self.d_m[0])).norm()
    }

    /// Joint angles near `q_near` that put the flange at `target`, or why there are none.
    ///
    /// Damped least squares on the 6-D pose error; converges to ~1e-12 from a seed within a
    /// few tenths of a radian, so a straight-line move can be followed step by step.
    pub fn inverse_near(
        &self,
        target: &Isometry3<f64>,
        q_near: &Joints,
    ) -> Result<Joints, KinematicsError> {
        if !finite_iso(target) {
            return Err(KinematicsError::NonFinite("target pose"));
        }
        if q_near.iter().any(|v| !v.is_finite()) {
            return Err(KinematicsError::NonFinite("seed joints"));
        }
        let distance_m = self.shoulder_distance_m(target);
        if distance_m > self.reach_m {
            return Err(KinematicsError::OutOfReach {
                distance_m,
                reach_m: self.reach_m,
            });
        }
        let mut q = *q_near;
        let mut residual = f64::INFINITY;
        for _ in 0..200 {
            let e = pose_error(target, &self.forward(&q));
            residual = e.norm();
            if residual < 1e-12 {
                return Ok(q);
            }
            let j = self.jacobian(&q);
            // Damping grows near singularities (small singular values) and vanishes at the goal.
            let lambda2 = (1e-4 * residual).min(1e-3);
            let jjt = j * j.transpose() + Matrix6::identity() * lambda2;
            let Some(step) = jjt.lu().solve(&e) else {
                break;
            };
            let dq = j.transpose() * step;
            // Bound each step so the iteration stays on the seed's branch.
            let scale = (0.5 / dq.amax()).min(1.0);
            for k in 0..6 {
                q[k] += scale * dq[k];
            }
        }
        if residual < 1e-9 {
            Ok(q)
        } else {
            Err(KinematicsError::NoSolution { residual })
        }
    }

    /// The first joint outside its position limit, if any.
    pub fn check_limits(&self, q: &Joints) -> Result<(), KinematicsError> {
        for (joint, &angle_rad) in q.iter().enumerate() {
            if !angle_rad.is_finite() {
                return Err(KinematicsError::NonFinite("joint angle"));
            }
            let (min_rad, max_rad) = (self.q_min_rad[joint], self.q_max_rad[joint]);
            if angle_rad < min_rad || angle_rad > max_rad {
                return Err(KinematicsError::JointLimit {
                    joint,
                    angle_rad,
                    min_rad,
                    max_rad,
                });
            }
        }
        Ok(())
    }
}

fn finite_iso(p: &Isometry3<f64>) -> bool {
    p.translation.vector.iter().all(|v| v.is_finite())
        && p.rotation.coords.iter().all(|v| v.is_finite())
}

/// The 6-D error taking `from` to `to`: position difference, then the rotation vector of
/// `to · from⁻¹`, both in the base frame.
pub fn pose_error(to: &Isometry3<f64>, from: &Isometry3<f64>) -> Vector6<f64> {
    let dp = to.translation.vector - from.translation.vector;
    let dr = (to.rotation * from.rotation.inverse()).scaled_axis();
    Vector6::new(dp.x, dp.y, dp.z, dr.x, dr.y, dr.z)
}

/// A UR pose (position + rotation vector) as an isometry.
pub fn to_isometry(pose: &Pose) -> Isometry3<f64> {
    let [x, y, z] = pose.position_m;
    let [rx, ry, rz] = pose.rotation_vec_rad;
    Isometry3::from_parts(
        Translation3::new(x, y, z),
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_scaled_axis(Vector3::new(
            rx, ry, rz,
        ))),
    )
}

/// An isometry as a UR pose (rotation vector with angle in `[0, π]`).
pub fn to_pose(iso: &Isometry3<f64>) -> Pose {
    let t = iso.translation.vector;
    let r = iso.rotation.scaled_axis();
    Pose {
        position_m: [t.x, t.y, t.z],
        rotation_vec_rad: [r.x, r.y, r.z],
    }
}

/// The angle between two orientations, in radians.
pub fn rotation_distance_rad(a: &Isometry3<f64>, b: &Isometry3<f64>) -> f64 {
    a.rotation.angle_to(&b.rotation)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jacobian_matches_finite_differences() {
        let m = UrModel::ur3();
        let q = [0.3, -1.2, 1.4, -1.7, -1.5, 0.2];
        let j = m.jacobian(&q);
        let h = 1e-7;
        for k in 0..6 {
            let mut qp = q;
            qp[k] += h;
            let d = pose_error(&m.forward(&qp), &m.forward(&q)) / h;
            for r in 0..6 {
                assert!(
                    (d[r] - j[(r, k)]).abs() < 1e-5,
                    "J[{r},{k}] {} vs {}",
                    j[(r, k)],
                    d[r]
                );
            }
        }
    }

    #[test]
    fn inverse_recovers_forward() {
        let m = UrModel::ur3();
        let q = [0.3, -1.2, 1.4, -1.7, -1.5, 0.2];
        let target = m.forward(&q);
        let seed = q.map(|v| v + 0.2);
        let sol = m.inverse_near(&target, &seed).expect("solvable");
        let err = pose_error(&target, &m.forward(&sol)).norm();
        assert!(err < 1e-9, "residual {err}");
    }

    #[test]
    fn out_of_reach_is_typed() {
        let m = UrModel::ur3();
        let mut target = m.forward(&[0.0, -1.57, 1.57, -1.57, -1.57, 0.0]);
        target.translation.vector.x = 0.9;
        assert!(matches!(
            m.inverse_near(&target, &[0.0; 6]),
            Err(KinematicsError::OutOfReach { .. })
        ));
        target.translation.vector.x = f64::NAN;
        assert!(matches!(
            m.inverse_near(&target, &[0.0; 6]),
            Err(KinematicsError::NonFinite(_))
        ));
    }

    #[test]
    fn stretched_arm_is_at_the_published_length() {
        // q = 0: upper arm + forearm along -x, so x = a2 + a3 and z = d1 - d5 (wrist 2 points down).
        let m = UrModel::ur3();
        let p = m.forward(&[0.0; 6]).translation.vector;
        assert!((p.x + 0.4569).abs() < 1e-12);
        assert!((p.y + (0.11235 + 0.0819)).abs() < 1e-12);
        assert!((p.z - (0.1519 - 0.08535)).abs() < 1e-12);
    }
}
