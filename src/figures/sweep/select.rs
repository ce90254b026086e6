//! What a sweep's figures show: the swept keys on x (one figure each), the measures (one panel
//! each) and the lines of a panel (one per combination of the other swept keys but the seed),
//! each choice checked against the table with an error that names it and what is allowed.

use super::err;
use super::metric::{allowed, DEFAULTS};
use super::stats::Series;
use super::table::{Table, SEED};
use crate::figures::FigureError;

/// The most lines a panel draws; beyond, its runs are pooled into one line and the caption
/// says so.
pub(super) const MAX_SERIES: usize = 6;

/// The keys to plot against: `x` (a swept key of the table), or every swept key but the
/// seed; the seed alone when it is the only one.
pub(super) fn x_keys(table: &Table, x: Option<&str>) -> Result<Vec<String>, FigureError> {
    let swept = || {
        if table.axes.is_empty() {
            "none: the study had no axes".to_string()
        } else {
            table.axes.join(", ")
        }
    };
    match x {
        Some(key) if table.axes.iter().any(|a| a == key) => Ok(vec![key.to_string()]),
        Some(key) => Err(err(
            &table.path,
            format!(
                "--x \"{key}\" is not a swept key of the table; allowed: {}",
                swept()
            ),
        )),
        None => {
            let keys: Vec<String> = table.axes.iter().filter(|a| *a != SEED).cloned().collect();
            match (keys.is_empty(), table.axes.is_empty()) {
                (false, _) => Ok(keys),
                (true, false) => Ok(vec![SEED.to_string()]),
                (true, true) => Err(err(
                    &table.path,
                    "no swept key (the study had no axes, or one value of each): nothing to \
                     plot against"
                        .into(),
                )),
            }
        }
    }
}

/// The measures to plot: `ys` (each a measure of the table), or the [`DEFAULTS`] it has.
pub(super) fn metrics(table: &Table, ys: &[String]) -> Result<Vec<String>, FigureError> {
    let allowed = allowed(table);
    if ys.is_empty() {
        return Ok(DEFAULTS
            .iter()
            .filter(|d| allowed.iter().any(|a| a == *d))
            .map(|d| d.to_string())
            .collect());
    }
    for y in ys {
        if !allowed.contains(y) {
            let why = if table.column(y).is_some() {
                format!("--y \"{y}\" is not a measure (text, or a swept key)")
            } else {
                format!("--y \"{y}\": the table has no such column")
            };
            return Err(err(
                &table.path,
                format!("{why}; allowed: {}", allowed.join(", ")),
            ));
        }
    }
    Ok(ys.to_vec())
}

/// The lines of a figure against `x`: one per combination of the other swept keys but the
/// seed, in the table's order; one line of every run when there is none, or when there are
/// more than [`MAX_SERIES`] (then with a note for the caption).
pub(super) fn series(table: &Table, x: &str) -> (Vec<Series>, Option<String>) {
    let others: Vec<usize> = table
        .axes
        .iter()
        .filter(|a| *a != x && *a != SEED)
        .filter_map(|a| table.column(a))
        .collect();
    let mut lines: Vec<Series> = Vec::new();
    for (r, row) in table.rows.iter().enumerate() {
        let label = others
            .iter()
            .map(|&c| format!("{} = {}", table.header[c], row[c]))
            .collect::<Vec<_>>()
            .join(", ");
        match lines.iter_mut().find(|l| l.label == label) {
            Some(l) => l.rows.push(r),
            None => lines.push(Series {
                label,
                rows: vec![r],
            }),
        }
    }
    if lines.len() <= MAX_SERIES {
        return (lines, None);
    }
    let note = format!(
        "{} combinations of {} are more than {MAX_SERIES} lines: pooled into one",
        lines.len(),
        others
            .iter()
            .map(|&c| table.header[c].as_str())
            .collect::<Vec<_>>()
            .join(", ")
    );
    let all = Series {
        label: String::new(),
        rows: (0..table.rows.len()).collect(),
    };
    (vec![all], Some(note))
}
