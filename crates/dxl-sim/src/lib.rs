//! Simulated Dynamixel Protocol 2.0 servos on a pseudo-terminal: a servo bus for tests of code
//! that drives one (the official ROBOTIS SDK, `hand-control`'s `ServoHand`, your own).
//!
//! [`SimBus::spawn`] opens a pty pair (`serial2::SerialPort::pair`), runs the servos on one end
//! in a thread and hands back the other end: give it to `hand_control::ServoHand::with_reply_latency`
//! (with [`REPLY_LATENCY`]), or open [`SimBus::client_path`] from another process (the ROBOTIS
//! Python SDK does; the `dxl-sim` binary prints it). The simulator answers PING, READ, WRITE,
//! REG_WRITE, ACTION, FACTORY RESET, REBOOT, SYNC READ / WRITE and BULK READ / WRITE with real
//! status packets (CRC-16, byte stuffing, error codes), keeps the MX-28(2.0) control table per
//! servo (`hand-control`'s, as data), drives each motor (see [`SimServo::step`]) and latches
//! the overload shutdown until REBOOT.
//!
//! # Simulated time
//!
//! Nothing here sleeps. The simulator's clock moves only when
//! - a packet crosses the bus: the instruction's and each status packet's bytes at the bus baud
//!   rate (10 bits a byte) plus each servo's Return Delay Time, and
//! - the test calls [`SimBus::advance`].
//!
//! `advance` is *in band*: it writes a simulator-only clock packet (ID 0xFD, which no servo may
//! use; instruction [`CLOCK_INSTRUCTION`]) through a clone of the client's port, so it is
//! ordered after every byte the client sent before it — a broadcast sync write included — and
//! it returns once the simulator has stepped. A test therefore steps a closed loop
//! deterministically: `hand.command(..)`, `sim.advance(dt)`, `hand.state()`, repeat.
//!
//! With [`Pace::WallClock`] simulated time also keeps up with the wall clock, for a client that
//! waits in real time instead (another process, a loop on `StdClock`): the `dxl-sim` binary runs
//! its bus so.
//!
//! ```
//! use dxl_sim::{SimBus, SimConfig};
//! use hand_control::ServoHand;
//! use hand_traits::{Effort, GripperActuator, GripperCommand};
//! use std::time::Duration;
//!
//! let (mut sim, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2]))?;
//! let mut hand = ServoHand::with_reply_latency(port, &[1, 2], dxl_sim::REPLY_LATENCY)?;
//! assert_eq!(hand.table().name, "MX-28(2.0)");
//! hand.set_torque(true)?;
//! hand.command(&GripperCommand { position_rad: 2.0, effort: Effort::from_torque_limit_raw(400) })?;
//! sim.advance(Duration::from_secs(2))?;
//! let s = hand.state()?;
//! assert!((s.position_rad - 2.0).abs() < 0.01, "{s:?}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Faults are injected per servo, and the driver sees each as a typed error:
//!
//! ```
//! use dxl_sim::{Fault, SimBus, SimConfig};
//! use hand_control::{Error, ServoHand};
//! use hand_traits::{Effort, GripperActuator, GripperCommand, SafeAction};
//! use std::time::Duration;
//!
//! let (mut sim, port) = SimBus::spawn(SimConfig::with_ids(&[1, 2]))?;
//! // Pings both and identifies MX-28(2.0); the simulator gets a generous reply allowance.
//! let mut hand = ServoHand::with_reply_latency(port, &[1, 2], dxl_sim::REPLY_LATENCY)?;
//! hand.set_torque(true)?;
//! // The grasping paper's torque limit 400 of 0…1023, closing towards 3.5 rad.
//! let cmd = GripperCommand { position_rad: 3.5, effort: Effort::from_torque_limit_raw(400) };
//! hand.command(&cmd)?; // two sync writes: Goal PWM 346 of 885, Goal Position
//! sim.advance(Duration::from_millis(500))?; // simulated time, no sleeping
//! assert!(hand.state()?.faults.is_empty()); // one sync read
//! // A servo that stops answering is a typed error; the broadcast torque-off still reaches it.
//! sim.inject(2, Fault::Mute);
//! assert!(matches!(hand.state(), Err(Error::Timeout { id: Some(2) })));
//! hand.safe_stop(SafeAction::TorqueOff)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The README follows (its examples run as this crate's doctests).
//!
#![doc = include_str!("../README.md")]
#![deny(unsafe_code)]

