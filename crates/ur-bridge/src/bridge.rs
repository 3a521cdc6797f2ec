//! [`UrArm`]: a UR arm driven through ur_rtde's `rtde_control`, `rtde_receive` and
//! `dashboard_client`, embedded with pyo3. The GIL and every Python object stay in here.

use std::net::{TcpStream, ToSocketAddrs};
use std::time::{Duration, Instant};

use hand_traits::{Arm, LinearMotion, Pose};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

use crate::kinematics::Joints;
use crate::rtde_frame;
use crate::status::ArmStatus;
use crate::{UrError, Venv};

/// How to reach the controller.
#[derive(Debug, Clone, PartialEq)]
pub struct UrConfig {
    /// Controller host name or address (ur_rtde uses the fixed ports 29999, 30003, 30004).
    pub host: String,
    /// The venv ur_rtde is installed in.
    pub venv: Venv,
    /// RTDE frequency; `None` lets ur_rtde choose (125 Hz CB3, 500 Hz e-Series).
    pub frequency_hz: Option<f64>,
    /// Longest wait for one move (or stop) to finish before [`UrError::Timeout`].
    pub move_timeout: Duration,
    /// How often a blocking move polls the controller state.
    pub poll_period: Duration,
    /// Power the arm on and release its brakes over the dashboard before uploading the script.
    pub power_up: bool,
}

impl UrConfig {
    /// Defaults for `host`: the venv from the environment, 60 s move timeout, 8 ms polling
    /// (one CB3 control cycle), no power-up.
    pub fn new(host: impl Into<String>) -> Self {
        Self {
            host: host.into(),
            venv: Venv::from_env(),
            frequency_hz: None,
            move_timeout: Duration::from_secs(60),
            poll_period: Duration::from_millis(8),
            power_up: false,
        }
    }
}

/// Speed and acceleration of a joint-space move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointMotion {
    /// Leading-joint speed, rad/s.
    pub speed_rad_per_s: f64,
    /// Leading-joint acceleration, rad/s².
    pub accel_rad_per_s2: f64,
}

impl Default for JointMotion {
    /// ur_rtde's `moveJ` defaults: 1.05 rad/s, 1.4 rad/s².
    fn default() -> Self {
        Self {
            speed_rad_per_s: 1.05,
            accel_rad_per_s2: 1.4,
        }
    }
}

/// Where an asynchronous move is going.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Target {
    Joints { from: Joints, to: Joints },
    Tool { from: Pose, to: Pose },
}

/// A move started with [`UrArm::start_move_linear`] or [`UrArm::start_move_joints`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoveHandle {
    target: Target,
    op_id_before: i32,
    started: Instant,
}

/// How far an asynchronous move has come.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MoveProgress {
    /// Whether the controller still runs the move.
    pub running: bool,
    /// Fraction of the distance covered, `0.0..=1.0` (tool distance for moveL, leading joint
    /// for moveJ).
    pub fraction: f64,
    /// The present tool pose.
    pub tcp: Pose,
}

/// A UR arm through ur_rtde.
pub struct UrArm {
    control: Py<PyAny>,
    receive: Py<PyAny>,
    dashboard: Py<PyAny>,
    config: UrConfig,
}

impl core::fmt::Debug for UrArm {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.debug_struct("UrArm")
            .field("config", &self.config)
            .finish_non_exhaustive()
    }
}

/// A Python exception as a typed error.
fn map_py(py: Python<'_>, err: PyErr, call: &'static str, host: &str) -> UrError {
    let message = err.value(py).to_string();
    if err.is_instance_of::<PyValueError>(py) {
        return UrError::InvalidArgument(format!("{call}: {message}"));
    }
    let lower = message.to_lowercase();
    if lower.contains("could not connect")
        || lower.contains("timeout connecting")
        || lower.contains("connection refused")
    {
        return UrError::Connect {
            host: host.to_owned(),
            message,
        };
    }
    UrError::Controller(format!("{call}: {message}"))
}

