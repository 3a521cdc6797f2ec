//! The real ur_rtde (from the venv) through the bridge against the simulated controller.
//!
//! ur_rtde's control interface uses the fixed ports 29999 / 30003 / 30004, so every test binds
//! its own loopback address (127.0.0.x) and the tests run in parallel. Each test is bounded by
//! `move_timeout` on every wait.

use std::net::Ipv4Addr;
use std::time::{Duration, Instant};

use ur_bridge::kinematics::{self, HOME_Q, UrModel};
use ur_bridge::status::robot_mode;
use ur_bridge::{JointMotion, LinearMotion, Pose, UrArm, UrConfig, UrError};
use ur_sim::{SimConfig, TimeScale, UrSim};

use crate::grid::Grid;

/// 0.1 mm: the bound on the final TCP position.
const TCP_TOLERANCE_M: f64 = 1e-4;

fn start(
    octet: u8,
    tweak: impl FnOnce(&mut SimConfig),
    arm_tweak: impl FnOnce(&mut UrConfig),
) -> (UrSim, UrArm) {
    let mut sim_config = SimConfig {
        address: Ipv4Addr::new(127, 0, 0, octet),
        ..SimConfig::default()
    };
    tweak(&mut sim_config);
    let sim = UrSim::start(sim_config).expect("bind the simulator");
    let mut config = UrConfig::new(format!("127.0.0.{octet}"));
    config.move_timeout = Duration::from_secs(20);
    arm_tweak(&mut config);
    let arm =
        UrArm::connect(config).unwrap_or_else(|e| panic!("connect: {e}; sim log {:?}", sim.log()));
    (sim, arm)
}

/// Waits `dt_s` of controller time (RTDE `timestamp`), bounded.
fn wait_controller(arm: &UrArm, dt_s: f64) {
    let t0 = arm.controller_time_s().unwrap();
    let start = Instant::now();
    while arm.controller_time_s().unwrap() < t0 + dt_s {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "controller clock stalled"
        );
    }
}

/// Whether the tool stays put over 50 ms of controller time (six RTDE packages at 125 Hz),
/// read after the receive link caught up with the stop (20 ms).
fn at_rest(arm: &UrArm) -> bool {
    wait_controller(arm, 0.02);
    let p0 = arm.tool_pose().unwrap();
    wait_controller(arm, 0.05);
    arm.tool_pose().unwrap().distance_m(&p0) < 1e-12
}

fn fast_linear() -> LinearMotion {
    LinearMotion {
        speed_m_per_s: 0.5,
        accel_m_per_s2: 2.0,
    }
}

fn fast_joint() -> JointMotion {
    JointMotion {
        speed_rad_per_s: 1.5,
        accel_rad_per_s2: 4.0,
    }
}

#[test]
fn connects_and_reports_state() {
    let (sim, arm) = start(11, |_| {}, |_| {});
    let status = arm.status().unwrap();
    assert_eq!(status.robot_mode, robot_mode::RUNNING);
    assert!(status.is_program_running(), "{status:?} {:?}", sim.log());
    assert!(!status.is_protective_stopped());
    let q = arm.joint_positions().unwrap();
    assert_eq!(q, HOME_Q);
    let expected = kinematics::to_pose(&UrModel::ur3().forward(&q));
    assert!(arm.tool_pose().unwrap().distance_m(&expected) < 1e-12);
    assert!(
        arm.dashboard("polyscopeVersion")
            .unwrap()
            .starts_with("3.15.8")
    );
}