mod servo;
mod trace;

pub use servo::{
    Load, MX28_NO_LOAD_SPEED_RAD_S, MX28_STALL_CURRENT_A, MX28_STALL_TORQUE_NM, Plant, ServoParams,
    SimServo,
};

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, Sender, channel};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use serial2::SerialPort;

use hand_control::InstructionError;
use hand_control::control_table::{ControlTable, MX_28};
use hand_control::protocol::{
    FrameError, Packet, Parser, encode, instruction_id as ins, packet_id,
};

/// The instruction of the simulator-only clock packet (undefined in Protocol 2.0).
pub const CLOCK_INSTRUCTION: u8 = 0xF0;
/// The ID the clock packet is addressed to (reserved in Protocol 2.0: never a servo).
pub const CLOCK_ID: u8 = 0xFD;
/// The status packet's instruction byte.
const STATUS: u8 = 0x55;
/// Longest an `advance` waits for the simulator thread (a bound, not a delay).
const ACK_TIMEOUT: Duration = Duration::from_secs(10);

/// The servo models the simulator runs; the other tables of `hand-control`'s
/// [`MODELS`](hand_control::control_table::MODELS) serve the driver only.
pub const SIMULATED_MODELS: [&ControlTable; 1] = [&MX_28];

/// What moves the simulator's clock besides the bytes on the bus.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pace {
    /// Nothing else: only [`SimBus::advance`]. Deterministic, as fast as the CPU (tests).
    #[default]
    Bus,
    /// The wall clock too: simulated time never falls behind the time since the bus started,
    /// so a client that waits in real time sees the servos move in real time.
    WallClock,
}

/// The reply allowance to give a [`ServoHand`](hand_control::ServoHand) on the simulated bus.
///
/// The simulator answers in microseconds, but it is a thread on a shared machine: under load it
/// can be descheduled for longer than a real servo's 34 ms allowance, and a test would see a
/// timeout the servo did not cause. On a 2-core machine running tests beside a compiler (even
/// one at idle priority), 250 ms was not enough: one reply of a 105 s simulated grasp came
/// later. Timeouts a test injects (a muted servo) cost this long each.
pub const REPLY_LATENCY: Duration = Duration::from_secs(1);

/// How to build a simulated bus.
#[derive(Debug, Clone)]
pub struct SimConfig {
    /// Servo IDs on the bus (all MX-28(2.0)).
    pub ids: Vec<u8>,
    /// Bus baud rate for wire-time accounting.
    pub baud: u32,
    /// Motor parameters, the same for every servo.
    pub params: ServoParams,
    /// Physics step.
    pub step: Duration,
    /// Initial output angle of every servo, rad.
    pub initial_position_rad: f64,
    /// Whether simulated time also follows the wall clock.
    pub pace: Pace,
    /// Keep a trace of every instruction executed, one line each ([`SimBus::take_trace`]).
    pub trace: bool,
}

impl SimConfig {
    /// MX-28s with these IDs at 1 Mbps (the paper's RS-485 hand), 0.25 ms physics steps,
    /// starting at π rad (Present Position 2048, mid-range).
    pub fn with_ids(ids: &[u8]) -> Self {
        Self {
            ids: ids.to_vec(),
            baud: 1_000_000,
            params: ServoParams::default(),
            step: Duration::from_micros(250),
            initial_position_rad: std::f64::consts::PI,
            pace: Pace::Bus,
            trace: false,
        }
    }
}

