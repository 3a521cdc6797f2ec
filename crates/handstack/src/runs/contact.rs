//! Contact location (Kim et al. 2020, §3–4) on the user's fingertip: for each cell asked, the
//! user taps it and the fingertip's microcontroller locates the tap, Arrival-of-Time on the
//! 3 × 3 grid and the contact MLP on the 4 × 6 pad. The run takes, for each, the cell reported
//! most often while the press was held (its summed rise within 10 % of its peak: a located
//! cell can change on the way up and down), and compares it with the cell asked.
//!
//! With the user's own MLP (`[estimators.contact] mlp_weights`), the host rebuilds the board's
//! MLP inputs from its frames ([`LiveTap`]: the board's clock and pressures, every frame in
//! order) and runs that model on them; the board's own MLP is reported beside it. Collecting
//! (`handstack collect`), the same questions label each tap's pressed frames with the cell
//! asked, and every frame is recorded whole (`/hand0/tactile/mcu`) for `handstack train
//! contact-mlp`.

use super::figure::{Target, finding, measured, percent, target};
use super::{Part, RunContext};
use crate::Plot;
use crate::collect::Sessions;
use crate::error::{Ending, RunError};
use crate::record::grasp::RawTopic;
use crate::record::mcu::{McuClock, McuTopic};
use crate::record::{HAND_FRAME, Labelled, now_ns};
use crate::scene::Scene;
use crate::scene::experiment::Contact;
use aot_locate::{CELLS, COLS as PAD_COLS, Cell, DetectorConfig, ROWS};
use fingertip_link::Frame;
use hand_traits::TactileSource;
use std::time::{Duration, Instant};
use tactile_nets::contact_mlp::{ContactMlp, LiveTap, features};

/// The stack's target for Arrival-of-Time on the 3 × 3 grid, percent of taps.
pub const AOT_TARGET_PCT: f64 = 90.0;
/// The stack's target for the contact MLP on the 4 × 6 pad, percent of taps.
pub const MLP_TARGET_PCT: f64 = 95.0;
/// Why eq. 3 as the paper writes it misses its target: a microcontroller that runs it as
/// written (as the handstack fingertip firmware does) names only some areas.
pub const EQ3_AS_WRITTEN: &str = "eq. 3 as the paper writes it: its argmax is always the area \
    nearest the sensor that rises most, so of the nine areas it names only those beside the \
    three sensors";
/// The experiment's name in a collect session's labels.
pub const EXPERIMENT: &str = "contact";
/// What a contact label gives: the cell tapped, `0..24` row-major.
pub const CELL: &str = "cell";
/// How the fingertip firmware decides that a contact has arrived; the host rebuilds the
/// board's MLP inputs with the same.
pub const FIRMWARE_DETECTOR: DetectorConfig = DetectorConfig::DEFAULT;
/// How close to the tap's peak rise a frame must be to count as held (a share of the peak).
const HELD_WITHIN: f64 = 0.1;
/// How long the pad must stay lifted before a tap counts as over.
const LIFTED: Duration = Duration::from_millis(100);
/// The longest a tap may be held: a pad still pressed by then fails the run.
const HELD_MAX: Duration = Duration::from_secs(30);
/// How long the fingertip may take to tare its zero after it opens (it averages its first
/// frames at rest).
const TARE_MAX: Duration = Duration::from_secs(10);
/// Columns of the Arrival-of-Time grid.
const GRID_SIDE: u8 = 3;

/// What was located for one tap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Located {
    /// The cell asked, `(row, column)` from 1.
    asked: (u8, u8),
    /// The scene's contact MLP's cell `0..24` (row-major), the one reported most often: the
    /// user's own model's when the scene names one, else the board's.
    mlp: Option<u8>,
    /// The board's own MLP's, beside the user's (`None` without a model of the user's).
    board_mlp: Option<Option<u8>>,
    /// Arrival-of-Time's area `0..9` (row-major), the one reported most often.
    aot: Option<u8>,
}

/// The index `0..24` of the cell at `(row, column)` from 1 (the scene's check keeps the
/// cells asked on the pad).
pub fn cell_index((row, col): (u8, u8)) -> Option<u8> {
    Cell::new(row, col).and_then(|c| u8::try_from(c.index()).ok())
}

impl Located {
    /// The asked cell's index `0..24`, row-major.
    fn asked_index(&self) -> Option<u8> {
        cell_index(self.asked)
    }

    /// The 3 × 3 area holding the asked cell's centre.
    fn asked_area(&self) -> Option<u8> {
        Cell::new(self.asked.0, self.asked.1).and_then(|c| u8::try_from(c.aot_area()).ok())
    }

