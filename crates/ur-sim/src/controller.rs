//! The kinematic UR3 controller: joint state, safety state, RTDE registers, and ur_rtde's
//! control-script register protocol executed natively.
//!
//! The protocol follows ur_rtde's `scripts/rtde_control.script`: the command number arrives in
//! `input_int_register_0`, its arguments in `input_double_register_0…` and
//! `input_int_register_1`; the script writes 1 (ready) / 2 (done with command) to
//! `output_int_register_0`, and the async-operation word (operation id in bits 24–30, write
//! count in bits 16–23, running flag bit 15, progress bits 0–14) to `output_int_register_2`.
//! Register numbers shift by the offset ur_rtde injects (`0`, or `24` for the upper range).

use std::collections::VecDeque;

use nalgebra::{Isometry3, Vector6};

use super::motion::Trapezoid;
use ur_bridge::kinematics::{self, Joints, UrModel};
use ur_bridge::status::{self, robot_mode, runtime_state, safety_mode};

/// ur_rtde command numbers this controller executes (`RTDE::RobotCommand::Type`).
mod cmd {
    pub(super) const MOVEJ: i32 = 1;
    pub(super) const MOVEJ_IK: i32 = 2;
    pub(super) const MOVEL: i32 = 3;
    pub(super) const MOVEL_FK: i32 = 4;
    pub(super) const SPEEDJ: i32 = 9;
    pub(super) const SPEEDL: i32 = 10;
    pub(super) const SPEED_STOP: i32 = 15;
    pub(super) const SET_PAYLOAD: i32 = 17;
    pub(super) const PROTECTIVE_STOP: i32 = 31;
    pub(super) const STOPL: i32 = 33;
    pub(super) const STOPJ: i32 = 34;
    pub(super) const SET_WATCHDOG: i32 = 35;
    pub(super) const IK_HAS_SOLUTION_DEFAULT: i32 = 60;
    pub(super) const IK_HAS_SOLUTION_ARGS: i32 = 61;
    pub(super) const STOP_SCRIPT: i32 = 255;
    /// Commands the script's main loop runs every cycle without the ready/done handshake.
    pub(super) const REALTIME: [i32; 10] = [24, 11, 9, 10, 6, 25, 26, 27, 38, 58];
}

/// A path being followed: joint-space (moveJ) or a straight tool line (moveL).
#[derive(Debug, Clone, Copy)]
enum PathKind {
    Joint {
        from: Joints,
        to: Joints,
    },
    Linear {
        from: Isometry3<f64>,
        to: Isometry3<f64>,
    },
}

/// What the arm is doing.
#[derive(Debug, Clone, Copy)]
enum Motion {
    Idle,
    Path {
        kind: PathKind,
        profile: Trapezoid,
        length: f64,
        t: f64,
        /// Distance covered and present path speed.
        s: f64,
        v: f64,
        /// Deceleration once a stop was commanded (path units / s²).
        stopping: Option<f64>,
    },
    Speed {
        /// Joint velocities (speedJ) or a tool twist (speedL).
        joint: bool,
        target: [f64; 6],
        current: [f64; 6],
        accel: f64,
        stopping: bool,
    },
}

/// Who is waiting for the present motion to end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Waiter {
    /// A synchronous command: write "done" when the arm is at rest.
    Blocking,
    /// ur_rtde's move thread: write "async finished" when the arm is at rest.
    MoveThread,
    /// ur_rtde's stop thread (async stopL / stopJ).
    StopThread,
}

/// The script's state: the offset it was sent with and its main-loop flags.
#[derive(Debug, Clone, Default)]
struct Script {
    reg_offset: usize,
    executing_cmd: bool,
    async_wr_count: i32,
    async_op_id: i32,
}

/// `rtde_set_watchdog(variable, min_frequency, "stop")`, as ur_rtde's `setWatchdog` arms it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Watchdog {
    /// The watched `input_int_register_N`.
    register: usize,
    min_frequency_hz: f64,
}