/// A one-shot or lasting fault a servo shows on the bus.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fault {
    /// Execute the next instruction but send no status packet.
    DropNextStatus,
    /// Send the next status packet with a corrupted CRC.
    CorruptNextCrc,
    /// Send the next status packet with its length field corrupted (line noise on the
    /// header): the receiver cannot frame it where it is.
    GarbleNextStatus,
    /// Stop answering (and executing) until [`SimBus::clear_faults`].
    Mute,
}

#[derive(Debug, Default, Clone, Copy)]
struct FaultState {
    drop_next: bool,
    corrupt_next: bool,
    garble_next: bool,
    mute: bool,
}

/// The servos and the clock, shared by the simulator thread and [`SimBus`].
struct World {
    servos: Vec<SimServo>,
    faults: Vec<FaultState>,
    now: Duration,
    physics_now: Duration,
    step: Duration,
    baud: u32,
    /// Where trace lines go, when the bus keeps a trace.
    trace: Option<Sender<String>>,
}

impl World {
    fn new(config: &SimConfig) -> Self {
        Self {
            servos: config
                .ids
                .iter()
                .map(|&id| SimServo::new(id, config.initial_position_rad, config.params))
                .collect(),
            faults: vec![FaultState::default(); config.ids.len()],
            now: Duration::ZERO,
            physics_now: Duration::ZERO,
            step: config.step.max(Duration::from_micros(1)),
            baud: config.baud,
            trace: None,
        }
    }

    fn index(&self, id: u8) -> Option<usize> {
        self.servos.iter().position(|s| s.id() == id)
    }

    /// Moves simulated time forward by `dt`, stepping the physics in fixed steps.
    fn advance(&mut self, dt: Duration) {
        self.now += dt;
        while self.physics_now + self.step <= self.now {
            self.physics_now += self.step;
            let (step, t) = (self.step, self.physics_now);
            for s in &mut self.servos {
                s.step(step, t);
            }
        }
    }

    /// Moves simulated time up to `t` where it is behind (the wall-clock pace).
    fn catch_up(&mut self, t: Duration) {
        if let Some(dt) = t.checked_sub(self.now) {
            self.advance(dt);
        }
    }

    /// Time `bytes` take on the wire.
    fn wire(&self, bytes: usize) -> Duration {
        Duration::from_nanos(bytes as u64 * 10 * 1_000_000_000 / u64::from(self.baud.max(1)))
    }

    /// Appends servo `i`'s status packet to `out` (unless a fault eats it) and accounts its time.
    fn status(&mut self, out: &mut Vec<u8>, i: usize, result: Result<Vec<u8>, InstructionError>) {
        let f = &mut self.faults[i];
        if f.mute {
            return;
        }
        if f.drop_next {
            f.drop_next = false;
            return;
        }
        let corrupt = std::mem::take(&mut f.corrupt_next);
        let garble = std::mem::take(&mut f.garble_next);
        let s = &self.servos[i];
        let alert = if s.hardware_error() != 0 { 0x80 } else { 0 };
        let (err, data) = match result {
            Ok(d) => (0, d),
            Err(e) => (e.code(), Vec::new()),
        };
        let mut params = Vec::with_capacity(1 + data.len());
        params.push(err | alert);
        params.extend_from_slice(&data);
        let start = out.len();
        encode(out, s.id(), STATUS, &params);
        if corrupt {
            let n = out.len();
            out[n - 1] ^= 0x5A;
        }
        if garble {
            // LEN_H: the frame now claims more bytes than follow it.
            out[start + 6] ^= 0x80;
        }
        let dt = s.return_delay() + self.wire(out.len() - start);
        self.advance(dt);
    }

    /// Whether servo `i` answers an instruction of this kind (Status Return Level, e-Manual).
    fn answers(&self, i: usize, instruction: u8) -> bool {
        match self.servos[i].status_return_level() {
            0 => instruction == ins::PING,
            1 => matches!(
                instruction,
                ins::PING | ins::READ | ins::SYNC_READ | ins::BULK_READ
            ),
            _ => true,
        }
    }

