//! The standard ROS 2 types the stack publishes, field for field as ROS 2 Jazzy defines them
//! (the hashes are checked against rosbags' Jazzy type store in tests/it/ros_interop.rs).

/// `builtin_interfaces`.
pub mod builtin_interfaces {
    super::super::ros_message! {
        /// A time: seconds and nanoseconds since the epoch of the clock that stamped it.
        pub struct Time = "builtin_interfaces/msg/Time" {
            /// Whole seconds.
            pub sec: i32,
            /// Nanoseconds within the second.
            pub nanosec: u32,
        }
    }

    impl Time {
        /// The time `t_ns` nanoseconds after the epoch (seconds wrap as ROS's `int32` does).
        pub fn from_nanos(t_ns: u64) -> Time {
            Time {
                sec: (t_ns / 1_000_000_000) as i32,
                nanosec: (t_ns % 1_000_000_000) as u32,
            }
        }

        /// Nanoseconds since the epoch (negative seconds count as zero).
        pub fn as_nanos(&self) -> u64 {
            u64::try_from(self.sec).unwrap_or(0) * 1_000_000_000 + u64::from(self.nanosec)
        }
    }
}

/// `std_msgs`.
pub mod std_msgs {
    use super::builtin_interfaces::Time;

    super::super::ros_message! {
        /// A stamp and the frame the data is in.
        pub struct Header = "std_msgs/msg/Header" {
            /// When the data was taken.
            pub stamp: Time,
            /// The coordinate frame (the device's name here).
            pub frame_id: String,
        }
    }
}

/// `geometry_msgs`.
pub mod geometry_msgs {
    use super::std_msgs::Header;

    super::super::ros_message! {
        /// A vector in free space.
        pub struct Vector3 = "geometry_msgs/msg/Vector3" {
            /// x.
            pub x: f64,
            /// y.
            pub y: f64,
            /// z.
            pub z: f64,
        }

        /// A position in free space.
        pub struct Point = "geometry_msgs/msg/Point" {
            /// x (m).
            pub x: f64,
            /// y (m).
            pub y: f64,
            /// z (m).
            pub z: f64,
        }

        /// An orientation as a unit quaternion.
        pub struct Quaternion = "geometry_msgs/msg/Quaternion" {
            /// x.
            pub x: f64,
            /// y.
            pub y: f64,
            /// z.
            pub z: f64,
            /// w.
            pub w: f64,
        }

        /// A position and an orientation.
        pub struct Pose = "geometry_msgs/msg/Pose" {
            /// Position (m).
            pub position: Point,
            /// Orientation.
            pub orientation: Quaternion,
        }

        /// A pose with a header.
        pub struct PoseStamped = "geometry_msgs/msg/PoseStamped" {
            /// Stamp and frame.
            pub header: Header,
            /// The pose.
            pub pose: Pose,
        }

        /// A force and a torque.
        pub struct Wrench = "geometry_msgs/msg/Wrench" {
            /// Force (N).
            pub force: Vector3,
            /// Torque (N·m).
            pub torque: Vector3,
        }

        /// A wrench with a header.
        pub struct WrenchStamped = "geometry_msgs/msg/WrenchStamped" {
            /// Stamp and frame.
            pub header: Header,
            /// The wrench.
            pub wrench: Wrench,
        }
    }
}

/// `sensor_msgs`.
pub mod sensor_msgs {
    use super::geometry_msgs::{Quaternion, Vector3};
    use super::std_msgs::Header;

    super::super::ros_message! {
        /// An inertial measurement. A covariance whose first element is −1 means "not
        /// measured" (REP 145).
        pub struct Imu = "sensor_msgs/msg/Imu" {
            /// Stamp and frame.
            pub header: Header,
            /// Orientation.
            pub orientation: Quaternion,
            /// Its covariance, row-major.
            pub orientation_covariance: [f64; 9],
            /// Angular velocity (rad/s).
            pub angular_velocity: Vector3,
            /// Its covariance, row-major.
            pub angular_velocity_covariance: [f64; 9],
            /// Linear acceleration (m/s²).
            pub linear_acceleration: Vector3,
            /// Its covariance, row-major.
            pub linear_acceleration_covariance: [f64; 9],
        }

        /// A named array of values (a sensor's channels): `string name`, `float32[] values`.
        pub struct ChannelFloat32 = "sensor_msgs/msg/ChannelFloat32" {
            /// The channel's (sensor's) name.
            pub name: String,
            /// Its values.
            pub values: Vec<f32>,
        }

        /// The state of named joints.
        pub struct JointState = "sensor_msgs/msg/JointState" {
            /// Stamp and frame.
            pub header: Header,
            /// Joint names.
            pub name: Vec<String>,
            /// Positions (rad).
            pub position: Vec<f64>,
            /// Velocities (rad/s).
            pub velocity: Vec<f64>,
            /// Efforts (N·m, or the device's unit).
            pub effort: Vec<f64>,
        }
    }
}

/// `service_msgs` (the part a service's type description refers to).
pub mod service_msgs {
    use crate::types::{FieldDescription, FieldType, TypeDescription, type_id};

    /// `service_msgs/msg/ServiceEventInfo`: only its description is needed here (services'
    /// type hashes include it); the stack does not publish service events.
    #[derive(Debug, Clone, Copy)]
    pub struct ServiceEventInfo;

    impl ServiceEventInfo {
        /// Its type description.
        pub fn description() -> TypeDescription {
            let f = |name, ty| FieldDescription { name, ty };
            TypeDescription {
                name: "service_msgs/msg/ServiceEventInfo",
                fields: vec![
                    f("event_type", FieldType::plain(type_id::UINT8)),
                    f(
                        "stamp",
                        FieldType::nested(
                            <super::builtin_interfaces::Time as crate::msg::Message>::description,
                        ),
                    ),
                    // `char[16]` in the .msg; rosidl hashes `char` as `uint8`.
                    f("client_gid", FieldType::plain(type_id::UINT8).array(16)),
                    f("sequence_number", FieldType::plain(type_id::INT64)),
                ],
            }
        }
    }
}

/// `std_srvs`.
pub mod std_srvs {
    super::super::ros_message! {
        /// `std_srvs/srv/Trigger`'s request: empty.
        pub struct TriggerRequest = "std_srvs/srv/Trigger_Request" {}

        /// `std_srvs/srv/Trigger`'s response.
        pub struct TriggerResponse = "std_srvs/srv/Trigger_Response" {
            /// Whether the service did what it is for.
            pub success: bool,
            /// What happened, for a person.
            pub message: String,
        }
    }

    /// `std_srvs/srv/Trigger`: do something, say whether it worked.
    #[derive(Debug, Clone, Copy)]
    pub struct Trigger;

    impl crate::msg::Service for Trigger {
        const NAME: &'static str = "std_srvs/srv/Trigger";
        const EVENT_NAME: &'static str = "std_srvs/srv/Trigger_Event";
        type Request = TriggerRequest;
        type Response = TriggerResponse;
    }
}
