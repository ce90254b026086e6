//! Drawing one panel of a sweep's figure: its title and axes (the key's values on x, numbers or
//! categories), then per line the min–max band, the quartile band, and the median as a line
//! through dots (a single x value: the bands as bars); a note when no run has the measure.

use super::metric::describe;
use super::stats::{points, Point};
use super::{SweepFigure, EXTREMES, KEY, LINES, QUARTILES};
use crate::figures::canvas::{Area, DrawResult};
use crate::figures::map::Chart2d;
use crate::figures::style::{self, text, LABEL, TICK};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

impl SweepFigure<'_> {
    pub(super) fn panel<DB: DrawingBackend>(
        &self,
        area: &Area<DB>,
        metric: &str,
    ) -> DrawResult<DB> {
        let lines: Vec<Vec<Point>> = self
            .series
            .iter()
            .map(|s| points(self.table, &self.x, s, metric))
            .collect();
        let (title, unit) = describe(metric);
        // a title wider than the panel would run off the figure: the measure's words alone,
        // else its column name
        let width = i64::from(area.dim_in_pixel().0) - 28;
        let fits = |t: &str| {
            area.estimate_text_size(t, &text(LABEL))
                .map_or(true, |(w, _)| i64::from(w) <= width)
        };
        let title = match title.split_once(": ") {
            Some(_) if fits(&title) => title,
            Some((_, what)) if fits(what) => what.to_string(),
            _ => metric.to_string(),
        };
        let (x_lo, x_hi) = self.x_range();
        let (y_lo, y_hi) = y_range(lines.iter().flatten(), metric);
        let mut chart: Chart2d<DB> = ChartBuilder::on(area)
            .caption(title, text(LABEL))
            .margin(14)
            .margin_right(26)
            .x_label_area_size(64)
            .y_label_area_size(96)
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)?;
        let values = &self.x.values;
        let x_label = |v: &f64| {
            let i = v.round();
            let near = (v - i).abs() < 1e-6 && i >= 0.0;
            if self.x.categorical {
                match values.get(i as usize) {
                    Some(s) if near => s.clone(),
                    _ => String::new(),
                }
            } else if values.len() > 12
                || values
                    .iter()
                    .any(|s| s.parse::<f64>().is_ok_and(|x| (x - v).abs() < 1e-9))
            {
                style::tick(v)
            } else {
                String::new()
            }
        };
        let x_labels = if self.x.categorical {
            values.len() + 1
        } else {
            40
        };
        chart
            .configure_mesh()
            .disable_x_mesh()
            // x labels only at the key's values: no marks at the unlabelled ticks
            .set_tick_mark_size(LabelAreaPosition::Bottom, 0)
            .x_desc(self.x.key.as_str())
            .y_desc(unit)
            .axis_desc_style(text(LABEL))
            .label_style(text(TICK))
            .light_line_style(TRANSPARENT)
            .bold_line_style(RGBColor(215, 215, 215))
            .x_labels(x_labels)
            .y_labels(8)
            .x_label_formatter(&x_label)
            .y_label_formatter(&|y| style::tick(y))
            .draw()?;
        for (i, pts) in lines.iter().enumerate() {
            self.line(&mut chart, pts, LINES[i])?;
        }
        if lines.iter().all(Vec::is_empty) {
            let style = text(TICK)
                .color(&KEY)
                .pos(Pos::new(HPos::Center, VPos::Center));
            let mid = (0.5 * (x_lo + x_hi), 0.5 * (y_lo + y_hi));
            chart
                .plotting_area()
                .draw(&Text::new("no run has this measure", mid, style))?;
        }
        Ok(())
    }

    /// One line: its bands, then the medians.
    fn line<DB: DrawingBackend>(
        &self,
        chart: &mut Chart2d<DB>,
        pts: &[Point],
        c: RGBColor,
    ) -> DrawResult<DB> {
        let band = |lo: fn(&Point) -> f64, hi: fn(&Point) -> f64| -> Vec<(f64, f64)> {
            let upper = pts.iter().map(|p| (p.x, hi(p)));
            let lower = pts.iter().rev().map(|p| (p.x, lo(p)));
            upper.chain(lower).collect()
        };
        if pts.len() >= 2 {
            let extremes = band(|p| p.min, |p| p.max);
            let quartiles = band(|p| p.q1, |p| p.q3);
            chart.draw_series(std::iter::once(Polygon::new(
                extremes,
                c.mix(EXTREMES).filled(),
            )))?;
            chart.draw_series(std::iter::once(Polygon::new(
                quartiles,
                c.mix(QUARTILES).filled(),
            )))?;
        } else if let Some(p) = pts.first() {
            // one value: the bands as bars
            let bar = |lo: f64, hi: f64, alpha: f64, w: u32| {
                PathElement::new(vec![(p.x, lo), (p.x, hi)], c.mix(alpha).stroke_width(w))
            };
            chart.draw_series([
                bar(p.min, p.max, 2.0 * EXTREMES, 18),
                bar(p.q1, p.q3, QUARTILES, 18),
            ])?;
        }
        let medians: Vec<(f64, f64)> = pts.iter().map(|p| (p.x, p.median)).collect();
        chart.draw_series(LineSeries::new(medians.clone(), c.stroke_width(3)))?;
        chart.draw_series(medians.into_iter().map(|m| Circle::new(m, 5, c.filled())))?;
        Ok(())
    }

    /// The x range: the values' with a margin, or one slot per category.
    fn x_range(&self) -> (f64, f64) {
        if self.x.categorical {
            return (-0.5, self.x.values.len() as f64 - 0.5);
        }
        let xs: Vec<f64> = self
            .x
            .values
            .iter()
            .filter_map(|v| v.parse().ok())
            .collect();
        let (lo, hi) = xs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        if !lo.is_finite() {
            return (0.0, 1.0);
        }
        let pad = if hi > lo { 0.08 * (hi - lo) } else { 1.0 };
        (lo - pad, hi + pad)
    }
}

/// The y range of `pts` (their extremes) with a margin; a fraction's from 0 to just over 1.
fn y_range<'p>(pts: impl Iterator<Item = &'p Point>, metric: &str) -> (f64, f64) {
    let (lo, hi) = pts.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.min), b.max(p.max))
    });
    if metric.ends_with("fraction") && lo >= 0.0 && hi <= 1.0 {
        return (0.0, 1.05);
    }
    if !lo.is_finite() {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    let pad = if span > 0.0 {
        0.08 * span
    } else {
        0.1 * lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}
