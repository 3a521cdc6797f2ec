//! A user's own fingertip, through the installed `handstack` binary as the README tells it: the
//! contact MLP built into the fingertip's firmware misplaces taps on a fingertip of another
//! silicone (hand-sim's `LawParams::other_skin`, on the firmware's pipeline run on the host,
//! its UART frames on a pty); `handstack collect` records taps of every cell (stopped by
//! Ctrl-C and resumed), `handstack train contact-mlp` trains on the board's inputs rebuilt from
//! the recorded frames, and a contact run with the new weights file locates taps on that
//! fingertip, the board's own MLP reported beside it.

use crate::common::{
    Mcu, Session, asked_cell as asked, collect_args, collect_in_two, figures, own_dir as dir,
    train_json,
};
use std::path::{Path, PathBuf};

/// The other fingertip: hand-sim's skin of this seed.
const SKIN: &str = "5";
/// The board's clock against the wall clock: the taps are simulated, their timing the
/// board's own, so a faster clock only shortens the test.
const SPEED: &str = "4";
/// Taps of each cell collected.
const ROUNDS: usize = 3;
/// Taps the first session records before it is stopped.
const FIRST_SESSION: usize = 30;

/// A contact scene on the fingertip `mcu` for `cells`, with the user's MLP `mlp` (none: the
/// board's built-in one).
fn scene(dir: &Path, name: &str, mcu: &Mcu, cells: &[(u8, u8)], mlp: Option<&Path>) -> PathBuf {
    let estimators = mlp.map_or(String::new(), |m| {
        format!(
            "[estimators.contact]\nlocators = [\"mlp\"]\nmlp_weights = \"{}\"\n",
            m.display()
        )
    });
    mcu.scene(&dir.join(format!("{name}.toml")), cells, &estimators)
}

/// Taps each of the next `n` cells `session` asks for, waiting for `after` each time; returns
/// the cells.
fn tap_asked(session: &mut Session, mcu: &mut Mcu, n: usize, after: &str) -> Vec<(u8, u8)> {
    (0..n)
        .map(|_| {
            let (r, c) = asked(&session.wait_for("Tap the fingertip at row"));
            mcu.say(&format!("tap {r} {c}"));
            session.wait_for(after);
            (r, c)
        })
        .collect()
}

#[test]
fn a_fingertip_of_another_silicone_locates_taps_with_its_own_contact_mlp() {
    let mut mcu = Mcu::start(&["--skin", SKIN, "--speed", SPEED]);
    let dir = dir("fingertip-mlp");
    let all: Vec<(u8, u8)> = (1..=4u8)
        .flat_map(|r| (1..=6u8).map(move |c| (r, c)))
        .collect();
    let rounds: Vec<(u8, u8)> = (0..ROUNDS).flat_map(|_| all.iter().copied()).collect();

    // Collect in two sessions, the first stopped by Ctrl-C at a question.
    let sessions = dir.join("sessions");
    let collect_scene = scene(&dir, "collect", &mcu, &rounds, None);
    let args = collect_args(&collect_scene, &sessions);
    collect_in_two(
        &args,
        &rounds,
        FIRST_SESSION,
        "Tap the fingertip at row",
        "contact-mlp",
        |session| tap_asked(session, &mut mcu, 1, "tap ")[0],
    );

    // Train: held-out taps scored with the new model and the board's built-in one.
    let model = dir.join("my-tip-mlp.safetensors");
    let trained = train_json("contact-mlp", &sessions, &model);
    let figure = |name: &str| trained.figure(name);
    let (ours, theirs) = (
        figure("heldout_accuracy_pct"),
        figure("builtin_accuracy_pct"),
    );
    eprintln!(
        "held out: own MLP {ours:.1} %, built-in {theirs:.1} % ({} taps); rebuilt {:.2} %",
        figure("heldout_taps"),
        figure("rebuilt_agreement_pct")
    );
    assert_eq!(figure("taps") + figure("taps_skipped"), rounds.len() as f64);

    // A contact run with the user's model: each cell once, the board's MLP beside it.
    let mut run = Session::start(&scene(&dir, "own", &mcu, &all, Some(&model)));
    tap_asked(&mut run, &mut mcu, all.len(), "located:");
    let (code, stdout, stderr) = run.finish();
    assert_eq!(code, Some(0), "{stdout}\n{stderr}");
    let f = figures(&stdout);
    let value = |name: &str| f(name)["value"].as_f64().expect("a value");
    let (own_run, board_run) = (value("mlp_accuracy_pct"), value("board_mlp_accuracy_pct"));
    eprintln!("run: own MLP {own_run:.1} %, the board's {board_run:.1} %");
    // The host rebuilds the board's inputs exactly: the built-in model on them gives the
    // board's cells (the host harness runs the float model, as the host does).
    assert!(
        figure("rebuilt_agreement_pct") >= 99.0,
        "{}",
        trained.outcome
    );
    // Measured (skin 5): held out own 24 / 24, the board's 16 / 24; run own 24 / 24, the
    // board's 16 / 24 (on the calibrated skin the board's MLP places 17 / 24: it does not carry
    // to another fingertip). The bounds: the stack's 95 % target for the user's model, and the
    // board's at least four taps of 24 behind it.
    let gap = 100.0 * 4.0 / 24.0;
    assert!(
        ours >= 95.0 && theirs <= ours - gap,
        "held out: own {ours} %, built-in {theirs} %"
    );
    assert!(
        own_run >= 95.0 && board_run <= own_run - gap,
        "run: own {own_run} %, the board's {board_run} %"
    );
}
