//! What the top views draw over the floor: paths with their start, end and window-start
//! markers, Step 2's links, and the depth colour bar beside the map.

use super::canvas::{Area, DrawResult};
use super::map::Chart2d;
use super::raster::{depth_colour, rgb, whiten};
use super::scene::{Scene, Stage};
use super::style::{outline, text, tick, vehicle_colour, Swatch, A2A, A2U, LABEL, TICK};
use crate::seafloor::Seafloor;
use plotters::prelude::*;

type Xy = (f64, f64);

/// A marker at a data point, outlined in black (a ring has no fill).
pub(crate) fn marker<DB: DrawingBackend>(
    chart: &Chart2d<'_, DB>,
    s: Swatch,
    at: (f64, f64),
) -> DrawResult<DB> {
    let area = chart.plotting_area();
    let e = EmptyElement::at(at);
    match s {
        Swatch::Square(c) => area.draw(
            &(e + Rectangle::new([(-7, -7), (7, 7)], c.filled())
                + Rectangle::new([(-7, -7), (7, 7)], BLACK.stroke_width(1))),
        ),
        Swatch::Ring(c) => area.draw(&(e + Circle::new((0, 0), 8, c.stroke_width(3)))),
        Swatch::Dot(c) | Swatch::Line(c, _) | Swatch::Dashed(c, _) => area.draw(
            &(e + Circle::new((0, 0), 7, c.filled())
                + Circle::new((0, 0), 7, BLACK.stroke_width(1))),
        ),
        Swatch::Area(_) | Swatch::Link(_) => Ok(()),
    }
}

/// Every vehicle's path of `stage` across the windows, with start (dot), end (square) and
/// window starts (rings).
pub(crate) fn paths<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    scene: &Scene,
    stage: Stage,
    width: u32,
) -> DrawResult<DB> {
    let k = scene.plan.scenario.horizon.steps;
    let windows = scene.plan.windows.len();
    let mut all: Vec<(Option<usize>, Vec<Xy>)> = (0..scene.n)
        .map(|n| {
            let p = scene.auv_path(stage, n);
            (Some(n), p.iter().map(|q| (q[0], q[1])).collect())
        })
        .collect();
    let usv = scene.usv_path(stage).iter().map(|q| (q[0], q[1])).collect();
    all.push((None, usv));
    for (v, p) in &all {
        let c = vehicle_colour(*v);
        chart.draw_series(LineSeries::new(p.iter().copied(), c.stroke_width(width)))?;
    }
    for (v, p) in &all {
        let c = vehicle_colour(*v);
        for w in 1..windows {
            if let Some(&q) = p.get(w * k) {
                marker(chart, Swatch::Ring(c), q)?;
            }
        }
        if let (Some(&a), Some(&b)) = (p.first(), p.last()) {
            marker(chart, Swatch::Dot(c), a)?;
            marker(chart, Swatch::Square(c), b)?;
        }
    }
    Ok(())
}

/// Step 2's links at every step, over the Step 1 positions they were chosen from: A2U light
/// blue, A2A yellow, each over a dark outline.
pub(crate) fn links<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    scene: &Scene,
) -> DrawResult<DB> {
    let mut segs = Vec::new();
    for (&(w, k, _), links) in scene.steps.iter().zip(scene.graph_links()) {
        let st = scene.stage(w, Stage::Step1);
        for l in links {
            let a = st.auvs[l.a].position[k];
            let b = match l.b {
                Some(b) => st.auvs[b].position[k],
                None => {
                    let u = st.usv.position[k];
                    [u[0], u[1], 0.0]
                }
            };
            let c = if l.b.is_some() { A2A } else { A2U };
            segs.push((c, (a[0], a[1]), (b[0], b[1])));
        }
    }
    for (w, col) in [(4, true), (2, false)] {
        chart.draw_series(segs.iter().map(|&(c, a, b)| {
            let c = if col { outline(c) } else { c };
            PathElement::new(vec![a, b], c.stroke_width(w))
        }))?;
    }
    Ok(())
}

/// The depth colour bar in `area`, aligned with a map drawn with the same margins.
pub(crate) fn colour_bar<DB: DrawingBackend>(
    area: &Area<DB>,
    floor: &Seafloor,
    muted: bool,
    margin: u32,
    x_area: u32,
) -> DrawResult<DB> {
    let (lo, hi) = floor.z_range();
    let (lo, hi) = if hi > lo {
        (lo, hi)
    } else {
        (lo - 1.0, hi + 1.0)
    };
    let mut chart = ChartBuilder::on(area)
        .margin_top(margin)
        .margin_bottom(margin)
        .margin_left(16)
        .margin_right(20)
        .x_label_area_size(x_area)
        .right_y_label_area_size(120)
        .build_cartesian_2d(0.0..1.0, lo..hi)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc("floor elevation z (m)")
        .axis_desc_style(text(LABEL))
        .label_style(text(TICK))
        .y_labels(8)
        .y_label_formatter(&tick)
        .draw()?;
    let n = 150;
    chart.draw_series((0..n).map(|i| {
        let z0 = lo + (hi - lo) * i as f64 / n as f64;
        let z1 = lo + (hi - lo) * (i + 1) as f64 / n as f64;
        let c = depth_colour(0.5 * (z0 + z1), (lo, hi));
        let c = if muted { whiten(c, 0.5) } else { c };
        Rectangle::new([(0.0, z0), (1.0, z1)], rgb(c).filled())
    }))?;
    chart.draw_series(std::iter::once(Rectangle::new(
        [(0.0, lo), (1.0, hi)],
        BLACK.stroke_width(1),
    )))?;
    Ok(())
}
