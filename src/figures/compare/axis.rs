//! The panels' y axes ([`Axis`]): the range of each panel in plotted units (log10 on a log
//! panel, with room for the reference line, failure counts and scenario names), and the
//! log-scale grid and tick labels (decades; powers of ten beyond 0.001…10000).

use super::metric::Metric;
use super::{Compare, PAPER_RRT_S};
use crate::figures::canvas::DrawResult;
use crate::figures::map::Chart2d;
use crate::figures::style;
use plotters::prelude::*;

/// A panel's y axis, in plotted units (log10 on a log panel).
pub(super) struct Axis {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) labels: usize,
}

impl Compare {
    pub(super) fn axis(&self, metric: Metric) -> Axis {
        let mut ys: Vec<f64> = self.points(metric).map(|p| p.1).collect();
        let groups = self.scenarios.len() > 1;
        if metric.log() {
            if metric == Metric::Wall {
                ys.push(PAPER_RRT_S.log10());
            }
            let (min, max) = bounds(&ys).unwrap_or((0.0, 1.0));
            let mut lo = min - 0.3;
            let mut hi = max + 0.3;
            if self.counts_failures(metric) {
                lo -= 0.35; // room for the counts above the x axis
            }
            if groups {
                hi += 0.3; // room for the scenario names
            }
            // at least two labelled decades
            if hi.floor() - lo.ceil() < 1.0 {
                lo = lo.floor();
                hi = hi.max(lo + 1.0);
            }
            let decades = (hi.floor() - lo.ceil()) as usize + 1;
            Axis {
                lo,
                hi,
                labels: decades.min(8),
            }
        } else {
            let (min, max) = bounds(&ys).unwrap_or((0.0, 1.0));
            let span = (max - min.min(0.0)).max(1e-9);
            let lo = if min >= 0.0 { 0.0 } else { min - 0.08 * span };
            let hi = max + if groups { 0.2 } else { 0.1 } * span;
            Axis { lo, hi, labels: 8 }
        }
    }
}

/// Decade lines (darker) and the 2…9 lines between them (lighter, when there are few decades)
/// of a log panel.
pub(super) fn log_grid<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    axis: &Axis,
    x_max: f64,
) -> DrawResult<DB> {
    let decades = axis.hi - axis.lo;
    let mut lines = Vec::new();
    let mut d = axis.lo.floor();
    while d <= axis.hi {
        if decades <= 6.0 {
            for k in 2..=9 {
                lines.push((d + f64::from(k).log10(), RGBColor(235, 235, 235)));
            }
        }
        lines.push((d, RGBColor(205, 205, 205)));
        d += 1.0;
    }
    let inside = lines
        .into_iter()
        .filter(|&(y, _)| y > axis.lo && y < axis.hi);
    chart.draw_series(inside.map(|(y, c)| PathElement::new(vec![(-0.5, y), (x_max, y)], c)))?;
    Ok(())
}

/// The tick label of 10^e: decimals from 0.001 to 10000, else a power of ten; blank between
/// powers.
pub(super) fn power_of_ten(e: f64) -> String {
    let r = e.round();
    if (e - r).abs() > 1e-6 {
        return String::new();
    }
    if (-3.0..=4.0).contains(&r) {
        return style::tick(&10f64.powf(r));
    }
    const SUP: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let digits: String = (r.abs() as u64)
        .to_string()
        .chars()
        .map(|c| SUP[c.to_digit(10).unwrap_or(0) as usize])
        .collect();
    format!("10{}{digits}", if r < 0.0 { "⁻" } else { "" })
}

/// Least and greatest of `ys`, if any.
fn bounds(ys: &[f64]) -> Option<(f64, f64)> {
    let (lo, hi) = ys
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
            (a.min(y), b.max(y))
        });
    (lo <= hi).then_some((lo, hi))
}