#[test]
fn move_j_and_move_l_reach_every_grid_pose() {
    let grid = Grid::ur3();
    let (sim, mut arm) = start(12, |_| {}, |_| {});
    let home = *grid.home();
    for region in 0..9u16 {
        let target = *grid.pose(region);
        arm.move_joints_to_pose(&target, &fast_joint())
            .unwrap_or_else(|e| panic!("moveJ {region}: {e} {:?}", sim.log()));
        let d = arm.tool_pose().unwrap().distance_m(&target);
        assert!(d < TCP_TOLERANCE_M, "moveJ region {region}: {d} m off");
        arm.move_joints(grid.home_joints(), &fast_joint()).unwrap();
        assert!(arm.tool_pose().unwrap().distance_m(&home) < TCP_TOLERANCE_M);
        arm.move_linear(&target, &fast_linear())
            .unwrap_or_else(|e| panic!("moveL {region}: {e} {:?}", sim.log()));
        let d = arm.tool_pose().unwrap().distance_m(&target);
        assert!(d < TCP_TOLERANCE_M, "moveL region {region}: {d} m off");
        arm.move_linear(&home, &fast_linear()).unwrap();
    }
}

#[test]
fn async_move_stops_midway() {
    let grid = Grid::ur3();
    let (_sim, mut arm) = start(13, |_| {}, |_| {});
    let target = *grid.pose(0);
    let slow = LinearMotion {
        speed_m_per_s: 0.05,
        accel_m_per_s2: 0.5,
    };
    let handle = arm.start_move_linear(&target, &slow).unwrap();
    let mut seen = Vec::new();
    // First the whole move, watching its progress, then the same move stopped at 30 %.
    arm.wait(&handle, |p| seen.push(p.fraction)).unwrap();
    assert!(
        seen.last().is_some_and(|f| *f > 1.0 - 1e-9),
        "progress ends at 100 %: {seen:?}"
    );
    assert!(
        seen.windows(2).all(|w| w[1] >= w[0] - 1e-9),
        "progress is monotonic"
    );
    arm.move_linear(grid.home(), &fast_linear()).unwrap();

    let handle = arm.start_move_linear(&target, &slow).unwrap();
    let start = Instant::now();
    let mut fraction = 0.0;
    while fraction < 0.3 {
        let p = arm.progress(&handle).unwrap();
        assert!(p.running, "stopped before 30 %: {p:?}");
        fraction = p.fraction;
        assert!(start.elapsed() < Duration::from_secs(20));
    }
    arm.stop_linear(1.0).unwrap();
    let p = arm.progress(&handle).unwrap();
    assert!(!p.running, "the move thread is over");
    assert!(
        p.fraction > 0.3 && p.fraction < 0.9,
        "stopped midway: {}",
        p.fraction
    );
    assert!(arm.tool_pose().unwrap().distance_m(&target) > 0.01);
    assert!(at_rest(&arm), "at rest after stopL");
}

#[test]
fn unreachable_pose_is_a_protective_stop() {
    let (sim, mut arm) = start(14, |_| {}, |_| {});
    let mut far = arm.tool_pose().unwrap();
    far.position_m[0] = -0.9; // a UR3 reaches 0.5 m
    match arm.move_linear(&far, &fast_linear()) {
        Err(UrError::ProtectiveStop { safety_status_bits }) => {
            assert_ne!(safety_status_bits & 0b100, 0)
        }
        other => panic!(
            "expected a protective stop, got {other:?}; log {:?}",
            sim.log()
        ),
    }
    assert!(arm.status().unwrap().is_protective_stopped());
    // A second client connecting now is told what holds the arm and how to unlock it (not
    // ur_rtde's "Failed to start control script, before timeout of 5 seconds").
    let mut config = UrConfig::new("127.0.0.14");
    config.move_timeout = Duration::from_secs(20);
    match UrArm::connect(config) {
        Err(e @ UrError::ProtectiveStop { safety_status_bits }) => {
            assert_ne!(safety_status_bits & 0b100, 0);
            let text = e.to_string();
            assert!(
                text.starts_with("the arm is in a protective stop")
                    && text.contains("`unlock protective stop` (port 29999)"),
                "{text}"
            );
        }
        Err(other) => panic!("expected a protective stop, got: {other}"),
        Ok(_) => panic!("connected to a protectively stopped arm"),
    }
    arm.recover_from_protective_stop().unwrap();
    let grid = Grid::ur3();
    arm.move_linear(grid.pose(4), &fast_linear()).unwrap();
    assert!(arm.tool_pose().unwrap().distance_m(grid.pose(4)) < TCP_TOLERANCE_M);
}

