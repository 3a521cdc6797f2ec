//! The UR controller simulator's three inputs, as a client's bytes.

use ur_sim::fuzzing;

/// RTDE packages (port 30004).
pub fn rtde(data: &[u8]) {
    let _ = fuzzing::rtde(crate::bounded(data));
}

/// Dashboard command lines (port 29999).
pub fn dashboard(data: &[u8]) {
    let _ = fuzzing::dashboard(crate::bounded(data));
}

/// A script (port 30003).
pub fn script(data: &[u8]) {
    let _ = fuzzing::script(crate::bounded(data));
}
