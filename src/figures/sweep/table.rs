//! Reading a sweep's table (`runs.csv`) for its figures: the columns, which of them are swept
//! keys, and each run's cells.

use super::err;
use crate::figures::FigureError;
use std::path::{Path, PathBuf};

/// The first of `shoal compare`'s columns: the swept keys sit between `run` and it.
const FIRST_ROW_COLUMN: &str = "scenario";
/// The seed column (the row's own), the axis the spread is taken over.
pub(super) const SEED: &str = "seed";

/// A sweep's table.
pub(super) struct Table {
    /// The file read.
    pub path: PathBuf,
    /// Its columns.
    pub header: Vec<String>,
    /// The swept keys, in the study's order, `seed` last when it takes more than one value.
    pub axes: Vec<String>,
    /// One row per run, a cell per column.
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// Read `path`: a table, or a sweep's directory (its `runs.csv`).
    pub fn read(path: &Path) -> Result<Table, FigureError> {
        let path = if path.is_dir() {
            path.join("runs.csv")
        } else {
            path.to_path_buf()
        };
        let bad = |why: String| err(&path, why);
        let mut r = csv::Reader::from_path(&path).map_err(|e| bad(e.to_string()))?;
        let header: Vec<String> = r
            .headers()
            .map_err(|e| bad(e.to_string()))?
            .iter()
            .map(String::from)
            .collect();
        let first = header.iter().position(|h| h == FIRST_ROW_COLUMN);
        let (Some(first), Some("run")) = (first, header.first().map(String::as_str)) else {
            return Err(bad(format!(
                "not a sweep's table: no columns \"run\" … \"{FIRST_ROW_COLUMN}\" (shoal sweep \
                 writes runs.csv)"
            )));
        };
        let rows: Vec<Vec<String>> = r
            .records()
            .filter_map(Result::ok)
            .filter(|rec| rec.len() == header.len())
            .map(|rec| rec.iter().map(String::from).collect())
            .collect();
        let mut axes: Vec<String> = header[1..first].to_vec();
        let mut t = Table {
            path,
            header,
            axes: Vec::new(),
            rows,
        };
        if t.distinct(SEED).len() > 1 {
            axes.push(SEED.into());
        }
        t.axes = axes;
        Ok(t)
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.header.iter().position(|h| h == name)
    }

    /// The values of column `name`, each once, in the order of the runs.
    pub fn distinct(&self, name: &str) -> Vec<String> {
        let Some(i) = self.column(name) else {
            return Vec::new();
        };
        let mut seen: Vec<String> = Vec::new();
        for r in &self.rows {
            if !seen.contains(&r[i]) {
                seen.push(r[i].clone());
            }
        }
        seen
    }

    /// Run `row`'s status: "passed", "violated" or "failed".
    pub fn status(&self, row: usize) -> &str {
        self.column("status")
            .map_or("", |i| self.rows[row][i].as_str())
    }

    /// Run `row`'s value of numeric column `col` (NaN when it has none).
    pub fn number(&self, row: usize, col: usize) -> f64 {
        self.rows[row][col].parse().unwrap_or(f64::NAN)
    }

    /// The file's name, for captions.
    pub fn name(&self) -> String {
        self.path
            .file_name()
            .map_or("runs.csv".into(), |n| n.to_string_lossy().into_owned())
    }
}
