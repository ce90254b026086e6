//! A table read against its study record: every row it cannot take is named by its line, and
//! the runs it lacks are named too. `shoal sweep collect` refuses a shard table with any such
//! problem; `--resume` makes the runs of the rows it could not take again.

use super::columns::{self, Kind};
use super::record::Record;
use super::study::Axis;
use super::SweepError;
use csv::{ByteRecord, StringRecord};
use std::collections::HashMap;
use std::path::Path;

/// What is wrong with a table or one of its rows.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Problem {
    /// The file is empty: not even a header.
    Empty,
    /// Its header is not its record's columns.
    Columns(String),
    /// Its last row is cut short (the file does not end with a line end): an interrupted write.
    Cut {
        /// The row's line, 1-based.
        line: u64,
    },
    /// A row that cannot be taken.
    Row {
        /// The row's line, 1-based.
        line: u64,
        /// Why.
        why: String,
    },
    /// Runs the table should hold and does not.
    Missing {
        /// The runs missing, ascending.
        runs: Vec<usize>,
        /// Runs the table should hold.
        of: usize,
    },
}

impl Problem {
    /// The problem as a phrase after the file's name ("FILE line 4: …", "FILE: …").
    pub fn describe(&self, file: &Path) -> String {
        let f = file.display();
        match self {
            Problem::Empty => format!("{f}: empty file (not even a header line)"),
            Problem::Columns(why) => format!("{f} line 1: {why}"),
            Problem::Cut { line } => format!(
                "{f} line {line}: cut short (the file ends inside this row: an interrupted write)"
            ),
            Problem::Row { line, why } => format!("{f} line {line}: {why}"),
            Problem::Missing { runs, of } => {
                const SHOWN: usize = 20;
                let mut list: Vec<String> = runs.iter().take(SHOWN).map(usize::to_string).collect();
                if runs.len() > SHOWN {
                    list.push(format!("… ({} more)", runs.len() - SHOWN));
                }
                format!(
                    "{f}: {} of its {of} runs missing (run {})",
                    runs.len(),
                    list.join(", ")
                )
            }
        }
    }
}

/// A table read against its record: the rows it can take (one per run, in the file's order)
/// and its problems.
#[derive(Debug, Default)]
pub struct Checked {
    /// The rows taken.
    pub rows: Vec<StringRecord>,
    /// What is wrong, in the file's order (the runs missing last).
    pub problems: Vec<Problem>,
}

/// Read table `path` against `record`: its header must be the record's columns; each row needs
/// as many fields, a run index of the study below its `record.runs` and among `expected` (the
/// table's runs, ascending: its shard's, or every run), that run's axis values, a status and
/// cells of its columns' types; a run found twice must be the same row. A missing file is a
/// table without rows.
pub fn table(path: &Path, record: &Record, expected: &[usize]) -> Result<Checked, SweepError> {
    let mut out = Checked::default();
    let bytes = match std::fs::read(path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Vec::new(),
        Err(e) => {
            return Err(SweepError::Table {
                path: path.to_path_buf(),
                why: format!("cannot read: {e}"),
            })
        }
    };
    if bytes.is_empty() {
        out.problems.push(Problem::Empty);
        missing(&mut out, expected, &HashMap::new());
        return Ok(out);
    }
    let cut = !bytes.ends_with(b"\n");
    let mut reader = csv::ReaderBuilder::new()
        .flexible(true)
        .has_headers(false)
        .from_reader(bytes.as_slice());
    let mut records = reader.byte_records();
    let header = match records.next() {
        Some(Ok(h)) => h,
        Some(Err(e)) => {
            out.problems
                .push(Problem::Columns(format!("unreadable header: {e}")));
            return Ok(out);
        }
        None => {
            out.problems.push(Problem::Empty);
            return Ok(out);
        }
    };
    let header = match StringRecord::from_byte_record(header) {
        Ok(h) => h,
        Err(_) => {
            out.problems
                .push(Problem::Columns("the header is not UTF-8 text".into()));
            return Ok(out);
        }
    };
    if let Some(why) = columns_differ(&header, &record.columns) {
        out.problems.push(Problem::Columns(why));
        return Ok(out);
    }
    let axes = &record.content.axes;
    let kind_of = |key: &str| {
        axes.iter()
            .find(|a| a.key == key)
            .map(|a| columns::values_kind(&a.values))
    };
    let kinds = columns::kinds(&header, &[], kind_of);
    // the axes with a column of their own (not `seed`: the row's own seed column is 0 in a
    // run whose scenario could not be made), and that column
    let (row_names, _) = super::table::row_fields(&crate::compare::Row::key("", "", 0, 0));
    let axis_cols: Vec<(usize, usize)> = axes
        .iter()
        .enumerate()
        .filter(|(_, a)| super::table::own_column(&a.key, &row_names))
        .filter_map(|(ai, a)| header.iter().position(|h| h == a.key).map(|c| (c, ai)))
        .collect();
    let status = header.iter().position(|h| h == "status");
    let rows: Vec<(u64, Result<ByteRecord, csv::Error>)> = records
        .map(|r| {
            let line = match &r {
                Ok(rec) => rec.position().map_or(0, |p| p.line()),
                Err(e) => e.position().map_or(0, |p| p.line()),
            };
            (line, r)
        })
        .collect();
    let last = rows.len();
    let mut seen: HashMap<usize, (u64, usize)> = HashMap::new();
    for (k, (line, rec)) in rows.into_iter().enumerate() {
        let bad = |why: String| Problem::Row { line, why };
        if cut && k + 1 == last {
            out.problems.push(Problem::Cut { line });
            continue;
        }
        let rec = match rec {
            Ok(r) => r,
            Err(e) => {
                out.problems.push(bad(format!("unreadable: {e}")));
                continue;
            }
        };
        let Ok(rec) = StringRecord::from_byte_record(rec) else {
            out.problems.push(bad("not UTF-8 text".into()));
            continue;
        };
        if rec.len() != header.len() {
            out.problems.push(bad(format!(
                "{} field{}, the header has {}",
                rec.len(),
                if rec.len() == 1 { "" } else { "s" },
                header.len()
            )));
            continue;
        }
        let cell = rec.get(0).unwrap_or("");
        let Ok(run) = cell.parse::<usize>() else {
            out.problems.push(bad(format!(
                "run \"{cell}\" is not a whole number (a run's index)"
            )));
            continue;
        };
        if run >= record.runs {
            out.problems.push(bad(format!(
                "run {run} is beyond the study's {} runs (0 to {})",
                record.runs,
                record.runs.saturating_sub(1)
            )));
            continue;
        }
        if expected.binary_search(&run).is_err() {
            let s = record.shard.map_or("this table's".into(), |s| {
                format!("shard {}/{}'s", s.index, s.count)
            });
            out.problems
                .push(bad(format!("run {run} is not one of {s} runs")));
            continue;
        }
        if let Some(why) = wrong_values(&rec, run, axes, &axis_cols) {
            out.problems.push(bad(why));
            continue;
        }
        if let Some(s) = status.and_then(|i| rec.get(i)) {
            if !matches!(s, "passed" | "violated" | "failed") {
                out.problems.push(bad(format!(
                    "status \"{s}\" is not passed, violated or failed"
                )));
                continue;
            }
        }
        if let Some(why) = wrong_type(&rec, &header, &kinds) {
            out.problems.push(bad(why));
            continue;
        }
        match seen.get(&run) {
            Some(&(first, i)) if out.rows[i] == rec => {
                let _ = first; // the same row twice: one is kept
            }
            Some(&(first, _)) => {
                out.problems.push(bad(format!(
                    "run {run} again (first on line {first}), with other values"
                )));
            }
            None => {
                seen.insert(run, (line, out.rows.len()));
                out.rows.push(rec);
            }
        }
    }
    missing(&mut out, expected, &seen);
    Ok(out)
}

