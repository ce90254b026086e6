//! The numbers a panel draws: the x axis's values (numbers, or categories in the table's
//! order), the runs of each line, and at each x value the median, quartiles and extremes of a
//! measure over those runs (the seeds), runs that made no plan left out.

use super::metric::PASSED_FRACTION;
use super::table::Table;

/// The x axis: a swept key and its values.
pub(super) struct XAxis {
    /// The key.
    pub key: String,
    /// Its column.
    pub col: usize,
    /// Whether its values are not all numbers (then placed at 0, 1, … in the table's order).
    pub categorical: bool,
    /// Its values, each once: ascending numbers, or categories in the table's order.
    pub values: Vec<String>,
}

impl XAxis {
    /// The axis of key `key` of `table` (a column it has).
    pub fn new(table: &Table, key: &str, col: usize) -> XAxis {
        let mut values = table.distinct(key);
        let numeric = values
            .iter()
            .all(|v| v.parse::<f64>().is_ok_and(f64::is_finite));
        if numeric {
            values.sort_by(|a, b| {
                let (a, b) = (a.parse::<f64>(), b.parse::<f64>());
                a.unwrap_or(0.0).total_cmp(&b.unwrap_or(0.0))
            });
        }
        XAxis {
            key: key.to_string(),
            col,
            categorical: !numeric,
            values,
        }
    }

    /// Where value `cell` sits on the axis.
    pub fn position(&self, cell: &str) -> f64 {
        if self.categorical {
            self.values.iter().position(|v| v == cell).unwrap_or(0) as f64
        } else {
            cell.parse().unwrap_or(f64::NAN)
        }
    }
}

/// One line of a panel: a label (the other swept keys' values) and its runs.
pub(super) struct Series {
    /// E.g. "sonar.range = 300"; empty when the panel has one line of every run.
    pub label: String,
    /// Its runs (rows of the table), failed ones included.
    pub rows: Vec<usize>,
}

/// A measure at one x value over a line's runs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Point {
    /// Where on the x axis.
    pub x: f64,
    /// How many runs it summarises.
    pub n: usize,
    pub min: f64,
    pub q1: f64,
    pub median: f64,
    pub q3: f64,
    pub max: f64,
}

/// `metric` along `x` over the runs of `series`: one point per x value that has a measure.
/// [`PASSED_FRACTION`] is the share of all the runs at that value (no spread).
pub(super) fn points(table: &Table, x: &XAxis, series: &Series, metric: &str) -> Vec<Point> {
    let col = table.column(metric);
    x.values
        .iter()
        .filter_map(|value| {
            let rows = series
                .rows
                .iter()
                .copied()
                .filter(|&r| &table.rows[r][x.col] == value);
            let at = x.position(value);
            if metric == PASSED_FRACTION {
                let all: Vec<usize> = rows.collect();
                let passed = all.iter().filter(|&&r| table.status(r) == "passed").count();
                let f = passed as f64 / all.len().max(1) as f64;
                return (!all.is_empty()).then_some(Point {
                    x: at,
                    n: all.len(),
                    min: f,
                    q1: f,
                    median: f,
                    q3: f,
                    max: f,
                });
            }
            let col = col?;
            let mut ys: Vec<f64> = rows
                .filter(|&r| table.status(r) != "failed")
                .map(|r| table.number(r, col))
                .filter(|y| y.is_finite())
                .collect();
            ys.sort_by(f64::total_cmp);
            summary(at, &ys)
        })
        .collect()
}

/// The point at `x` of sorted values `ys` (None when there are none).
fn summary(x: f64, ys: &[f64]) -> Option<Point> {
    Some(Point {
        x,
        n: ys.len(),
        min: *ys.first()?,
        q1: quantile(ys, 0.25),
        median: quantile(ys, 0.5),
        q3: quantile(ys, 0.75),
        max: *ys.last()?,
    })
}

/// Quantile `p` of sorted `ys`, interpolated linearly between order statistics (the default
/// of numpy and R's type 7).
fn quantile(ys: &[f64], p: f64) -> f64 {
    let h = (ys.len() - 1) as f64 * p;
    let (lo, frac) = (h.floor() as usize, h - h.floor());
    match ys.get(lo + 1) {
        Some(next) => ys[lo] + frac * (next - ys[lo]),
        None => ys[lo],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_interpolate_as_numpy_does() {
        let ys = [1.0, 2.0, 3.0, 4.0, 10.0];
        let p = summary(0.0, &ys).unwrap();
        assert_eq!(
            (p.min, p.q1, p.median, p.q3, p.max),
            (1.0, 2.0, 3.0, 4.0, 10.0)
        );
        let p = summary(0.0, &[1.0, 2.0]).unwrap();
        assert_eq!((p.q1, p.median, p.q3), (1.25, 1.5, 1.75));
        assert_eq!(summary(0.0, &[7.0]).unwrap().q3, 7.0);
        assert!(summary(0.0, &[]).is_none());
    }
}
