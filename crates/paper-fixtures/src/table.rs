//! The fixture CSV dialect: `#` comment lines (the citation), one header line, then rows of
//! comma-separated cells. No quoting: a cell never holds a comma, so a stray one is an error.

use crate::FixtureError;
use std::path::{Path, PathBuf};

/// One parsed fixture file.
#[derive(Debug, Clone)]
pub struct Table {
    file: PathBuf,
    citation: Vec<String>,
    columns: Vec<String>,
    records: Vec<(usize, Vec<String>)>,
}

/// One row of a [`Table`], with typed cell access by column name.
#[derive(Debug, Clone, Copy)]
pub struct Record<'a> {
    table: &'a Table,
    line: usize,
    cells: &'a [String],
}

impl Table {
    /// Loads `paper/<name>.csv` from [`fixtures_dir`](crate::fixtures_dir).
    pub fn load(name: &str) -> Result<Table, FixtureError> {
        Self::load_in(&crate::fixtures_dir(), name)
    }

    /// Loads `paper/<name>.csv` below the fixture tree `root`.
    pub fn load_in(root: &Path, name: &str) -> Result<Table, FixtureError> {
        let file = root.join("paper").join(format!("{name}.csv"));
        let text = std::fs::read_to_string(&file)
            .map_err(|e| FixtureError::new(&file, None, format!("cannot read: {e}")))?;
        Self::parse(file, &text)
    }

    /// Parses fixture CSV text; `file` names it in errors.
    ///
    /// ```
    /// let t = paper_fixtures::Table::parse("x.csv".into(), "# cite\na,b\n1,2\n")?;
    /// assert_eq!(t.citation(), ["cite"]);
    /// assert_eq!(t.records().next().unwrap().f64("b")?, 2.0);
    /// let err = paper_fixtures::Table::parse("x.csv".into(), "a,b\n1,2,3\n").unwrap_err();
    /// assert_eq!(err.to_string(), "x.csv:2: 3 cells, the header has 2");
    /// # Ok::<(), paper_fixtures::FixtureError>(())
    /// ```
    pub fn parse(file: PathBuf, text: &str) -> Result<Table, FixtureError> {
        let mut citation = Vec::new();
        let mut columns: Option<Vec<String>> = None;
        let mut records = Vec::new();
        for (index, raw) in text.lines().enumerate() {
            let line = index + 1;
            if let Some(comment) = raw.strip_prefix('#') {
                if columns.is_some() {
                    return Err(FixtureError::new(
                        &file,
                        Some(line),
                        "comment after the header",
                    ));
                }
                citation.push(comment.trim().to_string());
                continue;
            }
            if raw.trim().is_empty() {
                continue;
            }
            let cells: Vec<String> = raw.split(',').map(|c| c.trim().to_string()).collect();
            match &columns {
                None => columns = Some(cells),
                Some(header) if header.len() != cells.len() => {
                    let msg = format!("{} cells, the header has {}", cells.len(), header.len());
                    return Err(FixtureError::new(&file, Some(line), msg));
                }
                Some(_) => records.push((line, cells)),
            }
        }
        let columns = columns.ok_or_else(|| FixtureError::new(&file, None, "no header line"))?;
        if citation.is_empty() {
            return Err(FixtureError::new(
                &file,
                Some(1),
                "no citation: a fixture opens with `#` lines naming its source",
            ));
        }
        Ok(Table {
            file,
            citation,
            columns,
            records,
        })
    }

    /// The file the table came from.
    pub fn file(&self) -> &Path {
        &self.file
    }

    /// The `#` lines before the header: the source of every number in the file.
    pub fn citation(&self) -> &[String] {
        &self.citation
    }

    /// The column names, in file order.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// How many data rows the table has.
    pub fn len(&self) -> usize {
        self.records.len()
    }

    /// Whether the table has no data rows.
    pub fn is_empty(&self) -> bool {
        self.records.is_empty()
    }

    /// The data rows, in file order.
    pub fn records(&self) -> impl Iterator<Item = Record<'_>> {
        self.records.iter().map(|(line, cells)| Record {
            table: self,
            line: *line,
            cells,
        })
    }

    /// Maps every row through `f`, stopping at the first error.
    pub fn map<T>(
        &self,
        f: impl Fn(Record<'_>) -> Result<T, FixtureError>,
    ) -> Result<Vec<T>, FixtureError> {
        self.records().map(f).collect()
    }
}

impl<'a> Record<'a> {
    /// The 1-based line of this row in its file.
    pub fn line(&self) -> usize {
        self.line
    }

    /// The cell of `column` as text.
    pub fn str(&self, column: &str) -> Result<&'a str, FixtureError> {
        let index = self
            .table
            .columns
            .iter()
            .position(|c| c == column)
            .ok_or_else(|| {
                self.error(format!(
                    "no column `{column}` (columns: {})",
                    self.table.columns.join(", ")
                ))
            })?;
        Ok(&self.cells[index])
    }

    /// The cell of `column` as a finite number.
    pub fn f64(&self, column: &str) -> Result<f64, FixtureError> {
        let cell = self.str(column)?;
        match cell.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(self.error(format!(
                "column `{column}`: `{cell}` is not a finite number"
            ))),
        }
    }

    /// The cell of `column` as a number, or `None` when the cell is empty.
    pub fn opt_f64(&self, column: &str) -> Result<Option<f64>, FixtureError> {
        if self.str(column)?.is_empty() {
            Ok(None)
        } else {
            self.f64(column).map(Some)
        }
    }

    /// The cell of `column` as a whole number.
    pub fn u32(&self, column: &str) -> Result<u32, FixtureError> {
        let cell = self.str(column)?;
        cell.parse::<u32>()
            .map_err(|_| self.error(format!("column `{column}`: `{cell}` is not a whole number")))
    }

    /// An error that names this row's file and line.
    pub fn error(&self, message: impl Into<String>) -> FixtureError {
        FixtureError::new(&self.table.file, Some(self.line), message)
    }
}

/// Declares `name()` (default fixture tree) and `name_in(root)` loading `file` into `Vec<row>`.
macro_rules! typed_fixture {
    ($(#[$doc:meta])* $name:ident, $name_in:ident, $file:literal, $row:ty, $parse:expr) => {
        $(#[$doc])*
        pub fn $name() -> Result<Vec<$row>, crate::FixtureError> {
            $name_in(&crate::fixtures_dir())
        }

        #[doc = concat!("[`", stringify!($name), "`] from the fixture tree `root`.")]
        pub fn $name_in(root: &std::path::Path) -> Result<Vec<$row>, crate::FixtureError> {
            crate::Table::load_in(root, $file)?.map($parse)
        }
    };
}

/// Declares `name()` / `name_in(root)` loading a constants file.
macro_rules! constants_fixture {
    ($file:literal) => {
        /// The scalar figures this paper states in its text, with units and sections.
        pub fn constants() -> Result<crate::Constants, crate::FixtureError> {
            constants_in(&crate::fixtures_dir())
        }

        /// [`constants`] from the fixture tree `root`.
        pub fn constants_in(
            root: &std::path::Path,
        ) -> Result<crate::Constants, crate::FixtureError> {
            crate::Constants::load_in(root, $file)
        }
    };
}

pub(crate) use {constants_fixture, typed_fixture};