/// The simulated controller.
#[derive(Debug)]
pub(crate) struct Controller {
    pub(crate) model: UrModel,
    pub(crate) q: Joints,
    pub(crate) qd: Joints,
    pub(crate) time_s: f64,
    pub(crate) robot_mode: i32,
    pub(crate) safety_mode: i32,
    pub(crate) safety_status_bits: u32,
    pub(crate) runtime_state: u32,
    pub(crate) speed_fraction: f64,
    pub(crate) in_int: [i32; 48],
    pub(crate) in_double: [f64; 48],
    pub(crate) out_int: [i32; 48],
    pub(crate) out_double: [f64; 48],
    /// Controller time of the last RTDE write of each `input_int_register_N` (the watchdog's clock).
    in_int_written_s: [f64; 48],
    watchdog: Option<Watchdog>,
    /// The last script received (kept so that dashboard `play` can restart it).
    program: Option<Script>,
    motion: Motion,
    waiters: Vec<Waiter>,
    /// `textmsg` lines and safety events, newest last (bounded).
    pub(crate) log: VecDeque<String>,
}

impl Controller {
    /// A controller with the arm at `q`, in robot mode `mode`.
    pub(crate) fn new(model: UrModel, q: Joints, mode: i32) -> Self {
        Self {
            model,
            q,
            qd: [0.0; 6],
            time_s: 0.0,
            robot_mode: mode,
            safety_mode: safety_mode::NORMAL,
            safety_status_bits: status::SAFETY_NORMAL,
            runtime_state: runtime_state::STOPPED,
            speed_fraction: 1.0,
            in_int: [0; 48],
            in_double: [0.0; 48],
            out_int: [0; 48],
            out_double: [0.0; 48],
            in_int_written_s: [0.0; 48],
            watchdog: None,
            program: None,
            motion: Motion::Idle,
            waiters: Vec::new(),
            log: VecDeque::new(),
        }
    }

    pub(crate) fn textmsg(&mut self, msg: impl Into<String>) {
        if self.log.len() >= 256 {
            self.log.pop_front();
        }
        self.log.push_back(msg.into());
    }

    /// `robot_status_bits`: power on, program running.
    pub(crate) fn robot_status_bits(&self) -> u32 {
        let mut bits = 0;
        if matches!(
            self.robot_mode,
            robot_mode::IDLE | robot_mode::RUNNING | robot_mode::POWER_ON
        ) {
            bits |= status::STATUS_POWER_ON;
        }
        if self.runtime_state == runtime_state::PLAYING {
            bits |= status::STATUS_PROGRAM_RUNNING;
        }
        bits
    }

    pub(crate) fn tcp(&self) -> Isometry3<f64> {
        self.model.forward(&self.q)
    }

    pub(crate) fn tcp_vector(&self) -> [f64; 6] {
        let p = kinematics::to_pose(&self.tcp());
        [
            p.position_m[0],
            p.position_m[1],
            p.position_m[2],
            p.rotation_vec_rad[0],
            p.rotation_vec_rad[1],
            p.rotation_vec_rad[2],
        ]
    }

    pub(crate) fn tcp_speed(&self) -> [f64; 6] {
        let v = self.model.jacobian(&self.q) * Vector6::from_row_slice(&self.qd);
        core::array::from_fn(|i| v[i])
    }

    pub(crate) fn elbow_position(&self) -> [f64; 3] {
        let e = self.model.frames(&self.q)[3].translation.vector;
        [e.x, e.y, e.z]
    }

    pub(crate) fn is_protective_stopped(&self) -> bool {
        self.safety_status_bits & status::SAFETY_PROTECTIVE_STOPPED != 0
    }

    // ---- dashboard actions -------------------------------------------------------------

    pub(crate) fn power_on(&mut self) {
        if self.robot_mode == robot_mode::POWER_OFF {
            self.robot_mode = robot_mode::IDLE;
        }
    }

    pub(crate) fn power_off(&mut self) {
        self.stop_program();
        self.robot_mode = robot_mode::POWER_OFF;
    }

