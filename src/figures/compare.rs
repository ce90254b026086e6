//! The figure of `shoal compare` ([`Row`]s): the paper's Fig. 6 comparison, measured. Four
//! panels against the team size N: (a) wall time per plan (log scale, with the paper's "> 300 s
//! for one AUV" of the sampling planner as a dashed line), (b) mean height above the floor
//! (OF1_2: lower hugs the floor), (c) explored area at survey altitude, (d) input energy Σ‖U‖²
//! (OF1_1, log scale).
//!
//! One colour per method (MPC blue, RRT-like orange, any other from a further palette); in
//! each N slot the methods sit side by side, one point per run jittered by its seed (filled:
//! the check passes; hollow: it fails), a bar at the median over the seeds and a thin line
//! through the medians. Runs that made no plan have no measures: the legend counts them, and
//! the wall-time panel shows the time they took to give up (squares, with their count per
//! slot). With several scenarios the slots are grouped by scenario, named above each group.
//!
//! The frame (title and legend), fonts and axis styling are the plan figures' ([`super::style`]).

use super::canvas::{self, Area, DrawResult, Figure, Images};
use super::map::Chart2d;
use super::style::{self, text, Entry, Frame, Swatch, LABEL, TICK};
use super::FigureError;
use crate::compare::Row;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::{Path, PathBuf};

/// The file stem of the comparison figure: `compare.png` and `compare.svg`.
pub const COMPARE_FIGURE: &str = "compare";

/// Draw the comparison of `rows` (one per run of `shoal compare`) under `title` as
/// `dir/compare.png` and `dir/compare.svg` (creating `dir` if needed, each file written
/// atomically); returns both paths. Fails with [`FigureError::Compare`] when there are no rows
/// or no run made a plan.
pub fn write_compare(rows: &[Row], title: &str, dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    let fig = Compare::new(rows, title)?;
    canvas::write(&fig, dir)
}

const WIDTH: u32 = 1280;
/// Height of each of the two rows of panels.
const PANEL_H: u32 = 520;
/// The paper's wall time of its RRT-like planner for one AUV (Section V): "more than 300 s".
const PAPER_RRT_S: f64 = 300.0;
const PAPER_LABEL: &str = "paper: RRT-like > 300 s (N = 1)";

/// Method colours: MPC, RRT-like, then any other method in order of appearance.
const MPC: RGBColor = RGBColor(0x1f, 0x77, 0xb4);
const RRT_LIKE: RGBColor = RGBColor(0xf0, 0x7a, 0x0a);
const FURTHER: [RGBColor; 6] = [
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x12, 0x9e, 0xad),
];
/// The legend's neutral colour for marker kinds.
const KEY: RGBColor = RGBColor(0x5a, 0x5a, 0x5a);
/// Slot and group separators.
const SLOT_LINE: RGBColor = RGBColor(235, 235, 235);
const GROUP_LINE: RGBColor = RGBColor(150, 150, 150);

/// Width of an N slot taken by the methods (the slot is 1 wide).
const SLOT_USED: f64 = 0.8;
/// Point radius, pixels.
const DOT: i32 = 5;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Status {
    Passed,
    Violated,
    Failed,
}

/// A panel's measure.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Metric {
    Wall,
    Height,
    Area,
    Energy,
}

const METRICS: [Metric; 4] = [Metric::Wall, Metric::Height, Metric::Area, Metric::Energy];

impl Metric {
    fn value(self, r: &Row) -> f64 {
        match self {
            Metric::Wall => r.wall_s,
            Metric::Height => r.mean_height_m,
            Metric::Area => r.explored_km2,
            Metric::Energy => r.energy,
        }
    }

    fn log(self) -> bool {
        matches!(self, Metric::Wall | Metric::Energy)
    }

