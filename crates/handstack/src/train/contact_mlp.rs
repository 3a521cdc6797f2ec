//! `handstack train contact-mlp SESSIONS… --out FILE`: the contact MLP of the user's own
//! fingertip from `[experiment.contact]` collect sessions.
//!
//! The fingertip's microcontroller computes the MLP's inputs from every frame it samples
//! (Arrival-of-Time's detector on its clock, then each pressed frame's rises, shares and
//! arrivals). A collect session records every frame whole (`/hand0/tactile/mcu`), so the host
//! rebuilds those inputs exactly ([`LiveTap`] over the frames in order) and trains on them; a
//! tap whose frames were not all received (a sequence-number gap) or that the board flagged as
//! a failed cycle is skipped and counted. Each labelled tap gives its held frames (the summed
//! rise within 10 % of its peak, as the run reads a press), [`PER_TAP`] of them trained on.
//! Of each cell's taps, in the order tapped, every fourth from the second is held out and
//! never trained on; the model and the board's built-in MLP are scored on those as the run
//! scores a tap (the cell located most often over its held frames). The paper's network
//! (Kim et al. 2020, §4: 64 and 32 ReLU units, 30 % dropout, Adam with L2 0.001), with the
//! cell-set head, on our [`recipe`].

use super::{TrainError, Trained, cost_ns, held_out_by_class};
use crate::Outcome;
use crate::record::LABELS;
use crate::record::mcu::{McuClock, from_message, mcu_topic};
use crate::record::read::ReadError;
use crate::runs::contact::{
    CELL, EXPERIMENT, FIRMWARE_DETECTOR, MLP_TARGET_PCT, held, most_often, pressures, rise_over,
};
use crate::runs::figure::{Target, measured, target};
use aot_locate::CELLS;
use hand_zenoh::msg::handstack_msgs::FingertipFrame;
use std::path::PathBuf;
use tactile_nets::contact_mlp::{
    ContactExample, ContactMlp, Head, L2, LiveTap, TapReading, features,
};
use tactile_nets::pretrained::CONTACT_MLP_OSR1024;
use tactile_nets::train::TrainConfig;

/// The fewest taps of each cell tapped: one to hold out, one to train on.
pub const MIN_PER_CELL: usize = 2;
/// Held frames of each tap trained on, evenly spaced over its plateau (the frames of one
/// press differ by the sensors' noise; more of them weigh long presses over short ones).
pub const PER_TAP: usize = 8;

/// The training recipe: the paper's network, Adam at 3e-3 in minibatches of 16 (the committed
/// models' rate) for 300 passes over a session's few hundred frames.
pub fn recipe(seed: u64, progress: bool) -> TrainConfig {
    TrainConfig {
        epochs: 300,
        batch_size: 16,
        learning_rate: 3e-3,
        l2: L2,
        seed,
        progress,
        label: "contact MLP".into(),
    }
}

/// `handstack train contact-mlp`'s arguments.
#[derive(clap::Args)]
pub struct ContactMlpArgs {
    #[command(flatten)]
    common: super::SessionArgs,
}

impl ContactMlpArgs {
    /// Reads the sessions, trains, writes the weights and metrics.
    pub(super) fn run(&self) -> Result<(Outcome, bool), TrainError> {
        let c = &self.common;
        let kind = super::Kind {
            name: "contact-mlp",
            what: "Contact MLP of your fingertip",
            scene_key: "[estimators.contact] mlp_weights",
        };
        c.run(
            &kind,
            taps,
            |taps| train(taps, c.seed, !c.json),
            |m, p| m.save(p),
        )
    }
}

/// One held frame of a tap: the board's MLP inputs rebuilt from the frames, and the cell the
/// board's own MLP reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeldFrame {
    /// The inputs' reading (`None` before the detector saw the contact arrive).
    pub reading: Option<TapReading>,
    /// The board's cell for it.
    pub board: Option<u8>,
}

/// One tap of a session.
#[derive(Debug, Clone, PartialEq)]
pub struct Tap {
    /// The session's bag.
    pub bag: PathBuf,
    /// The cell asked for, `0..24` row-major.
    pub cell: u8,
    /// Its held frames.
    pub held: Vec<HeldFrame>,
}

/// The sessions' taps, and how many were skipped for frames lost or failed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Taps {
    /// The taps, in the order tapped.
    pub taps: Vec<Tap>,
    /// Taps skipped: a frame of theirs was lost on the way or flagged as a failed cycle.
    pub skipped: usize,
}

