//! The CSV dialect of the committed datasets (`fixtures/datasets/`), shared by hand-sim's
//! writers and paper-experiments' readers: `#` comment lines, one header naming the columns,
//! then one comma-separated row per record.
//!
//! Each file has one schema: a serde record type ([`Schema`]) that the writer serializes
//! ([`render`]) and the reader deserializes ([`parse`], [`read`]), so the two cannot disagree
//! on a column's name, order, type or number format. Numbers are written the way the datasets
//! have always been written (the committed bytes are checked by `cargo xtask fixtures
//! --check`): [`Fixed`] decimals, [`Exp`] notation or the [`Shortest`] form that reads back
//! exactly, never the csv crate's own float format.
//!
//! Reading checks, and names the file, the line and the column in every [`DatasetError`]:
//! the header is the schema's, column for column; every row has as many fields; every field
//! parses as its column's type; and no field is a non-finite number (`NaN`, `inf`): a
//! committed dataset never holds one.
//!
//! ```
//! use hand_sim::records::{self, Fixed, Schema};
//! use serde::{Deserialize, Serialize};
//!
//! #[derive(Debug, PartialEq, Serialize, Deserialize)]
//! struct Sample {
//!     id: u32,
//!     force_n: Fixed<f64, 2>,
//! }
//! impl Schema for Sample {}
//!
//! let text = records::render("# two samples\n", [
//!     Sample { id: 0, force_n: Fixed(1.0) },
//!     Sample { id: 1, force_n: Fixed(0.125) },
//! ]);
//! assert_eq!(text, "# two samples\nid,force_n\n0,1.00\n1,0.12\n");
//! let rows = records::parse::<Sample>("samples.csv".as_ref(), &text)?;
//! assert_eq!((rows[1].line, rows[1].record.force_n.0), (4, 0.12));
//! let err = records::parse::<Sample>("samples.csv".as_ref(), "id,force_n\n0,NaN\n").unwrap_err();
//! assert_eq!(err.to_string(), "samples.csv:2: column `force_n`: `NaN` is not a finite number");
//! # Ok::<(), records::DatasetError>(())
//! ```

use serde::de::{self, DeserializeOwned, Deserializer, Visitor};
use serde::{Deserialize, Serialize, Serializer};
use std::fmt;
use std::path::{Path, PathBuf};

/// A record type that is one row of a dataset file.
///
/// Its serde form is the row, field by field, in file order (nested sequences are spliced in:
/// a window of 152 values is 152 columns). Deserialization is by position, after the header
/// has been checked against [`Schema::columns`].
pub trait Schema: Serialize + DeserializeOwned {
    /// The header's column names, in file order. By default the struct's field names (after
    /// serde renames), which is right for every record without a nested sequence.
    fn columns() -> Vec<String> {
        struct_fields::<Self>()
            .iter()
            .map(|f| (*f).to_owned())
            .collect()
    }
}

/// A number written with exactly `D` decimals (`{:.D}`), read back as `T`.
///
/// ```
/// # use hand_sim::records::Fixed;
/// assert_eq!(Fixed::<f32, 3>(0.5).to_string(), "0.500");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default, Deserialize)]
#[serde(transparent)]
pub struct Fixed<T, const D: usize>(pub T);

impl<T: fmt::Display, const D: usize> fmt::Display for Fixed<T, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:.*}", D, self.0)
    }
}

impl<T: fmt::Display, const D: usize> Serialize for Fixed<T, D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Writes the plain number `v` as [`Fixed`] does, for a record that keeps its numbers plain:
/// `#[serde(serialize_with = "hand_sim::records::fixed::<_, 4, _>")]`.
pub fn fixed<T: fmt::Display, const D: usize, S: Serializer>(
    v: &T,
    s: S,
) -> Result<S::Ok, S::Error> {
    Fixed::<&T, D>(v).serialize(s)
}