    fn hit(&self, cell: Option<u8>) -> bool {
        cell.is_some() && cell == self.asked_index()
    }

    fn mlp_hit(&self) -> bool {
        self.hit(self.mlp)
    }

    fn aot_hit(&self) -> bool {
        self.aot.is_some() && self.aot == self.asked_area()
    }
}

/// One frame of a press: what each locator reported, its summed rise over the frame before the
/// press (Pa) and when it was read (bag time, ns).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Pressed {
    board_mlp: Option<u8>,
    aot: Option<u8>,
    own: Option<u8>,
    rise: f64,
    t_ns: u64,
}

/// A frame's pressures as the board's contact inputs take them (exact: below f32's 2^24 Pa).
pub fn pressures(frame: &Frame) -> [f32; 3] {
    frame.pressure_pa.map(|p| p as f32)
}

/// The summed rise of `frame` over `rest` (the frame before the press), Pa.
pub fn rise_over(frame: &Frame, rest: &Frame) -> f64 {
    let sum = |f: &Frame| f.pressure_pa.iter().map(|&p| f64::from(p)).sum::<f64>();
    sum(frame) - sum(rest)
}

/// Which of a press's frames count as held: those whose summed rise (`rise` of each) is within
/// 10 % of the press's peak, as the networks' training read a press, on its plateau, not on its
/// way up or down.
pub fn held<T>(pressed: &[T], rise: impl Fn(&T) -> f64) -> impl Iterator<Item = &T> {
    let peak = pressed.iter().map(&rise).fold(f64::NEG_INFINITY, f64::max);
    pressed
        .iter()
        .filter(move |p| rise(p) >= (1.0 - HELD_WITHIN) * peak)
}

/// The cell counted most often among `cells` (each below `n`); the lower on a tie; `None` when
/// none was counted.
pub fn most_often(cells: impl IntoIterator<Item = Option<u8>>, n: usize) -> Option<u8> {
    let mut counts = vec![0u32; n];
    for c in cells.into_iter().flatten() {
        if let Some(k) = counts.get_mut(usize::from(c)) {
            *k += 1;
        }
    }
    most(&counts)
}

/// The cells of `exp` without those `sessions` recorded already: each as many times as it is
/// listed, less the times it was recorded.
pub fn to_collect(cells: &[(u8, u8)], sessions: &Sessions) -> Vec<(u8, u8)> {
    sessions.left(cells, EXPERIMENT, CELL, |c| {
        cell_index(c).map_or(f64::NAN, f64::from)
    })
}

/// The user's own contact MLP on the host: the board's inputs rebuilt from its frames.
struct OwnMlp<'m> {
    model: &'m ContactMlp,
    live: LiveTap,
    clock: McuClock,
}

impl OwnMlp<'_> {
    /// Feeds `frame`; the model's cell once a contact has arrived (`None` before, or for
    /// inputs it refuses).
    fn push(&mut self, frame: &Frame) -> Option<u8> {
        let t_us = self.clock.unwrap(frame.t_us);
        let (_, reading) = self.live.push(t_us, pressures(frame))?;
        let p = self.model.predict(&features(&reading)).ok()?;
        u8::try_from(p.region).ok()
    }
}

