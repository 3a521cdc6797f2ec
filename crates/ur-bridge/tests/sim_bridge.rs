//! The real ur_rtde (from the venv) through the bridge against the simulated controller.
//!
//! ur_rtde's control interface uses the fixed ports 29999 / 30003 / 30004, so every test binds
//! its own loopback address (127.0.0.x) and the tests run in parallel. Each test is bounded by
//! `move_timeout` on every wait.

use std::net::Ipv4Addr;
use std::time::{Duration, Instant};

use hand_traits::{LinearMotion, Pose};
use ur_bridge::kinematics::{self, UrModel};
use ur_bridge::sim::{SimConfig, UrSim};
use ur_bridge::status::robot_mode;
use ur_bridge::{JointMotion, RegionToGrid, UrArm, UrConfig, UrError};

// The `ur-sim` binary and the README's CI job (in this test binary: one link, not two).
#[path = "sim_bridge/ur_sim_binary.rs"]
mod ur_sim_binary;

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
    assert_eq!(q, RegionToGrid::HOME_Q);
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
    let grid = RegionToGrid::ur3_default().unwrap();
    let (sim, mut arm) = start(12, |_| {}, |_| {});
    let home = *grid.home();
    for region in 0..9u16 {
        let target = *grid.pose(region).unwrap();
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
    let grid = RegionToGrid::ur3_default().unwrap();
    let (_sim, mut arm) = start(13, |_| {}, |_| {});
    let target = *grid.pose(0).unwrap();
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
    arm.recover_from_protective_stop().unwrap();
    let grid = RegionToGrid::ur3_default().unwrap();
    arm.move_linear(grid.pose(4).unwrap(), &fast_linear())
        .unwrap();
    assert!(arm.tool_pose().unwrap().distance_m(grid.pose(4).unwrap()) < TCP_TOLERANCE_M);
}

#[test]
fn joint_limit_is_a_protective_stop() {
    let limit = RegionToGrid::HOME_Q[0] + 0.2;
    let (sim, mut arm) = start(15, |c| c.model.q_max_rad[0] = limit, |_| {});
    let mut q = RegionToGrid::HOME_Q;
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
    let grid = RegionToGrid::ur3_default().unwrap();
    let (sim, mut arm) = start(16, |_| {}, |_| {});
    let slow = LinearMotion {
        speed_m_per_s: 0.05,
        accel_m_per_s2: 0.5,
    };
    let handle = arm.start_move_linear(grid.pose(8).unwrap(), &slow).unwrap();
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
