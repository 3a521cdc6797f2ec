//! `handstack calibrate` on the simulated hand board, as a user runs it on a hand whose
//! potentiometers were mounted a few degrees off (hand-sim's `other_hand`): the `zero_deg` it
//! gives reads each open joint as 0°, the stepper is not moved and its outputs are left off;
//! Ctrl-C at its question changes nothing.

use crate::common::{Session, figures, own_dir as dir, signal};
use hand_sim::underactuated::Material;
use paper_scenes::devices::hand_board::{HandBoard, HandBoardConfig, STEPPER_DEVICE};
use std::time::{Duration, Instant};

/// Two steps of the 10-bit ADC over the potentiometer's 270°: 0.53°. The average of 50
/// readings with half a step of noise lands within it.
const TOLERANCE_DEG: f64 = 0.53;

#[test]
fn calibrate_zeroes_a_hand_whose_potentiometers_sit_off() {
    let mut config = HandBoardConfig::new(Material::Sponge);
    config.hand = config.hand.other_hand(17);
    config.boot_delay = Duration::from_millis(150);
    let offsets = config.hand.sensors.pot_offset_deg;
    let board = HandBoard::spawn(config).expect("the hand's board starts");
    let dir = dir("calibrate");
    let scene = dir.join("my-hand.toml");
    std::fs::write(
        &scene,
        format!(
            "title = \"My hand\"\n[sensors.underactuated]\n[estimators.softness]\n\
             [hand]\nmodel = \"underactuated4\"\nserial_port = \"{}\"\n\
             [experiment.softness]\n",
            board.path().display()
        ),
    )
    .expect("scene written");
    let args = ["calibrate".as_ref(), scene.as_os_str(), "--json".as_ref()];

    // Stopped at its question: nothing read, nothing moved.
    let mut stopped = Session::command(&args);
    stopped.wait_for("Open the hand fully");
    signal(stopped.child.id(), "INT");
    let (code, _, stderr) = stopped.finish();
    assert_eq!(code, Some(130), "{stderr}");
    assert!(stderr.contains("nothing changed"), "{stderr}");

    let mut run = Session::command(&args);
    run.wait_for("Open the hand fully");
    run.answer("");
    let (code, stdout, stderr) = run.finish();
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let outcomes = format!("[{stdout}]");
    let figure = figures(&outcomes);
    let value = |name: &str| figure(name)["value"].as_f64().expect("a value");
    for (k, offset) in offsets.iter().enumerate() {
        let open = value(&format!("open_angle_deg_{}", k + 1));
        let zero = value(&format!("zero_deg_{}", k + 1));
        assert!(
            (open - offset).abs() < TOLERANCE_DEG,
            "finger {k}: {open} vs {offset}"
        );
        // The default mounting's open joint sits at 45° of the travel.
        assert!(
            (zero - (45.0 + offset)).abs() < TOLERANCE_DEG,
            "finger {k}: {zero}"
        );
    }
    assert!(value("rest_force_n") < 0.05, "{stdout}");
    assert!(
        stdout.contains("pot = [{ travel_deg = 270, zero_deg = "),
        "{stdout}"
    );
    // The stepper was not moved; its outputs are off (the last bytes the run wrote may reach
    // the board just after it exits).
    assert_eq!(board.truth().shaft_steps, 0);
    let deadline = Instant::now() + Duration::from_secs(5);
    let off = loop {
        let s = board.board().stepper(STEPPER_DEVICE).expect("configured");
        if !s.enabled || Instant::now() > deadline {
            break s;
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    assert!(!off.enabled && !off.running, "{off:?}");
}