/// Longest wait for one probe of a port that ur_rtde could not connect to.
const PROBE_TIMEOUT: Duration = Duration::from_secs(2);

/// ur_rtde says "Timeout connecting to UR dashboard server." (or "Could not connect") at once
/// also when the host refused the connection; a refused port is a different fix (start the
/// controller, check the address) from a host that does not answer, so the bridge asks each
/// of `ports` itself and names the first that refuses.
fn refine_connect_error(err: UrError, host: &str, ports: &[u16]) -> UrError {
    if !matches!(err, UrError::Connect { .. }) {
        return err;
    }
    match ports.iter().find(|port| refuses(host, **port)) {
        Some(&port) => UrError::ConnectionRefused {
            host: host.to_owned(),
            port,
        },
        None => err,
    }
}

/// Whether every address `host` resolves to refuses a TCP connection on `port` (bounded: at
/// most 4 addresses, [`PROBE_TIMEOUT`] each).
fn refuses(host: &str, port: u16) -> bool {
    let Ok(addrs) = (host, port).to_socket_addrs() else {
        return false;
    };
    let mut tried = 0;
    for addr in addrs.take(4) {
        tried += 1;
        match TcpStream::connect_timeout(&addr, PROBE_TIMEOUT) {
            Err(e) if e.kind() == std::io::ErrorKind::ConnectionRefused => {}
            _ => return false,
        }
    }
    tried > 0
}

/// ur_rtde's `DashboardClient::connect` deadline for the server's greeting (its default).
const DASHBOARD_GREETING_TIMEOUT: Duration = Duration::from_secs(2);
/// Longest wait for the controller to answer our RTDE protocol-version request.
const RTDE_HANDSHAKE_TIMEOUT: Duration = Duration::from_secs(2);
/// The RTDE port and the protocol version ur_rtde asks for.
const RTDE_PORT: u16 = 30004;
const RTDE_PROTOCOL_VERSION: u16 = 2;
/// How long [`UrArm::connect`] waits for its receive link to report the control script
/// running, once ur_rtde's control interface has started it.
const PROGRAM_SEEN_TIMEOUT: Duration = Duration::from_secs(5);

/// Asks the controller's RTDE server for protocol version 2 ourselves, each step bounded by
/// [`RTDE_HANDSHAKE_TIMEOUT`], before ur_rtde connects: ur_rtde's own handshake waits without
/// limit on a server that accepts the connection and never answers (measured here: its
/// `RTDEReceiveInterface` and `RTDEControlInterface` were still blocked after 40 s).
fn check_rtde_answers(host: &str) -> Result<(), UrError> {
    let connect = |message: String| UrError::Connect {
        host: host.to_owned(),
        message: format!("RTDE (port {RTDE_PORT}): {message}"),
    };
    let addr = (host, RTDE_PORT)
        .to_socket_addrs()
        .map_err(|e| connect(e.to_string()))?
        .next()
        .ok_or_else(|| connect("the host has no address".into()))?;
    let mut stream =
        TcpStream::connect_timeout(&addr, RTDE_HANDSHAKE_TIMEOUT).map_err(|e| match e.kind() {
            std::io::ErrorKind::ConnectionRefused => UrError::ConnectionRefused {
                host: host.to_owned(),
                port: RTDE_PORT,
            },
            _ => connect(e.to_string()),
        })?;
    let io = |e: std::io::Error| match e.kind() {
        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut => UrError::Timeout {
            after: RTDE_HANDSHAKE_TIMEOUT,
            what: "the controller's RTDE handshake (port 30004)",
        },
        _ => connect(e.to_string()),
    };
    stream
        .set_read_timeout(Some(RTDE_HANDSHAKE_TIMEOUT))
        .and_then(|()| stream.set_write_timeout(Some(RTDE_HANDSHAKE_TIMEOUT)))
        .map_err(io)?;
    rtde_frame::write_package(
        &mut stream,
        rtde_frame::REQUEST_PROTOCOL_VERSION,
        &RTDE_PROTOCOL_VERSION.to_be_bytes(),
    )
    .map_err(io)?;
    match rtde_frame::read_package(&mut stream).map_err(io)? {
        Some((rtde_frame::REQUEST_PROTOCOL_VERSION, reply)) if reply.first() == Some(&1) => Ok(()),
        Some((rtde_frame::REQUEST_PROTOCOL_VERSION, _)) => Err(UrError::BadReply {
            call: "RTDE protocol version",
            detail: format!("the controller refused version {RTDE_PROTOCOL_VERSION}"),
        }),
        Some((kind, _)) => Err(UrError::BadReply {
            call: "RTDE protocol version",
            detail: format!("a package of type {kind} in reply"),
        }),
        None => Err(connect("closed before answering".into())),
    }
}

