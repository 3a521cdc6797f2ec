//! A simulated Universal Robots controller on loopback that the unmodified ur_rtde client
//! accepts: dashboard server (29999), RTDE (30004), and a script intake (30003) that recognises
//! ur_rtde's control script and runs its register protocol on a kinematic UR3 (ur-bridge's
//! [`UrModel`]). The `ur-sim` program runs one as a process; [`UrSim`] runs one in yours.
//!
//! ur_rtde's `RTDEControlInterface` connects to the fixed ports 29999 / 30003 / 30004, so
//! simulators that must run side by side bind different loopback addresses (`127.0.0.2`,
//! `127.0.0.3`, … all reach the local host on Linux).
//!
//! ```no_run
//! use ur_sim::{SimConfig, UrSim};
//! let sim = UrSim::start(SimConfig::default())?; // 127.0.0.1
//! // … connect ur_rtde (or ur-bridge's `UrArm`) to 127.0.0.1 …
//! sim.kill(); // every socket closes at once, as if the controller died
//! # Ok::<(), std::io::Error>(())
//! ```
//!
//! - [`UrSim`], [`SimConfig`]: a controller on its three ports, its clock, joints and log;
//! - [`TimeScale`]: controller time against wall time;
//! - [`fuzzing`]: the three servers' request handling fed from bytes, for fuzzers.
//!
//! Plain Rust: ur-bridge without its default `rtde-client` feature, no pyo3, no Python.

mod controller;
mod dashboard;
pub mod fuzzing;
mod motion;
mod rtde;
mod time_scale;
mod variables;
mod wire;

pub use time_scale::{TimeScale, TimeScaleError};