/// A moveL 5 m away. A real controller does not refuse it up front: ur_rtde's
/// control script hands the pose to URScript `movel`, and the arm follows the line until it
/// leaves the workspace, then protective-stops (Universal Robots' own client library tests it
/// so: Universal_Robots_Client_Library PR #280). What refuses it without moving is asking
/// first, `UrArm::is_reachable` (the controller's `get_inverse_kin_has_solution`).
#[test]
fn move_l_five_metres_away_is_unreachable_and_stops_the_arm_inside_its_reach() {
    let (sim, mut arm) = start(26, |_| {}, |_| {});
    let q0 = sim.joints();
    let home = arm.tool_pose().unwrap();
    let mut far = home;
    far.position_m[0] += 5.0;

    // Asked first: no solution, and the arm does not move.
    assert!(!arm.is_reachable(&far).unwrap(), "{:?}", sim.log());
    let grid = Grid::ur3();
    assert!(arm.is_reachable(grid.pose(4)).unwrap());
    let q1 = sim.joints();
    assert!(
        q0.iter().zip(&q1).all(|(a, b)| (a - b).abs() < 1e-9),
        "{q0:?} → {q1:?}"
    );
    assert!(arm.status().unwrap().is_program_running());

    // Sent anyway: the controller's answer is a protective stop, typed as such.
    match arm.move_linear(&far, &LinearMotion::default()) {
        Err(UrError::ProtectiveStop { safety_status_bits }) => {
            assert_ne!(safety_status_bits & 0b100, 0)
        }
        other => panic!(
            "expected a protective stop, got {other:?}; log {:?}",
            sim.log()
        ),
    }
    let log = sim.log();
    assert!(
        log.iter().any(|l| l.starts_with("protective stop: ")),
        "{log:?}"
    );
    // It stopped on the way, inside its joint limits and short of the 5 m, and stays there.
    let model = UrModel::ur3();
    let q = sim.joints();
    model.check_limits(&q).unwrap();
    let stopped = kinematics::to_pose(&model.forward(&q));
    assert!(
        stopped.distance_m(&far) < home.distance_m(&far),
        "moved towards it"
    );
    assert!(stopped.distance_m(&home) < 1.0, "{stopped:?}");
    assert!(at_rest(&arm));
    assert!(arm.status().unwrap().is_protective_stopped());
}

#[test]
fn watchdog_kicked_keeps_the_script_and_unkicked_stops_it() {
    let (sim, mut arm) = start(29, |_| {}, |_| {});
    arm.set_watchdog(2.0)
        .unwrap_or_else(|e| panic!("setWatchdog: {e}; log {:?}", sim.log()));
    // Kicked every 0.1 s of controller time for 1 s: twice the period, still running.
    for _ in 0..10 {
        wait_controller(&arm, 0.1);
        arm.kick_watchdog().unwrap();
    }
    assert!(
        arm.status().unwrap().is_program_running(),
        "{:?}",
        sim.log()
    );
    // Left alone: the controller stops the program within the period.
    let start = Instant::now();
    while arm.status().unwrap().is_program_running() {
        assert!(start.elapsed() < Duration::from_secs(10), "{:?}", sim.log());
    }
    assert!(
        sim.log().iter().any(|l| l.starts_with("RTDE watchdog: ")),
        "{:?}",
        sim.log()
    );
}

#[test]
fn a_host_with_nothing_listening_is_connection_refused() {
    // A loopback port that was bound and let go: nothing listens, the host refuses.
    let listener = std::net::TcpListener::bind("127.0.0.25:29999").expect("bind");
    drop(listener);
    let mut config = UrConfig::new("127.0.0.25");
    config.move_timeout = Duration::from_secs(5);
    let t0 = Instant::now();
    let err = UrArm::connect(config).unwrap_err();
    assert!(
        matches!(&err, UrError::ConnectionRefused { host, port: 29999 } if host == "127.0.0.25"),
        "{err:?}"
    );
    let text = err.to_string();
    assert!(text.contains("connection refused"), "{text}");
    assert!(!text.to_lowercase().contains("timeout"), "{text}");
    assert!(t0.elapsed() < Duration::from_secs(5), "{:?}", t0.elapsed());
}

