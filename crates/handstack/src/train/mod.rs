//! `handstack train` (feature `train`): a user's own models from their collect sessions,
//! written as weights files a scene names, with their held-out figures and cost.

pub mod contact_cnn;
pub mod contact_mlp;
pub mod force;
pub mod softness;

use crate::Outcome;
use crate::record::read::ReadError;
use hand_zenoh::msg::handstack_msgs::Label;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use tactile_nets::NetError;

/// Why a model could not be trained or written.
#[derive(Debug, thiserror::Error)]
pub enum TrainError {
    /// A session's bag cannot be read or lacks what training needs.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// Too few distinct steps to hold some out.
    #[error(
        "{found} {what} recorded: {rule}, so it needs at least {needed}; collect more \
         (`handstack collect SCENE --into DIR`)"
    )]
    TooFew {
        /// What was counted (`weights`, `taps of region 4`).
        what: String,
        /// How many the sessions have.
        found: usize,
        /// How many are needed.
        needed: usize,
        /// Why that many.
        rule: &'static str,
    },
    /// Training itself failed (a non-finite sample, a diverging fit).
    #[error("training failed: {0}")]
    Net(#[from] NetError),
    /// The output file exists already.
    #[error("{} exists: name a new file, or remove it first", path.display())]
    Exists {
        /// The file.
        path: PathBuf,
    },
    /// The weights or metrics could not be written.
    #[error("cannot write {}: {reason}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The system's answer.
        reason: String,
    },
}

/// `handstack train`'s arguments.
#[derive(clap::Args)]
pub struct TrainCommand {
    #[command(subcommand)]
    model: Model,
}

#[derive(clap::Subcommand)]
enum Model {
    /// The force / weight DNN (Kim et al. 2020, §2.2) from `[experiment.weight]` sessions.
    Force(force::ForceArgs),
    /// The contact CNN (Al & Martinez-Hernandez, §IV-A) from `[experiment.tap_to_move]`
    /// sessions.
    ContactCnn(contact_cnn::ContactCnnArgs),
    /// The contact MLP (Kim et al. 2020, §4) from `[experiment.contact]` sessions of a
    /// fingertip's microcontroller.
    ContactMlp(contact_mlp::ContactMlpArgs),
    /// The softness net (the underactuated-hand softness paper, §3.3) from
    /// `[experiment.softness]` sessions with `objects`.
    Softness(softness::SoftnessArgs),
}

impl TrainCommand {
    /// Trains, prints the figures (a table, or JSON) and writes the files.
    pub fn main(&self) -> ExitCode {
        let ran = match &self.model {
            Model::Force(args) => args.run(),
            Model::ContactCnn(args) => args.run(),
            Model::ContactMlp(args) => args.run(),
            Model::Softness(args) => args.run(),
        };
        match ran {
            Ok((outcome, json)) => {
                crate::summary::print(&outcome, json);
                ExitCode::SUCCESS
            }
            Err(e) => {
                eprintln!("error: {e}");
                ExitCode::from(crate::error::EXIT_NOT_STARTED)
            }
        }
    }
}

/// A collect session's bag, read: its labels of one experiment and the messages they cover.
pub(crate) struct LabelledBag<M> {
    /// The bag's directory.
    pub bag: PathBuf,
    /// The bag.
    pub rec: crate::record::read::Recording,
    /// Its labels of the experiment, in the order recorded.
    pub labels: Vec<Label>,
    /// Its messages on the topic the labels cover, with their bag times.
    pub messages: Vec<(u64, M)>,
}