/// A number in exponent notation with `D` decimals (`{:.De}`, e.g. `2.0743e4`), read back as
/// `T`.
///
/// ```
/// # use hand_sim::records::Exp;
/// assert_eq!(Exp::<f64, 4>(20743.0).to_string(), "2.0743e4");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default, Deserialize)]
#[serde(transparent)]
pub struct Exp<T, const D: usize>(pub T);

impl<T: fmt::LowerExp, const D: usize> fmt::Display for Exp<T, D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:.*e}", D, self.0)
    }
}

impl<T: fmt::LowerExp, const D: usize> Serialize for Exp<T, D> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// A number in Rust's `Display` form: the shortest decimal that reads back as the same `T`,
/// never in exponent notation, and without a trailing `.0` (`101094`, `10`, `0.5`).
///
/// ```
/// # use hand_sim::records::Shortest;
/// assert_eq!(Shortest(101094.0f32).to_string(), "101094");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Default, Deserialize)]
#[serde(transparent)]
pub struct Shortest<T>(pub T);

impl<T: fmt::Display> fmt::Display for Shortest<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.fmt(f)
    }
}

impl<T: fmt::Display> Serialize for Shortest<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// One record read from a file, with the 1-based line it starts on.
#[derive(Debug, Clone, PartialEq)]
pub struct Row<R> {
    /// The line of the file the row is on.
    pub line: u64,
    /// The record.
    pub record: R,
}

/// What is wrong with a dataset file.
#[derive(Debug)]
pub enum ErrorKind {
    /// The file could not be read.
    Io(std::io::Error),
    /// The header ends before this schema's column (named in [`DatasetError::column`]).
    MissingColumn,
    /// The header names another column where the schema has [`DatasetError::column`].
    WrongColumn {
        /// What the header says.
        found: String,
    },
    /// The header has a column after the schema's last.
    ExtraColumn {
        /// Its name.
        found: String,
    },
    /// A row has another number of fields than the header.
    FieldCount {
        /// Fields in the row.
        found: usize,
        /// Columns in the header.
        expected: usize,
    },
    /// A field is a number, but not a finite one.
    NotFinite {
        /// The field as written.
        value: String,
    },
    /// A field does not parse as its column's type, or is outside what its dataset allows.
    Value(String),
    /// A row or the file breaks a rule of its dataset (an unknown id, a missing series…).
    Rule(String),
}

/// A dataset file that could not be read: the file, where in it, and what is wrong.
#[derive(Debug)]
pub struct DatasetError {
    /// The file.
    pub file: PathBuf,
    /// The 1-based line, when the problem is on one.
    pub line: Option<u64>,
    /// The column, when the problem is in one.
    pub column: Option<String>,
    /// What is wrong.
    pub kind: ErrorKind,
}

impl DatasetError {
    /// An error in `file`, at `line` and `column` where given.
    pub fn new(file: &Path, line: Option<u64>, column: Option<&str>, kind: ErrorKind) -> Self {
        DatasetError {
            file: file.to_path_buf(),
            line,
            column: column.map(str::to_owned),
            kind,
        }
    }

    /// A field of `column` on `line` that its dataset does not allow ([`ErrorKind::Value`]).
    pub fn value(file: &Path, line: u64, column: &str, problem: impl Into<String>) -> Self {
        Self::new(
            file,
            Some(line),
            Some(column),
            ErrorKind::Value(problem.into()),
        )
    }

    /// A broken rule of the dataset ([`ErrorKind::Rule`]), on `line` if it is on one.
    pub fn rule(file: &Path, line: Option<u64>, problem: impl Into<String>) -> Self {
        Self::new(file, line, None, ErrorKind::Rule(problem.into()))
    }
}