fn six(v: Vec<f64>, call: &'static str) -> Result<[f64; 6], UrError> {
    <[f64; 6]>::try_from(v).map_err(|v| UrError::BadReply {
        call,
        detail: format!("{} values, expected 6", v.len()),
    })
}

fn pose_of(v: [f64; 6]) -> Pose {
    Pose {
        position_m: [v[0], v[1], v[2]],
        rotation_vec_rad: [v[3], v[4], v[5]],
    }
}

fn vec_of(p: &Pose) -> Vec<f64> {
    p.position_m
        .iter()
        .chain(p.rotation_vec_rad.iter())
        .copied()
        .collect()
}

impl UrArm {
    /// Connects: dashboard, then (optionally power-up), then `RTDEReceiveInterface` and
    /// `RTDEControlInterface` (which uploads ur_rtde's control script on port 30003), and
    /// returns once the receive link reports the script running, so [`UrArm::status`] agrees
    /// with the arm just connected ([`UrError::Timeout`] after 5 s otherwise). A controller in
    /// a protective stop (RTDE's safety status bits) is [`UrError::ProtectiveStop`], before any
    /// script is sent.
    pub fn connect(config: UrConfig) -> Result<Self, UrError> {
        let arm = Python::attach(|py| {
            config.venv.activate(py)?;
            let import = |name: &str| {
                py.import(name)
                    .map_err(|e| UrError::Python(format!("import {name}: {e}")))
            };
            let (rtde_control, rtde_receive, dashboard_client) = (
                import("rtde_control")?,
                import("rtde_receive")?,
                import("dashboard_client")?,
            );
            let host = config.host.as_str();
            let freq = config.frequency_hz.unwrap_or(-1.0);
            let dashboard = dashboard_client
                .getattr("DashboardClient")
                .and_then(|c| c.call1((host,)))
                .map_err(|e| map_py(py, e, "DashboardClient", host))?;
            dashboard.call_method0("connect").map_err(|e| {
                match map_py(py, e, "dashboard connect", host) {
                    // ur_rtde's own 2 s deadline for the server's greeting ran out.
                    UrError::Controller(m) if m.to_lowercase().contains("operation canceled") => {
                        UrError::Timeout {
                            after: DASHBOARD_GREETING_TIMEOUT,
                            what: "the dashboard server's greeting (port 29999)",
                        }
                    }
                    e => refine_connect_error(e, host, &[29999]),
                }
            })?;
            if config.power_up {
                power_up(py, &dashboard, &config)?;
            }
            // Without the GIL: the check may wait its whole timeout.
            py.detach(|| check_rtde_answers(host))?;
            let receive = rtde_receive
                .getattr("RTDEReceiveInterface")
                .and_then(|c| c.call1((host, freq)))
                .map_err(|e| {
                    refine_connect_error(
                        map_py(py, e, "RTDEReceiveInterface", host),
                        host,
                        &[30004],
                    )
                })?;
            // A protectively stopped controller refuses ur_rtde's control script ("Failed to
            // start control script, before timeout of 5 seconds"): say what holds the arm, and
            // how to unlock it, instead. The receive interface has its first package by now.
            let bits = receive
                .call_method0("getSafetyStatusBits")
                .and_then(|b| b.extract::<f64>())
                .map_err(|e| map_py(py, e, "getSafetyStatusBits", host))?
                as u32;
            if bits & crate::status::SAFETY_PROTECTIVE_STOPPED != 0 {
                return Err(UrError::ProtectiveStop {
                    safety_status_bits: bits,
                });
            }
            let control = rtde_control
                .getattr("RTDEControlInterface")
                .and_then(|c| c.call1((host, freq)))
                .map_err(|e| {
                    let e = map_py(py, e, "RTDEControlInterface", host);
                    refine_connect_error(e, host, &[30004, 30003, 29999])
                })?;
            Ok::<_, UrError>(Self {
                control: control.unbind(),
                receive: receive.unbind(),
                dashboard: dashboard.unbind(),
                config,
            })
        })?;
        arm.wait_for_program_seen()?;
        Ok(arm)
    }