    /// Unicast targets of a packet: the servos with that ID that are not muted.
    fn target(&self, id: u8) -> Option<usize> {
        self.index(id).filter(|&i| !self.faults[i].mute)
    }

    /// What the bus does with one frame the parser found: a clock packet advances time (by at
    /// most `max_clock_step`) and reports its sequence number to `ack`; a good packet is
    /// executed; a frame with a bad CRC gets its servo's CRC-error status. Returns the bytes to
    /// send back. The simulator thread and [`answer_bytes`] share it.
    fn on_frame(
        &mut self,
        frame: Result<Packet, FrameError>,
        max_clock_step: Duration,
        ack: impl FnOnce(u32),
    ) -> Vec<u8> {
        match frame {
            Ok(p)
                if p.id == CLOCK_ID
                    && p.instruction == CLOCK_INSTRUCTION
                    && p.params.len() == 12 =>
            {
                let mut ns = [0u8; 8];
                ns.copy_from_slice(&p.params[..8]);
                self.advance(Duration::from_nanos(u64::from_le_bytes(ns)).min(max_clock_step));
                ack(u32::from_le_bytes([
                    p.params[8],
                    p.params[9],
                    p.params[10],
                    p.params[11],
                ]));
                Vec::new()
            }
            Ok(p) => self.handle(&p),
            Err(FrameError::Crc {
                id, instruction, ..
            }) => {
                let mut out = Vec::new();
                if let Some(i) = self.target(id).filter(|&i| self.answers(i, instruction)) {
                    self.status(&mut out, i, Err(InstructionError::Crc));
                }
                out
            }
            // A bad length (or a framing problem of a kind `hand-control` adds later): the frame
            // names no servo to answer.
            Err(_) => Vec::new(),
        }
    }

