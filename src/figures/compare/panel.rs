//! Drawing one panel: its chart and mesh (slot labels on x; decades on a log y axis), then the
//! grid, separators and reference line ([`super::annotations`]), the lines through the medians,
//! one marker per run (filled dot: passed; ring: violated; square: no plan), the median bars,
//! the failure counts, and a note on measures a log scale cannot show.

use super::axis::{log_grid, power_of_ten};
use super::metric::Metric;
use super::runs::Status;
use super::{Compare, DOT, KEY};
use crate::figures::canvas::{Area, DrawResult};
use crate::figures::map::Chart2d;
use crate::figures::style::{self, text, LABEL, TICK};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

impl Compare {
    pub(super) fn panel<DB: DrawingBackend>(
        &self,
        area: &Area<DB>,
        metric: Metric,
    ) -> DrawResult<DB> {
        let axis = &self.axes[Self::index(metric)];
        let x_max = self.slots.len() as f64 - 0.5;
        let mut chart: Chart2d<DB> = ChartBuilder::on(area)
            .caption(metric.caption(), text(LABEL))
            .margin(14)
            .margin_right(30)
            .x_label_area_size(70)
            .y_label_area_size(110)
            .build_cartesian_2d(-0.5..x_max, axis.lo..axis.hi)?;
        let x_label = |x: &f64| {
            let i = x.round();
            match self.slots.get(i as usize) {
                Some(s) if (x - i).abs() < 1e-6 && i >= 0.0 => s.auvs.to_string(),
                _ => String::new(),
            }
        };
        let y_label = |y: &f64| {
            if metric.log() {
                power_of_ten(*y)
            } else {
                style::tick(y)
            }
        };
        let x_desc = if self.scenarios.len() > 1 {
            "team size N, by scenario"
        } else {
            "team size N"
        };
        let mut mesh = chart.configure_mesh();
        mesh.disable_x_mesh();
        if metric.log() {
            mesh.disable_y_mesh();
        }
        mesh.x_desc(x_desc)
            .y_desc(metric.y_desc())
            .axis_desc_style(text(LABEL))
            .label_style(text(TICK))
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205))
            .x_labels(self.slots.len())
            .y_labels(axis.labels)
            .x_label_formatter(&x_label)
            .y_label_formatter(&y_label)
            .draw()?;
        if metric.log() {
            log_grid(&mut chart, axis, x_max)?;
        }
        self.separators(&mut chart, axis)?;
        if metric == Metric::Wall {
            self.reference(&mut chart, metric, x_max)?;
        }

        let i = Self::index(metric);
        // The medians over seeds, per scenario and method: a thin line through them, then a bar.
        let medians = self.medians(metric);
        for (s, _) in self.scenarios.iter().enumerate() {
            for (m, method) in self.methods.iter().enumerate() {
                let line: Vec<(f64, f64)> = medians
                    .iter()
                    .filter(|&&(slot, mm, _)| self.slots[slot].scenario == s && mm == m)
                    .map(|&(slot, _, y)| (self.place(slot, m).0, y))
                    .collect();
                let style = method.colour.mix(0.55).stroke_width(2);
                chart.draw_series(LineSeries::new(line, style))?;
            }
        }

        for (run, y) in self.points(metric) {
            let x = self.x(run);
            let c = self.methods[run.method].colour;
            let at = EmptyElement::at((x, y));
            match run.status {
                Status::Passed => chart.plotting_area().draw(
                    &(at + Circle::new((0, 0), DOT, c.mix(0.85).filled())
                        + Circle::new((0, 0), DOT, style::outline(c).stroke_width(1))),
                )?,
                Status::Violated => chart.plotting_area().draw(
                    &(at + Circle::new((0, 0), DOT, WHITE.filled())
                        + Circle::new((0, 0), DOT, c.stroke_width(2))),
                )?,
                Status::Failed => chart.plotting_area().draw(
                    &(at + Rectangle::new([(-4, -4), (4, 4)], c.mix(0.85).filled())
                        + Rectangle::new([(-4, -4), (4, 4)], style::outline(c).stroke_width(1))),
                )?,
            }
        }

        for &(slot, m, y) in &medians {
            let (centre, band) = self.place(slot, m);
            let (a, b) = (centre - 0.42 * band, centre + 0.42 * band);
            let c = self.methods[m].colour;
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(a, y), (b, y)],
                style::outline(c).stroke_width(4),
            )))?;
        }

        if self.counts_failures(metric) {
            self.failure_counts(&mut chart, axis)?;
        }
        // Measures a log scale cannot show (zero or negative): say so.
        let hidden = self
            .runs
            .iter()
            .filter(|r| Self::shown(r, metric) && r.values[i].is_finite())
            .filter(|r| metric.plotted(r.values[i]).is_none())
            .count();
        if self.points(metric).next().is_none() {
            let note = if hidden > 0 {
                "no value above 0 to show on a log scale"
            } else {
                "no run has this measure"
            };
            let style = text(TICK)
                .color(&KEY)
                .pos(Pos::new(HPos::Center, VPos::Center));
            let mid = (x_max / 2.0 - 0.25, 0.5 * (axis.lo + axis.hi));
            chart.plotting_area().draw(&Text::new(note, mid, style))?;
        } else if hidden > 0 {
            let style = text(TICK - 3)
                .color(&KEY)
                .pos(Pos::new(HPos::Left, VPos::Top));
            let note = format!("{hidden} at ≤ 0 not shown (log scale)");
            chart
                .plotting_area()
                .draw(&(EmptyElement::at((-0.5, axis.hi)) + Text::new(note, (6, 6), style)))?;
        }
        Ok(())
    }
}
