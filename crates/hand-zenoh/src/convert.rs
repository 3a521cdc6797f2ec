//! The `hand-traits` values as ROS 2 messages and back: a tool pose (rotation vector, as UR
//! controllers give it) as a `geometry_msgs/Pose` (unit quaternion), an IMU frame as
//! `sensor_msgs/Imu`, a contact as `handstack_msgs/Contact`, a force estimate as
//! `geometry_msgs/WrenchStamped`.
//!
//! ```
//! use hand_traits::Pose;
//! use hand_zenoh::convert::{pose_from_msg, pose_to_msg};
//!
//! let p = Pose { position_m: [0.3, -0.1, 0.2], rotation_vec_rad: [0.0, 3.1, 0.2] };
//! let back = pose_from_msg(&pose_to_msg(&p));
//! assert!(p.distance_m(&back) < 1e-12);
//! assert!((0..3).all(|i| (p.rotation_vec_rad[i] - back.rotation_vec_rad[i]).abs() < 1e-12));
//! ```

use crate::msg::builtin_interfaces::Time;
use crate::msg::geometry_msgs::{self as geo, Point, Quaternion, Vector3, Wrench, WrenchStamped};
use crate::msg::handstack_msgs;
use crate::msg::sensor_msgs::Imu;
use crate::msg::std_msgs::Header;
use hand_traits::{Contact, ForceEstimate, ImuFrame, Pose};

/// A header stamped `t_ns` (ns since the Unix epoch) in frame `frame_id`.
pub fn header(t_ns: i64, frame_id: &str) -> Header {
    Header {
        stamp: Time::from_nanos(u64::try_from(t_ns).unwrap_or(0)),
        frame_id: frame_id.to_owned(),
    }
}

/// A tool pose as a ROS pose: the rotation vector becomes a unit quaternion.
pub fn pose_to_msg(p: &Pose) -> geo::Pose {
    let [rx, ry, rz] = p.rotation_vec_rad;
    let angle = (rx * rx + ry * ry + rz * rz).sqrt();
    let orientation = if angle < 1e-12 {
        Quaternion {
            w: 1.0,
            ..Quaternion::default()
        }
    } else {
        let s = (angle / 2.0).sin() / angle;
        Quaternion {
            x: rx * s,
            y: ry * s,
            z: rz * s,
            w: (angle / 2.0).cos(),
        }
    };
    let [x, y, z] = p.position_m;
    geo::Pose {
        position: Point { x, y, z },
        orientation,
    }
}

/// A ROS pose as a tool pose: the quaternion (normalised; the sign with `w ≥ 0`) becomes a
/// rotation vector of angle at most π.
pub fn pose_from_msg(p: &geo::Pose) -> Pose {
    let q = &p.orientation;
    let norm = (q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w).sqrt();
    let sign = if q.w < 0.0 { -1.0 } else { 1.0 };
    let (x, y, z, w) = if norm > 0.0 {
        let k = sign / norm;
        (q.x * k, q.y * k, q.z * k, q.w * k)
    } else {
        (0.0, 0.0, 0.0, 1.0)
    };
    let s = (x * x + y * y + z * z).sqrt();
    let angle = 2.0 * s.atan2(w);
    let rotation_vec_rad = if s < 1e-12 {
        [0.0; 3]
    } else {
        [x / s * angle, y / s * angle, z / s * angle]
    };
    Pose {
        position_m: [p.position.x, p.position.y, p.position.z],
        rotation_vec_rad,
    }
}

/// An IMU frame as `sensor_msgs/Imu`: no orientation (its covariance's first element −1, as
/// REP 145 says for "not measured"), covariances unknown (zeros).
pub fn imu_to_msg(f: &ImuFrame, header: Header) -> Imu {
    let mut orientation_covariance = [0.0; 9];
    orientation_covariance[0] = -1.0;
    let mut msg = Imu {
        header,
        orientation: Quaternion {
            w: 1.0,
            ..Quaternion::default()
        },
        orientation_covariance,
        angular_velocity: Vector3::default(),
        angular_velocity_covariance: [0.0; 9],
        linear_acceleration: Vector3::default(),
        linear_acceleration_covariance: [0.0; 9],
    };
    set_imu(&mut msg, f);
    msg
}

/// Puts frame `f`'s rates and accelerations into `msg` (a message [`imu_to_msg`] made, reused
/// from frame to frame without allocating).
pub fn set_imu(msg: &mut Imu, f: &ImuFrame) {
    let v = |a: [f32; 3]| Vector3 {
        x: f64::from(a[0]),
        y: f64::from(a[1]),
        z: f64::from(a[2]),
    };
    msg.angular_velocity = v(f.gyro_rps);
    msg.linear_acceleration = v(f.accel_mps2);
}

/// A located contact as `handstack_msgs/Contact`.
pub fn contact_to_msg(c: &Contact) -> handstack_msgs::Contact {
    handstack_msgs::Contact {
        region: c.region,
        regions: c.regions,
        confidence: c.confidence,
    }
}

/// A force estimate as a wrench: the load along the pad's normal (`z`, positive into the pad);
/// shear and torque are not measured and stay zero.
pub fn force_to_msg(f: ForceEstimate, header: Header) -> WrenchStamped {
    WrenchStamped {
        header,
        wrench: Wrench {
            force: Vector3 {
                z: f64::from(f.force_n),
                ..Vector3::default()
            },
            torque: Vector3::default(),
        },
    }
}