    /// Executes one packet; returns the bytes to send back.
    fn handle(&mut self, p: &Packet) -> Vec<u8> {
        let mut out = Vec::new();
        self.advance(self.wire(p.wire_len));
        if let Some(trace) = &self.trace {
            // The receiver may be gone (nobody reads the trace): nothing to do then.
            let _ = trace.send(trace::line(&MX_28, self.now, p));
        }
        let broadcast = p.id == packet_id::BROADCAST;
        let u16_at = |b: &[u8], i: usize| u16::from_le_bytes([b[i], b[i + 1]]);
        let prm = &p.params;
        match p.instruction {
            ins::PING => {
                let ids: Vec<usize> = if broadcast {
                    let mut v: Vec<usize> = (0..self.servos.len())
                        .filter(|&i| !self.faults[i].mute)
                        .collect();
                    v.sort_by_key(|&i| self.servos[i].id());
                    v
                } else {
                    self.target(p.id).into_iter().collect()
                };
                for i in ids {
                    let m = self.servos[i].model_number().to_le_bytes();
                    // Firmware version 45 (a Protocol 2.0 MX firmware).
                    self.status(&mut out, i, Ok(vec![m[0], m[1], 45]));
                }
            }
            ins::READ if !broadcast => {
                if let Some(i) = self.target(p.id) {
                    let r = if prm.len() == 4 {
                        self.servos[i].refresh();
                        self.servos[i].read(u16_at(prm, 0), u16_at(prm, 2))
                    } else {
                        Err(InstructionError::DataLength)
                    };
                    if self.answers(i, ins::READ) {
                        self.status(&mut out, i, r);
                    }
                }
            }
            ins::WRITE | ins::REG_WRITE => {
                let targets: Vec<usize> = if broadcast {
                    (0..self.servos.len())
                        .filter(|&i| !self.faults[i].mute)
                        .collect()
                } else {
                    self.target(p.id).into_iter().collect()
                };
                for i in targets {
                    let r = if prm.len() < 3 {
                        Err(InstructionError::DataLength)
                    } else if p.instruction == ins::WRITE {
                        self.servos[i].write(u16_at(prm, 0), &prm[2..])
                    } else {
                        self.servos[i].reg_write(u16_at(prm, 0), &prm[2..])
                    };
                    if !broadcast && self.answers(i, p.instruction) {
                        self.status(&mut out, i, r.map(|()| Vec::new()));
                    }
                }
            }
            ins::ACTION => {
                if broadcast {
                    for s in &mut self.servos {
                        // A broadcast ACTION only concerns servos with a registered write.
                        let _ = s.action();
                    }
                } else if let Some(i) = self.target(p.id) {
                    let r = self.servos[i].action();
                    if self.answers(i, ins::ACTION) {
                        self.status(&mut out, i, r.map(|()| Vec::new()));
                    }
                }
            }
            ins::REBOOT => {
                if broadcast {
                    self.servos.iter_mut().for_each(SimServo::reboot);
                } else if let Some(i) = self.target(p.id) {
                    if self.answers(i, ins::REBOOT) {
                        self.status(&mut out, i, Ok(Vec::new()));
                    }
                    self.servos[i].reboot();
                }
            }
            ins::FACTORY_RESET => {
                let kind = prm.first().copied().unwrap_or(0xFF);
                if broadcast {
                    // Firmware ≥ 42 ignores a broadcast reset of everything (dynamixel2 docs).
                    if kind != 0xFF {
                        self.servos.iter_mut().for_each(|s| s.factory_reset(kind));
                    }
                } else if let Some(i) = self.target(p.id) {
                    if self.answers(i, ins::FACTORY_RESET) {
                        self.status(&mut out, i, Ok(Vec::new()));
                    }
                    self.servos[i].factory_reset(kind);
                }
            }
            ins::SYNC_READ if broadcast && prm.len() >= 4 => {
                let (a, n) = (u16_at(prm, 0), u16_at(prm, 2));
                for &id in &prm[4..] {
                    if let Some(i) = self.target(id) {
                        self.servos[i].refresh();
                        let r = self.servos[i].read(a, n);
                        if self.answers(i, ins::SYNC_READ) {
                            self.status(&mut out, i, r);
                        }
                    }
                }
            }
            ins::SYNC_WRITE if broadcast && prm.len() >= 4 => {
                let (a, n) = (u16_at(prm, 0), usize::from(u16_at(prm, 2)));
                for chunk in prm[4..].chunks_exact(1 + n.max(1)) {
                    if let Some(i) = self.target(chunk[0]) {
                        // Sync write has no status packet: errors are silent, as on hardware.
                        let _ = self.servos[i].write(a, &chunk[1..]);
                    }
                }
            }
            ins::BULK_READ if broadcast => {
                for c in prm.chunks_exact(5) {
                    if let Some(i) = self.target(c[0]) {
                        self.servos[i].refresh();
                        let r = self.servos[i].read(u16_at(c, 1), u16_at(c, 3));
                        if self.answers(i, ins::BULK_READ) {
                            self.status(&mut out, i, r);
                        }
                    }
                }
            }
            ins::BULK_WRITE if broadcast => {
                let mut rest = &prm[..];
                while rest.len() >= 5 {
                    let (id, a, n) = (rest[0], u16_at(rest, 1), usize::from(u16_at(rest, 3)));
                    let Some(data) = rest.get(5..5 + n) else {
                        break;
                    };
                    if let Some(i) = self.target(id) {
                        let _ = self.servos[i].write(a, data);
                    }
                    rest = &rest[5 + n..];
                }
            }
            _ if !broadcast => {
                if let Some(i) = self.target(p.id) {
                    self.status(&mut out, i, Err(InstructionError::Instruction));
                }
            }
            _ => {}
        }
        out
    }
}

/// A running simulated bus. Dropping it stops the simulator thread.
pub struct SimBus {
    world: Arc<Mutex<World>>,
    clock: SerialPort,
    acks: Receiver<u32>,
    seq: u32,
    stop: Arc<AtomicBool>,
    thread: Option<JoinHandle<()>>,
    client_path: PathBuf,
    trace: Option<Receiver<String>>,
}

impl std::fmt::Debug for SimBus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SimBus")
            .field("client_path", &self.client_path)
            .finish_non_exhaustive()
    }
}