impl fmt::Display for DatasetError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some(line) = self.line {
            write!(f, ":{line}")?;
        }
        f.write_str(": ")?;
        let column = self.column.as_deref().unwrap_or("?");
        match &self.kind {
            ErrorKind::Io(e) => write!(f, "cannot read: {e}"),
            ErrorKind::MissingColumn => write!(f, "missing column `{column}`"),
            ErrorKind::WrongColumn { found } => {
                write!(f, "column `{found}` where `{column}` belongs")
            }
            ErrorKind::ExtraColumn { found } => write!(f, "unexpected column `{found}`"),
            ErrorKind::FieldCount { found, expected } => {
                write!(f, "{found} fields, the header has {expected}")
            }
            ErrorKind::NotFinite { value } => {
                write!(f, "column `{column}`: `{value}` is not a finite number")
            }
            ErrorKind::Value(problem) | ErrorKind::Rule(problem) => match &self.column {
                Some(c) => write!(f, "column `{c}`: {problem}"),
                None => f.write_str(problem),
            },
        }
    }
}

impl std::error::Error for DatasetError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match &self.kind {
            ErrorKind::Io(e) => Some(e),
            _ => None,
        }
    }
}

/// The dataset file `preamble` (its `#` lines, each ending in a newline), the header of `R`
/// and one line per record of `rows`.
///
/// # Panics
///
/// Only if `R`'s serde form holds a map or an enum variant with data, which the csv format
/// cannot write and no dataset schema has (each schema's writer is tested). Writing to memory
/// cannot fail otherwise.
pub fn render<R: Schema>(preamble: &str, rows: impl IntoIterator<Item = R>) -> String {
    let write = || -> Result<String, Box<dyn std::error::Error>> {
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(preamble.as_bytes().to_vec());
        w.write_record(R::columns())?;
        for row in rows {
            w.serialize(row)?;
        }
        Ok(String::from_utf8(
            w.into_inner().map_err(|e| e.to_string())?,
        )?)
    };
    match write() {
        Ok(text) => text,
        Err(e) => panic!("a dataset schema the csv writer cannot write: {e}"),
    }
}

/// Reads the dataset file at `path` as rows of `R` (see [`parse`]); a path ending in `.gz` is
/// a [`gzip`]ped file, decompressed first.
pub fn read<R: Schema>(path: &Path) -> Result<Vec<Row<R>>, DatasetError> {
    let io = |e| DatasetError::new(path, None, None, ErrorKind::Io(e));
    let text = if path.extension().is_some_and(|x| x == "gz") {
        let bytes = std::fs::read(path).map_err(io)?;
        let mut text = String::new();
        std::io::Read::read_to_string(&mut flate2::read::GzDecoder::new(&bytes[..]), &mut text)
            .map_err(io)?;
        text
    } else {
        std::fs::read_to_string(path).map_err(io)?
    };
    parse(path, &text)
}

/// `text` gzip-compressed for a committed `.gz` dataset file: best compression, a header with
/// no name and no time, so the bytes depend on the text alone (and the pure-Rust deflate).
pub fn gzip(text: &str) -> Vec<u8> {
    use std::io::Write;
    let mut gz = flate2::GzBuilder::new().write(Vec::new(), flate2::Compression::best());
    // Writing into a Vec cannot fail.
    match gz.write_all(text.as_bytes()).and_then(|()| gz.finish()) {
        Ok(bytes) => bytes,
        Err(e) => panic!("gzip into memory failed: {e}"),
    }
}

