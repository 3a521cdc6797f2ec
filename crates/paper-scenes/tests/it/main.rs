//! paper-scenes' tests, one binary: the papers' scenes run as written against the committed
//! figures, bad scenes, the command line, the report, the devices (seed 001's hand behind a
//! simulated Arduino among them), the full hand and the cell;
//! and handstack's grasp hold on simulated devices.

mod bad_scenes;
mod calibrate_hand;
mod cell;
mod cli;
mod common;
mod contact_location;
mod contact_run;
mod devices;
mod full_hand;
mod grasp_board;
mod grasp_table5;
mod hand_board;
mod hand_loop_faults;
mod own_contact_cnn;
mod own_contact_mlp;
mod own_force_model;
mod own_softness;
#[cfg(feature = "cell")]
mod pad_node;
mod report_render;
mod scene_props;
mod softness;
mod softness_run;
mod stack_hold;
mod tap_run;
mod tap_to_ur3;
mod weight_estimation;
mod weight_run;
