//! What a panel draws besides its runs and medians: the lines between N slots and between
//! scenarios with the scenarios' names, the paper's 300 s reference line of the RRT-like
//! planner with its label placed clear of the points, and under each slot of the wall-time panel
//! the count of runs that made no plan.

use super::axis::Axis;
use super::metric::Metric;
use super::runs::Status;
use super::{Compare, DOT, GROUP_LINE, PAPER_LABEL, PAPER_RRT_S, SLOT_LINE};
use crate::figures::canvas::DrawResult;
use crate::figures::map::Chart2d;
use crate::figures::style::{self, text, TICK};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

impl Compare {
    /// Light lines between N slots, darker ones between scenarios, and the scenarios' names.
    pub(super) fn separators<DB: DrawingBackend>(
        &self,
        chart: &mut Chart2d<'_, DB>,
        axis: &Axis,
    ) -> DrawResult<DB> {
        for (i, pair) in self.slots.windows(2).enumerate() {
            let x = i as f64 + 0.5;
            let (c, w) = if pair[0].scenario != pair[1].scenario {
                (GROUP_LINE, 2)
            } else {
                (SLOT_LINE, 1)
            };
            chart.draw_series(std::iter::once(PathElement::new(
                vec![(x, axis.lo), (x, axis.hi)],
                c.stroke_width(w),
            )))?;
        }
        if self.scenarios.len() < 2 {
            return Ok(());
        }
        for (s, name) in self.scenarios.iter().enumerate() {
            let mine: Vec<usize> = (0..self.slots.len())
                .filter(|&i| self.slots[i].scenario == s)
                .collect();
            let (Some(&a), Some(&b)) = (mine.first(), mine.last()) else {
                continue;
            };
            let style = text(TICK)
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Top));
            let at = (0.5 * (a + b) as f64, axis.hi);
            chart
                .plotting_area()
                .draw(&(EmptyElement::at(at) + Text::new(name.clone(), (0, 6), style)))?;
        }
        Ok(())
    }

    /// The paper's 300 s of the RRT-like planner for one AUV: a dashed line, labelled above or
    /// below it, at its right or left end or in the middle, wherever the label covers the fewest
    /// points of the panel.
    pub(super) fn reference<DB: DrawingBackend>(
        &self,
        chart: &mut Chart2d<'_, DB>,
        metric: Metric,
        x_max: f64,
    ) -> DrawResult<DB> {
        let y = PAPER_RRT_S.log10();
        chart.draw_series(std::iter::once(plotters::element::DashedPathElement::new(
            vec![(-0.5, y), (x_max, y)],
            12,
            7,
            style::LIMIT.stroke_width(3),
        )))?;
        let font = text(TICK);
        let w = font.font.box_size(PAPER_LABEL).map_or(300, |b| b.0 as i32);
        let h = TICK as i32;
        let points: Vec<(i32, i32)> = self
            .points(metric)
            .map(|(run, y)| chart.backend_coord(&(self.x(run), y)))
            .collect();
        // Candidates: anchor (data), the label box relative to it (pixels), in order of
        // preference; below the line first, clear of the scenario names along the top.
        let mid = 0.5 * (x_max - 0.5);
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        let mut best: Option<(usize, (f64, [i32; 2]))> = None;
        for (x, dx) in [(x_max, -w - 10), (-0.5, 10), (mid, -w / 2)] {
            for dy in [6, -h - 6] {
                let a = chart.backend_coord(&(x, y));
                let (x0, y0) = (a.0 + dx - 4, a.1 + dy - 2);
                let (x1, y1) = (x0 + w + 8, y0 + h + 4);
                if x0 < xs.start || x1 > xs.end || y0 < ys.start || y1 > ys.end {
                    continue;
                }
                let r = DOT + 1;
                let covered = points
                    .iter()
                    .filter(|p| p.0 + r >= x0 && p.0 - r <= x1 && p.1 + r >= y0 && p.1 - r <= y1)
                    .count();
                if best.as_ref().map_or(usize::MAX, |b| b.0) > covered {
                    best = Some((covered, (x, [dx, dy])));
                }
            }
        }
        let (x, [dx, dy]) = best.map_or((x_max, [-w - 10, -h - 6]), |b| b.1);
        let style = font
            .color(&style::LIMIT)
            .pos(Pos::new(HPos::Left, VPos::Top));
        chart.plotting_area().draw(
            &(EmptyElement::at((x, y))
                + Rectangle::new(
                    [(dx - 4, dy - 2), (dx + w + 4, dy + h + 2)],
                    WHITE.mix(0.85).filled(),
                )
                + Text::new(PAPER_LABEL, (dx, dy), style)),
        )
    }

    /// Under each slot of the wall-time panel, in each method's colour: how many of its runs made
    /// no plan ("2 no plan", or "2" where that does not fit).
    pub(super) fn failure_counts<DB: DrawingBackend>(
        &self,
        chart: &mut Chart2d<'_, DB>,
        axis: &Axis,
    ) -> DrawResult<DB> {
        let font = text(TICK - 3);
        let px = |x: f64| chart.backend_coord(&(x, axis.lo)).0;
        for slot in 0..self.slots.len() {
            let failed: Vec<(usize, usize)> = (0..self.methods.len())
                .map(|m| {
                    let n = self
                        .runs
                        .iter()
                        .filter(|r| r.slot == slot && r.method == m && r.status == Status::Failed);
                    (m, n.count())
                })
                .filter(|&(_, n)| n > 0)
                .collect();
            // The labels share the slot; each is centred on its method's place, kept inside
            // the slot.
            let (left, right) = (px(slot as f64 - 0.5), px(slot as f64 + 0.5));
            let room = (right - left) / failed.len().max(1) as i32;
            for &(m, n) in &failed {
                let full = format!("{n} no plan");
                let width = |s: &str| font.font.box_size(s).map_or(room, |b| b.0 as i32);
                let label = if width(&full) + 6 <= room {
                    full
                } else {
                    n.to_string()
                };
                let w = width(&label);
                let centre = self.place(slot, m).0;
                let c = px(centre);
                let (l, r) = (c - w / 2 - 3, c + w / 2 + 3);
                let shift = if failed.len() > 1 {
                    0
                } else if l < left {
                    left - l
                } else if r > right {
                    right - r
                } else {
                    0
                };
                let colour = style::outline(self.methods[m].colour);
                let style = font
                    .clone()
                    .color(&colour)
                    .pos(Pos::new(HPos::Center, VPos::Bottom));
                chart.plotting_area().draw(
                    &(EmptyElement::at((centre, axis.lo)) + Text::new(label, (shift, -6), style)),
                )?;
            }
        }
        Ok(())
    }
}
