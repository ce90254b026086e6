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
//!
//! This module holds the public API, the figure's sizes and colours and its top-level draw; the
//! rest is split by what it does: [`metric`] (the four measures), [`runs`] (rows into methods,
//! slots, runs and medians), [`axis`] (the y axes and log-scale ticks), [`legend`], [`panel`]
//! (drawing one panel) and [`annotations`] (separators, the paper's reference line, failure
//! counts).

mod annotations;
mod axis;
mod legend;
mod metric;
mod panel;
mod runs;
#[cfg(test)]
mod tests;

use super::canvas::{self, Area, DrawResult, Figure, Images};
use super::style::Frame;
use super::FigureError;
use crate::compare::Row;
use axis::Axis;
use metric::METRICS;
use plotters::prelude::*;
use runs::{Method, Run, Slot};
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
const MPC: RGBColor = super::style::SERIES[0];
const RRT_LIKE: RGBColor = super::style::SERIES[1];
const FURTHER: [RGBColor; 6] = [
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x12, 0x9e, 0xad),
];
/// The legend's neutral colour for marker kinds.
const KEY: RGBColor = super::style::KEY_GREY;
/// Slot and group separators.
const SLOT_LINE: RGBColor = RGBColor(235, 235, 235);
const GROUP_LINE: RGBColor = RGBColor(150, 150, 150);

/// Width of an N slot taken by the methods (the slot is 1 wide).
const SLOT_USED: f64 = 0.8;
/// Point radius, pixels.
const DOT: i32 = 5;

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