    fn caption(self) -> &'static str {
        match self {
            Metric::Wall => "(a) Wall time per plan",
            Metric::Height => "(b) Mean height above the floor (OF1_2: lower)",
            Metric::Area => "(c) Explored area at survey altitude",
            Metric::Energy => "(d) Input energy Σ‖U‖² (OF1_1: lower)",
        }
    }

    fn y_desc(self) -> &'static str {
        match self {
            Metric::Wall => "wall time (s, log scale)",
            Metric::Height => "mean height (m)",
            Metric::Area => "explored area (km²)",
            Metric::Energy => "Σ‖U‖² ((m/s²)², log scale)",
        }
    }

    /// The value as plotted: log10 on a log panel; `None` when it cannot be shown.
    fn plotted(self, v: f64) -> Option<f64> {
        match (v.is_finite(), self.log()) {
            (false, _) => None,
            (true, true) => (v > 0.0).then(|| v.log10()),
            (true, false) => Some(v),
        }
    }
}

struct Method {
    name: String,
    colour: RGBColor,
}

/// An x position: one team size of one scenario.
struct Slot {
    scenario: usize,
    auvs: usize,
}

struct Run {
    slot: usize,
    method: usize,
    seed: u64,
    status: Status,
    /// The measures, in the order of [`METRICS`] (NaN when missing).
    values: [f64; 4],
}

/// A panel's y axis, in plotted units (log10 on a log panel).
struct Axis {
    lo: f64,
    hi: f64,
    labels: usize,
}

/// The comparison figure.
struct Compare {
    frame: Frame,
    methods: Vec<Method>,
    scenarios: Vec<String>,
    slots: Vec<Slot>,
    runs: Vec<Run>,
    /// Per metric.
    axes: Vec<Axis>,
}

impl Compare {
    fn new(rows: &[Row], title: &str) -> Result<Compare, FigureError> {
        let bad = |why: String| Err(FigureError::Compare(why));
        if rows.is_empty() {
            return bad("there are no runs to plot".into());
        }
        if rows.iter().all(|r| !r.planned()) {
            return bad(format!(
                "none of the {} runs made a plan, so there is nothing to measure",
                rows.len()
            ));
        }

        // Methods: MPC, RRT-like, then the others in order of appearance.
        let mut names: Vec<&str> = Vec::new();
        for r in rows {
            if !names.contains(&r.method.as_str()) {
                names.push(&r.method);
            }
        }
        let rank = |m: &str| match m {
            crate::plan::METHOD_MPC => 0,
            crate::plan::METHOD_RRT_LIKE => 1,
            _ => 2,
        };
        names.sort_by_key(|m| rank(m)); // stable: the others keep their order
        let mut further = FURTHER.iter().cycle();
        let methods: Vec<Method> = names
            .iter()
            .map(|&m| Method {
                name: m.to_string(),
                colour: match rank(m) {
                    0 => MPC,
                    1 => RRT_LIKE,
                    _ => *further.next().unwrap_or(&FURTHER[0]),
                },
            })
            .collect();

        // Slots: per scenario (in order of appearance), its team sizes in increasing order.
        let mut scenarios: Vec<String> = Vec::new();
        for r in rows {
            if !scenarios.contains(&r.scenario) {
                scenarios.push(r.scenario.clone());
            }
        }
        let mut slots = Vec::new();
        for (s, name) in scenarios.iter().enumerate() {
            let mut sizes: Vec<usize> = rows
                .iter()
                .filter(|r| &r.scenario == name)
                .map(|r| r.auvs)
                .collect();
            sizes.sort_unstable();
            sizes.dedup();
            slots.extend(sizes.into_iter().map(|auvs| Slot { scenario: s, auvs }));
        }

        let runs: Vec<Run> = rows
            .iter()
            .map(|r| Run {
                slot: slots
                    .iter()
                    .position(|s| scenarios[s.scenario] == r.scenario && s.auvs == r.auvs)
                    .unwrap_or(0),
                method: names.iter().position(|&m| m == r.method).unwrap_or(0),
                seed: r.seed,
                status: match r.status.as_str() {
                    "failed" => Status::Failed,
                    "violated" => Status::Violated,
                    _ => Status::Passed,
                },
                values: METRICS.map(|m| m.value(r)),
            })
            .collect();

        let mut entries = Vec::new();
        for (i, m) in methods.iter().enumerate() {
            let of = runs.iter().filter(|r| r.method == i);
            let count = |s: Status| of.clone().filter(|r| r.status == s).count();
            let mut label = format!("{}: {} runs", m.name, of.clone().count());
            let (violated, failed) = (count(Status::Violated), count(Status::Failed));
            if violated > 0 {
                label.push_str(&format!(", {violated} violated"));
            }
            if failed > 0 {
                label.push_str(&format!(", {failed} made no plan"));
            }
            entries.push(Entry::new(label, Swatch::Dot(m.colour)));
        }
        entries.push(Entry::new("check passed", Swatch::Dot(KEY)));
        if runs.iter().any(|r| r.status == Status::Violated) {
            entries.push(Entry::new("check violated", Swatch::Ring(KEY)));
        }
        if runs.iter().any(|r| r.status == Status::Failed) {
            entries.push(Entry::new(
                "no plan: time to give up (a), count at its foot",
                Swatch::Square(KEY),
            ));
        }
        entries.push(Entry::new("median over seeds", Swatch::Line(KEY, 4)));
        entries.push(Entry::new(PAPER_LABEL, Swatch::Dashed(style::LIMIT, 3)));

        let mut fig = Compare {
            frame: Frame::new(title.to_string(), entries, WIDTH),
            methods,
            scenarios,
            slots,
            runs,
            axes: Vec::new(),
        };
        fig.axes = METRICS.iter().map(|&m| fig.axis(m)).collect();
        Ok(fig)
    }

