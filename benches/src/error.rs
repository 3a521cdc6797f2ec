//! Why a cycle could not be built or run.

/// A fault in building or running a cycle, from the part that raised it.
#[derive(Debug, thiserror::Error)]
pub enum CycleError {
    /// The simulator (a chip model through its driver, or a configuration).
    #[error("simulator: {0}")]
    Sim(#[from] hand_sim::SimError),
    /// A learned model (loading the committed weights, or a bad input).
    #[error("model: {0}")]
    Net(#[from] tactile_nets::NetError),
    /// The grasp estimator (non-finite or out-of-order frame).
    #[error("estimate: {0}")]
    Estimate(#[from] hand_control::grasp_loop::EstimateError),
    /// The fuzzy controller.
    #[error("fuzzy policy: {0}")]
    Policy(#[from] fuzzy_mamdani::EvalError),
    /// Arrival-of-Time localisation.
    #[error("AoT: {0}")]
    Aot(aot_locate::AotError),
    /// The ranging scorer's constants.
    #[error("ranging: {0:?}")]
    Ranging(aot_locate::RangingError),
    /// The region-to-grid map.
    #[error("grid: {0}")]
    Grid(#[from] handstack::tap_to_move::GridError),
    /// The torque band or a paper fixture.
    #[error("configuration: {0}")]
    Config(String),
}

impl From<tactile_nets::RunError> for CycleError {
    fn from(e: tactile_nets::RunError) -> Self {
        CycleError::Net(e.into())
    }
}

impl From<aot_locate::AotError> for CycleError {
    fn from(e: aot_locate::AotError) -> Self {
        CycleError::Aot(e)
    }
}
