//! paper-experiments' tests, one binary: the papers' protocols against the committed models,
//! metrics and datasets, the grasp loop's closed-loop and fault runs, tap-to-move.

mod aot_eval_drift;
mod common;
mod contact_location_drift;
mod grasp_closed_loop;
mod grasp_faults;
mod nets_contact_cnn;
mod nets_contact_mlp;
mod nets_force_dnn;
mod nets_softness;
#[cfg(feature = "arm")]
mod tap_to_move;
mod trade_drift;