impl SimBus {
    /// Starts the servos of `config` on a new pty; returns the bus and the client's port.
    ///
    /// # Errors
    /// Creating the pty or the thread.
    pub fn spawn(config: SimConfig) -> std::io::Result<(Self, SerialPort)> {
        let (mut device, client) = SerialPort::pair()?;
        let clock = client.try_clone()?;
        let client_path = {
            use std::os::fd::AsRawFd;
            std::fs::read_link(format!("/proc/self/fd/{}", client.as_raw_fd()))?
        };
        let mut world = World::new(&config);
        let trace = config.trace.then(|| {
            let (tx, rx) = channel();
            world.trace = Some(tx);
            rx
        });
        let world = Arc::new(Mutex::new(world));
        let stop = Arc::new(AtomicBool::new(false));
        let (tx, acks) = channel();
        // The thread notices `stop` within one read timeout.
        device.set_read_timeout(Duration::from_millis(20))?;
        let thread = {
            let (world, stop) = (Arc::clone(&world), Arc::clone(&stop));
            let pace = config.pace;
            std::thread::Builder::new()
                .name("dxl-sim".into())
                .spawn(move || serve(&device, &world, &stop, &tx, pace))?
        };
        Ok((
            Self {
                world,
                clock,
                acks,
                seq: 0,
                stop,
                thread: Some(thread),
                client_path,
                trace,
            },
            client,
        ))
    }

    /// The instruction trace ([`SimConfig::trace`]): one line per instruction executed, in
    /// the order executed (see the `trace` lines' format in the `dxl-sim` binary's docs).
    /// `None` without a trace, or once taken.
    pub fn take_trace(&mut self) -> Option<Receiver<String>> {
        self.trace.take()
    }

    /// The client end's device path (`/dev/pts/N`), for another process to open.
    pub fn client_path(&self) -> &Path {
        &self.client_path
    }

    fn world(&self) -> MutexGuard<'_, World> {
        // A panic in the simulator thread poisons the lock; the state is still usable to inspect.
        self.world
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Advances simulated time by `dt` after every byte the client sent so far; returns once
    /// the simulator has stepped.
    ///
    /// # Errors
    /// Writing the clock packet, or the simulator not acknowledging within 10 s (wall clock).
    pub fn advance(&mut self, dt: Duration) -> std::io::Result<()> {
        self.seq = self.seq.wrapping_add(1);
        let mut params = Vec::with_capacity(12);
        params.extend_from_slice(&(dt.as_nanos() as u64).to_le_bytes());
        params.extend_from_slice(&self.seq.to_le_bytes());
        let mut pkt = Vec::new();
        encode(&mut pkt, CLOCK_ID, CLOCK_INSTRUCTION, &params);
        self.clock.write_all(&pkt)?;
        loop {
            match self.acks.recv_timeout(ACK_TIMEOUT) {
                Ok(s) if s == self.seq => return Ok(()),
                Ok(_) => continue,
                Err(e) => return Err(std::io::Error::new(std::io::ErrorKind::TimedOut, e)),
            }
        }
    }

    /// Waits until the simulator has handled every byte the client sent so far (an
    /// `advance` of zero): call it before inspecting a servo after a broadcast write, which
    /// gets no answer to wait for.
    ///
    /// # Errors
    /// As [`SimBus::advance`].
    pub fn sync(&mut self) -> std::io::Result<()> {
        self.advance(Duration::ZERO)
    }

    /// Simulated time since the bus started, once the simulator has handled every byte the
    /// client sent so far ([`SimBus::sync`]): a write that gets no answer moves the time by its
    /// wire time when the simulator thread reads it, so a bare read would race that thread
    /// (and a loaded machine would change what a simulated run computes).
    ///
    /// # Errors
    /// As [`SimBus::advance`].
    pub fn now(&mut self) -> std::io::Result<Duration> {
        self.sync()?;
        Ok(self.world().now)
    }