#[test]
fn joint_limit_is_a_protective_stop() {
    let limit = HOME_Q[0] + 0.2;
    let (sim, mut arm) = start(15, |c| c.model.q_max_rad[0] = limit, |_| {});
    let mut q = HOME_Q;
    q[0] += 0.5;
    let err = arm.move_joints(&q, &fast_joint()).unwrap_err();
    assert!(matches!(err, UrError::ProtectiveStop { .. }), "{err}");
    let stopped_at = sim.joints()[0];
    assert!(
        stopped_at <= limit && stopped_at > limit - 0.05,
        "stopped at the limit: {stopped_at}"
    );
}

#[test]
fn killed_controller_is_a_typed_error_without_hang() {
    let grid = Grid::ur3();
    let (sim, mut arm) = start(16, |_| {}, |_| {});
    let slow = LinearMotion {
        speed_m_per_s: 0.05,
        accel_m_per_s2: 0.5,
    };
    let handle = arm.start_move_linear(grid.pose(8), &slow).unwrap();
    while arm.progress(&handle).unwrap().fraction < 0.1 {}
    sim.kill();
    let t0 = Instant::now();
    let err = arm.wait(&handle, |_| {}).unwrap_err();
    assert!(matches!(err, UrError::ConnectionLost), "{err}");
    assert!(
        t0.elapsed() < Duration::from_secs(5),
        "noticed in {:?}",
        t0.elapsed()
    );
    // A stop sent now says the link is gone, at once (ur_rtde itself would try to reconnect).
    let t1 = Instant::now();
    let err = arm.stop_linear(1.0).unwrap_err();
    assert!(matches!(err, UrError::ConnectionLost), "{err}");
    assert!(t1.elapsed() < Duration::from_secs(1), "{:?}", t1.elapsed());
    let t1 = Instant::now();
    drop(arm);
    assert!(
        t1.elapsed() < Duration::from_secs(5),
        "closed in {:?}",
        t1.elapsed()
    );
}

#[test]
fn speed_l_then_speed_stop() {
    let (_sim, mut arm) = start(17, |_| {}, |_| {});
    let p0 = arm.tool_pose().unwrap();
    arm.speed_linear(&[0.05, 0.0, 0.0, 0.0, 0.0, 0.0], 0.5, 0.0)
        .unwrap();
    let start = Instant::now();
    while arm.tool_pose().unwrap().position_m[0] - p0.position_m[0] < 0.01 {
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "speedL did not move the tool"
        );
    }
    arm.speed_stop(1.0).unwrap();
    let p1: Pose = arm.tool_pose().unwrap();
    assert!(at_rest(&arm), "at rest after speedStop");
    // How far depends on when this thread got the GIL back (other tests hold it while they
    // connect): only the direction and the straightness are checked.
    let dx = p1.position_m[0] - p0.position_m[0];
    assert!(dx > 0.01 && dx < 0.5, "{dx}");
    assert!((p1.position_m[1] - p0.position_m[1]).abs() < 0.01 * dx);
    assert!((p1.position_m[2] - p0.position_m[2]).abs() < 0.01 * dx);
}

#[test]
fn powers_up_over_the_dashboard() {
    let (_sim, arm) = start(
        18,
        |c| c.initial_mode = robot_mode::POWER_OFF,
        |c| c.power_up = true,
    );
    let status = arm.status().unwrap();
    assert_eq!(status.robot_mode, robot_mode::RUNNING);
    assert!(status.is_program_running());
}

