//! The frame ids of a cell's messages, one scheme for every node: a device's messages are in
//! the frame named after its namespace (`/hand0` → `hand0`), an arm's poses in its base frame
//! (`/arm0` → `arm0_base`), so a goal for an arm names the frame that arm publishes in.

/// The frame of the device in `namespace`: `/hand0` → `hand0`.
pub fn device_frame(namespace: &str) -> String {
    namespace.trim_matches('/').replace('/', "_")
}

/// The base frame of the arm in `namespace`, its poses' and goals' frame: `/arm0` → `arm0_base`.
pub fn base_frame(namespace: &str) -> String {
    format!("{}_base", device_frame(namespace))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_are_named_after_the_namespace() {
        assert_eq!(device_frame("/hand0"), "hand0");
        assert_eq!(base_frame("/arm0"), "arm0_base");
        // A nested namespace still gives one tf2-valid frame name (no slashes).
        assert_eq!(base_frame("/cell1/arm0"), "cell1_arm0_base");
    }
}
