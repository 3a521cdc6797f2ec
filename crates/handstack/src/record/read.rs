//! Reading a recorded bag back: the messages of one topic, decoded, with their bag times.
//! What `handstack train` and a resumed `handstack collect` read.

use hand_zenoh::msg::Message;
use std::path::{Path, PathBuf};

/// Why a bag could not be read, or lacks what a reader needs. Each names the file (and the
/// topic, where one is at fault).
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// The directory holds no `.mcap` file.
    #[error("{}: not a recorded bag (no .mcap file in it)", dir.display())]
    NotABag {
        /// The directory.
        dir: PathBuf,
    },
    /// The file could not be read.
    #[error("cannot read {}: {reason}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The system's answer.
        reason: String,
    },
    /// The file ends inside a record. A recorder ends every flush with a footer, so even a
    /// killed run's bag reads to its last flush: this is a copy cut short, or a disk that
    /// filled.
    #[error(
        "{} is truncated after {messages} messages (a copy cut short, or a disk that filled): \
         copy it again, or record it again",
        path.display()
    )]
    Truncated {
        /// The file.
        path: PathBuf,
        /// The messages read before the end.
        messages: usize,
    },
    /// The file is not MCAP, or is damaged.
    #[error("{} is not a readable MCAP file: {reason}", path.display())]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// What the reader found.
        reason: String,
    },
    /// The bag has no message on a topic a reader needs.
    #[error("{}: no {topic} messages{why}", path.display())]
    MissingTopic {
        /// The file.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// Why it is needed, or what the bag is instead (`, so it was not recorded by
        /// `handstack collect`` …), empty for nothing more.
        why: String,
    },
    /// A message on a topic is not of the type a reader needs.
    #[error("{}: {topic} carries {found}, not {expected}", path.display())]
    WrongType {
        /// The file.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// The type the bag declares.
        found: String,
        /// The type needed.
        expected: &'static str,
    },
    /// A message does not decode as its type.
    #[error("{}: a {topic} message does not decode: {reason}", path.display())]
    Decode {
        /// The file.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// The decoder's answer.
        reason: String,
    },
    /// The messages are there but do not say what a reader needs (a label without its frames,
    /// frames of another device).
    #[error("{}: {topic}: {problem}", path.display())]
    Content {
        /// The file.
        path: PathBuf,
        /// The topic.
        topic: String,
        /// What is wrong, in words.
        problem: String,
    },
}

/// One recorded message: topic, declared type, bag time and CDR payload.
struct Raw {
    topic: String,
    schema: String,
    t_ns: u64,
    data: Vec<u8>,
}

/// A bag read into memory (a collect session's bag is a few MB).
pub struct Recording {
    path: PathBuf,
    messages: Vec<Raw>,
}

impl Recording {
    /// Reads the bag in the directory `dir` (as `handstack run --record` or `handstack collect`
    /// wrote it).
    ///
    /// Errors: [`ReadError::NotABag`], [`ReadError::Io`], [`ReadError::Truncated`],
    /// [`ReadError::Corrupt`].
    pub fn open(dir: &Path) -> Result<Recording, ReadError> {
        let io = |path: &Path, e: std::io::Error| ReadError::Io {
            path: path.to_owned(),
            reason: e.to_string(),
        };
        let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
            .map_err(|e| io(dir, e))?
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.extension().is_some_and(|x| x == "mcap"))
            .collect();
        files.sort();
        let path = files.into_iter().next().ok_or_else(|| ReadError::NotABag {
            dir: dir.to_owned(),
        })?;
        let bytes = std::fs::read(&path).map_err(|e| io(&path, e))?;
        let corrupt = |reason: String| ReadError::Corrupt {
            path: path.clone(),
            reason,
        };
        let stream = mcap::MessageStream::new(&bytes).map_err(|e| corrupt(e.to_string()))?;
        let mut messages = Vec::new();
        for m in stream {
            match m {
                Ok(m) => messages.push(Raw {
                    topic: m.channel.topic.clone(),
                    schema: m
                        .channel
                        .schema
                        .as_ref()
                        .map(|s| s.name.clone())
                        .unwrap_or_default(),
                    t_ns: m.log_time,
                    data: m.data.into_owned(),
                }),
                Err(mcap::McapError::UnexpectedEof) => {
                    return Err(ReadError::Truncated {
                        path,
                        messages: messages.len(),
                    });
                }
                Err(e) => return Err(corrupt(e.to_string())),
            }
        }
        Ok(Recording { path, messages })
    }

    /// The bag's `.mcap` file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Every message on `topic` with its bag time (ns since the Unix epoch), in bag order;
    /// empty when the bag has none.
    ///
    /// Errors: [`ReadError::WrongType`] when the topic carries another type,
    /// [`ReadError::Decode`] for a message that does not decode.
    pub fn messages<M: Message>(&self, topic: &str) -> Result<Vec<(u64, M)>, ReadError> {
        self.messages
            .iter()
            .filter(|m| m.topic == topic)
            .map(|m| {
                if m.schema != M::NAME {
                    return Err(ReadError::WrongType {
                        path: self.path.clone(),
                        topic: topic.to_owned(),
                        found: m.schema.clone(),
                        expected: M::NAME,
                    });
                }
                M::from_cdr(&m.data)
                    .map(|msg| (m.t_ns, msg))
                    .map_err(|e| ReadError::Decode {
                        path: self.path.clone(),
                        topic: topic.to_owned(),
                        reason: e.to_string(),
                    })
            })
            .collect()
    }

    /// The topics the bag has messages on, sorted.
    pub fn topics(&self) -> Vec<&str> {
        let mut t: Vec<&str> = self.messages.iter().map(|m| m.topic.as_str()).collect();
        t.sort_unstable();
        t.dedup();
        t
    }
}