    /// Runs `f` on servo `id` (e.g. to read its true angle); `None` if no such servo.
    pub fn with_servo<R>(&self, id: u8, f: impl FnOnce(&mut SimServo) -> R) -> Option<R> {
        let mut w = self.world();
        let i = w.index(id)?;
        Some(f(&mut w.servos[i]))
    }

    /// Couples an external load to servo `id` (replacing the previous one).
    pub fn set_plant(&self, id: u8, plant: impl Plant + 'static) -> bool {
        self.with_servo(id, |s| s.set_plant(Some(Box::new(plant))))
            .is_some()
    }

    /// Injects a bus fault on servo `id`.
    pub fn inject(&self, id: u8, fault: Fault) -> bool {
        let mut w = self.world();
        let Some(i) = w.index(id) else { return false };
        let f = &mut w.faults[i];
        match fault {
            Fault::DropNextStatus => f.drop_next = true,
            Fault::CorruptNextCrc => f.corrupt_next = true,
            Fault::GarbleNextStatus => f.garble_next = true,
            Fault::Mute => f.mute = true,
        }
        true
    }

    /// Clears every injected bus fault of servo `id`.
    pub fn clear_faults(&self, id: u8) {
        let mut w = self.world();
        if let Some(i) = w.index(id) {
            w.faults[i] = FaultState::default();
        }
    }
}

impl Drop for SimBus {
    fn drop(&mut self) {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// The bytes a bus of `config`'s servos answers to `input`, fed in `chunk`s of at most that
/// many bytes through the simulator thread's own parse → execute path, without a pty or a
/// thread; clock packets advance at most `max_clock_step`, so that one packet cannot ask for
/// years of physics. What a fuzzer (and its corpus replay) drives the simulator with.
///
/// ```
/// use dxl_sim::{SimConfig, answer_bytes};
/// use hand_control::protocol::{Parser, encode, instruction_id};
/// use std::time::Duration;
///
/// let mut ping = Vec::new();
/// encode(&mut ping, 2, instruction_id::PING, &[]);
/// let answer = answer_bytes(&SimConfig::with_ids(&[1, 2]), &ping, 3, Duration::from_millis(100));
/// let mut parser = Parser::default();
/// parser.push(&answer);
/// let status = parser.next_packet().expect("one packet").expect("a good CRC");
/// assert_eq!((status.id, status.params), (2, vec![0, 30, 0, 45])); // MX-28(2.0), firmware 45
/// ```
pub fn answer_bytes(
    config: &SimConfig,
    input: &[u8],
    chunk: usize,
    max_clock_step: Duration,
) -> Vec<u8> {
    let mut world = World::new(config);
    let mut parser = Parser::default();
    let mut out = Vec::new();
    for c in input.chunks(chunk.max(1)) {
        parser.push(c);
        while let Some(frame) = parser.next_packet() {
            out.extend(world.on_frame(frame, max_clock_step, |_| {}));
        }
    }
    out
}

/// The simulator thread: read, parse, execute, answer, until `stop`.
fn serve(
    device: &SerialPort,
    world: &Mutex<World>,
    stop: &AtomicBool,
    acks: &Sender<u32>,
    pace: Pace,
) {
    let mut parser = Parser::default();
    let mut buf = [0u8; 4096];
    let started = Instant::now();
    while !stop.load(Ordering::Relaxed) {
        let read = device.read(&mut buf);
        if pace == Pace::WallClock {
            // Before the packets are handled, so their answers show the present physics.
            world
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .catch_up(started.elapsed());
        }
        let n = match read {
            Ok(n) => n,
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::TimedOut
                        | std::io::ErrorKind::WouldBlock
                        | std::io::ErrorKind::Interrupted
                ) =>
            {
                continue;
            }
            // The client side is gone for good.
            Err(_) => return,
        };
        parser.push(&buf[..n]);
        while let Some(frame) = parser.next_packet() {
            let mut w = world
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            let out = w.on_frame(frame, Duration::MAX, |seq| {
                let _ = acks.send(seq);
            });
            drop(w);
            if !out.is_empty() && device.write_all(&out).is_err() {
                return;
            }
        }
    }
}
