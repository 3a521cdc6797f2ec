//! A fingertip with its own microcontroller (the fingertip firmware on a Cortex-M board): it
//! reads its three MS5611 and estimates force and contact itself, and sends one
//! `fingertip-link` frame per sensor cycle on a serial port. The host reads the frames.

use crate::error::RunError;
use fingertip_link::{Frame, FrameReader};
use serial2::SerialPort;
use std::time::{Duration, Instant};

/// How long opening waits for the first valid frame: the board's reset (a USB serial adapter's
/// DTR) and its start-up (the sensors' PROM reads) take well under this.
pub const OPEN_TIMEOUT: Duration = Duration::from_secs(2);
/// How long a read waits for the next valid frame: 16 cycles at OSR 1024.
pub const FRAME_TIMEOUT: Duration = Duration::from_millis(100);

const DEVICE: &str = "sensors.fingertip";

/// The serial link to a fingertip's microcontroller.
pub struct McuLink {
    port: SerialPort,
    path: String,
    reader: FrameReader,
    buf: [u8; 512],
    held: std::ops::Range<usize>,
    last: Option<Frame>,
}

impl McuLink {
    /// Opens `path` at `baud`, drops what the port held before (frames sent while no one
    /// listened), and waits for a valid frame ([`OPEN_TIMEOUT`]): a port that cannot be
    /// opened, or that carries no frame, is a [`RunError::Open`] saying which.
    pub fn open(path: &str, baud: u32) -> Result<McuLink, RunError> {
        let fail = |reason: String| RunError::Open {
            device: DEVICE,
            path: path.to_owned(),
            reason,
        };
        let mut port = SerialPort::open(path, baud).map_err(|e| fail(e.to_string()))?;
        port.set_read_timeout(FRAME_TIMEOUT)
            .map_err(|e| fail(e.to_string()))?;
        // What queued before the open is stale; the next frames are this run's.
        let _ = port.discard_input_buffer();
        let mut link = McuLink {
            port,
            path: path.to_owned(),
            reader: FrameReader::new(),
            buf: [0; 512],
            held: 0..0,
            last: None,
        };
        link.next_within(OPEN_TIMEOUT).map_err(|e| {
            fail(format!(
                "{e} (is the fingertip firmware running, and sending at {baud} baud?)"
            ))
        })?;
        Ok(link)
    }

    /// The next valid frame ([`FRAME_TIMEOUT`]); damaged frames are skipped (counted by
    /// [`McuLink::bad_frames`]). A frame flagged as a failed cycle is returned: the caller
    /// decides what a fault means.
    pub fn next_frame(&mut self) -> Result<Frame, RunError> {
        self.next_within(FRAME_TIMEOUT)
            .map_err(|reason| RunError::Device {
                device: DEVICE,
                reason: format!("{}: {reason}", self.path),
            })
    }

    /// The last valid frame read.
    pub fn last(&self) -> Option<&Frame> {
        self.last.as_ref()
    }

    /// Frames that arrived damaged so far.
    pub fn bad_frames(&self) -> u64 {
        self.reader.bad_frames()
    }

    fn next_within(&mut self, timeout: Duration) -> Result<Frame, String> {
        let deadline = Instant::now() + timeout;
        loop {
            for i in self.held.by_ref() {
                if let Some(Ok(frame)) = self.reader.push(self.buf[i]) {
                    self.last = Some(frame);
                    return Ok(frame);
                }
            }
            if Instant::now() >= deadline {
                return Err(format!(
                    "no valid frame from the fingertip in {} ms ({} damaged)",
                    timeout.as_millis(),
                    self.reader.bad_frames()
                ));
            }
            match self.port.read(&mut self.buf) {
                Ok(0) => {
                    return Err("the serial port closed (the board unplugged or reset?)".into());
                }
                Ok(n) => self.held = 0..n,
                Err(e) if e.kind() == std::io::ErrorKind::TimedOut => {}
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                // A pty whose other end closed, a USB adapter unplugged.
                Err(e) if matches!(e.raw_os_error(), Some(5 | 19)) => {
                    return Err(format!(
                        "the serial port went away (I/O error {}: the board unplugged or \
                         reset?)",
                        e.raw_os_error().unwrap_or_default()
                    ));
                }
                Err(e) => return Err(format!("serial port: {e}")),
            }
        }
    }
}
