//! firmata-sim's integration tests, one binary: `firmata-host` against the simulated board on a
//! pty (every message kind, the reset, I2C through the real MS5611 and ICM-20789 drivers, the
//! stepper), bad input and a board that vanishes, the I2C read rate at two baud rates, and
//! pyfirmata2 against the `firmata-sim` binary.

mod client;
mod drivers;
mod faults;
mod pyfirmata;
mod rate;
mod stepper;

use std::time::Duration;

use firmata_host::{Board, Options};
use firmata_sim::{FirmwareKind, SimBoard, SimConfig};

/// A boot delay short enough for many tests, long enough to be seen.
pub const BOOT: Duration = Duration::from_millis(150);

/// A simulated board with `firmware` and the default bus, and our client on it.
pub fn board(firmware: FirmwareKind) -> (SimBoard, Board) {
    let sim = SimBoard::spawn(SimConfig::default().firmware(firmware).boot_delay(BOOT))
        .expect("spawn the simulated board");
    let board = Board::open(sim.path(), &Options::default()).expect("open the simulated board");
    (sim, board)
}

/// Waits (bounded) until the board has seen its port close, so that the next open resets it.
pub fn wait_closed(sim: &SimBoard) {
    let deadline = std::time::Instant::now() + Duration::from_secs(5);
    while sim.port_open() {
        assert!(
            std::time::Instant::now() < deadline,
            "the board never saw the close"
        );
        std::thread::yield_now();
    }
}

/// Sends SIGKILL to a process we started when dropped (a no-op once it has ended), so that a
/// failing test leaves no simulator running.
pub struct KillOnDrop(pub String);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = std::process::Command::new("kill")
            .args(["-KILL", &self.0])
            .stderr(std::process::Stdio::null())
            .status();
    }
}
