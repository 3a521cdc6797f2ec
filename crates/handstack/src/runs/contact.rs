//! Contact location (Kim et al. 2020, §3–4) on the user's fingertip: for each cell asked, the
//! user taps it and the fingertip's microcontroller locates the tap, Arrival-of-Time on the
//! 3 × 3 grid and the contact MLP on the 4 × 6 pad. The run takes, for each, the cell the
//! board reported most often while the press was held (its summed rise within 10 % of its
//! peak: a located cell can change on the way up and down), and compares it with the cell
//! asked.

use super::figure::{Target, finding, measured, percent, target};
use super::{Part, RunContext};
use crate::Plot;
use crate::error::{Ending, RunError};
use crate::record::grasp::RawTopic;
use crate::record::now_ns;
use crate::scene::Scene;
use crate::scene::experiment::Contact;
use aot_locate::{CELLS, COLS as PAD_COLS, Cell, ROWS};
use fingertip_link::Frame;
use hand_traits::TactileSource;
use std::time::{Duration, Instant};

/// The stack's target for Arrival-of-Time on the 3 × 3 grid, percent of taps.
pub const AOT_TARGET_PCT: f64 = 90.0;
/// The stack's target for the contact MLP on the 4 × 6 pad, percent of taps.
pub const MLP_TARGET_PCT: f64 = 95.0;
/// Why eq. 3 as the paper writes it misses its target: a microcontroller that runs it as
/// written (as the handstack fingertip firmware does) names only some areas.
pub const EQ3_AS_WRITTEN: &str = "eq. 3 as the paper writes it: its argmax is always the area \
    nearest the sensor that rises most, so of the nine areas it names only those beside the \
    three sensors";
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

/// What the board reported for one tap.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Located {
    /// The cell asked, `(row, column)` from 1.
    asked: (u8, u8),
    /// The contact MLP's cell `0..24` (row-major), the one reported most often.
    mlp: Option<u8>,
    /// Arrival-of-Time's area `0..9` (row-major), the one reported most often.
    aot: Option<u8>,
}

impl Located {
    /// The cell asked (the scene's check keeps it on the pad).
    fn cell(&self) -> Option<Cell> {
        Cell::new(self.asked.0, self.asked.1)
    }

    /// The asked cell's index `0..24`, row-major.
    fn asked_index(&self) -> Option<u8> {
        self.cell().and_then(|c| u8::try_from(c.index()).ok())
    }

    /// The 3 × 3 area holding the asked cell's centre.
    fn asked_area(&self) -> Option<u8> {
        self.cell().and_then(|c| u8::try_from(c.aot_area()).ok())
    }

    fn mlp_hit(&self) -> bool {
        self.mlp.is_some() && self.mlp == self.asked_index()
    }

    fn aot_hit(&self) -> bool {
        self.aot.is_some() && self.aot == self.asked_area()
    }
}

/// Runs `[experiment.contact]` of `scene` on its fingertip's microcontroller.
pub fn run(scene: &Scene, exp: &Contact, cx: &RunContext<'_>) -> Result<Part, RunError> {
    let mut tip = crate::stack::fingertip::open(scene, &*cx.platform)?;
    if tip.mcu_frame().is_none() {
        return Err(RunError::Device {
            device: "sensors.fingertip",
            reason: "contact location needs the fingertip's microcontroller (`serial_port`)".into(),
        });
    }
    let mut raw = cx.record.map(RawTopic::new);
    let mut next = |what: &str| -> Result<Frame, RunError> {
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
        if let Some(raw) = &mut raw {
            raw.record(now_ns(), &pressures.pressure_pa);
        }
        tip.mcu_frame().copied().ok_or_else(|| RunError::Device {
            device: "sensors.fingertip",
            reason: "the microcontroller's frame is gone".into(),
        })
    };
    cx.progress.stage("contact: tare", 0);
    let start = Instant::now();
    while !next("while the fingertip tared")?.tared {
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
    let cells = exp.cells();
    let n = cells.len();
    let wait = Duration::from_secs_f64(exp.wait_s());
    cx.progress.stage("contact: taps", n as u64);
    let mut taps = Vec::with_capacity(n);
    for (i, &(row, col)) in cells.iter().enumerate() {
        let at = format!("at tap {} of {n}", i + 1);
        cx.progress.say(&format!(
            "Tap the fingertip at row {row}, column {col} of its pad, then lift (tap {} of {n}).",
            i + 1
        ));
        let asked_at = Instant::now();
        // Wait for the press (the last tap ended with the pad lifted).
        let mut frame = next(&at)?;
        let mut last_rest = frame;
        while !frame.in_contact {
            last_rest = frame;
            if asked_at.elapsed() > wait {
                return Err(RunError::Ended {
                    ending: Ending::Failed,
                    what: format!("contact: no tap within {} s {at}", exp.wait_s()),
                });
            }
            frame = next(&at)?;
        }
        // Each pressed frame's cells and its summed pressure; the frame before it, at rest.
        let rest: f64 = last_rest.pressure_pa.iter().map(|&p| f64::from(p)).sum();
        let mut pressed: Vec<(Option<u8>, Option<u8>, f64)> = Vec::new();
        let pressed_at = Instant::now();
        let mut lifted_at: Option<Instant> = None;
        loop {
            if frame.in_contact {
                lifted_at = None;
                let sum = frame.pressure_pa.iter().map(|&p| f64::from(p)).sum::<f64>();
                pressed.push((frame.pad_cell, frame.grid_cell, sum - rest));
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
            frame = next(&at)?;
        }
        let (mlp, aot) = held_cells(&pressed);
        let tap = Located {
            asked: (row, col),
            mlp,
            aot,
        };
        let name = |c: Option<u8>, cols: u8| {
            c.map_or("nothing".to_owned(), |c| {
                format!("row {}, column {}", c / cols + 1, c % cols + 1)
            })
        };
        cx.progress.say(&format!(
            "  located: MLP {}{}; Arrival-of-Time area {}{}",
            name(tap.mlp, PAD_COLS),
            if tap.mlp_hit() { "" } else { " (missed)" },
            name(tap.aot, GRID_SIDE),
            if tap.aot_hit() { "" } else { " (missed)" },
        ));
        cx.progress.advance(1);
        taps.push(tap);
    }
    Ok(part(&taps))
}

/// The cells the board reported while the press was held: over the frames whose summed rise
/// is within [`HELD_WITHIN`] of the tap's peak (as the networks' training read a press, on its
/// plateau, not on its way up or down), the MLP's and Arrival-of-Time's cell reported most
/// often.
fn held_cells(pressed: &[(Option<u8>, Option<u8>, f64)]) -> (Option<u8>, Option<u8>) {
    let peak = pressed
        .iter()
        .map(|p| p.2)
        .fold(f64::NEG_INFINITY, f64::max);
    let (mut mlp, mut aot) = ([0u32; CELLS], [0u32; 9]);
    for &(pad, grid, rise) in pressed {
        if rise < (1.0 - HELD_WITHIN) * peak {
            continue;
        }
        // The frame's decoder keeps both cells in range.
        if let Some(n) = pad.and_then(|c| mlp.get_mut(usize::from(c))) {
            *n += 1;
        }
        if let Some(n) = grid.and_then(|a| aot.get_mut(usize::from(a))) {
            *n += 1;
        }
    }
    (most(&mlp), most(&aot))
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