    pub(crate) fn brake_release(&mut self) {
        if self.robot_mode == robot_mode::IDLE {
            self.robot_mode = robot_mode::RUNNING;
        }
    }

    /// `unlock protective stop`: true if there was one to unlock.
    pub(crate) fn unlock_protective_stop(&mut self) -> bool {
        if !self.is_protective_stopped() {
            return false;
        }
        self.safety_mode = safety_mode::NORMAL;
        self.safety_status_bits = status::SAFETY_NORMAL;
        true
    }

    /// Dashboard `stop`: ends the program, the arm decelerates to rest.
    pub(crate) fn stop_program(&mut self) {
        self.runtime_state = runtime_state::STOPPED;
        self.end_program();
    }

    /// What every program end shares: its threads die, the arm stops, and (URScript manual,
    /// `rtde_set_watchdog`) "all watchdogs are removed on program stop".
    fn end_program(&mut self) {
        self.waiters.clear();
        self.watchdog = None;
        self.halt();
    }

    /// Dashboard `play`: restarts the last script; false when there is none or the arm can't.
    pub(crate) fn play(&mut self) -> bool {
        match self.program.clone() {
            Some(s) if self.robot_mode == robot_mode::RUNNING && !self.is_protective_stopped() => {
                self.start_script(s.reg_offset);
                true
            }
            _ => false,
        }
    }