/// Every tap of `bags`. A session that recorded no label (stopped at its first question) is
/// skipped; any other bag without tap labels is an error.
///
/// Errors: a bag that cannot be read, has no labels or frames of the microcontroller, labels
/// of another experiment, or a label whose stamps match no frame — each naming the file and the
/// topic.
pub fn taps(bags: &[PathBuf]) -> Result<Taps, ReadError> {
    let read = super::labelled::<FingertipFrame>(
        bags,
        EXPERIMENT,
        "tapped",
        &mcu_topic(),
        "the fingertip microcontroller's frames",
    )?;
    let mut out = Taps::default();
    for b in &read {
        let frames: Vec<(u64, fingertip_link::Frame)> = b
            .messages
            .iter()
            .map(|(t, m)| (*t, from_message(m)))
            .collect();
        // The board's inputs, rebuilt frame by frame over the whole session.
        let (mut live, mut clock) = (LiveTap::new(FIRMWARE_DETECTOR), McuClock::default());
        let readings: Vec<Option<TapReading>> = frames
            .iter()
            .map(|(_, f)| {
                live.push(clock.unwrap(f.t_us), pressures(f))
                    .map(|(_, r)| r)
            })
            .collect();
        let content = |problem: String| ReadError::Content {
            path: b.rec.path().to_owned(),
            topic: LABELS.into(),
            problem,
        };
        for l in b.labels.iter().filter(|l| l.name == CELL) {
            let cell = u8::try_from(l.value as i64)
                .ok()
                .filter(|&c| usize::from(c) < CELLS && f64::from(c) == l.value)
                .ok_or_else(|| {
                    content(format!("`{CELL}` = {}: the pad has cells 0…23", l.value))
                })?;
            let at = |t: u64| frames.iter().position(|(s, _)| *s == t);
            let (Some(first), Some(last)) = (at(l.start.as_nanos()), at(l.end.as_nanos())) else {
                return Err(content(format!(
                    "`{CELL}` = {cell} covers no {} frame at its first or last stamp",
                    mcu_topic()
                )));
            };
            let (Some(rest), true) = (first.checked_sub(1), first <= last) else {
                return Err(content(format!(
                    "`{CELL}` = {cell} covers no press after a frame at rest"
                )));
            };
            let lost = (first..=last).any(|i| {
                let (prev, f) = (&frames[i - 1].1, &frames[i].1);
                f.fault || f.seq != prev.seq.wrapping_add(1)
            });
            if lost {
                out.skipped += 1;
                continue;
            }
            let pressed: Vec<(usize, f64)> = (first..=last)
                .filter(|&i| frames[i].1.in_contact)
                .map(|i| (i, rise_over(&frames[i].1, &frames[rest].1)))
                .collect();
            out.taps.push(Tap {
                bag: b.bag.clone(),
                cell,
                held: held(&pressed, |p| p.1)
                    .map(|&(i, _)| HeldFrame {
                        reading: readings[i],
                        board: frames[i].1.pad_cell,
                    })
                    .collect(),
            });
        }
    }
    Ok(out)
}

/// `n` of `items` evenly spaced (all of them when there are no more than `n`).
fn spaced<T>(items: &[T], n: usize) -> impl Iterator<Item = &T> {
    let step = items.len().div_ceil(n.max(1)).max(1);
    items.iter().step_by(step)
}

/// The cell `mlp` locates for each held frame of `tap`, the one located most often.
fn located(tap: &Tap, mut cell_of: impl FnMut(&TapReading) -> Option<u8>) -> Option<u8> {
    most_often(
        tap.held
            .iter()
            .map(|h| h.reading.as_ref().and_then(&mut cell_of)),
        CELLS,
    )
}

