//! Guided collect sessions (`handstack collect SCENE --into DIR`): the scene's experiment asks
//! the user what to do next, as a run does, and records the frames and a label of what was done
//! (the weight placed, the region tapped) into a bag of its own, `DIR/session-NNN`. A later session in the same
//! directory asks only for what no earlier one recorded, so a session stopped half-way is
//! resumed by starting it again. `handstack train` reads the directory.

use crate::record::LABELS;
use crate::record::read::{ReadError, Recording};
use hand_zenoh::msg::handstack_msgs::Label;
use std::path::{Path, PathBuf};

/// The prefix of each session's bag directory (`session-001`).
const SESSION_PREFIX: &str = "session-";

/// A collect directory: the sessions recorded in it so far.
#[derive(Debug, Clone, Default)]
pub struct Sessions {
    dir: PathBuf,
    /// The session bags, in order.
    bags: Vec<PathBuf>,
    /// Every label the sessions recorded.
    labels: Vec<Label>,
}

impl Sessions {
    /// The sessions in `dir` (created when missing), each bag read for its labels.
    ///
    /// Errors: the directory cannot be created or listed, or a session's bag cannot be read
    /// (a truncated one names itself: remove it and collect its part again).
    pub fn open(dir: &Path) -> Result<Sessions, ReadError> {
        std::fs::create_dir_all(dir).map_err(|e| ReadError::Io {
            path: dir.to_owned(),
            reason: e.to_string(),
        })?;
        let bags = session_bags(dir)?;
        let mut labels = Vec::new();
        for bag in &bags {
            let rec = Recording::open(bag)?;
            labels.extend(rec.messages::<Label>(LABELS)?.into_iter().map(|(_, l)| l));
        }
        Ok(Sessions {
            dir: dir.to_owned(),
            bags,
            labels,
        })
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The sessions recorded so far.
    pub fn count(&self) -> usize {
        self.bags.len()
    }

    /// The directory the next session records into.
    pub fn next_session(&self) -> PathBuf {
        let n = self
            .bags
            .iter()
            .filter_map(|b| session_number(b))
            .max()
            .unwrap_or(0);
        self.dir.join(format!("{SESSION_PREFIX}{:03}", n + 1))
    }

    /// Whether a session recorded `name` = `value` (to 1e-9) for `experiment`.
    pub fn has(&self, experiment: &str, name: &str, value: f64) -> bool {
        self.recorded(experiment, name, value) > 0
    }

    /// How many times the sessions recorded `name` = `value` (to 1e-9) for `experiment`.
    pub fn recorded(&self, experiment: &str, name: &str, value: f64) -> usize {
        self.labels
            .iter()
            .filter(|l| {
                l.experiment == experiment && l.name == name && (l.value - value).abs() < 1e-9
            })
            .count()
    }

    /// What of `asked` is still to collect: each step as many times as `asked` lists it (its
    /// label `name` = `value(step)`), less the times the sessions recorded it; in `asked`'s
    /// order.
    ///
    /// ```
    /// use handstack::collect::Sessions;
    /// let none = Sessions::default();
    /// assert_eq!(none.left(&[4u8, 1, 4], "tap_to_move", "region", f64::from), [4, 1, 4]);
    /// ```
    pub fn left<T: Copy>(
        &self,
        asked: &[T],
        experiment: &str,
        name: &str,
        value: impl Fn(T) -> f64,
    ) -> Vec<T> {
        // Each value asked so far and how many times.
        let mut seen: Vec<(f64, usize)> = Vec::new();
        asked
            .iter()
            .copied()
            .filter(|&a| {
                let v = value(a);
                let k = seen
                    .iter()
                    .position(|(u, _)| (u - v).abs() < 1e-9)
                    .unwrap_or_else(|| {
                        seen.push((v, 0));
                        seen.len() - 1
                    });
                seen[k].1 += 1;
                seen[k].1 > self.recorded(experiment, name, v)
            })
            .collect()
    }
}

/// The labels of `experiment` among `labels` (the bag `rec`'s), what the user `did` (placed,
/// tapped) in the error of a bag without labels.
///
/// Errors: [`ReadError::MissingTopic`] when the bag has no labels (it was not recorded by
/// `handstack collect`), [`ReadError::Content`] when it has only another experiment's.
pub fn labels_of<'l>(
    rec: &Recording,
    labels: &'l [(u64, Label)],
    experiment: &str,
    did: &str,
) -> Result<Vec<&'l Label>, ReadError> {
    let path = rec.path().to_owned();
    if labels.is_empty() {
        return Err(ReadError::MissingTopic {
            path,
            topic: LABELS.into(),
            why: format!(
                ": it was not recorded by `handstack collect`, which labels what was {did} \
                 (`handstack collect SCENE --into DIR`)"
            ),
        });
    }
    let ours: Vec<&Label> = labels
        .iter()
        .map(|(_, l)| l)
        .filter(|l| l.experiment == experiment)
        .collect();
    if ours.is_empty() {
        let mut theirs: Vec<&str> = labels.iter().map(|(_, l)| l.experiment.as_str()).collect();
        theirs.dedup();
        return Err(ReadError::Content {
            path,
            topic: LABELS.into(),
            problem: format!(
                "labels of `{}`, none of `{experiment}`: it is the training data of another model",
                theirs.join("`, `")
            ),
        });
    }
    Ok(ours)
}

/// Whether `bag` is a collect session's bag (a directory named `session-NNN`).
pub fn is_session(bag: &Path) -> bool {
    session_number(bag).is_some()
}

/// The session number of a bag directory named `session-NNN`.
fn session_number(bag: &Path) -> Option<u32> {
    bag.file_name()?
        .to_str()?
        .strip_prefix(SESSION_PREFIX)?
        .parse()
        .ok()
}

/// The `session-NNN` directories in `dir`, in order.
fn session_bags(dir: &Path) -> Result<Vec<PathBuf>, ReadError> {
    let mut bags: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| ReadError::Io {
            path: dir.to_owned(),
            reason: e.to_string(),
        })?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir() && session_number(p).is_some())
        .collect();
    bags.sort();
    Ok(bags)
}

/// The bags `paths` name: each a bag directory, or a collect directory of session bags.
///
/// Errors: a path that is neither ([`ReadError::NotABag`]), or that cannot be listed.
pub fn bags(paths: &[PathBuf]) -> Result<Vec<PathBuf>, ReadError> {
    let mut out = Vec::new();
    for p in paths {
        let sessions = session_bags(p)?;
        if !sessions.is_empty() {
            out.extend(sessions);
            continue;
        }
        let is_bag = std::fs::read_dir(p)
            .map_err(|e| ReadError::Io {
                path: p.clone(),
                reason: e.to_string(),
            })?
            .filter_map(|e| e.ok())
            .any(|e| e.path().extension().is_some_and(|x| x == "mcap"));
        if !is_bag {
            return Err(ReadError::NotABag { dir: p.clone() });
        }
        out.push(p.clone());
    }
    Ok(out)
}