/// Parses dataset text as rows of `R`; `file` names it in errors. `#` lines are skipped
/// wherever they are; the first other line is the header.
pub fn parse<R: Schema>(file: &Path, text: &str) -> Result<Vec<Row<R>>, DatasetError> {
    let columns = R::columns();
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .has_headers(true)
        .flexible(true)
        .from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| csv_error(file, &columns, e))?
        .clone();
    let header_line = header.position().map_or(1, |p| line_of(text, p));
    check_header(file, header_line, &columns, &header)?;
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| csv_error(file, &columns, e))?;
        let line = record.position().map_or(0, |p| line_of(text, p));
        if record.len() != columns.len() {
            return Err(DatasetError::new(
                file,
                Some(line),
                None,
                ErrorKind::FieldCount {
                    found: record.len(),
                    expected: columns.len(),
                },
            ));
        }
        if let Some((i, value)) = record
            .iter()
            .enumerate()
            .find(|(_, v)| v.parse::<f64>().is_ok_and(|x| !x.is_finite()))
        {
            return Err(DatasetError::new(
                file,
                Some(line),
                Some(&columns[i]),
                ErrorKind::NotFinite {
                    value: value.to_owned(),
                },
            ));
        }
        let parsed = record
            .deserialize::<R>(None)
            .map_err(|e| deserialize_error(file, line, &columns, &record, e))?;
        rows.push(Row {
            line,
            record: parsed,
        });
    }
    Ok(rows)
}

/// The line a record read from `position` is on: the csv reader places a record where it
/// started reading, before the blank and `#` lines it skipped.
fn line_of(text: &str, position: &csv::Position) -> u64 {
    let mut line = position.line();
    let start = usize::try_from(position.byte()).unwrap_or(usize::MAX);
    for l in text.get(start..).unwrap_or_default().split_inclusive('\n') {
        if !(l.starts_with('#') || l.trim_end_matches(['\r', '\n']).is_empty()) {
            break;
        }
        line += 1;
    }
    line
}

/// A row that did not deserialize, as a [`DatasetError`] naming its column.
fn deserialize_error(
    file: &Path,
    line: u64,
    columns: &[String],
    record: &csv::StringRecord,
    e: csv::Error,
) -> DatasetError {
    let csv::ErrorKind::Deserialize { err, .. } = e.kind() else {
        return csv_error(file, columns, e);
    };
    let problem = err.kind().to_string();
    let at = |i: usize, problem: String| match columns.get(i) {
        Some(column) => DatasetError::value(file, line, column, problem),
        None => DatasetError::new(file, Some(line), None, ErrorKind::Value(problem)),
    };
    if let Some(i) = err.field().and_then(|i| usize::try_from(i).ok()) {
        let value = record.get(i).unwrap_or_default();
        return at(i, format!("`{value}`: {problem}"));
    }
    // A value serde refused after reading it (an unknown name) carries no field index; its
    // message quotes the value, which names the column when exactly one field holds it.
    let quoted = problem.split('`').nth(1).unwrap_or_default();
    let mut holding = record.iter().enumerate().filter(|(_, v)| *v == quoted);
    match (holding.next(), holding.next()) {
        (Some((i, _)), None) => at(i, problem),
        _ => DatasetError::new(file, Some(line), None, ErrorKind::Value(problem)),
    }
}

/// Checks that `header`, on `line`, names `columns` in order and nothing else.
fn check_header(
    file: &Path,
    line: u64,
    columns: &[String],
    header: &csv::StringRecord,
) -> Result<(), DatasetError> {
    let at = |column: &str, kind| Err(DatasetError::new(file, Some(line), Some(column), kind));
    for (i, column) in columns.iter().enumerate() {
        match header.get(i) {
            None => return at(column, ErrorKind::MissingColumn),
            Some(found) if found != column => {
                return at(
                    column,
                    ErrorKind::WrongColumn {
                        found: found.to_owned(),
                    },
                );
            }
            Some(_) => {}
        }
    }
    match header.get(columns.len()) {
        Some(found) => at(
            found,
            ErrorKind::ExtraColumn {
                found: found.to_owned(),
            },
        ),
        None => Ok(()),
    }
}

