//! What goes wrong loading a scene file: every error names the file, the line and column, the
//! key and what is allowed there.

use std::fmt;
use std::path::PathBuf;

/// A position in a scene file, 1-based.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Location {
    /// Line, from 1.
    pub line: usize,
    /// Column (in characters), from 1.
    pub column: usize,
}

impl Location {
    /// The location of byte offset `offset` in `text` (clamped to its end).
    pub fn of(text: &str, offset: usize) -> Location {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let before = &text[..offset];
        let line = before.matches('\n').count() + 1;
        let column = before
            .rfind('\n')
            .map_or(before, |i| &before[i + 1..])
            .chars()
            .count()
            + 1;
        Location { line, column }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// A scene file that cannot be read, parsed or built.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// The file cannot be read.
    #[error("{}: cannot read: {source}", .path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Not TOML, or not the scene schema (unknown key or part, missing field, wrong type):
    /// the toml parser's message, which names the key and the allowed ones.
    #[error("{file}:{at}: {message}")]
    Syntax {
        /// The file (or `<text>`).
        file: String,
        /// Where.
        at: Location,
        /// The key at fault, when the message names one.
        key: Option<String>,
        /// The parser's message.
        message: String,
    },
    /// Well-formed, but impossible: a value out of range, or parts that cannot work together.
    #[error("{file}:{at}: `{key}` {problem}; allowed: {allowed}")]
    Invalid {
        /// The file (or `<text>`).
        file: String,
        /// Where the offending key is.
        at: Location,
        /// The key, dotted (`sensors.fingertip.osr`).
        key: String,
        /// What is wrong.
        problem: String,
        /// What would be accepted.
        allowed: String,
    },
}

impl SceneError {
    /// The key the error is about, if it names one.
    pub fn key(&self) -> Option<&str> {
        match self {
            SceneError::Read { .. } => None,
            SceneError::Syntax { key, .. } => key.as_deref(),
            SceneError::Invalid { key, .. } => Some(key),
        }
    }

    /// Where in the file the error is, if it is in the file.
    pub fn location(&self) -> Option<Location> {
        match self {
            SceneError::Read { .. } => None,
            SceneError::Syntax { at, .. } | SceneError::Invalid { at, .. } => Some(*at),
        }
    }

    /// A parse error of `text` (named `file`) from the toml crate.
    pub(crate) fn syntax(file: &str, text: &str, e: &toml::de::Error) -> SceneError {
        let at = Location::of(text, e.span().map_or(0, |s| s.start));
        let message = e.message().trim().to_owned();
        // toml / serde quote the key first: "unknown field `x`", "missing field `y`".
        let key = message
            .split('`')
            .nth(1)
            .filter(|k| !k.is_empty())
            .map(str::to_owned);
        SceneError::Syntax {
            file: file.to_owned(),
            at,
            key,
            message,
        }
    }
}