use std::collections::HashMap;
use std::io::Read;
use std::net::{Ipv4Addr, Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use controller::Controller;
use ur_bridge::kinematics::{Joints, UrModel};
use ur_bridge::status::robot_mode;

/// How the simulated controller is set up.
#[derive(Debug, Clone, PartialEq)]
pub struct SimConfig {
    /// Loopback address to bind (default 127.0.0.1).
    pub address: Ipv4Addr,
    /// Dashboard port (29999 on a real controller).
    pub dashboard_port: u16,
    /// Script intake port (30003).
    pub script_port: u16,
    /// RTDE port (30004).
    pub rtde_port: u16,
    /// Arm geometry and the safety system's joint position / speed limits.
    pub model: UrModel,
    /// Joint angles at start-up.
    pub initial_q: Joints,
    /// Robot mode at start-up (`RUNNING`, or `POWER_OFF` to exercise power-up).
    pub initial_mode: i32,
    /// Control cycle (CB3: 8 ms, 125 Hz).
    pub control_period: Duration,
    /// Reported controller version (major, minor, bugfix, build).
    pub controller_version: (u32, u32, u32, u32),
    /// Highest RTDE output frequency served (CB3: 125 Hz).
    pub max_frequency_hz: f64,
    /// Simulated time per wall-clock time (real time by default).
    pub time_scale: TimeScale,
}

impl Default for SimConfig {
    /// A CB3 UR3 (software 3.15.8) on 127.0.0.1 at the real ports, powered, brakes released,
    /// at the home pose of [`ur_bridge::kinematics::HOME_Q`].
    fn default() -> Self {
        Self {
            address: Ipv4Addr::LOCALHOST,
            dashboard_port: 29999,
            script_port: 30003,
            rtde_port: 30004,
            model: UrModel::ur3(),
            initial_q: ur_bridge::kinematics::HOME_Q,
            initial_mode: robot_mode::RUNNING,
            control_period: Duration::from_millis(8),
            controller_version: (3, 15, 8, 106_339),
            max_frequency_hz: 125.0,
            time_scale: TimeScale::REAL_TIME,
        }
    }
}

/// State every server thread shares.
pub(crate) struct Shared {
    config: SimConfig,
    controller: Mutex<Controller>,
    stop: AtomicBool,
    /// A clone of each open client connection, by id, so that a kill can close it; removed
    /// when its handler returns (clients that come and go must not pile up descriptors).
    streams: Mutex<HashMap<u64, TcpStream>>,
    threads: Mutex<Vec<JoinHandle<()>>>,
    input_claims: Mutex<HashMap<String, u64>>,
    /// Signalled when a connection's input claims are released.
    claims_released: Condvar,
    next_id: AtomicU64,
}

/// How long a claim of RTDE input registers held by another connection waits for that
/// connection to release them before the answer is `IN_USE`. A client that reconnects (as
/// ur_rtde's control interface does when it finds its link down) has closed the old
/// connection first, but the simulator reads that close on the old connection's own thread,
/// which a loaded machine can run after the new connection's claim (1 s was seen too short
/// while a whole test suite ran on two cores).
pub(crate) const CLAIM_WAIT: Duration = Duration::from_secs(3);

impl Shared {
    /// Simulator state without sockets: the controller at the configured start pose and mode.
    pub(crate) fn new(config: SimConfig) -> Self {
        let controller =
            Controller::new(config.model.clone(), config.initial_q, config.initial_mode);
        Self {
            config,
            controller: Mutex::new(controller),
            stop: AtomicBool::new(false),
            streams: Mutex::new(HashMap::new()),
            threads: Mutex::new(Vec::new()),
            input_claims: Mutex::new(HashMap::new()),
            claims_released: Condvar::new(),
            next_id: AtomicU64::new(1),
        }
    }

    pub(crate) fn lock(&self) -> MutexGuard<'_, Controller> {
        self.controller.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub(crate) fn stopped(&self) -> bool {
        self.stop.load(Ordering::SeqCst)
    }

    pub(crate) fn spawn(&self, f: impl FnOnce() + Send + 'static) {
        let handle = std::thread::spawn(f);
        let mut threads = self.threads.lock().unwrap_or_else(|e| e.into_inner());
        // Finished connection threads are dropped here, so reconnecting clients leave nothing.
        threads.retain(|t| !t.is_finished());
        threads.push(handle);
    }

    /// Claims RTDE input variables for connection `id`; false where another connection still
    /// holds one after [`CLAIM_WAIT`] (logged, naming the holder).
    pub(crate) fn claim_inputs(&self, id: u64, names: &[String]) -> Vec<bool> {
        let deadline = Instant::now() + CLAIM_WAIT;
        let mut claims = self.input_claims.lock().unwrap_or_else(|e| e.into_inner());
        loop {
            let free: Vec<bool> = names
                .iter()
                .map(|n| claims.get(n).is_none_or(|owner| *owner == id))
                .collect();
            if free.iter().all(|f| *f) {
                for n in names {
                    claims.insert(n.clone(), id);
                }
                return free;
            }
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() || self.stopped() {
                let held = names
                    .iter()
                    .find_map(|n| claims.get(n).filter(|o| **o != id).map(|o| (n, *o)));
                drop(claims);
                if let Some((name, owner)) = held {
                    self.lock().textmsg(format!(
                        "rtde: connection {id} asked for {name}, held by connection {owner}: IN_USE"
                    ));
                }
                return free;
            }
            claims = self
                .claims_released
                .wait_timeout(claims, left)
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }

    pub(crate) fn release_inputs(&self, id: u64) {
        self.input_claims
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .retain(|_, owner| *owner != id);
        self.claims_released.notify_all();
    }
}

/// What each bound port serves, in the order of [`UrSim::addresses`].
pub const SERVICES: [&str; 3] = ["dashboard", "script", "rtde"];

/// A running simulated controller; dropping it is [`UrSim::kill`].
pub struct UrSim {
    shared: Arc<Shared>,
    addrs: Vec<SocketAddr>,
}

impl core::fmt::Debug for UrSim {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("UrSim")
            .field("addrs", &self.addrs)
            .finish_non_exhaustive()
    }
}

type Handler = fn(&Arc<Shared>, TcpStream, u64) -> std::io::Result<()>;

impl UrSim {
    /// Binds the three ports and starts the control loop.
    pub fn start(config: SimConfig) -> std::io::Result<Self> {
        let ports: [(u16, Handler); 3] = [
            (config.dashboard_port, |s, stream, _| {
                dashboard::serve(s, stream)
            }),
            (config.script_port, |s, stream, _| serve_script(s, stream)),
            (config.rtde_port, rtde::serve),
        ];
        let listeners = ports
            .iter()
            .map(|(port, _)| TcpListener::bind((config.address, *port)))
            .collect::<std::io::Result<Vec<_>>>()?;
        let shared = Arc::new(Shared::new(config));
        let mut addrs = Vec::new();
        for (listener, (_, handler)) in listeners.into_iter().zip(ports) {
            addrs.push(listener.local_addr()?);
            let s = shared.clone();
            shared.spawn(move || accept_loop(&s, &listener, handler));
        }
        let s = shared.clone();
        shared.spawn(move || control_loop(&s));
        Ok(Self { shared, addrs })
    }

    /// The bound addresses: dashboard, script, RTDE.
    pub fn addresses(&self) -> &[SocketAddr] {
        &self.addrs
    }

    /// Each bound address with what it serves ([`SERVICES`]).
    pub fn services(&self) -> impl Iterator<Item = (&'static str, SocketAddr)> + '_ {
        SERVICES.into_iter().zip(self.addrs.iter().copied())
    }

    /// The present joint angles.
    pub fn joints(&self) -> Joints {
        self.shared.lock().q
    }

    /// The controller's clock (RTDE `timestamp`), s since it started.
    pub fn controller_time_s(&self) -> f64 {
        self.shared.lock().time_s
    }

    /// How many client connections are open now, on all three ports.
    pub fn connections(&self) -> usize {
        self.shared
            .streams
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .len()
    }

    /// The script's `textmsg` lines, the safety events and the RTDE input registers refused
    /// as in use, oldest first.
    pub fn log(&self) -> Vec<String> {
        self.shared.lock().log.iter().cloned().collect()
    }

    /// Stops the controller at once: every connection and listener closes, no goodbye.
    pub fn kill(self) {
        drop(self);
    }

    fn shutdown(&self) {
        if self.shared.stop.swap(true, Ordering::SeqCst) {
            return;
        }
        for s in self
            .shared
            .streams
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .drain()
        {
            let _ = s.1.shutdown(Shutdown::Both);
        }
        // Wake the blocking accepts so their threads see the stop flag.
        for a in &self.addrs {
            let _ = TcpStream::connect_timeout(a, Duration::from_millis(200));
        }
        let threads: Vec<_> = self
            .shared
            .threads
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .drain(..)
            .collect();
        for t in threads {
            let _ = t.join();
        }
    }
}

impl Drop for UrSim {
    fn drop(&mut self) {
        self.shutdown();
    }
}

fn accept_loop(shared: &Arc<Shared>, listener: &TcpListener, handler: Handler) {
    for stream in listener.incoming() {
        if shared.stopped() {
            break;
        }
        let Ok(stream) = stream else { continue };
        let Ok(clone) = stream.try_clone() else {
            continue;
        };
        let id = shared.next_id.fetch_add(1, Ordering::SeqCst);
        shared
            .streams
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .insert(id, clone);
        let s = shared.clone();
        // A client's I/O error ends its own connection only.
        shared.spawn(move || {
            let _ = handler(&s, stream, id);
            s.streams
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .remove(&id);
        });
    }
}

/// Steps the controller every control period (of simulated time: the time scale shortens the
/// wall-clock wait), paced against the start time.
fn control_loop(shared: &Shared) {
    let period = shared.config.control_period;
    let dt = period.as_secs_f64();
    let wall_period = shared.config.time_scale.wall(period);
    let start = Instant::now();
    let mut n: u32 = 0;
    while !shared.stopped() {
        shared.lock().tick(dt);
        n = n.wrapping_add(1);
        if let Some(wait) = (start + wall_period * n).checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
    }
}

/// The most a script may hold before its closing `end` line (ur_rtde's control script is
/// about 40 kB); more is dropped with the connection, so a client cannot grow memory unbounded.
pub(crate) const MAX_SCRIPT_BYTES: usize = 1 << 20;

/// Port 30003: collects `def …():` … `end` programs and hands each to the controller.
fn serve_script(shared: &Arc<Shared>, stream: TcpStream) -> std::io::Result<()> {
    serve_script_io(shared, stream, |_| {})
}

/// The script intake over any byte source (a socket, or a fuzzer's bytes); `after_program`
/// runs after each program was handed over.
pub(crate) fn serve_script_io(
    shared: &Shared,
    mut input: impl Read,
    mut after_program: impl FnMut(&Shared),
) -> std::io::Result<()> {
    let mut text: Vec<u8> = Vec::new();
    let mut buf = [0_u8; 16 * 1024];
    loop {
        let n = input.read(&mut buf)?;
        if n == 0 || shared.stopped() {
            return Ok(());
        }
        text.extend_from_slice(&buf[..n]);
        // A program ends with an unindented `end` line.
        while let Some(end) = program_end(&text) {
            let program: Vec<u8> = text.drain(..end).collect();
            shared
                .lock()
                .receive_script(&String::from_utf8_lossy(&program));
            after_program(shared);
        }
        if text.len() > MAX_SCRIPT_BYTES {
            shared.lock().textmsg(format!(
                "script intake: over {MAX_SCRIPT_BYTES} bytes without a closing `end` line: dropped"
            ));
            return Ok(());
        }
    }
}

/// The byte index just past the `end` line closing the first top-level `def`, if it arrived.
fn program_end(text: &[u8]) -> Option<usize> {
    let mut pos = 0;
    for line in text.split_inclusive(|b| *b == b'\n') {
        pos += line.len();
        if line.ends_with(b"\n") && line.trim_ascii_end() == b"end" {
            return Some(pos);
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn time_scale_runs_controller_time_faster_than_the_wall() {
        // Before the start: the control loop's clock starts inside it.
        let start = Instant::now();
        let sim = UrSim::start(SimConfig {
            // Off sim_bridge's 127.0.0.11–20.
            address: Ipv4Addr::new(127, 0, 0, 21),
            time_scale: TimeScale::new(10.0).expect("positive"),
            ..SimConfig::default()
        })
        .expect("bind");
        // Polls the controller clock (no client needed), bounded.
        while sim.shared.lock().time_s < 1.0 {
            assert!(start.elapsed() < Duration::from_secs(10), "clock stalled");
            std::thread::sleep(Duration::from_millis(1));
        }
        // Controller time first: the wall time read after it bounds it from above.
        let sim_s = sim.shared.lock().time_s;
        let wall = start.elapsed().as_secs_f64();
        // 1 s of controller time in a tenth of that; never ahead of 10 × wall (+ one cycle).
        assert!(
            wall < 1.0,
            "1 s of controller time took {wall} s of wall time"
        );
        assert!(sim_s <= 10.0 * wall + 0.008 + 1e-9, "{sim_s} s in {wall} s");
    }

    /// A claim that meets another connection's registers gets them when that connection's
    /// thread releases them within [`CLAIM_WAIT`] (its close read late), and is refused when
    /// it holds them on.
    #[test]
    fn a_claim_waits_for_a_closing_holder_and_is_refused_by_a_live_one() {
        let shared = Arc::new(Shared::new(SimConfig::default()));
        let names = [String::from("input_int_register_0")];
        assert_eq!(shared.claim_inputs(1, &names), [true]);
        let releaser = {
            let shared = shared.clone();
            std::thread::spawn(move || {
                std::thread::sleep(CLAIM_WAIT / 5);
                shared.release_inputs(1);
            })
        };
        assert_eq!(
            shared.claim_inputs(2, &names),
            [true],
            "{:?}",
            shared.lock().log
        );
        releaser.join().expect("releaser");
        let start = Instant::now();
        assert_eq!(shared.claim_inputs(3, &names), [false]);
        assert!(start.elapsed() >= CLAIM_WAIT);
        let log = &shared.lock().log;
        assert_eq!(
            log.back().map(String::as_str),
            Some("rtde: connection 3 asked for input_int_register_0, held by connection 2: IN_USE")
        );
    }
}
