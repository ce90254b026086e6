//! A sweep's table (CSV): one row per run, `run` (its index), the swept keys, then the columns
//! of `shoal compare`'s rows ([`crate::compare::Row`]: status, error, times, metrics, the
//! check's margins). Rows are appended as runs finish (each flushed, so an interrupted sweep
//! keeps what it finished) and sorted by run when the sweep ends, when a typed copy is written
//! beside it as Parquet (`runs.parquet`, [`super::parquet_path`]).

use super::SweepError;
use crate::compare::Row;
use csv::StringRecord;
use std::fs::OpenOptions;
use std::io::Write as _;
use std::path::Path;

/// The names and values of a row's columns, as `compare` writes them.
pub fn row_fields(row: &Row) -> (StringRecord, StringRecord) {
    let mut w = csv::Writer::from_writer(Vec::new());
    // a Row has only scalar fields: serialising it cannot fail
    let _ = w.serialize(row);
    let bytes = w.into_inner().unwrap_or_default();
    let mut r = csv::Reader::from_reader(bytes.as_slice());
    let names = r.headers().cloned().unwrap_or_default();
    let values = r.records().next().and_then(Result::ok).unwrap_or_default();
    (names, values)
}

/// Whether axis `key` has a column of its own: not when a row column has its name (`seed`:
/// the row's `seed` is the same value).
pub(crate) fn own_column(key: &str, names: &StringRecord) -> bool {
    !names.iter().any(|n| n == key)
}

/// The table's header: `run`, the axes' keys (but those a row column already holds), the
/// row's columns.
pub fn header(axes: &[String]) -> StringRecord {
    let (names, _) = row_fields(&Row::key("", "", 0, 0));
    let mut h = StringRecord::new();
    h.push_field("run");
    axes.iter()
        .filter(|a| own_column(a, &names))
        .for_each(|a| h.push_field(a));
    names.iter().for_each(|n| h.push_field(n));
    h
}

/// The record of run `index` whose axes `axes` take `values` (TOML text; strings are written
/// unquoted).
pub fn record(index: usize, axes: &[String], values: &[String], row: &Row) -> StringRecord {
    let (names, fields) = row_fields(row);
    let mut r = StringRecord::new();
    r.push_field(&index.to_string());
    axes.iter()
        .zip(values)
        .filter(|(a, _)| own_column(a, &names))
        .for_each(|(_, v)| r.push_field(v.trim_matches('"')));
    fields.iter().for_each(|f| r.push_field(f));
    r
}

/// The table at `path`: its header and records (None when there is no file). A last line cut
/// short by an interruption is dropped.
pub fn read(path: &Path) -> Result<Option<(StringRecord, Vec<StringRecord>)>, SweepError> {
    if !path.exists() {
        return Ok(None);
    }
    let bad = |e: csv::Error| SweepError::Table {
        path: path.to_path_buf(),
        why: e.to_string(),
    };
    let mut r = csv::ReaderBuilder::new()
        .flexible(true)
        .from_path(path)
        .map_err(bad)?;
    let header = r.headers().map_err(bad)?.clone();
    let records = r
        .records()
        .filter_map(Result::ok)
        .filter(|rec| rec.len() == header.len())
        .collect();
    Ok(Some((header, records)))
}

/// Appends records to a table file, writing the header first if the file is new.
pub struct Appender {
    file: std::fs::File,
}

impl Appender {
    /// Open `path` for appending; a new (or empty) file gets `header`, an existing one must
    /// have it.
    pub fn open(path: &Path, header: &StringRecord) -> Result<Appender, SweepError> {
        let io = |e: std::io::Error| SweepError::Table {
            path: path.to_path_buf(),
            why: e.to_string(),
        };
        if let Some((found, _)) = read(path)? {
            if &found != header {
                return Err(SweepError::Table {
                    path: path.to_path_buf(),
                    why: "its columns are not this study's (another study's table?); remove it \
                          or write elsewhere"
                        .into(),
                });
            }
        }
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir).map_err(io)?;
        }
        // a last line cut short by an interruption is dropped, so appended rows start on a
        // line of their own
        if let Ok(bytes) = std::fs::read(path) {
            if !bytes.is_empty() && !bytes.ends_with(b"\n") {
                let keep = bytes.iter().rposition(|&b| b == b'\n').map_or(0, |i| i + 1);
                let f = OpenOptions::new().write(true).open(path).map_err(io)?;
                f.set_len(keep as u64).map_err(io)?;
            }
        }
        let mut file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(io)?;
        if file.metadata().map_err(io)?.len() == 0 {
            file.write_all(&line(header)).map_err(io)?;
        }
        Ok(Appender { file })
    }

    /// Append one record and flush it.
    pub fn append(&mut self, rec: &StringRecord) -> std::io::Result<()> {
        self.file.write_all(&line(rec))?;
        self.file.flush()
    }
}

/// One CSV line.
fn line(rec: &StringRecord) -> Vec<u8> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let _ = w.write_record(rec);
    w.into_inner().unwrap_or_default()
}

/// Write `records` under `header` to `path`, sorted by run and one per run (the last kept),
/// atomically; returns the records written.
pub fn write_sorted(
    path: &Path,
    header: &StringRecord,
    mut records: Vec<StringRecord>,
) -> Result<Vec<StringRecord>, SweepError> {
    let run = |r: &StringRecord| {
        r.get(0)
            .and_then(|v| v.parse::<usize>().ok())
            .unwrap_or(usize::MAX)
    };
    records.sort_by_key(run); // stable: the last of equal runs stays last
    let mut kept: Vec<StringRecord> = Vec::with_capacity(records.len());
    for r in records {
        match kept.last_mut() {
            Some(last) if run(last) == run(&r) => *last = r,
            _ => kept.push(r),
        }
    }
    let mut bytes = line(header);
    kept.iter().for_each(|r| bytes.extend(line(r)));
    crate::output::write_atomic(path, &bytes).map_err(|e| SweepError::Table {
        path: path.to_path_buf(),
        why: e.to_string(),
    })?;
    Ok(kept)
}