    /// Waits until the receive link reports the control script playing. ur_rtde's control
    /// interface returns once the script runs as *its* receive link saw it; ours is another
    /// connection and can still hold an older package (seen under load: runtime state STOPPED
    /// right after `connect`), so `status()` would contradict the arm just connected.
    fn wait_for_program_seen(&self) -> Result<(), UrError> {
        let start = std::time::Instant::now();
        while !self.status()?.is_program_running() {
            if start.elapsed() > PROGRAM_SEEN_TIMEOUT {
                return Err(UrError::Timeout {
                    after: PROGRAM_SEEN_TIMEOUT,
                    what: "the receive link to report the control script running",
                });
            }
            // One RTDE package is 2–8 ms (500 / 125 Hz): poll at a fraction of it.
            std::thread::sleep(Duration::from_millis(1));
        }
        Ok(())
    }

    /// The configuration this arm was connected with.
    pub fn config(&self) -> &UrConfig {
        &self.config
    }

    fn with<T>(
        &self,
        call: &'static str,
        f: impl for<'py> FnOnce(Python<'py>, &Bound<'py, PyAny>, &Bound<'py, PyAny>) -> PyResult<T>,
    ) -> Result<T, UrError> {
        Python::attach(|py| {
            f(py, self.control.bind(py), self.receive.bind(py))
                .map_err(|e| map_py(py, e, call, &self.config.host))
        })
    }

    /// Whether both RTDE connections are up.
    pub fn is_connected(&self) -> Result<bool, UrError> {
        self.with("isConnected", |_, c, r| {
            Ok(c.call_method0("isConnected")?.extract::<bool>()?
                && r.call_method0("isConnected")?.extract::<bool>()?)
        })
    }

    /// The controller's state words.
    pub fn status(&self) -> Result<ArmStatus, UrError> {
        self.with("status", |_, _, r| {
            Ok(ArmStatus {
                robot_mode: r.call_method0("getRobotMode")?.extract()?,
                safety_mode: r.call_method0("getSafetyMode")?.extract()?,
                safety_status_bits: r.call_method0("getSafetyStatusBits")?.extract::<f64>()? as u32,
                robot_status_bits: r.call_method0("getRobotStatus")?.extract::<f64>()? as u32,
                runtime_state: r.call_method0("getRuntimeState")?.extract::<f64>()? as u32,
            })
        })
    }

    /// The controller's clock (RTDE `timestamp`), s since it started.
    pub fn controller_time_s(&self) -> Result<f64, UrError> {
        self.with("getTimestamp", |_, _, r| {
            r.call_method0("getTimestamp")?.extract::<f64>()
        })
    }

    /// The present joint angles, rad.
    pub fn joint_positions(&self) -> Result<Joints, UrError> {
        let v = self.with("getActualQ", |_, _, r| {
            r.call_method0("getActualQ")?.extract::<Vec<f64>>()
        })?;
        six(v, "getActualQ")
    }

    /// The present tool pose.
    pub fn tool_pose(&self) -> Result<Pose, UrError> {
        let v = self.with("getActualTCPPose", |_, _, r| {
            r.call_method0("getActualTCPPose")?.extract::<Vec<f64>>()
        })?;
        Ok(pose_of(six(v, "getActualTCPPose")?))
    }

    /// Why a command came back `false`: the stop, the lost link or the dead script behind it.
    fn explain(&self, call: &'static str) -> UrError {
        match self.is_connected() {
            Ok(false) => return UrError::ConnectionLost,
            Err(e) => return e,
            Ok(true) => {}
        }
        match self.status() {
            Ok(s) if s.is_emergency_stopped() => UrError::EmergencyStop {
                safety_status_bits: s.safety_status_bits,
            },
            Ok(s) if s.is_protective_stopped() => UrError::ProtectiveStop {
                safety_status_bits: s.safety_status_bits,
            },
            Ok(s) if !s.is_program_running() => UrError::ScriptNotRunning,
            Ok(_) => UrError::Rejected(call),
            Err(e) => e,
        }
    }

    /// Sends `call` through the control interface: [`UrError::ConnectionLost`] at once when the
    /// link is down (ur_rtde would try to reconnect inside the call and block for its own
    /// timeouts: a stop sent after the controller went away must not hang its sender).
    fn command(
        &self,
        call: &'static str,
        f: impl for<'py> FnOnce(&Bound<'py, PyAny>) -> PyResult<Bound<'py, PyAny>>,
    ) -> Result<(), UrError> {
        if !self.is_connected()? {
            return Err(UrError::ConnectionLost);
        }
        let accepted = self.with(call, |_, c, _| {
            let out = f(c)?;
            // stopL / stopJ return None; the move commands return a bool.
            if out.is_none() {
                Ok(true)
            } else {
                out.extract::<bool>()
            }
        })?;
        if accepted {
            Ok(())
        } else {
            Err(self.explain(call))
        }
    }

    fn op_id(&self) -> Result<i32, UrError> {
        self.with("getAsyncOperationProgressEx", |_, c, _| {
            c.call_method0("getAsyncOperationProgressEx")?
                .call_method0("operationId")?
                .extract()
        })
    }

    fn check_finite(values: &[f64], what: &'static str) -> Result<(), UrError> {
        if values.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(crate::kinematics::KinematicsError::NonFinite(what).into())
        }
    }

    /// Starts `call` (`moveL` or `moveJ_IK`) to a tool pose, asynchronous, and returns at once.
    fn start_tool_move(
        &mut self,
        call: &'static str,
        target: &Pose,
        speed: f64,
        accel: f64,
    ) -> Result<MoveHandle, UrError> {
        let v = vec_of(target);
        Self::check_finite(&v, "target pose")?;
        let from = self.tool_pose()?;
        let op_id_before = self.op_id()?;
        self.command(call, |c| c.call_method1(call, (v, speed, accel, true)))?;
        Ok(MoveHandle {
            target: Target::Tool { from, to: *target },
            op_id_before,
            started: Instant::now(),
        })
    }

    /// Starts a straight-line tool move (`moveL`, asynchronous) and returns at once.
    pub fn start_move_linear(
        &mut self,
        target: &Pose,
        motion: &LinearMotion,
    ) -> Result<MoveHandle, UrError> {
        self.start_tool_move("moveL", target, motion.speed_m_per_s, motion.accel_m_per_s2)
    }

    /// Starts a joint-space move (`moveJ`, asynchronous) and returns at once.
    pub fn start_move_joints(
        &mut self,
        q: &Joints,
        motion: &JointMotion,
    ) -> Result<MoveHandle, UrError> {
        Self::check_finite(q, "moveJ target")?;
        let from = self.joint_positions()?;
        let op_id_before = self.op_id()?;
        self.command("moveJ", |c| {
            c.call_method1(
                "moveJ",
                (
                    q.to_vec(),
                    motion.speed_rad_per_s,
                    motion.accel_rad_per_s2,
                    true,
                ),
            )
        })?;
        Ok(MoveHandle {
            target: Target::Joints { from, to: *q },
            op_id_before,
            started: Instant::now(),
        })
    }

    /// How far `handle`'s move has come; a protective stop, an emergency stop or a lost link
    /// is an error.
    pub fn progress(&mut self, handle: &MoveHandle) -> Result<MoveProgress, UrError> {
        if !self.is_connected()? {
            return Err(UrError::ConnectionLost);
        }
        let status = self.status()?;
        if status.is_emergency_stopped() {
            return Err(UrError::EmergencyStop {
                safety_status_bits: status.safety_status_bits,
            });
        }
        if status.is_protective_stopped() {
            return Err(UrError::ProtectiveStop {
                safety_status_bits: status.safety_status_bits,
            });
        }
        let (op_id, op_running) = self.with("getAsyncOperationProgressEx", |_, c, _| {
            let s = c.call_method0("getAsyncOperationProgressEx")?;
            Ok((
                s.call_method0("operationId")?.extract::<i32>()?,
                s.call_method0("isAsyncOperationRunning")?
                    .extract::<bool>()?,
            ))
        })?;
        // The script bumps the operation id when the move thread starts.
        let running = op_id == handle.op_id_before || op_running;
        if running && !status.is_program_running() {
            return Err(UrError::ScriptNotRunning);
        }
        let tcp = self.tool_pose()?;
        let fraction = match handle.target {
            Target::Tool { from, to } => covered(from.distance_m(&to), tcp.distance_m(&to)),
            Target::Joints { from, to } => {
                let q = self.joint_positions()?;
                covered(max_abs_diff(&from, &to), max_abs_diff(&q, &to))
            }
        };
        Ok(MoveProgress {
            running,
            fraction,
            tcp,
        })
    }

    /// Waits for `handle`'s move to finish, calling `on_progress` at every poll; bounded by
    /// [`UrConfig::move_timeout`].
    pub fn wait(
        &mut self,
        handle: &MoveHandle,
        mut on_progress: impl FnMut(&MoveProgress),
    ) -> Result<(), UrError> {
        loop {
            let p = self.progress(handle)?;
            if !p.running {
                // The end was read on the control interface's RTDE link; the pose comes from
                // the receive link, up to one package older. Report it once it caught up.
                self.catch_up(handle.started)?;
                on_progress(&self.progress(handle)?);
                return Ok(());
            }
            on_progress(&p);
            if handle.started.elapsed() > self.config.move_timeout {
                return Err(UrError::Timeout {
                    after: self.config.move_timeout,
                    what: "move to finish",
                });
            }
            std::thread::sleep(self.config.poll_period);
        }
    }

    /// Waits until the receive link has delivered two new packages (so its state is newer than
    /// anything the control link reported before), bounded by the move timeout.
    fn catch_up(&self, started: Instant) -> Result<(), UrError> {
        let mut last = self.controller_time_s()?;
        let mut changes = 0;
        while changes < 2 {
            if started.elapsed() > self.config.move_timeout {
                return Err(UrError::Timeout {
                    after: self.config.move_timeout,
                    what: "RTDE data",
                });
            }
            std::thread::sleep(self.config.poll_period / 8);
            let t = self.controller_time_s()?;
            if t != last {
                changes += 1;
                last = t;
            }
        }
        Ok(())
    }

    /// Moves the tool in a straight line and returns when it is there.
    pub fn move_linear(&mut self, target: &Pose, motion: &LinearMotion) -> Result<(), UrError> {
        let h = self.start_move_linear(target, motion)?;
        self.wait(&h, |_| {})
    }

    /// Moves in joint space to `q` and returns when the arm is there.
    pub fn move_joints(&mut self, q: &Joints, motion: &JointMotion) -> Result<(), UrError> {
        let h = self.start_move_joints(q, motion)?;
        self.wait(&h, |_| {})
    }

    /// Moves in joint space to the joint angles that put the tool at `target` (ur_rtde
    /// `moveJ_IK`: the controller's inverse kinematics, nearest the present joints).
    pub fn move_joints_to_pose(
        &mut self,
        target: &Pose,
        motion: &JointMotion,
    ) -> Result<(), UrError> {
        let h = self.start_tool_move(
            "moveJ_IK",
            target,
            motion.speed_rad_per_s,
            motion.accel_rad_per_s2,
        )?;
        self.wait(&h, |_| {})
    }

    /// Whether the controller's inverse kinematics finds joint angles for `target` near the
    /// present ones (ur_rtde `getInverseKinematicsHasSolution`, URScript
    /// `get_inverse_kin_has_solution`: PolyScope 3.15 / 5.10 and later).
    ///
    /// A moveL to a pose without a solution is not refused up front by the controller: the arm
    /// follows the line until it leaves the workspace and then protective-stops. Ask this first
    /// where a target may be out of reach.
    pub fn is_reachable(&self, target: &Pose) -> Result<bool, UrError> {
        let v = vec_of(target);
        Self::check_finite(&v, "target pose")?;
        self.with("getInverseKinematicsHasSolution", |_, c, _| {
            c.call_method1("getInverseKinematicsHasSolution", (v,))?
                .extract::<bool>()
        })
    }

    /// Arms the control script's RTDE watchdog (ur_rtde `setWatchdog`): from now on the
    /// controller stops the program, and with it the arm, when no command or
    /// [`UrArm::kick_watchdog`] reaches it for `1 / min_frequency_hz` s — so the arm stops when
    /// this client goes away mid-move (process killed, cable pulled). Without it a real
    /// controller finishes the running move.
    pub fn set_watchdog(&mut self, min_frequency_hz: f64) -> Result<(), UrError> {
        if !(min_frequency_hz.is_finite() && min_frequency_hz > 0.0) {
            return Err(UrError::InvalidArgument(format!(
                "setWatchdog: min_frequency {min_frequency_hz} Hz"
            )));
        }
        self.command("setWatchdog", |c| {
            c.call_method1("setWatchdog", (min_frequency_hz,))
        })
    }

    /// Feeds the watchdog armed by [`UrArm::set_watchdog`] (ur_rtde `kickWatchdog`).
    pub fn kick_watchdog(&mut self) -> Result<(), UrError> {
        self.command("kickWatchdog", |c| c.call_method0("kickWatchdog"))
    }

    /// Decelerates the tool to rest at `decel_m_per_s2` (ur_rtde `stopL`, synchronous).
    pub fn stop_linear(&mut self, decel_m_per_s2: f64) -> Result<(), UrError> {
        Self::check_finite(&[decel_m_per_s2], "stopL deceleration")?;
        self.command("stopL", |c| {
            c.call_method1("stopL", (decel_m_per_s2, false))
        })
    }

    /// Accelerates the tool to the twist `xd` (m/s, rad/s, base frame) and keeps it until
    /// [`UrArm::speed_stop`] (ur_rtde `speedL`; `time_s` 0 means "until the next command").
    pub fn speed_linear(
        &mut self,
        xd: &[f64; 6],
        accel_m_per_s2: f64,
        time_s: f64,
    ) -> Result<(), UrError> {
        Self::check_finite(xd, "speedL twist")?;
        self.command("speedL", |c| {
            c.call_method1("speedL", (xd.to_vec(), accel_m_per_s2, time_s))
        })
    }

    /// Ends a [`UrArm::speed_linear`] motion, decelerating at `decel_m_per_s2`.
    pub fn speed_stop(&mut self, decel_m_per_s2: f64) -> Result<(), UrError> {
        self.command("speedStop", |c| {
            c.call_method1("speedStop", (decel_m_per_s2,))
        })
    }

    /// After a protective stop: unlocks it on the dashboard and re-uploads the control script.
    pub fn recover_from_protective_stop(&mut self) -> Result<(), UrError> {
        Python::attach(|py| {
            let host = self.config.host.as_str();
            self.dashboard
                .bind(py)
                .call_method0("unlockProtectiveStop")
                .map_err(|e| map_py(py, e, "unlockProtectiveStop", host))?;
            let ok = self
                .control
                .bind(py)
                .call_method0("reuploadScript")
                .and_then(|v| v.extract::<bool>())
                .map_err(|e| map_py(py, e, "reuploadScript", host))?;
            if ok {
                Ok(())
            } else {
                Err(UrError::Rejected("reuploadScript"))
            }
        })?;
        // The script reports ready within a few control cycles.
        let start = Instant::now();
        while !self.status()?.is_program_running() {
            if start.elapsed() > Duration::from_secs(5) {
                return Err(UrError::Timeout {
                    after: Duration::from_secs(5),
                    what: "control script to run",
                });
            }
            std::thread::sleep(self.config.poll_period);
        }
        Ok(())
    }

    /// The dashboard's one-line answer to `command` (e.g. `"robotmode"`, `"safetystatus"`).
    pub fn dashboard(&self, method: &'static str) -> Result<String, UrError> {
        Python::attach(|py| {
            let out = self
                .dashboard
                .bind(py)
                .call_method0(method)
                .map_err(|e| map_py(py, e, method, &self.config.host))?;
            Ok(out.str().map(|s| s.to_string()).unwrap_or_default())
        })
    }
}

