//! The `handstack` crate as a user gets it: scene files of their own, real devices (here
//! substitutes behind the real transports), the installed binary with no repository around it.

#[cfg(feature = "cell")]
mod cell_arm;
mod cli;
mod ending;
mod firmata_pad;
mod firmata_tip;
mod hardware;
mod process;
mod record;
mod scenes;
#[cfg(feature = "train")]
mod train_bags;
#[cfg(feature = "train")]
mod train_grasps;
#[cfg(feature = "train")]
mod train_taps;
#[cfg(feature = "train")]
mod train_touches;

/// A new, empty directory `handstack-KIND-PID-NAME` under the system's temporary directory.
#[cfg(feature = "train")]
fn fresh_dir(kind: &str, name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("handstack-{kind}-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("dir");
    d
}