/// Runs `[experiment.contact]` of `scene` on its fingertip's microcontroller, or, in a
/// collect session ([`RunContext::collect`]), records the taps still to collect.
pub fn run(scene: &Scene, exp: &Contact, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let mut tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
    if tip.mcu_frame().is_none() {
        return Err(RunError::Device {
            device: "sensors.fingertip",
            reason: "contact location needs the fingertip's microcontroller (`serial_port`)".into(),
        });
    }
    let collecting = match (&cx.collect, cx.record) {
        (Some(sessions), Some(recorder)) => Some((sessions, recorder)),
        _ => None,
    };
    let own_model = collecting.is_none() && scene.mlp.is_some();
    let mut own = match (&scene.mlp, &collecting) {
        (Some(model), None) => Some(OwnMlp {
            model,
            live: LiveTap::new(FIRMWARE_DETECTOR),
            clock: McuClock::default(),
        }),
        _ => None,
    };
    let mut raw = cx.record.map(RawTopic::new);
    let mut mcu = cx.record.map(McuTopic::new);
    let mut next = |what: &str| -> Result<(Frame, u64, Option<u8>), RunError> {
        if let Some(reason) = cx.stop.reason() {
            return Err(RunError::Ended {
                ending: Ending::Stopped(reason),
                what: format!("contact: stopped by {reason} {what}"),
            });
        }
        let pressures = tip.read_frame().map_err(|e| RunError::Ended {
            ending: Ending::Fault,
            what: format!("contact: {e} {what}"),
        })?;
        let frame = tip.mcu_frame().copied().ok_or_else(|| RunError::Device {
            device: "sensors.fingertip",
            reason: "the microcontroller's frame is gone".into(),
        })?;
        let t_ns = now_ns();
        if let Some(raw) = &mut raw {
            raw.record(t_ns, &pressures.pressure_pa);
        }
        if let Some(mcu) = &mut mcu {
            mcu.record(t_ns, &frame);
        }
        let own_cell = own.as_mut().and_then(|m| m.push(&frame));
        Ok((frame, t_ns, own_cell))
    };
    cx.progress.stage("contact: tare", 0);
    let start = Instant::now();
    while !next("while the fingertip tared")?.0.tared {
        if start.elapsed() > TARE_MAX {
            return Err(RunError::Ended {
                ending: Ending::Failed,
                what: format!(
                    "contact: the fingertip did not tare its zero within {} s (is the pad \
                     pressed?)",
                    TARE_MAX.as_secs()
                ),
            });
        }
    }
    let cells = match &collecting {
        Some((sessions, _)) => to_collect(&exp.cells(), sessions),
        None => exp.cells(),
    };
    let n = cells.len();
    let wait = Duration::from_secs_f64(exp.wait_s());
    cx.progress.stage(
        if collecting.is_some() {
            "contact: collect"
        } else {
            "contact: taps"
        },
        n as u64,
    );
    let mut taps = Vec::with_capacity(n);
    for (i, &(row, col)) in cells.iter().enumerate() {
        let at = format!("at tap {} of {n}", i + 1);
        cx.progress.say(&format!(
            "Tap the fingertip at row {row}, column {col} of its pad, then lift (tap {} of {n}).",
            i + 1
        ));
        let asked_at = Instant::now();
        // Wait for the press (the last tap ended with the pad lifted).
        let (mut frame, mut t_ns, mut own_cell) = next(&at)?;
        let mut last_rest = frame;
        while !frame.in_contact {
            last_rest = frame;
            if asked_at.elapsed() > wait {
                return Err(RunError::Ended {
                    ending: Ending::Failed,
                    what: format!("contact: no tap within {} s {at}", exp.wait_s()),
                });
            }
            (frame, t_ns, own_cell) = next(&at)?;
        }
        // Each pressed frame's cells and rise over the frame before it, at rest.
        let mut pressed: Vec<Pressed> = Vec::new();
        let pressed_at = Instant::now();
        let mut lifted_at: Option<Instant> = None;
        loop {
            if frame.in_contact {
                lifted_at = None;
                pressed.push(Pressed {
                    board_mlp: frame.pad_cell,
                    aot: frame.grid_cell,
                    own: own_cell,
                    rise: rise_over(&frame, &last_rest),
                    t_ns,
                });
            } else if lifted_at.get_or_insert_with(Instant::now).elapsed() >= LIFTED {
                break;
            }
            if pressed_at.elapsed() > HELD_MAX {
                return Err(RunError::Ended {
                    ending: Ending::Failed,
                    what: format!(
                        "contact: the pad stayed pressed for {} s {at}",
                        HELD_MAX.as_secs()
                    ),
                });
            }
            (frame, t_ns, own_cell) = next(&at)?;
        }
        if let Some((_, recorder)) = &collecting {
            let span = |p: Option<&Pressed>| p.map_or(t_ns, |p| p.t_ns);
            recorder.label(
                HAND_FRAME,
                &Labelled {
                    experiment: EXPERIMENT,
                    name: CELL,
                    value: cell_index((row, col)).map_or(f64::NAN, f64::from),
                    start_ns: span(pressed.first()),
                    end_ns: span(pressed.last()),
                },
            );
            cx.progress.say(&format!(
                "  tap {} of {n}: row {row}, column {col} recorded",
                i + 1
            ));
            cx.progress.advance(1);
            continue;
        }
        let on_plateau: Vec<&Pressed> = held(&pressed, |p| p.rise).collect();
        let board_mlp = most_often(on_plateau.iter().map(|p| p.board_mlp), CELLS);
        let aot = most_often(on_plateau.iter().map(|p| p.aot), 9);
        let tap = Located {
            asked: (row, col),
            mlp: if own_model {
                most_often(on_plateau.iter().map(|p| p.own), CELLS)
            } else {
                board_mlp
            },
            board_mlp: own_model.then_some(board_mlp),
            aot,
        };
        let name = |c: Option<u8>, cols: u8| {
            c.map_or("nothing".to_owned(), |c| {
                format!("row {}, column {}", c / cols + 1, c % cols + 1)
            })
        };
        let missed = |hit: bool| if hit { "" } else { " (missed)" };
        cx.progress.say(&format!(
            "  located: MLP {}{}{}; Arrival-of-Time area {}{}",
            name(tap.mlp, PAD_COLS),
            missed(tap.mlp_hit()),
            tap.board_mlp.map_or(String::new(), |b| format!(
                " [the board's built-in MLP: {}{}]",
                name(b, PAD_COLS),
                missed(tap.hit(b))
            )),
            name(tap.aot, GRID_SIDE),
            missed(tap.aot_hit()),
        ));
        cx.progress.advance(1);
        taps.push(tap);
    }
    if let Some((_, recorder)) = &collecting {
        let mut part = Part::default();
        part.figures
            .push(measured("taps_collected", "taps collected", n as f64, ""));
        part.notes.push(format!(
            "{n} taps recorded into {}",
            recorder.dir().display()
        ));
        return Ok(part);
    }
    Ok(part(&taps))
}