fn power_up(
    py: Python<'_>,
    dashboard: &Bound<'_, PyAny>,
    config: &UrConfig,
) -> Result<(), UrError> {
    let host = config.host.as_str();
    let mode = |py: Python<'_>| -> Result<String, UrError> {
        dashboard
            .call_method0("robotmode")
            .and_then(|s| s.extract::<String>())
            .map_err(|e| map_py(py, e, "robotmode", host))
    };
    let wait_for = |py: Python<'_>, want: &str, what: &'static str| -> Result<(), UrError> {
        let start = Instant::now();
        while !mode(py)?.contains(want) {
            if start.elapsed() > config.move_timeout {
                return Err(UrError::Timeout {
                    after: config.move_timeout,
                    what,
                });
            }
            std::thread::sleep(config.poll_period);
        }
        Ok(())
    };
    dashboard
        .call_method0("powerOn")
        .map_err(|e| map_py(py, e, "powerOn", host))?;
    wait_for(py, "IDLE", "power on")?;
    dashboard
        .call_method0("brakeRelease")
        .map_err(|e| map_py(py, e, "brakeRelease", host))?;
    wait_for(py, "RUNNING", "brake release")
}

fn max_abs_diff(a: &Joints, b: &Joints) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn covered(total: f64, left: f64) -> f64 {
    if total <= 0.0 {
        1.0
    } else {
        (1.0 - left / total).clamp(0.0, 1.0)
    }
}

