//! Composition: the devices a scene names, opened — simulated ones speaking their real
//! interfaces, real ones by the port, bus or host the scene gives.

pub mod arm;
