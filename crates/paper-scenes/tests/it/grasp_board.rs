//! Seed 000's grasp rig as two real-time devices (`devices::grasp_board`), through the real
//! clients on their ptys: the Dynamixel driver closing the MX-28 on a paper cup presses the
//! fingertip, whose MS5611s the barometer driver reads through the Firmata board and its
//! TCA9548A — the coupling a whole grasp through `handstack run` relies on.

use std::time::{Duration, Instant};

use baro_drivers::{Address, Ms5611, Osr};
use firmata_host::{Board, Options, StdDelay};
use firmata_sim::{MS5611_ADDRESS, MUX_ADDRESS};
use hand_control::ServoHand;
use hand_control::control_table::MX_28;
use hand_sim::grasp::ObjectKind;
use paper_scenes::devices::grasp_board::{GraspBoard, GraspBoardConfig};

/// A conversion wait with a margin: the chip's conversion starts when the board executes the
/// command, which a loaded line (or a USB bridge) delays after the host sent it.
struct MarginDelay;

impl embedded_hal::delay::DelayNs for MarginDelay {
    fn delay_ns(&mut self, ns: u32) {
        StdDelay.delay_ns(ns);
        StdDelay.delay_ms(5);
    }
}

/// Sensor 1's pressure through the board (mux channel 0), mbar.
fn sensor1_mbar(board: &mut Board) -> f64 {
    board
        .i2c_write(MUX_ADDRESS, &[1])
        .expect("select channel 0");
    let mut delay = MarginDelay;
    let mut baro = Ms5611::new_with_i2c(&mut *board, Address::CsbLow)
        .init(&mut delay)
        .map_err(|e| e.error)
        .expect("the MS5611 on channel 0");
    f64::from(
        baro.measure(&mut delay, Osr::Osr1024)
            .expect("a reading")
            .pressure_mbar(),
    )
}

#[test]
fn closing_the_servo_on_the_object_presses_the_fingertip_the_board_reads() {
    assert_eq!(MS5611_ADDRESS, 0x77);
    let config = GraspBoardConfig {
        boot_delay: Duration::from_millis(100),
        ..GraspBoardConfig::new(ObjectKind::PaperCup)
    };
    let rig = GraspBoard::spawn(&config).expect("the rig starts");
    let mut board = Board::open(
        rig.board_path(),
        &Options {
            baud: config.baud,
            ..Options::default()
        },
    )
    .expect("the fingertip board opens");
    let rest = sensor1_mbar(&mut board);
    let port = serial2::SerialPort::open(rig.servo_path(), 1_000_000).expect("the servo bus");
    let mut hand = ServoHand::with_reply_latency(port, &[1], dxl_sim::REPLY_LATENCY)
        .expect("the MX-28 answers");
    hand.set_position_mode().expect("position mode");
    hand.set_torque(true).expect("torque on");
    // The grasp loop's closing goal (0.2 rad) under a mid-band torque limit.
    hand.write_register(1, MX_28.goal_effort.address, 300)
        .expect("Goal PWM");
    hand.write_register(1, MX_28.goal_position.address, 130)
        .expect("Goal Position");
    let deadline = Instant::now() + Duration::from_secs(15);
    let pressed = loop {
        let now = sensor1_mbar(&mut board);
        if now - rest > 1.0 {
            break now;
        }
        assert!(
            Instant::now() < deadline,
            "the fingertip never rose: rest {rest:.2} mbar, now {now:.2}, {:?}",
            rig.state()
        );
    };
    let s = rig.state().expect("the servo");
    assert!(s.grip_force_n > 0.1, "{s:?}");
    assert!(rig.error().is_none(), "{:?}", rig.error());
    eprintln!(
        "rest {rest:.2} mbar → {pressed:.2} mbar at a grip of {:.2} N",
        s.grip_force_n
    );
}

/// The README's first try, as a user runs it: the committed scene
/// (`crates/handstack/examples/try-it.toml`) with the rig's two ports, the built `handstack`
/// binary, a whole grasp: the loop settles inside the band while the fingertip reads the
/// object, and the hand is released and powered down at the end.
#[test]
fn the_try_it_scene_grasps_the_object_through_the_handstack_binary() {
    let config = GraspBoardConfig {
        boot_delay: Duration::from_millis(150),
        ..GraspBoardConfig::new(ObjectKind::Cylinder)
    };
    let mut rig = GraspBoard::spawn(&config).expect("the rig starts");
    let root = crate::common::root();
    let text = std::fs::read_to_string(root.join("crates/handstack/examples/try-it.toml"))
        .expect("the try-it scene")
        .replace("/dev/pts/1", &rig.board_path().display().to_string())
        .replace("/dev/pts/0", &rig.servo_path().display().to_string())
        .replace("hold_s = 8", "hold_s = 5");
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("try-it");
    std::fs::create_dir_all(&dir).expect("dir");
    let scene = dir.join("try-it.toml");
    std::fs::write(&scene, text).expect("scene");
    let run = std::process::Command::new(crate::common::handstack())
        .arg("run")
        .arg(&scene)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("handstack runs");
    // Mid-run: the servo squeezes the object (read from the rig's physics, which no client sees).
    let deadline = Instant::now() + Duration::from_secs(30);
    while !rig.state().is_some_and(|s| s.grip_force_n > 0.5) {
        assert!(Instant::now() < deadline, "no grip: {:?}", rig.state());
        std::thread::sleep(Duration::from_millis(10));
    }
    let out = run.wait_with_output().expect("handstack ends");
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert_eq!(out.status.code(), Some(0), "{stdout}\n{stderr}");
    let settled = stdout
        .lines()
        .find(|l| l.contains("settled torque limit"))
        .unwrap_or_else(|| panic!("{stdout}"));
    assert!(settled.trim_end().ends_with("yes"), "{settled}");
    assert!(stdout.contains("hand released"), "{stdout}");
    rig.sync().expect("the bus has read what the binary sent");
    let s = rig.state().expect("the servo");
    assert!(!s.torque_enabled && s.position_rad < 0.1, "{s:?}");
    assert!(rig.error().is_none(), "{:?}", rig.error());
}