/// Trains on `taps` (of each cell every fourth tap from the second held out) with `seed`,
/// scores the held-out taps with it and with the board's built-in MLP.
///
/// Errors: a cell tapped fewer than [`MIN_PER_CELL`] times, no tap at all, or a failed fit.
pub fn train(taps: &Taps, seed: u64, progress: bool) -> Result<Trained<ContactMlp>, TrainError> {
    let all = &taps.taps;
    let mut per_cell = [0usize; CELLS];
    for t in all {
        per_cell[usize::from(t.cell)] += 1;
    }
    // The cell tapped fewest times (of those tapped); no tap at all counts as cell 0's none.
    let (cell, found) = (0..CELLS)
        .filter(|&c| per_cell[c] > 0)
        .map(|c| (c, per_cell[c]))
        .min_by_key(|&(_, n)| n)
        .unwrap_or((0, 0));
    if found < MIN_PER_CELL {
        return Err(TrainError::TooFew {
            what: format!(
                "taps of cell {cell} (row {}, column {})",
                cell / usize::from(aot_locate::COLS) + 1,
                cell % usize::from(aot_locate::COLS) + 1
            ),
            found,
            needed: MIN_PER_CELL,
            rule: "training holds a tap of each cell out to test the model on and learns \
                   every cell from the rest",
        });
    }
    let out = held_out_by_class(all, CELLS, |t| usize::from(t.cell));
    /// A tap and its place in the order tapped.
    type Numbered<'t> = Vec<(usize, &'t Tap)>;
    let (held_out, fit_on): (Numbered<'_>, Numbered<'_>) =
        all.iter().enumerate().partition(|(i, _)| out[*i]);
    let examples: Vec<ContactExample> = fit_on
        .iter()
        .flat_map(|(_, t)| {
            let readings: Vec<TapReading> = t.held.iter().filter_map(|h| h.reading).collect();
            spaced(&readings, PER_TAP)
                .map(|r| ContactExample::new(*r, 1 << t.cell))
                .collect::<Vec<_>>()
        })
        .collect();
    let (mlp, log) = ContactMlp::train(&examples, Head::CellSet, &recipe(seed, progress))?;

    let own = |r: &TapReading| {
        mlp.predict(&features(r))
            .ok()
            .and_then(|p| u8::try_from(p.region).ok())
    };
    let pct = |hits: usize, n: usize| 100.0 * hits as f64 / n.max(1) as f64;
    let n_held = held_out.len();
    let ours = held_out
        .iter()
        .filter(|(_, t)| located(t, own) == Some(t.cell))
        .count();
    let board = held_out
        .iter()
        .filter(|(_, t)| most_often(t.held.iter().map(|h| h.board), CELLS) == Some(t.cell))
        .count();
    // The host's rebuild checked against the board: the built-in model on the rebuilt inputs
    // gives the cell the board sent, frame by frame (a board running the fixed-point form may
    // differ where two cells are near equal).
    let (mut same, mut compared) = (0usize, 0usize);
    for h in all.iter().flat_map(|t| &t.held) {
        if let (Some(r), Some(b)) = (h.reading, h.board) {
            compared += 1;
            let rebuilt = CONTACT_MLP_OSR1024.predict(&features(&r)).ok();
            same += usize::from(rebuilt.is_some_and(|p| p.region == u16::from(b)));
        }
    }
    let probe = examples.first().map_or([0.0; 9], |e| features(&e.reading));
    let ns = cost_ns(|| {
        std::hint::black_box(mlp.predict(std::hint::black_box(&probe)).ok());
    });

    let figures = vec![
        measured("taps", "taps recorded", all.len() as f64, ""),
        measured(
            "taps_skipped",
            "taps skipped (a frame lost or failed)",
            taps.skipped as f64,
            "",
        ),
        measured(
            "train_samples",
            "held frames trained on",
            examples.len() as f64,
            "",
        ),
        measured("heldout_taps", "taps held out", n_held as f64, ""),
        target(
            measured(
                "heldout_accuracy_pct",
                &format!("held out: the cell tapped, {n_held} taps"),
                pct(ours, n_held),
                "%",
            ),
            Target::AtLeast(MLP_TARGET_PCT),
        ),
        measured(
            "builtin_accuracy_pct",
            "the board's built-in MLP, same taps: the cell tapped",
            pct(board, n_held),
            "%",
        ),
        measured(
            "rebuilt_agreement_pct",
            &format!("the board's inputs rebuilt on the host: its MLP's cell, {compared} frames"),
            pct(same, compared),
            "%",
        ),
        measured(
            "locate_ns",
            "cost per frame located (this machine, median)",
            ns,
            "ns",
        ),
    ];
    let plots = vec![super::loss_plot(
        "Training loss",
        "epoch",
        "cross-entropy",
        1,
        log.epoch_loss.iter().map(|l| f64::from(*l)),
    )];
    let notes = vec![format!(
        "held out (never trained on): taps {} in the order tapped",
        super::places(&held_out)
    )];
    Ok(Trained {
        model: mlp,
        figures,
        plots,
        notes,
    })
}
