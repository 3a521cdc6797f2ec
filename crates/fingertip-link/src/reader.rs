//! Frames out of a byte stream.

use crate::frame::{Frame, FrameError, LEN, SYNC};

/// Finds frames in the bytes of a UART, one byte at a time: it waits for the sync bytes,
/// collects a frame's length, and decodes it. A frame that fails its checksum is reported
/// once and the search for the next sync starts one byte after the failed frame's sync, so a
/// sync pattern inside a damaged frame's payload cannot hide the next good frame for long.
#[derive(Debug, Clone)]
pub struct FrameReader {
    buf: [u8; LEN],
    len: usize,
    dropped_bytes: u64,
    bad_frames: u64,
}

impl Default for FrameReader {
    fn default() -> Self {
        Self::new()
    }
}

impl FrameReader {
    /// A reader waiting for a frame's sync.
    pub const fn new() -> Self {
        Self {
            buf: [0; LEN],
            len: 0,
            dropped_bytes: 0,
            bad_frames: 0,
        }
    }

    /// Takes one byte; a complete frame (or why the bytes were not one) when it ends one.
    pub fn push(&mut self, byte: u8) -> Option<Result<Frame, FrameError>> {
        if self.len < SYNC.len() && byte != SYNC[self.len] {
            // Not a sync: what was collected was noise, and this byte may start a new sync.
            self.dropped_bytes += self.len as u64;
            self.len = 0;
            if byte != SYNC[0] {
                self.dropped_bytes += 1;
                return None;
            }
        }
        self.buf[self.len] = byte;
        self.len += 1;
        if self.len < LEN {
            return None;
        }
        self.len = 0;
        match Frame::decode(&self.buf) {
            Ok(frame) => Some(Ok(frame)),
            Err(e) => {
                self.bad_frames += 1;
                self.rescan();
                Some(Err(e))
            }
        }
    }

    /// Bytes skipped so far: noise, partial frames and damaged frames.
    pub fn dropped_bytes(&self) -> u64 {
        self.dropped_bytes
    }

    /// Frames that failed their checksum or held a value the fingertip never sends.
    pub fn bad_frames(&self) -> u64 {
        self.bad_frames
    }

    /// After a damaged frame: the bytes after its sync may hold the start of the next frame
    /// (a byte lost inside a frame shifts the next sync into it).
    fn rescan(&mut self) {
        let at = (SYNC.len()..LEN)
            .find(|&i| self.buf[i] == SYNC[0])
            .unwrap_or(LEN);
        self.dropped_bytes += at as u64;
        let frame = self.buf;
        for &b in &frame[at..] {
            // Fewer than LEN bytes are replayed: none completes a frame.
            let _ = self.push(b);
        }
    }
}
