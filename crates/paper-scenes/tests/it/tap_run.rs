//! Seed 002's tap-to-move through the installed `handstack` binary, on the simulated pad board
//! (`devices::pad_board`: the ICM-20789 on a Firmata board over its pty) and ur-sim's UR3
//! controller on loopback, which the real ur_rtde client in `handstack` drives: the run asks for
//! a tap on each region; the test, as the user, taps it on the board; the regions the CNN named,
//! the arm's moves and where the arm was left are read back.

use crate::common::{self, Session, figures, signal};
use handstack::tap_to_move::RegionToGrid;
use paper_scenes::devices::pad_board::{PadBoard, PadBoardConfig};
use std::net::Ipv4Addr;
use std::path::PathBuf;
use std::time::{Duration, Instant};
use ur_sim::{SimConfig, TimeScale, UrSim};

fn pad() -> PadBoard {
    PadBoard::spawn(&PadBoardConfig {
        boot_delay: Duration::from_millis(150),
        ..PadBoardConfig::default()
    })
    .expect("the pad board starts")
}

/// ur-sim's UR3 at `address`, ten times real time (the tap scene's).
fn arm(address: Ipv4Addr) -> UrSim {
    UrSim::start(SimConfig {
        address,
        time_scale: TimeScale::new(10.0).expect("a scale"),
        ..SimConfig::default()
    })
    .expect("the UR controller simulator starts")
}

/// A tap-to-move scene on `pad` and the arm at `address`, for `regions`.
fn scene(name: &str, pad: &PadBoard, address: Ipv4Addr, regions: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("handstack-tap-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scene dir");
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "title = \"Taps that move my arm\"\n\
             [sensors.imu_pad]\npressure_mode = \"LowNoise\"\nfirmata_port = \"{}\"\n\
             firmata_baud = 115200\n\
             [estimators.contact]\nlocators = [\"cnn\"]\n\
             [arm]\nmodel = \"ur3\"\nhost = \"{address}\"\n\
             [experiment.tap_to_move]\nregions = {regions:?}\n",
            pad.path().display()
        ),
    )
    .expect("scene written");
    path
}

/// The largest joint difference, rad.
fn joint_distance(a: &[f64; 6], b: &[f64; 6]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

#[test]
fn each_region_tapped_moves_the_arm_to_the_located_grid_pose_then_home() {
    let pad = pad();
    let address = Ipv4Addr::new(127, 0, 0, 93);
    let ur = arm(address);
    let grid = RegionToGrid::ur3_default().expect("the grid");
    let regions: Vec<u8> = (0..9).collect();
    let mut run = Session::start(&scene("all", &pad, address, &regions));
    let mut located = Vec::new();
    for &r in &regions {
        run.wait_for(&format!("Tap region {r} of the pad"));
        pad.tap(r).expect("tapped");
        let line = run.wait_for("located region");
        let region: u16 = line
            .trim_start()
            .strip_prefix("located region ")
            .and_then(|l| l.split_whitespace().next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{line}"));
        // The arm stands at the located region's grid pose (the move returned).
        let at = ur.joints();
        let want = grid.joints(region).expect("a grid pose");
        assert!(
            joint_distance(&at, want) < 1e-3,
            "after tap {r}: {at:?} vs {want:?}"
        );
        located.push(region);
    }
    let (code, stdout, stderr) = run.finish();
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let figure = figures(&stdout);
    assert_eq!(figure("taps")["value"], 9.0);
    let hits = regions
        .iter()
        .zip(&located)
        .filter(|(a, l)| u16::from(**a) == **l)
        .count();
    let acc = figure("tap_accuracy_pct");
    assert_eq!(acc["value"], 100.0 * hits as f64 / 9.0, "{acc}");
    assert_eq!(acc["paper"], 93.0);
    eprintln!("located {located:?}: {hits} of 9; {acc}");
    // Home again at the end.
    assert!(
        joint_distance(&ur.joints(), grid.home_joints()) < 1e-3,
        "{:?}",
        ur.joints()
    );
    assert!(stdout.contains("home after 9 taps"), "{stdout}");
    common::script_uploaded_once(&ur);
}

#[test]
fn ctrl_c_while_waiting_for_a_tap_stops_the_arm_and_ends_the_run() {
    let pad = pad();
    let address = Ipv4Addr::new(127, 0, 0, 94);
    let _ur = arm(address);
    let mut run = Session::start(&scene("ctrl-c", &pad, address, &[4, 4]));
    run.wait_for("Tap region 4 of the pad");
    let at = Instant::now();
    signal(run.child.id(), "INT");
    let (code, stdout, stderr) = run.finish();
    assert_eq!(code, Some(130), "{stdout}\n{stderr}");
    assert!(
        stderr.contains(
            "tap-to-move: stopped by SIGINT (Ctrl-C) at tap 1 of 2; arm at 127.0.0.94 told to stop"
        ),
        "{stderr}"
    );
    // The wait reads a frame every 33 ms and looks at the stop before each.
    assert!(at.elapsed() < Duration::from_secs(5), "{:?}", at.elapsed());
}

/// `paper-scenes pad-board` as a user without a pad runs it: the port first, then `tap R` on
/// stdin, each answered; a region the pad does not have is refused in words.
#[test]
fn the_pad_board_process_taps_on_stdin() {
    let run =
        crate::common::device_process(&["pad-board", "--boot-ms", "100"], "tap 4\ntap 12\ntap\n");
    let (rest, stderr) = (&run.rest, &run.stderr);
    assert!(
        run.port_line.starts_with("firmata_port = \"/dev/pts/"),
        "{}",
        run.port_line
    );
    assert_eq!(run.code, Some(0), "{rest}\n{stderr}");
    let lines: Vec<&str> = rest.lines().collect();
    assert_eq!(lines.len(), 2, "{rest}");
    assert!(
        lines[0].starts_with("tapping region 4 (column 2, row "),
        "{rest}"
    );
    assert_eq!(lines[1], "left: 1 taps made");
    assert!(
        stderr.contains("error: pad board: region 12: the pad has regions 0…8"),
        "{stderr}"
    );
    assert!(
        stderr.contains("error: \"tap\": `tap R` (a region, 0…8)"),
        "{stderr}"
    );
}