/// Each of `bags` with its labels of `experiment` (what the user `did`: placed, tapped,
/// grasped) and the messages on `topic` (`what` they are) they cover. A collect session that
/// recorded no label (stopped at its first question) is skipped.
///
/// Errors: a bag that cannot be read, has no labels or labels only of another experiment
/// ([`crate::collect::labels_of`]), or no message on `topic` — each naming the file and the
/// topic.
pub(crate) fn labelled<M: hand_zenoh::msg::Message>(
    bags: &[PathBuf],
    experiment: &str,
    did: &str,
    topic: &str,
    what: &str,
) -> Result<Vec<LabelledBag<M>>, ReadError> {
    let mut out = Vec::new();
    for bag in bags {
        let rec = crate::record::read::Recording::open(bag)?;
        let all = rec.messages::<Label>(crate::record::LABELS)?;
        if all.is_empty() && crate::collect::is_session(bag) {
            continue;
        }
        let labels = crate::collect::labels_of(&rec, &all, experiment, did)?
            .into_iter()
            .cloned()
            .collect();
        let messages = rec.messages::<M>(topic)?;
        if messages.is_empty() {
            return Err(ReadError::MissingTopic {
                path: rec.path().to_owned(),
                topic: topic.to_owned(),
                why: format!(", {what} its labels cover (a bag of another device?)"),
            });
        }
        out.push(LabelledBag {
            bag: bag.clone(),
            rec,
            labels,
            messages,
        });
    }
    Ok(out)
}

/// The metrics file written beside weights file `weights`: `my-tip.safetensors` →
/// `my-tip.metrics.json`.
pub fn metrics_path(weights: &Path) -> PathBuf {
    weights.with_extension("metrics.json")
}

/// Every how many steps (weights, taps) one is held out.
pub const HOLD_OUT_EVERY: usize = 4;

/// Whether step `i` of `n` is held out: every [`HOLD_OUT_EVERY`]th from the third, never the
/// last.
pub fn held_out_at(i: usize, n: usize) -> bool {
    i % HOLD_OUT_EVERY == 2 && i + 1 < n
}

/// Which of `items` are held out when each has a class (`class_of`, below `classes`): of each
/// class, in order, every [`HOLD_OUT_EVERY`]th from the second (the second, the sixth, …), so
/// that every class with two or more is both tested and learnt, where steps held out in turn
/// might all be of a few classes.
pub fn held_out_by_class<T>(
    items: &[T],
    classes: usize,
    class_of: impl Fn(&T) -> usize,
) -> Vec<bool> {
    let mut seen = vec![0usize; classes];
    items
        .iter()
        .map(|t| {
            let Some(k) = seen.get_mut(class_of(t)) else {
                return false;
            };
            *k += 1;
            *k % HOLD_OUT_EVERY == 2
        })
        .collect()
}

/// Fails when `path` exists (training never overwrites a file).
fn refuse_existing(path: &Path) -> Result<(), TrainError> {
    if path.exists() {
        return Err(TrainError::Exists {
            path: path.to_owned(),
        });
    }
    Ok(())
}

/// Fails when the weights file `out` or its metrics file exists.
fn refuse_outputs(out: &Path) -> Result<(), TrainError> {
    refuse_existing(out)?;
    refuse_existing(&metrics_path(out))
}

/// The outcome's name: `out`'s file stem, or `default`.
fn stem(out: &Path, default: &str) -> String {
    out.file_stem()
        .map_or_else(|| default.into(), |s| s.to_string_lossy().into_owned())
}

/// The arguments every `handstack train` model takes.
#[derive(clap::Args)]
pub struct SessionArgs {
    /// Collect directories (every session in them) or session bags.
    #[arg(required = true)]
    sessions: Vec<PathBuf>,
    /// The weights file to write (a scene names it); the figures go beside it as FILE's stem +
    /// `.metrics.json`.
    #[arg(long, value_name = "FILE")]
    out: PathBuf,
    /// The training seed: the same sessions and seed give the same weights.
    #[arg(long, default_value_t = 8)]
    seed: u64,
    /// Print the figures as JSON on stdout (no progress, no table).
    #[arg(long)]
    json: bool,
}

impl SessionArgs {
    /// The bags to train on, once the output files are known not to exist.
    fn bags(&self) -> Result<Vec<PathBuf>, TrainError> {
        refuse_outputs(&self.out)?;
        Ok(crate::collect::bags(&self.sessions)?)
    }
}

/// A trained model and what it was scored.
pub struct Trained<M> {
    /// The model (trained without the held-out steps).
    pub model: M,
    /// Its figures.
    pub figures: Vec<crate::Figure>,
    /// The held-out estimates and the training curve.
    pub plots: Vec<crate::Plot>,
    /// What was held out, in words.
    pub notes: Vec<String>,
}

