//! A user's own underactuated hand, through the installed `handstack` binary as the README
//! tells it: on a hand built again (hand-sim's `UnderactuatedConfig::other_hand`: its FSRs read
//! forces higher, its potentiometers sit degrees off; the simulated hand board over its pty)
//! the built-in softness net misclassifies objects; `handstack collect` records grasps of each
//! class (stopped by Ctrl-C and resumed), `handstack train softness` trains on them, and the
//! softness experiment with the new weights file classifies the objects on that hand. The
//! closes are the user's own too: 10 mm/s and a 2 s window, where the paper's are 1.5 mm/s and
//! 14 s (a user trading the paper's pace for a grasp in seconds trains a net for it).

use crate::common::{Session, collect_args, collect_in_two, figures, own_dir as dir, train_json};
use hand_sim::underactuated::Material;
use paper_scenes::devices::hand_board::{HandBoard, HandBoardConfig};
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The other hand: hand-sim's build of this seed. Builds differ: in-process (8 grasps of each
/// class at 10 mm/s, 2 s windows), the built-in net classifies 8–24 of 24 right on builds 1–24
/// (24 of 24 on 6 of them); on this one 8 — only the hard objects.
const BUILD: u64 = 17;
/// Grasps of each class collected.
const ROUNDS: usize = 4;
/// Grasps the first session records before it is stopped.
const FIRST_SESSION: usize = 5;
const CLASSES: [&str; 3] = ["soft", "moderate", "hard"];

fn material(class: &str) -> Material {
    match class {
        "soft" => Material::Sponge,
        "moderate" => Material::SiliconeRubber,
        _ => Material::Wood,
    }
}

/// A softness scene on `board` grasping `objects` in turn, with `weights` as the extra line of
/// its `[estimators.softness]`.
fn scene(dir: &Path, name: &str, board: &HandBoard, objects: &[&str], weights: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(
        &path,
        format!(
            "title = \"My hand\"\n[sensors.underactuated]\n[estimators.softness]\n{weights}\n\
             [hand]\nmodel = \"underactuated4\"\nserial_port = \"{}\"\n\
             [experiment.softness]\nobjects = {objects:?}\nclosing_speed_mm_s = 10.0\n\
             window_s = 2.0\n",
            board.path().display()
        ),
    )
    .expect("scene written");
    path
}

/// The class a `Put a C object in the hand…` question asks for.
fn asked(question: &str) -> String {
    question
        .trim_start()
        .strip_prefix("Put a ")
        .and_then(|r| r.split_whitespace().next())
        .unwrap_or_else(|| panic!("no class in {question:?}"))
        .to_owned()
}

/// Answers the next `n` questions of `session`, the object asked for put in the hand each
/// time, and waits for each grasp's line starting `done`; returns the classes asked.
fn grasp_asked(session: &mut Session, board: &HandBoard, n: usize, done: &str) -> Vec<String> {
    (0..n)
        .map(|_| {
            let class = asked(&session.wait_for("Put a "));
            board
                .hold(material(&class))
                .expect("the open hand takes it");
            session.answer("");
            session.wait_for(done);
            class
        })
        .collect()
}

/// A softness run of `objects` with `weights`: the accuracy figure.
fn classify(dir: &Path, name: &str, board: &HandBoard, objects: &[&str], weights: &str) -> f64 {
    let mut run = Session::start(&scene(dir, name, board, objects, weights));
    grasp_asked(&mut run, board, objects.len(), "object ");
    let (code, stdout, stderr) = run.finish();
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    eprintln!(
        "{name}: {}",
        stderr
            .lines()
            .filter(|l| l.trim_start().starts_with("object "))
            .collect::<Vec<_>>()
            .join("; ")
    );
    figures(&stdout)("classified_pct")["value"]
        .as_f64()
        .expect("a value")
}

#[test]
fn a_hand_built_again_classifies_softness_with_its_own_net() {
    let mut config = HandBoardConfig::new(Material::Sponge);
    config.hand = config.hand.other_hand(BUILD);
    config.hand.object.size_mm = 90.0;
    config.boot_delay = Duration::from_millis(150);
    let board = HandBoard::spawn(config).expect("the hand's board starts");
    let dir = dir("hand");
    let rounds: Vec<&str> = (0..ROUNDS).flat_map(|_| CLASSES).collect();

    // Collect in two sessions, the first stopped by Ctrl-C at a question (the hand released).
    let sessions = dir.join("sessions");
    let collect_scene = scene(&dir, "collect", &board, &rounds, "");
    let args = collect_args(&collect_scene, &sessions);
    let asked: Vec<String> = rounds.iter().map(|c| c.to_string()).collect();
    let first = collect_in_two(&args, &asked, FIRST_SESSION, "Put a ", "softness", |s| {
        grasp_asked(s, &board, 1, "grasp ").remove(0)
    });
    assert!(first.contains("hand released"), "{first}");

    // Train: held-out grasps classified with the new net and the built-in one.
    let model = dir.join("my-hand-softness.safetensors");
    let trained = train_json("softness", &sessions, &model);
    let figure = |name: &str| trained.figure(name);
    assert_eq!(figure("grasps"), rounds.len() as f64);
    assert_eq!(
        figure("heldout_grasps"),
        3.0,
        "the second grasp of each class"
    );
    let (ours, theirs) = (
        figure("heldout_accuracy_pct"),
        figure("builtin_accuracy_pct"),
    );
    eprintln!(
        "held out: own net {ours:.1} %, built-in {theirs:.1} %; {}",
        trained.outcome["notes"][1]
    );

    // The experiment on the same hand, one object of each class: the built-in net, then the
    // user's.
    let builtin = classify(&dir, "builtin", &board, &CLASSES, "");
    let weights = format!("weights = \"{}\"", model.display());
    let own = classify(&dir, "own", &board, &CLASSES, &weights);
    eprintln!("run: built-in {builtin:.1} %, own {own:.1} %");
    // Measured: held out, the built-in net 1 of 3 (soft read as moderate, moderate as hard),
    // the user's 3 of 3; in the runs the built-in 2 of 3 (soft read as moderate), the user's 3
    // of 3. A net trained on three grasps of each class got every grasp of other sessions on
    // such a hand at every training seed (the recipe's measurement).
    assert!(
        ours == 100.0 && theirs < ours,
        "held out: own {ours} %, built-in {theirs} %"
    );
    assert!(
        own == 100.0 && builtin < own,
        "run: own {own} %, built-in {builtin} %"
    );
}
