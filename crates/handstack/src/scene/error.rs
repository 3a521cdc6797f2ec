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

    /// A parse error of `text` (named `file`) from the toml crate. A value of the wrong type
    /// or out of its type's range is said in a scene's words, by its dotted key
    /// (`` `experiment.grasp.hold_s` is the string "5"; allowed: a number ``), not in serde's
    /// (`invalid type: string "5", expected f64`).
    pub(crate) fn syntax(file: &str, text: &str, e: &toml::de::Error) -> SceneError {
        let offset = e.span().map_or(0, |s| s.start);
        let at = Location::of(text, offset);
        let raw = e.message().trim();
        let rewritten = plain_value_error(raw).and_then(|(got, allowed)| {
            let key = key_at(text, offset)?;
            Some((format!("`{key}` is {got}; allowed: {allowed}"), key))
        });
        let (message, key) = match rewritten {
            Some((message, key)) => (message, Some(key)),
            None => {
                // toml / serde quote the key first: "unknown field `x`", "missing field `y`".
                let key = raw
                    .split('`')
                    .nth(1)
                    .filter(|k| !k.is_empty())
                    .map(str::to_owned);
                (raw.to_owned(), key)
            }
        };
        SceneError::Syntax {
            file: file.to_owned(),
            at,
            key,
            message,
        }
    }
}

/// The dotted key of the value at byte `offset` of `text` (`experiment.grasp.hold_s`,
/// `node[1].scene`), if a value is there.
fn key_at(text: &str, offset: usize) -> Option<String> {
    use toml::de::{DeTable, DeValue};
    fn value(v: &toml::Spanned<DeValue<'_>>, path: String, offset: usize) -> Option<String> {
        match v.get_ref() {
            DeValue::Table(t) => table(t, &path, offset),
            DeValue::Array(items) => items
                .iter()
                .enumerate()
                .find_map(|(i, item)| value(item, format!("{path}[{i}]"), offset))
                .or_else(|| v.span().contains(&offset).then_some(path)),
            _ => v.span().contains(&offset).then_some(path),
        }
    }
    fn table(t: &DeTable<'_>, prefix: &str, offset: usize) -> Option<String> {
        t.iter().find_map(|(k, v)| {
            let path = if prefix.is_empty() {
                k.get_ref().to_string()
            } else {
                format!("{prefix}.{}", k.get_ref())
            };
            value(v, path, offset)
        })
    }
    let doc = DeTable::parse(text).ok()?;
    table(doc.get_ref(), "", offset)
}

/// serde's "invalid type: X, expected Y" and "invalid value: X, expected Y" in a scene's words:
/// (what the value is, what is allowed).
fn plain_value_error(message: &str) -> Option<(String, String)> {
    let rest = message
        .strip_prefix("invalid type: ")
        .or_else(|| message.strip_prefix("invalid value: "))?;
    let (got, expected) = rest.split_once(", expected ")?;
    let got = match got.split_once(' ') {
        Some(("string", v)) => format!("the string {v}"),
        Some(("integer" | "floating", v)) => {
            v.trim_start_matches("point ").trim_matches('`').to_owned()
        }
        Some(("boolean", v)) => v.trim_matches('`').to_owned(),
        _ => match got {
            "sequence" => "an array".to_owned(),
            "map" => "a table".to_owned(),
            other => other.to_owned(),
        },
    };
    let allowed = match expected {
        "f32" | "f64" => "a number".to_owned(),
        "u8" => "a whole number 0…255".to_owned(),
        "u16" => "a whole number 0…65535".to_owned(),
        "u32" => "a whole number 0…4294967295".to_owned(),
        "u64" | "usize" => "a whole number, 0 or more".to_owned(),
        "i8" | "i16" | "i32" | "i64" | "isize" => "a whole number".to_owned(),
        "a boolean" => "true or false".to_owned(),
        "a string" => "a string in quotes".to_owned(),
        "a sequence" => "an array [ … ]".to_owned(),
        "a map" => "a table".to_owned(),
        other if other.starts_with("struct ") => "a table".to_owned(),
        other => other.to_owned(),
    };
    Some((got, allowed))
}

#[cfg(test)]
mod tests {
    use super::{key_at, plain_value_error};

    #[test]
    fn a_value_is_found_by_its_dotted_key() {
        let text = "title = \"t\"\n[experiment.grasp]\nhold_s = \"5\"\n[[node]]\nscene = 1\n\
                    [[node]]\nscene = 2\n";
        let at = |needle: &str| text.find(needle).unwrap();
        assert_eq!(
            key_at(text, at("\"5\"")).as_deref(),
            Some("experiment.grasp.hold_s")
        );
        assert_eq!(key_at(text, at("2")).as_deref(), Some("node[1].scene"));
        assert_eq!(key_at(text, at("title")), None);
    }

    #[test]
    fn serdes_words_become_a_scenes() {
        let said = |m: &str| plain_value_error(m).unwrap();
        assert_eq!(
            said("invalid type: string \"5\", expected f64"),
            ("the string \"5\"".into(), "a number".into())
        );
        assert_eq!(
            said("invalid value: integer `-1`, expected u16"),
            ("-1".into(), "a whole number 0…65535".into())
        );
        assert_eq!(
            said("invalid type: sequence, expected struct Readout"),
            ("an array".into(), "a table".into())
        );
        assert_eq!(plain_value_error("unknown field `x`, expected `y`"), None);
    }
}