/// Record the runs of `expected` not `seen`.
fn missing(out: &mut Checked, expected: &[usize], seen: &HashMap<usize, (u64, usize)>) {
    let runs: Vec<usize> = expected
        .iter()
        .copied()
        .filter(|r| !seen.contains_key(r))
        .collect();
    if !runs.is_empty() {
        out.problems.push(Problem::Missing {
            runs,
            of: expected.len(),
        });
    }
}

/// Why `header` is not `columns`, naming the first column that differs.
fn columns_differ(header: &StringRecord, columns: &[String]) -> Option<String> {
    if header.iter().eq(columns.iter().map(String::as_str)) {
        return None;
    }
    let at = header
        .iter()
        .zip(columns)
        .position(|(h, c)| h != c)
        .unwrap_or(header.len().min(columns.len()));
    Some(format!(
        "its columns are not its study's: column {} is {}, the study's is {} ({} columns, the \
         study's {})",
        at + 1,
        header
            .get(at)
            .map_or("missing".into(), |h| format!("\"{h}\"")),
        columns
            .get(at)
            .map_or("none".into(), |c| format!("\"{c}\"")),
        header.len(),
        columns.len()
    ))
}

/// Why the axis cells of `rec` are not run `run`'s values, if they are not.
fn wrong_values(
    rec: &StringRecord,
    run: usize,
    axes: &[Axis],
    axis_cols: &[(usize, usize)],
) -> Option<String> {
    let values = super::study::values_of(axes, run);
    axis_cols.iter().find_map(|&(col, ai)| {
        let want = values[ai].trim_matches('"');
        let got = rec.get(col).unwrap_or("");
        (got != want).then(|| {
            format!(
                "run {run} has {} = {got}, the study's run {run} has {want}",
                axes[ai].key
            )
        })
    })
}

/// Why a cell of `rec` is not of its column's type, if one is not (an empty cell is a null).
fn wrong_type(rec: &StringRecord, header: &StringRecord, kinds: &[Kind]) -> Option<String> {
    rec.iter()
        .zip(header.iter())
        .zip(kinds)
        .find_map(|((cell, name), kind)| {
            let ok = cell.is_empty()
                || (*kind != Kind::Text && cell.eq_ignore_ascii_case("nan"))
                || match kind {
                    Kind::Int => columns::int(cell).is_some(),
                    Kind::Real => columns::real(cell).is_some(),
                    Kind::Bool => matches!(cell, "true" | "false"),
                    Kind::Text => true,
                };
            (!ok).then(|| {
                let want = match kind {
                    Kind::Int => "a whole number",
                    Kind::Real => "a number",
                    Kind::Bool => "true or false",
                    Kind::Text => "text",
                };
                format!("column {name} = \"{cell}\" is not {want}")
            })
        })
}
