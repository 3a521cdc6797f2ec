//! Our own messages. Their `.msg` files are `ros/handstack_msgs/msg/*.msg` (a ROS 2 package);
//! tests/it/ros_interop.rs checks that rosbags, reading those files, gives the same type hashes
//! and the same CDR bytes as these declarations.

/// `handstack_msgs`.
pub mod handstack_msgs {
    use super::super::standard::builtin_interfaces::Time;
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

        /// One reading of a hand's fingers (hand-traits' `FingerFrame`): each finger's force
        /// sensor and distal joint angle.
        pub struct FingerFrame = "handstack_msgs/msg/FingerFrame" {
            /// When it was read; frame_id names the hand.
            pub header: Header,
            /// Normal force on each finger's force sensor (N).
            pub force_n: Vec<f32>,
            /// Each finger's distal joint angle (rad).
            pub distal_angle_rad: Vec<f32>,
        }

        /// A grasped object's softness, as a classifier put it.
        pub struct Softness = "handstack_msgs/msg/Softness" {
            /// When it was classified; frame_id names the hand.
            pub header: Header,
            /// The class: 0 soft, 1 moderate, 2 hard.
            pub level: u8,
            /// The class in words (`soft`, `moderate`, `hard`).
            pub label: String,
            /// The classifier's mean output per class, in class order.
            pub scores: [f32; 3],
        }

        /// One figure of a run: a measured value, with the published value and a target when it
        /// has them.
        pub struct Figure = "handstack_msgs/msg/Figure" {
            /// When the run measured it; frame_id names the run's scene.
            pub header: Header,
            /// Its key (`grasp_settled_torque`).
            pub name: String,
            /// What it is, in words.
            pub label: String,
            /// The value.
            pub value: f64,
            /// Its unit (empty: a count or a ratio).
            pub unit: String,
            /// The published value (NaN: none).
            pub paper: f64,
            /// Where that value is published (empty: none).
            pub source: String,
            /// The target in words (empty: none).
            pub target: String,
            /// Whether the value meets it: -1 no target, 0 not met, 1 met.
            pub met: i8,
        }

        /// Something that went wrong in a run: a device's fault, or what ended the run.
        pub struct Fault = "handstack_msgs/msg/Fault" {
            /// When it was seen; frame_id names the run's scene.
            pub header: Header,
            /// The part it came from, as the scene names it (`hand`, `sensors.fingertip`,
            /// `controller`), or `run` for what ended the run.
            pub source: String,
            /// What happened, in words.
            pub what: String,
            /// Whether it ended the run.
            pub ends_run: bool,
        }

        /// One frame of a fingertip's own microcontroller (the `fingertip-link` UART frame),
        /// as it sent it: its sequence number and clock, so that a host can rebuild what the
        /// board computed from an unbroken run of frames.
        pub struct FingertipFrame = "handstack_msgs/msg/FingertipFrame" {
            /// When the host read it; frame_id names the fingertip.
            pub header: Header,
            /// The board's sequence number (wraps at 256: a gap is a frame lost).
            pub seq: u8,
            /// The board's clock when it sampled the frame (µs, wraps after 71 min).
            pub t_us: u32,
            /// The three compensated pressures (Pa), in the sensor order of `SensorInfo`.
            pub pressure_pa: [i32; 3],
            /// Whether the board has tared its zero (until then nothing is estimated).
            pub tared: bool,
            /// Whether the pad is touched (mean rise above the board's threshold).
            pub in_contact: bool,
            /// Whether the board's cycle failed (everything else but `seq` and `t_us` is 0).
            pub fault: bool,
            /// The board's force estimate (gf; NaN: none).
            pub force_gf: f32,
            /// The board's Arrival-of-Time area on the 3 × 3 grid, row-major (255: none).
            pub grid_cell: u8,
            /// The board's contact-MLP cell on the 4 × 6 pad, row-major (255: none).
            pub pad_cell: u8,
            /// The grasp torque limit the board chose (MX-28 counts).
            pub torque_raw: u16,
        }

        /// What a guided collect session asked for and the user did: the truth a recording is
        /// trained on (a weight placed, a cell tapped), over the window of frames it covers.
        pub struct Label = "handstack_msgs/msg/Label" {
            /// When it was recorded; frame_id names the device the frames came from.
            pub header: Header,
            /// The experiment that asked (`weight`).
            pub experiment: String,
            /// What is labelled (`tare`, `weight_gf`).
            pub name: String,
            /// Its value (gf for a weight).
            pub value: f64,
            /// The first frame's stamp it covers.
            pub start: Time,
            /// The last frame's stamp it covers.
            pub end: Time,
        }
    }
}