/// The index counted most often; the lower on a tie; `None` when nothing was counted.
fn most(counts: &[u32]) -> Option<u8> {
    let (i, &n) = counts
        .iter()
        .enumerate()
        .max_by(|(i, a), (j, b)| a.cmp(b).then(j.cmp(i)))?;
    (n > 0).then(|| u8::try_from(i).ok()).flatten()
}

/// The taps' figures and plot.
fn part(taps: &[Located]) -> Part {
    let mut part = Part::default();
    let n = taps.len().max(1) as f64;
    let mlp_hits = taps.iter().filter(|t| t.mlp_hit()).count();
    let aot_hits = taps.iter().filter(|t| t.aot_hit()).count();
    part.figures.push(measured(
        "contact_taps",
        "taps located",
        taps.len() as f64,
        "",
    ));
    part.figures.push(target(
        measured(
            "mlp_accuracy_pct",
            &format!("contact MLP: the cell tapped, {} taps", taps.len()),
            100.0 * mlp_hits as f64 / n,
            "%",
        ),
        Target::AtLeast(MLP_TARGET_PCT),
    ));
    part.figures.push(finding(
        target(
            measured(
                "aot_accuracy_pct",
                &format!(
                    "Arrival-of-Time: the 3 × 3 area of the cell tapped, {} taps",
                    taps.len()
                ),
                100.0 * aot_hits as f64 / n,
                "%",
            ),
            Target::AtLeast(AOT_TARGET_PCT),
        ),
        EQ3_AS_WRITTEN,
    ));
    let board: Vec<Option<u8>> = taps.iter().filter_map(|t| t.board_mlp).collect();
    if !board.is_empty() {
        let hits = taps
            .iter()
            .filter(|t| t.board_mlp.is_some_and(|b| t.hit(b)))
            .count();
        part.figures.push(measured(
            "board_mlp_accuracy_pct",
            &format!(
                "the board's built-in contact MLP on the same {} taps",
                board.len()
            ),
            100.0 * hits as f64 / board.len() as f64,
            "%",
        ));
    }
    // Per cell of the pad: the share of its taps the MLP put on it.
    let mut per_cell = [(0u32, 0u32); CELLS];
    for t in taps {
        if let Some(cell) = t
            .asked_index()
            .and_then(|i| per_cell.get_mut(usize::from(i)))
        {
            cell.0 += 1;
            cell.1 += u32::from(t.mlp_hit());
        }
    }
    part.plots.push(Plot::Grid {
        title: "Contact MLP on the fingertip: taps located on the cell tapped".into(),
        rows: usize::from(ROWS),
        cols: usize::from(PAD_COLS),
        values: per_cell.iter().map(|&(n, hits)| percent(hits, n)).collect(),
        unit: "%".into(),
    });
    part
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tap_hits_when_the_board_names_the_cell_and_its_area() {
        // Row 2, column 5: cell 10, in the middle row's right area (5).
        let t = |mlp, aot| Located {
            asked: (2, 5),
            mlp,
            board_mlp: None,
            aot,
        };
        assert!(t(Some(10), Some(5)).mlp_hit() && t(Some(10), Some(5)).aot_hit());
        assert!(!t(Some(11), Some(4)).mlp_hit() && !t(Some(11), Some(4)).aot_hit());
        assert!(!t(None, None).mlp_hit() && !t(None, None).aot_hit());
    }

    #[test]
    fn the_cell_counted_most_wins_the_lower_on_a_tie() {
        assert_eq!(most(&[0, 3, 5, 5]), Some(2));
        assert_eq!(most(&[1, 0]), Some(0));
        assert_eq!(most(&[0, 0]), None);
        assert_eq!(most(&[]), None);
    }
}
