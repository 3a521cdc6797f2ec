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
mod train_taps;