impl<M> Trained<M> {
    /// The value of the figure named `name` (`heldout_accuracy_pct`), if it has one.
    pub fn figure(&self, name: &str) -> Option<f64> {
        self.figures
            .iter()
            .find(|f| f.name == name)
            .map(|f| f.value)
    }
}

/// What a `handstack train` command makes.
struct Kind {
    /// The outcome's name when `--out` has no file stem (`force`).
    name: &'static str,
    /// What the model is, for the outcome's title (`Force DNN of your fingertip`).
    what: &'static str,
    /// How a scene names its weights file (`[estimators.force] weights`).
    scene_key: &'static str,
}

impl SessionArgs {
    /// One `handstack train` command: the sessions' bags read with `read`, a model of `kind`
    /// trained on what they hold with `train`, written with `save` to `--out`, and its
    /// outcome (with a note of how a scene names the file) to the metrics file beside it.
    /// Returns the outcome written and whether to print it as JSON.
    fn run<D, M>(
        &self,
        kind: &Kind,
        read: impl FnOnce(&[PathBuf]) -> Result<D, ReadError>,
        train: impl FnOnce(&D) -> Result<Trained<M>, TrainError>,
        save: impl FnOnce(&M, &Path) -> Result<(), tactile_nets::NetError>,
    ) -> Result<(Outcome, bool), TrainError> {
        let start = std::time::Instant::now();
        let bags = self.bags()?;
        let trained = train(&read(&bags)?)?;
        let out = &self.out;
        save(&trained.model, out).map_err(|e| TrainError::Write {
            path: out.to_owned(),
            reason: e.to_string(),
        })?;
        let mut outcome = Outcome {
            scene: stem(out, kind.name),
            title: format!("{}, from {} session(s)", kind.what, bags.len()),
            figures: trained.figures,
            plots: trained.plots,
            notes: trained.notes,
            wall_s: start.elapsed().as_secs_f64(),
        };
        let metrics = metrics_path(out);
        outcome.notes.push(format!(
            "weights written to {}, figures to {}: name it in a scene as `{} = \"{}\"`",
            out.display(),
            metrics.display(),
            kind.scene_key,
            out.display()
        ));
        write_metrics(&metrics, &outcome)?;
        Ok((outcome, self.json))
    }
}

/// Writes `outcome` as JSON to `path`.
fn write_metrics(path: &Path, outcome: &Outcome) -> Result<(), TrainError> {
    let write = |reason: String| TrainError::Write {
        path: path.to_owned(),
        reason,
    };
    let text = serde_json::to_string_pretty(outcome).map_err(|e| write(e.to_string()))?;
    std::fs::write(path, text + "\n").map_err(|e| write(e.to_string()))
}

/// The training curve as a plot: `loss` per pass (counted from `first`), in `y_label`'s words.
pub(crate) fn loss_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    first: usize,
    loss: impl IntoIterator<Item = f64>,
) -> crate::Plot {
    crate::Plot::Lines {
        title: title.into(),
        x_label: x_label.into(),
        y_label: y_label.into(),
        lines: vec![crate::Line {
            label: "training".into(),
            points: loss
                .into_iter()
                .enumerate()
                .map(|(i, l)| ((i + first) as f64, l))
                .collect(),
        }],
    }
}

/// The places (counted from 1) of the numbered steps `held`, listed.
pub(crate) fn places<T>(held: &[(usize, T)]) -> String {
    held.iter()
        .map(|(i, _)| (i + 1).to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The median time of one call of `f`, ns: 15 repeats of 1 000 calls (the trade report's cost
/// measure, on this machine).
pub fn cost_ns(mut f: impl FnMut()) -> f64 {
    let mut per_call: Vec<f64> = (0..15)
        .map(|_| {
            let t = std::time::Instant::now();
            for _ in 0..1000 {
                f();
            }
            t.elapsed().as_secs_f64() * 1e6
        })
        .collect();
    per_call.sort_by(f64::total_cmp);
    per_call[per_call.len() / 2]
}
