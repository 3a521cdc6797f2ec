//! The ROS tactile toolbox's raw-data convention (ubi-agni/tactile_toolbox, `tactile_msgs`,
//! whose tools — the tactile state publisher, RViz's tactile display — read it): one
//! `TactileState` holds one named array of values per tactile sensor. Its `.msg`
//! (`tactile_msgs/msg/TactileState.msg`, commit db670ce) reads `Header header` and
//! `sensor_msgs/ChannelFloat32[] sensors`; ROS 2 spells the header `std_msgs/Header`, as here.

/// `tactile_msgs`.
pub mod tactile_msgs {
    use super::super::standard::sensor_msgs::ChannelFloat32;
    use super::super::standard::std_msgs::Header;

    super::super::ros_message! {
        /// Raw data of one or more tactile sensors, each a named array (normal forces or the
        /// sensor's raw unit).
        pub struct TactileState = "tactile_msgs/msg/TactileState" {
            /// The stamp (the frame is not used by the convention).
            pub header: Header,
            /// One named array per sensor.
            pub sensors: Vec<ChannelFloat32>,
        }
    }
}