impl Drop for UrArm {
    fn drop(&mut self) {
        // Stop the control script and close the links while the controller is still there;
        // against a dead controller only the local sockets are closed.
        Python::attach(|py| {
            let c = self.control.bind(py);
            let r = self.receive.bind(py);
            let up = |o: &Bound<'_, PyAny>| {
                o.call_method0("isConnected")
                    .and_then(|v| v.extract::<bool>())
                    .unwrap_or(false)
            };
            // The receive link never reconnects by itself, so it tells whether the controller
            // is still there; stopScript against a dead one would wait out ur_rtde's 300 s.
            if up(r) && up(c) {
                let _ = c.call_method0("stopScript");
            }
            let _ = c.call_method0("disconnect");
            let _ = r.call_method0("disconnect");
            let _ = self.dashboard.bind(py).call_method0("disconnect");
        });
    }
}

impl Arm for UrArm {
    type Error = UrError;

    fn move_linear(&mut self, target: &Pose, motion: &LinearMotion) -> Result<(), UrError> {
        UrArm::move_linear(self, target, motion)
    }

    fn tcp_pose(&mut self) -> Result<Pose, UrError> {
        self.tool_pose()
    }

    /// `stopL` at Universal Robots' default 10 m/s².
    fn stop(&mut self) -> Result<(), UrError> {
        self.stop_linear(10.0)
    }
}