/// A csv crate error as a [`DatasetError`], with the column its field index names.
fn csv_error(file: &Path, columns: &[String], e: csv::Error) -> DatasetError {
    let line = e.position().map(|p| p.line());
    match e.into_kind() {
        csv::ErrorKind::Deserialize { err, .. } => {
            let column = err
                .field()
                .and_then(|i| columns.get(usize::try_from(i).ok()?))
                .map(String::as_str);
            DatasetError::new(file, line, column, ErrorKind::Value(err.kind().to_string()))
        }
        csv::ErrorKind::Utf8 { err, .. } => DatasetError::new(
            file,
            line,
            columns.get(err.field()).map(String::as_str),
            ErrorKind::Value(err.to_string()),
        ),
        csv::ErrorKind::Io(e) => DatasetError::new(file, line, None, ErrorKind::Io(e)),
        other => DatasetError::new(file, line, None, ErrorKind::Value(format!("{other:?}"))),
    }
}

/// The field names of the struct `T` deserializes as (serde's own list, renames applied).
fn struct_fields<T: DeserializeOwned>() -> &'static [&'static str] {
    let mut fields: &'static [&'static str] = &[];
    // The probe only records the names and then refuses, so the result is always an error.
    let _ = T::deserialize(FieldProbe(&mut fields));
    fields
}

/// A deserializer that answers `deserialize_struct` by noting the field names.
struct FieldProbe<'a>(&'a mut &'static [&'static str]);