    pub(crate) fn program_name(&self) -> &'static str {
        if self.program.is_some() {
            "rtde_control"
        } else {
            "<unnamed>"
        }
    }

    // ---- script intake --------------------------------------------------------------------

    /// A script arrived on port 30003. ur_rtde's control script is recognised by its
    /// function and markers; anything else is logged and not run.
    pub(crate) fn receive_script(&mut self, text: &str) {
        let Some(reg_offset) = recognise_rtde_control(text) else {
            self.textmsg(format!(
                "script not run: not ur_rtde's control script ({} bytes)",
                text.len()
            ));
            return;
        };
        if self.robot_mode != robot_mode::RUNNING || self.is_protective_stopped() {
            self.textmsg("script not run: robot is not in RUNNING mode");
            return;
        }
        self.start_script(reg_offset);
    }

    pub(crate) fn start_script(&mut self, reg_offset: usize) {
        // A new program replaces the running one: its threads die, the arm stops.
        self.end_program();
        let mut s = Script {
            reg_offset,
            ..Script::default()
        };
        self.runtime_state = runtime_state::PLAYING;
        self.textmsg("RTDE Control Script Loaded");
        // reset_async_progress(); signal_ready()
        self.write_async(&mut s, -1);
        self.out_int[reg_offset] = 1;
        self.program = Some(s);
    }

    /// `write_async_progress_register(value)` of the script.
    fn write_async(&mut self, s: &mut Script, value: i32) {
        s.async_wr_count = (s.async_wr_count + 1) % 128;
        if value == 0 {
            s.async_op_id = (s.async_op_id + 1) % 128;
        }
        let mut reg = s.async_wr_count * 65_536 + s.async_op_id * 16_777_216;
        if value >= 0 {
            reg += value.min(32_767) + 32_768;
        }
        self.out_int[2 + s.reg_offset] = reg;
    }

    // ---- one control cycle ----------------------------------------------------------------

    /// Advances `dt` seconds: the script's main loop reads its registers, then the arm moves.
    pub(crate) fn tick(&mut self, dt: f64) {
        self.time_s += dt;
        self.check_watchdog();
        self.script_cycle();
        self.step_motion(dt);
        if matches!(self.motion, Motion::Idle) {
            self.motion_ended();
        }
    }

    /// The "stop" action of an armed RTDE watchdog: no update of the watched register for
    /// longer than `1 / min_frequency` (a client that went away, or stopped kicking) stops the
    /// program, and with it the arm.
    fn check_watchdog(&mut self) {
        let Some(w) = self.watchdog else { return };
        if self.runtime_state != runtime_state::PLAYING {
            return;
        }
        let silent_s = self.time_s - self.in_int_written_s[w.register];
        if silent_s > 1.0 / w.min_frequency_hz {
            self.textmsg(format!(
                "RTDE watchdog: input_int_register_{} not updated for {silent_s:.3} s (minimum {} Hz): program stopped",
                w.register, w.min_frequency_hz
            ));
            self.stop_program();
        }
    }

    fn script_cycle(&mut self) {
        if self.runtime_state != runtime_state::PLAYING {
            return;
        }
        let Some(mut s) = self.program.take() else {
            return;
        };
        let off = s.reg_offset;
        // A synchronous command blocks the main loop until the arm is at rest.
        if !self.waiters.contains(&Waiter::Blocking) {
            let c = self.in_int[off];
            if cmd::REALTIME.contains(&c) {
                self.process(&mut s, c);
                self.out_int[off] = 1;
            } else if c == 0 {
                s.executing_cmd = false;
                self.out_int[off] = 1;
            } else if !s.executing_cmd {
                s.executing_cmd = true;
                self.process(&mut s, c);
            }
        }
        if self.runtime_state == runtime_state::PLAYING {
            self.program = Some(s);
        } else {
            // Keep the script so that `play` can restart it.
            self.program = Some(Script {
                reg_offset: s.reg_offset,
                ..Script::default()
            });
        }
    }

    fn arg(&self, s: &Script, i: usize) -> f64 {
        self.in_double[i + s.reg_offset]
    }

    fn args6(&self, s: &Script) -> [f64; 6] {
        core::array::from_fn(|i| self.arg(s, i))
    }

    fn int_arg(&self, s: &Script, i: usize) -> i32 {
        self.in_int[i + s.reg_offset]
    }

    /// `process_cmd(cmd)`: start what the command asks and signal done now or when the arm rests.
    fn process(&mut self, s: &mut Script, c: i32) {
        let off = s.reg_offset;
        let done_now = match c {
            cmd::MOVEJ | cmd::MOVEJ_IK | cmd::MOVEL | cmd::MOVEL_FK => {
                let (v, a, asynchronous) =
                    (self.arg(s, 6), self.arg(s, 7), self.int_arg(s, 1) == 1);
                let target = self.args6(s);
                self.stop_async_move(s);
                let kind = match c {
                    cmd::MOVEJ => Ok(PathKind::Joint {
                        from: self.q,
                        to: target,
                    }),
                    cmd::MOVEJ_IK => self
                        .model
                        .inverse_near(&kinematics::to_isometry(&pose6(&target)), &self.q)
                        .map(|to| PathKind::Joint { from: self.q, to }),
                    // No reach check up front, as on a real controller: ur_rtde's
                    // rtde_control.script hands the pose to URScript `movel` unchecked (cmd 3;
                    // MOVEJ_IK alone calls get_inverse_kin first), and the controller follows
                    // the line until it leaves the workspace, then protective-stops. Universal
                    // Robots' own client library tests it so (Universal_Robots_Client_Library
                    // PR #280, test `unfeasible_movel_target_results_in_failure`: "with `movel`
                    // we cannot request a motion running outside the reachable volume without
                    // running into a singularity, we'll have to check for a protective stop");
                    // UR forum "Cartesian linear move can wind up the wrist": "the protective
                    // stop occurs after the robot started executing the path". A client that
                    // wants the check asks first: getInverseKinematicsHasSolution (cmd 60).
                    cmd::MOVEL => Ok(PathKind::Linear {
                        from: self.tcp(),
                        to: kinematics::to_isometry(&pose6(&target)),
                    }),
                    _ => Ok(PathKind::Linear {
                        from: self.tcp(),
                        to: self.model.forward(&target),
                    }),
                };
                match kind {
                    Ok(kind) => {
                        self.start_path(kind, v, a);
                        self.wait_for_rest(s, asynchronous, Waiter::MoveThread)
                    }
                    Err(e) => {
                        // get_inverse_kin raised: on a UR this is a runtime error that halts the program.
                        self.textmsg(format!("runtime error: get_inverse_kin: {e}"));
                        self.runtime_state = runtime_state::STOPPED;
                        self.end_program();
                        return;
                    }
                }
            }
            cmd::SPEEDJ | cmd::SPEEDL => {
                let (target, accel) = (self.args6(s), self.arg(s, 6));
                let joint = c == cmd::SPEEDJ;
                let current = match self.motion {
                    Motion::Speed {
                        current, joint: j, ..
                    } if j == joint => current,
                    _ => [0.0; 6],
                };
                self.motion = Motion::Speed {
                    joint,
                    target,
                    current,
                    accel,
                    stopping: false,
                };
                true
            }
            cmd::SPEED_STOP | cmd::STOPL | cmd::STOPJ => {
                let decel = self.arg(s, 0);
                let asynchronous = c != cmd::SPEED_STOP && self.int_arg(s, 1) == 1;
                self.stop_async_move(s);
                self.begin_stop(decel);
                self.wait_for_rest(s, asynchronous, Waiter::StopThread)
            }
            cmd::SET_PAYLOAD => true, // the kinematic model carries no payload
            cmd::SET_WATCHDOG => {
                let hz = self.arg(s, 0);
                // The script watches input_int_register_0 (+ offset); the controller refuses a
                // frequency it cannot use (a runtime error, the program stops).
                if !(hz.is_finite() && hz > 0.0) {
                    self.textmsg(format!(
                        "runtime error: rtde_set_watchdog: min_frequency {hz}"
                    ));
                    self.runtime_state = runtime_state::STOPPED;
                    self.end_program();
                    return;
                }
                self.watchdog = Some(Watchdog {
                    register: off,
                    min_frequency_hz: hz,
                });
                // The watchdog's period starts now, not at the register's last write.
                self.in_int_written_s[off] = self.time_s;
                self.textmsg(format!(
                    "rtde_set_watchdog(\"input_int_register_{off}\", {hz}, \"stop\")"
                ));
                true
            }
            cmd::IK_HAS_SOLUTION_DEFAULT | cmd::IK_HAS_SOLUTION_ARGS => {
                // get_inverse_kin_has_solution(x[, qnear, …]) into output_int_register_1.
                let x = kinematics::to_isometry(&pose6(&self.args6(s)));
                let qnear = if c == cmd::IK_HAS_SOLUTION_ARGS {
                    core::array::from_fn(|i| self.arg(s, 6 + i))
                } else {
                    self.q
                };
                let found = self.model.inverse_near(&x, &qnear).is_ok();
                self.out_int[1 + off] = i32::from(found);
                true
            }
            cmd::PROTECTIVE_STOP => {
                self.protective_stop("protective_stop() called by the script");
                return;
            }
            cmd::STOP_SCRIPT => {
                self.textmsg("Received stop script!");
                self.runtime_state = runtime_state::STOPPED;
                self.end_program();
                return;
            }
            other => {
                // Not modelled: on purpose a visible failure, never a silent success.
                self.textmsg(format!("runtime error: command {other} is not simulated"));
                self.runtime_state = runtime_state::STOPPED;
                self.end_program();
                return;
            }
        };
        if done_now {
            self.out_int[off] = 2;
        }
    }

    /// Who learns when the arm comes to rest: the script's `thread` (asynchronous: started now,
    /// the command is done at once) or the main loop (blocking: done at rest). Returns whether
    /// the command is done now.
    fn wait_for_rest(&mut self, s: &mut Script, asynchronous: bool, thread: Waiter) -> bool {
        if asynchronous {
            self.write_async(s, 0);
            self.waiters.push(thread);
        } else {
            self.waiters.push(Waiter::Blocking);
        }
        asynchronous
    }

    /// `stop_async_move()`: kills the move thread (reporting it finished); the arm keeps its
    /// velocity until the next command replaces or stops the motion.
    fn stop_async_move(&mut self, s: &mut Script) {
        if let Some(i) = self.waiters.iter().position(|w| *w == Waiter::MoveThread) {
            self.waiters.remove(i);
            self.write_async(s, -1);
        }
        if let Some(i) = self.waiters.iter().position(|w| *w == Waiter::StopThread) {
            self.waiters.remove(i);
            self.write_async(s, -1);
        }
    }

    fn start_path(&mut self, kind: PathKind, v: f64, a: f64) {
        let length = match kind {
            PathKind::Joint { from, to } => from
                .iter()
                .zip(&to)
                .map(|(x, y)| (x - y).abs())
                .fold(0.0, f64::max),
            PathKind::Linear { from, to } => {
                let d = (to.translation.vector - from.translation.vector).norm();
                // A pure reorientation runs its angle at v rad/s.
                if d > 1e-9 {
                    d
                } else {
                    kinematics::rotation_distance_rad(&from, &to)
                }
            }
        };
        let profile = Trapezoid::new(length, v.abs(), a.abs());
        self.motion = Motion::Path {
            kind,
            profile,
            length,
            t: 0.0,
            s: 0.0,
            v: 0.0,
            stopping: None,
        };
    }

    fn begin_stop(&mut self, decel: f64) {
        let decel = decel.abs().max(1e-6);
        match &mut self.motion {
            Motion::Path { stopping, .. } => *stopping = Some(decel),
            Motion::Speed {
                stopping,
                accel,
                target,
                ..
            } => {
                *stopping = true;
                *accel = decel;
                *target = [0.0; 6];
            }
            Motion::Idle => {}
        }
    }

    /// Ends every motion at once (program stop, new program).
    fn halt(&mut self) {
        self.motion = Motion::Idle;
        self.qd = [0.0; 6];
    }

    /// A protective stop: the arm stops where it is, the program pauses.
    pub(crate) fn protective_stop(&mut self, why: &str) {
        self.textmsg(format!("protective stop: {why}"));
        self.safety_mode = safety_mode::PROTECTIVE_STOP;
        self.safety_status_bits =
            status::SAFETY_PROTECTIVE_STOPPED | status::SAFETY_STOPPED_DUE_TO_SAFETY;
        if self.runtime_state == runtime_state::PLAYING {
            self.runtime_state = runtime_state::PAUSED;
        }
        self.waiters.clear();
        self.halt();
    }

    /// The arm is at rest: whoever waited for it is told.
    fn motion_ended(&mut self) {
        if self.waiters.is_empty() || self.runtime_state != runtime_state::PLAYING {
            return;
        }
        let Some(mut s) = self.program.take() else {
            return;
        };
        for w in core::mem::take(&mut self.waiters) {
            match w {
                Waiter::Blocking => self.out_int[s.reg_offset] = 2,
                Waiter::MoveThread | Waiter::StopThread => self.write_async(&mut s, -1),
            }
        }
        self.program = Some(s);
    }

    // ---- kinematics of one cycle --------------------------------------------------------

    fn step_motion(&mut self, dt: f64) {
        let next = match &mut self.motion {
            Motion::Idle => return,
            Motion::Path {
                kind,
                profile,
                length,
                t,
                s,
                v,
                stopping,
            } => {
                let finished;
                if let Some(decel) = *stopping {
                    let v_new = (*v - decel * dt).max(0.0);
                    *s = (*s + 0.5 * (*v + v_new) * dt).min(*length);
                    *v = v_new;
                    finished = v_new == 0.0 || *s >= *length;
                } else {
                    *t += dt;
                    (*s, *v) = profile.at(*t);
                    finished = *t >= profile.duration_s();
                }
                let u = if *length > 0.0 { *s / *length } else { 1.0 };
                let q = match *kind {
                    PathKind::Joint { from, to } => {
                        Ok(core::array::from_fn(|i| from[i] + u * (to[i] - from[i])))
                    }
                    PathKind::Linear { from, to } => {
                        let p = Isometry3::from_parts(
                            (from.translation.vector.lerp(&to.translation.vector, u)).into(),
                            from.rotation.slerp(&to.rotation, u),
                        );
                        self.model.inverse_near(&p, &self.q)
                    }
                };
                (q, finished)
            }
            Motion::Speed {
                joint,
                target,
                current,
                accel,
                stopping,
            } => {
                // Ramp the commanded velocity towards its target at `accel`.
                let diff: Vector6<f64> =
                    Vector6::from_row_slice(target) - Vector6::from_row_slice(current);
                let max_step = *accel * dt;
                let step = if diff.norm() > max_step {
                    diff * (max_step / diff.norm())
                } else {
                    diff
                };
                for i in 0..6 {
                    current[i] += step[i];
                }
                let finished = *stopping && current.iter().all(|c| *c == 0.0);
                let qd = if *joint {
                    Some(Vector6::from_row_slice(current))
                } else {
                    self.model
                        .jacobian(&self.q)
                        .lu()
                        .solve(&Vector6::from_row_slice(current))
                };
                let q = match qd {
                    Some(qd) => Ok(core::array::from_fn(|i| self.q[i] + qd[i] * dt)),
                    None => Err(kinematics::KinematicsError::NoSolution {
                        residual: f64::INFINITY,
                    }),
                };
                (q, finished)
            }
        };
        let (q, finished) = next;
        match q
            .map_err(|e| e.to_string())
            .and_then(|q| self.check_step(&q, dt).map(|()| q))
        {
            Ok(q) => {
                self.qd = core::array::from_fn(|i| (q[i] - self.q[i]) / dt);
                self.q = q;
                if finished {
                    self.motion = Motion::Idle;
                    self.qd = [0.0; 6];
                }
            }
            Err(why) => self.protective_stop(&why),
        }
    }

    /// Joint position and speed limits, as the safety system checks them every cycle.
    fn check_step(&self, q: &Joints, dt: f64) -> Result<(), String> {
        self.model.check_limits(q).map_err(|e| e.to_string())?;
        for (i, ((new, old), max)) in q
            .iter()
            .zip(&self.q)
            .zip(&self.model.qd_max_rad_per_s)
            .enumerate()
        {
            let speed = (new - old).abs() / dt;
            // 1 % over the limit trips it (the safety system's own tolerance is not published).
            if speed > max * 1.01 {
                return Err(format!("joint {i} speed {speed:.3} rad/s over {max:.3}"));
            }
        }
        Ok(())
    }

    /// Writes input variable `name` (from an RTDE data package).
    pub(crate) fn set_input(&mut self, name: &str, value: super::wire::Value) {
        use super::wire::Value;
        let idx = |p: &str| {
            name.strip_prefix(p)
                .and_then(|n| n.parse::<usize>().ok())
                .filter(|i| *i < 48)
        };
        match value {
            Value::Int32(v) => {
                if let Some(i) = idx("input_int_register_") {
                    self.in_int[i] = v;
                    self.in_int_written_s[i] = self.time_s;
                }
            }
            Value::Double(v) => {
                if let Some(i) = idx("input_double_register_") {
                    self.in_double[i] = v;
                } else if name == "speed_slider_fraction" {
                    self.speed_fraction = v.clamp(0.0, 1.0);
                }
            }
            _ => {}
        }
    }
}

