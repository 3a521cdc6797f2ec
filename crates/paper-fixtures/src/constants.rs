//! Scalar figures stated in a paper's text: `name,value,unit[,source]` files.

use crate::{FixtureError, Table};
use std::path::Path;

/// One scalar figure with its unit and where the paper states it.
#[derive(Debug, Clone, PartialEq)]
pub struct Constant {
    /// The value.
    pub value: f64,
    /// The unit (`N`, `hPa`, `count`, `1` for a ratio; empty where the paper gives none).
    pub unit: String,
    /// Where the paper states it (section, equation), if the file has a `source` column.
    pub source: Option<String>,
}

/// A constants file, looked up by name.
#[derive(Debug, Clone)]
pub struct Constants {
    table: Table,
}

impl Constants {
    /// Loads `paper/<name>.csv` from the fixture tree `root`.
    pub fn load_in(root: &Path, name: &str) -> Result<Constants, FixtureError> {
        let table = Table::load_in(root, name)?;
        // Parse every row now, so a malformed value fails the load, not a later lookup.
        table.map(|r| Self::constant(r).map(drop))?;
        Ok(Constants { table })
    }

    fn constant(r: crate::Record<'_>) -> Result<Constant, FixtureError> {
        let source = r.str("source").ok().map(str::to_string);
        Ok(Constant {
            value: r.f64("value")?,
            unit: r.str("unit")?.to_string(),
            source,
        })
    }

    /// The constant called `name`.
    pub fn get(&self, name: &str) -> Result<Constant, FixtureError> {
        let record = self
            .table
            .records()
            .find(|r| r.str("name").is_ok_and(|n| n == name));
        match record {
            Some(r) => Self::constant(r),
            None => Err(FixtureError::new(
                self.table.file(),
                None,
                format!("no constant `{name}`"),
            )),
        }
    }

    /// The value of the constant called `name`, checked to be in `unit`.
    ///
    /// ```
    /// let c = paper_fixtures::seed002::constants()?;
    /// assert_eq!(c.value("grid_rows", "count")?, 24.0);
    /// assert!(c.value("grid_rows", "mm").is_err());
    /// # Ok::<(), paper_fixtures::FixtureError>(())
    /// ```
    pub fn value(&self, name: &str, unit: &str) -> Result<f64, FixtureError> {
        let c = self.get(name)?;
        if c.unit == unit {
            Ok(c.value)
        } else {
            let msg = format!("constant `{name}` is in `{}`, not `{unit}`", c.unit);
            Err(FixtureError::new(self.table.file(), None, msg))
        }
    }

    /// Every constant, in file order.
    pub fn iter(&self) -> impl Iterator<Item = (String, Constant)> + '_ {
        self.table
            .records()
            .filter_map(|r| Some((r.str("name").ok()?.to_string(), Self::constant(r).ok()?)))
    }
}
