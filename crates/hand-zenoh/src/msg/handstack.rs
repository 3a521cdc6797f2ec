//! Our own messages. Their `.msg` files are `ros/handstack_msgs/msg/*.msg` (a ROS 2 package);
//! tests/it/ros_interop.rs checks that rosbags, reading those files, gives the same type hashes
//! and the same CDR bytes as these declarations.

/// `handstack_msgs`.
pub mod handstack_msgs {
    use super::super::standard::std_msgs::Header;

    super::super::ros_message! {
        /// One frame of a barometric fingertip or pad: a pressure per sensor.
        pub struct PressureFrame = "handstack_msgs/msg/PressureFrame" {
            /// When the frame was read; frame_id names the device.
            pub header: Header,
            /// Pressure per sensor (Pa), in the sensor order of `SensorInfo`.
            pub pressure_pa: Vec<f32>,
        }

        /// One located contact.
        pub struct Contact = "handstack_msgs/msg/Contact" {
            /// The area touched, 0-based, of `regions`.
            pub region: u16,
            /// How many areas the locator tells apart.
            pub regions: u16,
            /// The locator's confidence, 0 to 1.
            pub confidence: f32,
        }

        /// The contacts located in one frame.
        pub struct ContactArray = "handstack_msgs/msg/ContactArray" {
            /// The frame's stamp and device.
            pub header: Header,
            /// Its contacts (empty when nothing touches).
            pub contacts: Vec<Contact>,
        }

        /// What a tactile device is (published at 1 Hz).
        pub struct SensorInfo = "handstack_msgs/msg/SensorInfo" {
            /// Stamp and device.
            pub header: Header,
            /// The chip (`MS5611`, `ICM-20789`).
            pub chip: String,
            /// Sensors per frame.
            pub sensor_count: u8,
            /// Frames per second.
            pub rate_hz: f32,
            /// The zero subtracted from each sensor for `touch` (Pa).
            pub tare_pa: Vec<f32>,
        }

        /// The grasp loop's state, once per cycle.
        pub struct GraspState = "handstack_msgs/msg/GraspState" {
            /// Stamp and hand.
            pub header: Header,
            /// The loop's mode: 0 tare, 1 grasp, 2 safe, 3 halted.
            pub mode: u8,
            /// Mean pressure rise of the fingertip over its tared zero (Pa).
            pub pressure_pa: f32,
            /// Whether that rise is above the contact threshold.
            pub in_contact: bool,
            /// Torque limit sent, a fraction of the servo's maximum (0 to 1).
            pub effort: f32,
            /// Gripper position (rad).
            pub position_rad: f32,
            /// Servo load, a fraction of its limit (signed).
            pub load_fraction: f32,
            /// Fault bits: 1 overload, 2 overheat, 4 voltage, 8 encoder, 16 electrical.
            pub faults: u8,
        }

        /// A gripper goal.
        pub struct GripperCommand = "handstack_msgs/msg/GripperCommand" {
            /// Stamp and hand.
            pub header: Header,
            /// Target position (rad).
            pub position_rad: f32,
            /// Effort, a fraction of the servo's torque limit (0 to 1).
            pub effort: f32,
        }
    }
}
