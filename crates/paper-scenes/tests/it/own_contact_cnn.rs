//! A user's own pad, through the installed `handstack` binary as the README tells it: the
//! built-in contact CNN misplaces taps on a pad built again (hand-sim's
//! `ImuPadConfig::other_pad`: its chip turned on a board laid out again, half a row to a row
//! off, its tilt per newton scaled; on the simulated pad board over its pty); `handstack collect` records taps of every region
//! (stopped by Ctrl-C and resumed), `handstack train contact-cnn` trains on them, and
//! tap-to-move with the new weights file locates taps on that pad, the arm (ur-sim on
//! loopback) moving where they were located.

use crate::common::{Session, collect_args, collect_in_two, figures, own_dir as dir, train_json};
use paper_scenes::devices::pad_board::{PadBoard, PadBoardConfig};
use std::net::Ipv4Addr;
use std::path::{Path, PathBuf};
use std::time::Duration;
use ur_sim::{SimConfig, TimeScale, UrSim};

/// The other pad: hand-sim's build of this seed.
const SKIN: u64 = 1;
/// Taps of each region collected.
const ROUNDS: usize = 6;
/// Taps the first session records before it is stopped.
const FIRST_SESSION: usize = 11;

/// A tap-to-move scene on `pad` and the arm at `address` for `regions`, with `cnn` as the
/// extra line of its `[estimators.contact]`.
fn scene(
    dir: &Path,
    name: &str,
    pad: &PadBoard,
    address: Ipv4Addr,
    regions: &[u8],
    cnn: &str,
) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "title = \"My pad\"\n\
             [sensors.imu_pad]\npressure_mode = \"LowNoise\"\nfirmata_port = \"{}\"\n\
             firmata_baud = 115200\n\
             [estimators.contact]\nlocators = [\"cnn\"]\n{cnn}\n\
             [arm]\nmodel = \"ur3\"\nhost = \"{address}\"\n\
             [experiment.tap_to_move]\nregions = {regions:?}\n",
            pad.path().display()
        ),
    )
    .expect("scene written");
    path
}

/// The region a `Tap region R …` question asks for.
fn asked(question: &str) -> u8 {
    question
        .trim_start()
        .strip_prefix("Tap region ")
        .and_then(|r| r.split_whitespace().next())
        .and_then(|r| r.parse().ok())
        .unwrap_or_else(|| panic!("no region in {question:?}"))
}

/// Taps the region `session` asks for next; returns it.
fn tap_asked(session: &mut Session, pad: &PadBoard) -> u8 {
    let r = asked(&session.wait_for("Tap region "));
    pad.tap(r).expect("tapped");
    session.wait_for("tap ");
    r
}

/// A tap-to-move run of `regions` with `cnn`: the regions located, and the accuracy figure.
fn locate(
    dir: &Path,
    name: &str,
    pad: &PadBoard,
    address: Ipv4Addr,
    regions: &[u8],
    cnn: &str,
) -> (Vec<u16>, f64) {
    let mut run = Session::start(&scene(dir, name, pad, address, regions, cnn));
    let mut located = Vec::new();
    for &r in regions {
        run.wait_for(&format!("Tap region {r} of the pad"));
        pad.tap(r).expect("tapped");
        let line = run.wait_for("located region");
        located.push(
            line.trim_start()
                .strip_prefix("located region ")
                .and_then(|l| l.split_whitespace().next())
                .and_then(|n| n.parse().ok())
                .unwrap_or_else(|| panic!("{line}")),
        );
    }
    let (code, stdout, stderr) = run.finish();
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let acc = figures(&stdout)("tap_accuracy_pct")["value"]
        .as_f64()
        .expect("a value");
    (located, acc)
}

#[test]
fn a_pad_built_again_locates_taps_with_its_own_contact_cnn() {
    let pad = PadBoard::spawn(&PadBoardConfig {
        boot_delay: Duration::from_millis(150),
        skin: Some(SKIN),
        ..PadBoardConfig::default()
    })
    .expect("the pad board starts");
    let address = Ipv4Addr::new(127, 0, 0, 98);
    let dir = dir("pad");
    let rounds: Vec<u8> = (0..ROUNDS).flat_map(|_| 0..9u8).collect();

    // Collect, with the arm off (a collect session leaves it alone), in two sessions, the first
    // stopped by Ctrl-C at a question.
    let sessions = dir.join("sessions");
    let collect_scene = scene(&dir, "collect", &pad, address, &rounds, "");
    let args = collect_args(&collect_scene, &sessions);
    collect_in_two(
        &args,
        &rounds,
        FIRST_SESSION,
        "Tap region ",
        "contact-cnn",
        |session| tap_asked(session, &pad),
    );

    // Train: held-out taps scored with the new model and the built-in one.
    let model = dir.join("my-pad-cnn.safetensors");
    let trained = train_json("contact-cnn", &sessions, &model);
    let figure = |name: &str| trained.figure(name);
    let (ours, theirs) = (
        figure("heldout_accuracy_pct"),
        figure("builtin_accuracy_pct"),
    );
    eprintln!(
        "held out: own CNN {ours:.1} %, built-in {theirs:.1} % ({} taps)",
        figure("heldout_taps")
    );
    assert_eq!(figure("taps"), rounds.len() as f64);

    // The arm, on for the runs.
    let _ur = UrSim::start(SimConfig {
        address,
        time_scale: TimeScale::new(10.0).expect("a scale"),
        ..SimConfig::default()
    })
    .expect("the UR controller simulator starts");
    // Tap-to-move on the same pad: the built-in CNN, one tap per region; the user's, two.
    let once: Vec<u8> = (0..9).collect();
    let (builtin, builtin_acc) = locate(&dir, "builtin", &pad, address, &once, "");
    let twice: Vec<u8> = (0..2).flat_map(|_| 0..9u8).collect();
    let weights = format!("cnn_weights = \"{}\"", model.display());
    let (own, own_acc) = locate(&dir, "own", &pad, address, &twice, &weights);
    eprintln!("run: built-in {builtin:?} {builtin_acc:.1} %, own {own:?} {own_acc:.1} %");
    // The built-in CNN reads the turned chip's axes as the paper's: measured in-process on
    // 90 taps of such pads (seeds 1–5), 1–7 % located, where 5 taps per region of the pad's
    // own reach 86–94 % (the paper's real-time test: 93 %). The bounds show that gap on 9 to 18
    // taps without being a coin toss.
    assert!(
        theirs <= 30.0 && ours >= theirs + 40.0,
        "held out: own {ours} %, built-in {theirs} %"
    );
    assert!(
        builtin_acc <= 100.0 / 3.0 && own_acc >= 50.0,
        "run: own {own_acc} %, built-in {builtin_acc} %"
    );
}