fn pose6(v: &[f64; 6]) -> ur_bridge::Pose {
    ur_bridge::Pose {
        position_m: [v[0], v[1], v[2]],
        rotation_vec_rad: [v[3], v[4], v[5]],
    }
}

/// ur_rtde's control script: `def rtde_control():` with its header markers and `process_cmd`;
/// returns the integer register offset ur_rtde injected (`0` or `24`) right after the
/// `# int register offset` comment's newline.
fn recognise_rtde_control(text: &str) -> Option<usize> {
    const MARKER: &str = "# int register offset\n";
    let t = text.trim_start();
    if !(t.starts_with("def rtde_control():")
        && t.contains("# HEADER_BEGIN")
        && t.contains("def process_cmd(cmd):")
        && t.contains("def signal_ready():"))
    {
        return None;
    }
    let after = &t[t.find(MARKER)? + MARKER.len()..];
    let digits: String = after.chars().take_while(char::is_ascii_digit).collect();
    let off: usize = digits.parse().ok()?;
    (off == 0 || off == 24).then_some(off)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn running() -> Controller {
        let mut c = Controller::new(
            UrModel::ur3(),
            ur_bridge::kinematics::HOME_Q,
            robot_mode::RUNNING,
        );
        c.receive_script("def rtde_control():\n# HEADER_BEGIN\n    global reg_offset_float = # float register offset\n0    global reg_offset_int = # int register offset\n0    global y = 1\n    def signal_ready():\n    def process_cmd(cmd):\nend\n");
        c
    }

    #[test]
    fn script_offset_is_read_after_the_injection() {
        // The injection puts the number right after the marker's newline.
        let text = "def rtde_control():\n# HEADER_BEGIN\n    global reg_offset_int = # int register offset\n24    global x = 2\n    def signal_ready():\n    def process_cmd(cmd):\n";
        assert_eq!(recognise_rtde_control(text), Some(24));
        let missing = text.replace("offset\n24", "offset\n");
        assert_eq!(recognise_rtde_control(&missing), None);
        assert_eq!(recognise_rtde_control("def other():\nend\n"), None);
    }

    #[test]
    fn blocking_movej_signals_done_at_rest() {
        let mut c = Controller::new(UrModel::ur3(), [0.0; 6], robot_mode::RUNNING);
        c.start_script(0);
        assert_eq!(c.out_int[0], 1);
        let target = [0.1, -0.2, 0.3, -0.1, 0.2, 0.0];
        c.in_double[..6].copy_from_slice(&target);
        c.in_double[6] = 1.0;
        c.in_double[7] = 2.0;
        c.in_int[1] = 0;
        c.in_int[0] = cmd::MOVEJ;
        let mut ticks = 0;
        while c.out_int[0] != 2 {
            c.tick(0.008);
            ticks += 1;
            assert!(ticks < 1000);
        }
        assert_eq!(c.q, target);
        // 0.3 rad at 2 rad/s² never reaches 1 rad/s (0.3 < 1²/2): a triangle of 2·√(0.3/2)
        // = 0.775 s, the 97th cycle of 8 ms.
        assert_eq!(ticks, 97);
        c.in_int[0] = 0;
        c.tick(0.008);
        assert_eq!(c.out_int[0], 1);
    }

    #[test]
    fn joint_limit_trips_a_protective_stop() {
        let mut c = running();
        assert_eq!(c.runtime_state, runtime_state::PLAYING, "{:?}", c.log);
        c.model.q_max_rad[0] = 0.05;
        c.in_double[..6].copy_from_slice(&{
            let mut q = ur_bridge::kinematics::HOME_Q;
            q[0] = 0.2;
            q
        });
        c.in_double[6] = 1.0;
        c.in_double[7] = 2.0;
        c.in_int[0] = cmd::MOVEJ;
        for _ in 0..200 {
            c.tick(0.008);
        }
        assert!(c.is_protective_stopped());
        assert!(c.q[0] <= 0.05 && c.q[0] > 0.0);
        assert_eq!(c.runtime_state, runtime_state::PAUSED);
    }

    #[test]
    fn async_word_counts_operations() {
        let mut c = Controller::new(UrModel::ur3(), [0.0; 6], robot_mode::RUNNING);
        c.start_script(0);
        let mut s = c.program.take().unwrap();
        c.write_async(&mut s, 0);
        let w = c.out_int[2];
        assert_eq!((w >> 24) & 0x7f, 1, "operation id");
        assert_ne!(w & 0x8000, 0, "running");
        c.write_async(&mut s, -1);
        assert_eq!(c.out_int[2] & 0x8000, 0);
    }
}