    /// Index of `metric` in [`METRICS`].
    fn index(metric: Metric) -> usize {
        METRICS.iter().position(|&m| m == metric).unwrap_or(0)
    }

    /// Whether a run is drawn in `metric`'s panel: runs with a plan, and in the wall-time panel
    /// also those without (the time they took to give up).
    fn shown(run: &Run, metric: Metric) -> bool {
        run.status != Status::Failed || metric == Metric::Wall
    }

    /// The plotted values of `metric`'s panel: (run, y).
    fn points(&self, metric: Metric) -> impl Iterator<Item = (&Run, f64)> + '_ {
        let i = Self::index(metric);
        self.runs
            .iter()
            .filter(move |r| Self::shown(r, metric))
            .filter_map(move |r| metric.plotted(r.values[i]).map(|y| (r, y)))
    }

    /// Whether the wall-time panel counts runs without a plan under its slots.
    fn counts_failures(&self, metric: Metric) -> bool {
        metric == Metric::Wall && self.runs.iter().any(|r| r.status == Status::Failed)
    }

    fn axis(&self, metric: Metric) -> Axis {
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

    /// Centre of `method`'s place in `slot`, and its width.
    fn place(&self, slot: usize, method: usize) -> (f64, f64) {
        let band = SLOT_USED / self.methods.len() as f64;
        (
            slot as f64 - SLOT_USED / 2.0 + (method as f64 + 0.5) * band,
            band,
        )
    }

    /// A run's x: its place in its slot, jittered by its seed.
    fn x(&self, run: &Run) -> f64 {
        let (centre, band) = self.place(run.slot, run.method);
        centre + 0.6 * band * jitter(run.seed)
    }

    fn panel<DB: DrawingBackend>(&self, area: &Area<DB>, metric: Metric) -> DrawResult<DB> {
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
        let mut medians = Vec::new();
        for slot in 0..self.slots.len() {
            for method in 0..self.methods.len() {
                let mut vs: Vec<f64> = self
                    .runs
                    .iter()
                    .filter(|r| r.slot == slot && r.method == method)
                    .filter(|r| r.status != Status::Failed)
                    .map(|r| r.values[i])
                    .filter(|v| metric.plotted(*v).is_some())
                    .collect();
                if let Some(y) = median(&mut vs).and_then(|v| metric.plotted(v)) {
                    medians.push((slot, method, y));
                }
            }
        }
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

    /// Light lines between N slots, darker ones between scenarios, and the scenarios' names.
    fn separators<DB: DrawingBackend>(
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
    fn reference<DB: DrawingBackend>(
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
        // preference.
        let mid = 0.5 * (x_max - 0.5);
        let (xs, ys) = chart.plotting_area().get_pixel_range();
        let mut best: Option<(usize, (f64, [i32; 2]))> = None;
        for (x, dx) in [(x_max, -w - 10), (-0.5, 10), (mid, -w / 2)] {
            for dy in [-h - 6, 6] {
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
    fn failure_counts<DB: DrawingBackend>(
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

impl Figure for Compare {
    fn name(&self) -> &'static str {
        COMPARE_FIGURE
    }

    fn size(&self) -> (u32, u32) {
        (WIDTH, self.frame.height() + 2 * PANEL_H + 10)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let (body, _) = body.split_vertically(2 * PANEL_H);
        let panels = body.split_evenly((2, 2));
        for (area, &metric) in panels.iter().zip(METRICS.iter()) {
            self.panel(area, metric)?;
        }
        Ok(())
    }
}

/// Decade lines (darker) and the 2…9 lines between them (lighter, when there are few decades)
/// of a log panel.
fn log_grid<DB: DrawingBackend>(
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
fn power_of_ten(e: f64) -> String {
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

/// The median of `vs` (finite values), if any.
fn median(vs: &mut [f64]) -> Option<f64> {
    if vs.is_empty() {
        return None;
    }
    vs.sort_by(f64::total_cmp);
    let n = vs.len();
    Some(if n % 2 == 1 {
        vs[n / 2]
    } else {
        0.5 * (vs[n / 2 - 1] + vs[n / 2])
    })
}

/// A run's offset within its place, in [−0.5, 0.5): the fractional part of seed × the golden
/// ratio, so that consecutive seeds spread evenly and the same seed always lands in the same
/// spot.
fn jitter(seed: u64) -> f64 {
    ((seed % 1_000_003) as f64 * 0.618_033_988_749_895).fract() - 0.5
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run with a plan.
    fn run(method: &str, auvs: usize, seed: u64, status: &str, wall_s: f64) -> Row {
        let mut r = Row::key("default", method, auvs, seed);
        r.status = status.into();
        r.wall_s = wall_s;
        let k = seed as f64;
        r.energy = 0.02 * (auvs as f64) * (1.0 + 0.1 * k);
        r.mean_height_m = if method == "mpc" {
            12.0 + k
        } else {
            40.0 + 2.0 * k
        };
        r.explored_km2 = 0.1 * auvs as f64 + 0.01 * k;
        r.usv_moved_m = 100.0 + k;
        r
    }

    /// Twelve runs: two methods, N = 1 and 3, one violated and one failed.
    fn rows() -> Vec<Row> {
        let mut rows = Vec::new();
        for seed in 1..=3 {
            rows.push(run("mpc", 1, seed, "passed", 2.0 + seed as f64));
            let status = if seed == 2 { "violated" } else { "passed" };
            rows.push(run("mpc", 3, seed, status, 10.0 + seed as f64));
            rows.push(run(
                "rrt-like",
                1,
                seed,
                "passed",
                200.0 + 60.0 * seed as f64,
            ));
            if seed == 3 {
                let mut r = Row::key("default", "rrt-like", 3, seed);
                r.status = "failed".into();
                r.error = "no tree reached the goal".into();
                r.wall_s = 600.0;
                rows.push(r);
            } else {
                rows.push(run("rrt-like", 3, seed, "passed", 400.0 + seed as f64));
            }
        }
        rows
    }

    const TITLE: &str = "MPC vs RRT-like, default scenario, seeds 1–3";

    #[test]
    fn writes_a_png_and_an_svg_with_the_title_and_every_method() {
        let rows = rows();
        assert_eq!(rows.len(), 12);
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("figs");
        let written = write_compare(&rows, TITLE, &out).unwrap();
        let png_path = out.join("compare.png");
        let svg_path = out.join("compare.svg");
        assert_eq!(written, vec![png_path.clone(), svg_path.clone()]);
        assert!(png_path.is_file() && svg_path.is_file());

        let bytes = std::fs::read(&png_path).unwrap();
        let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
            .read_info()
            .unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!(info.width, WIDTH);
        assert!(
            info.height >= 2 * PANEL_H && info.height <= 2 * PANEL_H + 400,
            "{}",
            info.height
        );
        let pixels = &buf[..info.buffer_size()];
        let inked = pixels.chunks(3).filter(|p| p != &[255, 255, 255]).count();
        assert!(inked * 50 > pixels.len() / 3, "the PNG is nearly blank");

        let svg = std::fs::read_to_string(&svg_path).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        assert_eq!(doc.root_element().tag_name().name(), "svg");
        let texts: Vec<&str> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .filter_map(|n| n.text())
            .map(str::trim)
            .collect();
        let all = texts.join("\n");
        assert!(texts.contains(&TITLE), "no title in {all}");
        for needle in [
            "mpc: 6 runs, 1 violated",
            "rrt-like: 6 runs, 1 made no plan",
            "1 no plan",
            PAPER_LABEL,
            "team size N",
            "wall time (s, log scale)",
            "explored area (km²)",
        ] {
            assert!(all.contains(needle), "no {needle:?} in {all}");
        }
        // log ticks: decades only
        assert!(texts.contains(&"100") && texts.contains(&"1000"), "{all}");
    }

    #[test]
    fn several_scenarios_are_grouped_and_named() {
        let mut rows = rows();
        rows.extend(rows.clone().into_iter().map(|mut r| {
            r.scenario = "ridge".into();
            r
        }));
        let fig = Compare::new(&rows, TITLE).unwrap();
        assert_eq!(fig.slots.len(), 4);
        assert_eq!(fig.scenarios, ["default", "ridge"]);
        let dir = tempfile::tempdir().unwrap();
        write_compare(&rows, TITLE, dir.path()).unwrap();
        let svg = std::fs::read_to_string(dir.path().join("compare.svg")).unwrap();
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let texts: Vec<&str> = doc
            .descendants()
            .filter_map(|n| n.text())
            .map(str::trim)
            .collect();
        for needle in ["default", "ridge", "team size N, by scenario"] {
            assert!(texts.contains(&needle), "no {needle:?} in {texts:?}");
        }
    }

    #[test]
    fn methods_take_fixed_colours_and_others_a_further_palette() {
        let mut rows = rows();
        let mut other = run("ompl-rrtstar", 1, 1, "passed", 50.0);
        other.scenario = "default".into();
        rows.insert(0, other);
        let fig = Compare::new(&rows, TITLE).unwrap();
        let names: Vec<&str> = fig.methods.iter().map(|m| m.name.as_str()).collect();
        assert_eq!(names, ["mpc", "rrt-like", "ompl-rrtstar"]);
        assert_eq!(fig.methods[0].colour, MPC);
        assert_eq!(fig.methods[1].colour, RRT_LIKE);
        assert_eq!(fig.methods[2].colour, FURTHER[0]);
    }

    #[test]
    fn no_rows_or_only_failed_runs_are_a_clear_error() {
        let dir = tempfile::tempdir().unwrap();
        let err = write_compare(&[], TITLE, dir.path()).unwrap_err();
        assert!(matches!(err, FigureError::Compare(_)), "{err}");
        assert!(err.to_string().contains("no runs"), "{err}");

        let failed: Vec<Row> = rows()
            .into_iter()
            .map(|mut r| {
                r.status = "failed".into();
                r
            })
            .collect();
        let err = write_compare(&failed, TITLE, dir.path()).unwrap_err();
        assert!(matches!(err, FigureError::Compare(_)), "{err}");
        assert!(err.to_string().contains("none of the 12 runs"), "{err}");
        assert!(!dir.path().join("compare.png").exists());
    }

    #[test]
    fn log_ticks_and_jitter() {
        assert_eq!(power_of_ten(2.0), "100");
        assert_eq!(power_of_ten(-2.0), "0.01");
        assert_eq!(power_of_ten(-5.0), "10⁻⁵");
        assert_eq!(power_of_ten(12.0), "10¹²");
        assert_eq!(power_of_ten(0.5), "");
        for seed in 0..100 {
            let j = jitter(seed);
            assert!((-0.5..0.5).contains(&j));
            assert_eq!(j, jitter(seed));
        }
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&mut [4.0, 1.0]), Some(2.5));
        assert_eq!(median(&mut []), None);
    }
}

#[cfg(test)]
mod tmp_render {
    use super::*;

    #[test]
    fn tmp_render_compare() {
        let mut rows = Vec::new();
        for &n in &[1usize, 3, 5] {
            for seed in 1..=10u64 {
                let k = seed as f64;
                let j = jitter(seed * 7 + n as u64);
                let mut m = Row::key("default", "mpc", n, seed);
                m.status = if seed == 4 && n == 5 {
                    "violated"
                } else {
                    "passed"
                }
                .into();
                m.wall_s = (3.0 + 2.0 * n as f64) * (1.0 + 0.3 * j);
                m.energy = 0.05 * n as f64 * (1.0 + 0.5 * j);
                m.mean_height_m = 14.0 + 3.0 * j + 0.5 * n as f64;
                m.explored_km2 = 0.12 * n as f64 * (1.0 + 0.2 * j);
                rows.push(m);
                let mut r = Row::key("default", "rrt-like", n, seed);
                if (n == 3 && seed % 5 == 0) || (n == 5 && seed % 3 == 0) {
                    r.status = "failed".into();
                    r.wall_s = 600.0;
                } else {
                    r.status = if seed == 2 { "violated" } else { "passed" }.into();
                    r.wall_s = (250.0 + 60.0 * n as f64) * (1.0 + 0.6 * j);
                    r.energy = 2.0 * n as f64 * (1.0 + 0.8 * j) + 0.1 * k;
                    r.mean_height_m = 45.0 + 15.0 * j + 2.0 * n as f64;
                    r.explored_km2 = 0.08 * n as f64 * (1.0 + 0.3 * j);
                }
                rows.push(r);
            }
        }
        write_compare(
            &rows,
            "MPC vs RRT-like, default scenario, seeds 1–10",
            Path::new("/work/compare-fig"),
        )
        .unwrap();
        let mut two = rows.clone();
        two.extend(rows.iter().cloned().map(|mut r| {
            r.scenario = "ridge".into();
            r.wall_s *= 1.5;
            r
        }));
        write_compare(
            &two,
            "MPC vs RRT-like, two scenarios, seeds 1–10",
            Path::new("/work/compare-fig/two"),
        )
        .unwrap();
        let mut edge = Vec::new();
        for seed in 1..=4u64 {
            let mut m = Row::key("default", "mpc", 1, seed);
            m.status = "passed".into();
            m.wall_s = 0.02 * seed as f64;
            m.energy = 0.0;
            m.mean_height_m = 10.0;
            m.explored_km2 = 0.1;
            edge.push(m);
            let mut o = Row::key("default", "ompl-rrtstar", 1, seed);
            o.status = "failed".into();
            o.wall_s = 30.0;
            edge.push(o);
        }
        write_compare(&edge, "edge", Path::new("/work/compare-fig/edge")).unwrap();
    }
}
