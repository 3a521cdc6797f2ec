//! What can fail with the hand on its board, in words that name the board and the part.

/// An error of the hand on its board.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum HandError {
    /// The board failed (it names its port and what failed: a timeout, a hang-up, bytes that
    /// are not Firmata, a refusal).
    #[error(transparent)]
    Board(#[from] firmata_host::Error),
    /// The wiring, calibration, drive or plan is inconsistent.
    #[error("hand set-up: {0}")]
    Setup(String),
    /// The firmware does not drive steppers (StandardFirmata, or ConfigurableFirmata built
    /// without AccelStepperFirmata).
    #[error(
        "board on {port}: its firmware ({firmware}) does not answer AccelStepperFirmata; flash \
         ConfigurableFirmata with AccelStepperFirmata enabled"
    )]
    NoSteppers {
        /// The board's port.
        port: String,
        /// The firmware it reported.
        firmware: String,
    },
    /// The board restarted (its sketch sent a new version report): pin modes, reporting and the
    /// stepper's target are gone.
    #[error("board on {port}: it restarted (reset or power loss); its stepper stopped")]
    Restarted {
        /// The board's port.
        port: String,
    },
    /// The board stopped reporting an analog input it was asked to report.
    #[error("board on {port}: no report of A{channel} for {silent_ms} ms")]
    Silent {
        /// The board's port.
        port: String,
        /// The analog channel.
        channel: u8,
        /// How long it has been silent, ms.
        silent_ms: u64,
    },
}