impl<'de> Deserializer<'de> for FieldProbe<'_> {
    type Error = de::value::Error;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
        Err(de::Error::custom("a dataset schema is a struct"))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        fields: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Self::Error> {
        *self.0 = fields;
        Err(de::Error::custom("field names noted"))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        option unit unit_struct newtype_struct seq tuple tuple_struct map enum identifier
        ignored_any
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
    struct Tap {
        tap: u32,
        shape: String,
        force_kgf: Shortest<f64>,
        held_pa: Fixed<f32, 1>,
        modulus_pa: Exp<f64, 4>,
        t1_s: Option<Fixed<f64, 3>>,
    }
    impl Schema for Tap {}

    const TEXT: &str = "# a comment\n# another\n\
        tap,shape,force_kgf,held_pa,modulus_pa,t1_s\n\
        0,4-1,5,102547.6,2.0743e4,5.750\n\
        1,9,7.5,-3.0,1.0000e9,\n";

    fn path() -> &'static Path {
        Path::new("taps.csv")
    }

    #[test]
    fn the_header_is_the_field_names_and_rows_round_trip() -> Result<(), DatasetError> {
        assert_eq!(
            Tap::columns(),
            ["tap", "shape", "force_kgf", "held_pa", "modulus_pa", "t1_s"]
        );
        let rows = parse::<Tap>(path(), TEXT)?;
        assert_eq!(rows.iter().map(|r| r.line).collect::<Vec<_>>(), [4, 5]);
        assert_eq!(rows[0].record.held_pa, Fixed(102547.6));
        assert_eq!(rows[1].record.t1_s, None);
        let preamble = "# a comment\n# another\n";
        assert_eq!(render(preamble, rows.into_iter().map(|r| r.record)), TEXT);
        Ok(())
    }

    fn error(text: &str) -> DatasetError {
        match parse::<Tap>(path(), text) {
            Err(e) => e,
            Ok(rows) => panic!("parsed {} rows of a bad file", rows.len()),
        }
    }

    #[test]
    fn a_missing_or_wrong_column_names_the_column_and_the_header_line() {
        let e = error("# c\ntap,shape,force_kgf,held_pa,modulus_pa\n0,1,5,1.0,1e4\n");
        assert!(matches!(e.kind, ErrorKind::MissingColumn));
        assert_eq!((e.line, e.column.as_deref()), (Some(2), Some("t1_s")));
        assert_eq!(e.to_string(), "taps.csv:2: missing column `t1_s`");
        let e = error("tap,shape,force,held_pa,modulus_pa,t1_s\n");
        assert!(matches!(&e.kind, ErrorKind::WrongColumn { found } if found == "force"));
        assert_eq!(e.column.as_deref(), Some("force_kgf"));
        let e = error("tap,shape,force_kgf,held_pa,modulus_pa,t1_s,x\n");
        assert!(matches!(&e.kind, ErrorKind::ExtraColumn { found } if found == "x"));
        let e = error("");
        assert!(matches!(e.kind, ErrorKind::MissingColumn));
        assert_eq!(e.column.as_deref(), Some("tap"));
    }

    #[test]
    fn lines_count_blank_and_comment_lines() -> Result<(), DatasetError> {
        let text = TEXT.replace("\n1,9,", "\n\n# between\n\n1,9,");
        let rows = parse::<Tap>(path(), &text)?;
        assert_eq!(rows.iter().map(|r| r.line).collect::<Vec<_>>(), [4, 8]);
        let e = error(&format!("\n\n{}", text.replace("\n1,9,", "\n-1,9,")));
        assert_eq!((e.line, e.column.as_deref()), (Some(10), Some("tap")));
        let e = error("# only a comment\n");
        assert_eq!((e.line, e.column.as_deref()), (Some(2), Some("tap")));
        Ok(())
    }

    #[test]
    fn a_bad_row_names_its_line_and_column() {
        let e = error(&TEXT.replace("0,4-1,5,", "0,4-1,five,"));
        assert!(matches!(e.kind, ErrorKind::Value(_)));
        assert_eq!((e.line, e.column.as_deref()), (Some(4), Some("force_kgf")));
        assert_eq!(
            e.to_string(),
            "taps.csv:4: column `force_kgf`: `five`: invalid float literal"
        );
        let e = error(&TEXT.replace("\n1,9,", "\n-1,9,"));
        assert_eq!((e.line, e.column.as_deref()), (Some(5), Some("tap")));
        let e = error(&TEXT.replace("5.750\n", "5.750,3\n"));
        assert!(matches!(
            e.kind,
            ErrorKind::FieldCount {
                found: 7,
                expected: 6
            }
        ));
        assert_eq!(e.line, Some(4));
        assert_eq!(e.to_string(), "taps.csv:4: 7 fields, the header has 6");
    }

    #[test]
    fn a_non_finite_number_is_refused_in_any_column() {
        for (bad, column) in [
            ("0,4-1,5,NaN,", "held_pa"),
            ("0,4-1,inf,102547.6,", "force_kgf"),
            ("0,nan,5,102547.6,", "shape"),
        ] {
            let e = error(&TEXT.replace("0,4-1,5,102547.6,", bad));
            assert!(matches!(e.kind, ErrorKind::NotFinite { .. }), "{e}");
            assert_eq!((e.line, e.column.as_deref()), (Some(4), Some(column)));
        }
    }

    #[test]
    fn an_unreadable_file_is_an_io_error_naming_it() {
        let e = match read::<Tap>(Path::new("/nonexistent/taps.csv")) {
            Err(e) => e,
            Ok(_) => panic!("read a file that does not exist"),
        };
        assert!(matches!(e.kind, ErrorKind::Io(_)));
        assert!(
            e.to_string()
                .starts_with("/nonexistent/taps.csv: cannot read")
        );
    }

    #[test]
    fn a_gzipped_file_reads_as_its_text_and_a_corrupt_one_is_an_io_error() {
        let dir = std::env::temp_dir().join(format!("records-gz-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("taps.csv.gz");
        let bytes = gzip(TEXT);
        assert_eq!(bytes, gzip(TEXT), "the same text, the same bytes");
        std::fs::write(&path, &bytes).unwrap();
        let from_gz = read::<Tap>(&path).unwrap();
        assert_eq!(from_gz, parse::<Tap>(Path::new("taps.csv"), TEXT).unwrap());
        std::fs::write(&path, &bytes[..bytes.len() / 2]).unwrap();
        let e = read::<Tap>(&path).unwrap_err();
        std::fs::remove_dir_all(&dir).unwrap();
        assert!(matches!(e.kind, ErrorKind::Io(_)), "{e}");
        assert!(e.to_string().contains("taps.csv.gz: cannot read"), "{e}");
    }
}
