//! hand-sim's tests, one binary: each model against the papers' figures and its datasheets,
//! its datasets' schemas and determinism, its properties at the extremes.

mod dataset_schemas;
mod fingertip_calibration;
mod fingertip_dataset;
mod fingertip_model;
mod fingertip_props;
mod grasp_props;
mod grasp_scene;
mod grasp_servo;
mod grasp_table5;
mod imu_pad_calibration;
mod imu_pad_common;
mod imu_pad_determinism;
mod imu_pad_patterns;
mod imu_pad_props;
mod imu_pad_scene;
mod underactuated_calibration;
mod underactuated_determinism;
mod underactuated_props;