/// One moveL home → region 0 at UR's default 0.25 m/s, 1.2 m/s²: (controller time, wall time).
/// The arm polls every 1 ms, so the client sees the end within a tenth of a cycle at either
/// scale (the default 8 ms poll would add up to `scale` × 8 ms of controller time).
fn timed_grid_move(octet: u8, scale: f64) -> (f64, f64) {
    let grid = Grid::ur3();
    let (sim, mut arm) = start(
        octet,
        |c| c.time_scale = TimeScale::new(scale).unwrap(),
        |c| c.poll_period = Duration::from_millis(1),
    );
    let target = *grid.pose(0);
    let t0 = arm.controller_time_s().unwrap();
    let wall = Instant::now();
    arm.move_linear(&target, &LinearMotion::default())
        .unwrap_or_else(|e| panic!("moveL at scale {scale}: {e} {:?}", sim.log()));
    let wall_s = wall.elapsed().as_secs_f64();
    let controller_s = arm.controller_time_s().unwrap() - t0;
    let d = arm.tool_pose().unwrap().distance_m(&target);
    assert!(d < TCP_TOLERANCE_M, "scale {scale}: {d} m off");
    let status = arm.status().unwrap();
    assert_eq!(status.robot_mode, robot_mode::RUNNING, "scale {scale}");
    assert!(status.is_program_running(), "scale {scale}: {status:?}");
    // No safety event, no script error: the speed checks ran in controller time.
    assert!(
        sim.log()
            .iter()
            .all(|l| !l.contains("protective stop") && !l.contains("runtime error")),
        "{:?}",
        sim.log()
    );
    (controller_s, wall_s)
}

#[test]
fn time_scale_shortens_the_wall_time_of_a_move_not_its_controller_time() {
    const SCALE: f64 = 10.0;
    let grid = Grid::ur3();
    // The trapezoid: 0.141 m at 0.25 m/s with 1.2 m/s² ramps.
    let length = grid.home().distance_m(grid.pose(0));
    let profile_s = length / 0.25 + 0.25 / 1.2;
    // Real time, then ten times faster: one after the other, so neither loads the other.
    let (real_ctrl, real_wall) = timed_grid_move(19, 1.0);
    let (fast_ctrl, fast_wall) = timed_grid_move(22, SCALE);
    let ctx = format!(
        "profile {profile_s:.3} s; real time: {real_ctrl:.3} s controller, {real_wall:.3} s wall; \
         × {SCALE}: {fast_ctrl:.3} s controller, {fast_wall:.3} s wall"
    );
    // Controller time (RTDE `timestamp`, which ur_rtde reports as the controller's clock): the
    // profile, plus at most 6 cycles (48 ms) of command handshake, the two receive packages
    // `UrArm::wait` waits for and the staleness of the first read, plus the client's own wall
    // latency in seeing the end (ur_rtde's polls, the GIL, a loaded machine: at most
    // `CLIENT_LATENCY_S` of wall time, as the wall check below allows), which at scale s is s
    // times as much controller time. Measured under a full `cargo xtask test`: 0.792 s at scale
    // 1, 0.840 s at scale 10 (6.6 ms of wall latency). A simulator whose motion did not run in
    // controller time would take 7.7 s of it at scale 10; one that skipped the profile, less
    // than the lower bound.
    const CLIENT_LATENCY_S: f64 = 0.05;
    for (ctrl, scale) in [(real_ctrl, 1.0), (fast_ctrl, SCALE)] {
        assert!(
            ctrl > profile_s - 0.008 && ctrl < profile_s + 0.048 + scale * CLIENT_LATENCY_S,
            "{ctx}"
        );
    }
    // Wall time: real time runs the profile on the wall clock; × 10 takes a tenth of it, plus
    // at most 50 ms of client-side latency (ur_rtde's handshake polls, the GIL, a loaded
    // machine), well under the real-time move.
    assert!(real_wall > profile_s - 0.008, "{ctx}");
    assert!(fast_wall < fast_ctrl / SCALE + CLIENT_LATENCY_S, "{ctx}");
    assert!(fast_wall < real_wall / 5.0, "{ctx}");
    println!("{ctx}");
}
