//! Top views: the seafloor alone (Fig. 4(a)), and the paths of Step 1 or of the final plan, or
//! Step 2's links, over it; x and y to the same scale, with contours and a depth colour bar.

use super::canvas::{Area, DrawResult, Figure, Images};
use super::overlay;
use super::raster::{self, Grid, View};
use super::scene::{Scene, Stage};
use super::style::{self, text, DrawErr, Entry, Frame, Swatch, LABEL, TICK};
use crate::seafloor::Seafloor;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// Layout of a top view, pixels: margin around the map, x and y label areas, colour bar.
pub(crate) const MARGIN: u32 = 20;
pub(crate) const X_AREA: u32 = 70;
pub(crate) const Y_AREA: u32 = 110;
pub(crate) const BAR: u32 = 215;
/// Largest and smallest plot area, pixels.
const MAX_PLOT: (f64, f64) = (980.0, 780.0);
const MIN_PLOT: (f64, f64) = (560.0, 380.0);

#[derive(Clone, Copy, PartialEq)]
enum Kind {
    Floor,
    Paths(Stage),
    Links,
}

pub(crate) struct Map<'a> {
    scene: &'a Scene<'a>,
    kind: Kind,
    view: View,
    plot: (u32, u32),
    frame: Frame,
    contour_step: f64,
}

pub(crate) type Chart2d<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

impl<'a> Map<'a> {
    /// Fig. 4(a): the whole floor.
    pub fn floor(scene: &'a Scene<'a>) -> Map<'a> {
        Map::new(scene, Kind::Floor)
    }

    /// Fig. 4(b) or 4(d) as a top view (`links`: Fig. 4(c), Step 2's links over Step 1).
    pub fn paths(scene: &'a Scene<'a>, stage: Stage, links: bool) -> Map<'a> {
        Map::new(
            scene,
            if links {
                Kind::Links
            } else {
                Kind::Paths(stage)
            },
        )
    }

    fn new(scene: &'a Scene<'a>, kind: Kind) -> Map<'a> {
        let e = scene.floor.extent();
        let extent = [e.x_min, e.x_max, e.y_min, e.y_max];
        let data = if kind == Kind::Floor {
            extent
        } else {
            pad(scene.bbox())
        };
        let (view, plot) = fit(data, extent);
        let contour_step = contour_step(scene.floor);
        let (title, mut entries) = match kind {
            Kind::Floor => ("Seafloor".to_string(), Vec::new()),
            Kind::Paths(s) => (
                format!("{}, top view", scene.paths_name(s)),
                paths_legend(scene),
            ),
            Kind::Links => (
                format!("{}, top view", scene.links_name()),
                links_legend(scene),
            ),
        };
        entries.push(contour_entry(contour_step));
        if kind == Kind::Floor {
            entries.push(Entry::new("USV start", Swatch::Square(BLACK)));
            entries.push(Entry::new(
                "area of the path figures",
                Swatch::Dashed(BLACK, 2),
            ));
        }
        let width = MARGIN * 2 + Y_AREA + plot.0 + BAR;
        let frame = Frame::new(scene.title(&title), entries, width);
        Map {
            scene,
            kind,
            view,
            plot,
            frame,
            contour_step,
        }
    }
}

fn paths_legend(scene: &Scene) -> Vec<Entry> {
    let mut e = style::vehicles(scene.n, true);
    e.push(Entry::new("start", Swatch::Dot(BLACK)));
    e.push(Entry::new("end", Swatch::Square(BLACK)));
    if scene.plan.windows.len() > 1 {
        e.push(Entry::new("window start", Swatch::Ring(BLACK)));
    }
    e
}

fn links_legend(scene: &Scene) -> Vec<Entry> {
    let mut e = style::vehicles(scene.n, true);
    e.push(Entry::new("A2U link (P3)", Swatch::Link(style::A2U)));
    if scene.n > 1 {
        // one AUV has no A2A link to show
        e.push(Entry::new("A2A link (P4)", Swatch::Link(style::A2A)));
    }
    e
}

/// The spacing of the depth contours over `floor`, m.
pub(crate) fn contour_step(floor: &Seafloor) -> f64 {
    let (lo, hi) = floor.z_range();
    raster::nice_step(hi - lo, 9.0)
}

/// The legend entry of the depth contours.
pub(crate) fn contour_entry(step: f64) -> Entry {
    Entry::new(
        format!("depth contours every {step} m"),
        Swatch::Line(RGBColor(60, 60, 60), 1),
    )
}

/// The data's box with a margin around it.
pub(crate) fn pad(b: View) -> View {
    let m = 0.03 * (b[1] - b[0]).max(b[3] - b[2]) + 100.0;
    [b[0] - m, b[1] + m, b[2] - m, b[3] + m]
}

/// A view containing `data` at one scale in x and y, and its plot size in pixels: as large as
/// fits [`MAX_PLOT`], and widened (kept inside `extent` where it can be) to at least
/// [`MIN_PLOT`].
pub(crate) fn fit(data: View, extent: View) -> (View, (u32, u32)) {
    let (xr, yr) = ((data[1] - data[0]).max(1.0), (data[3] - data[2]).max(1.0));
    let scale = (MAX_PLOT.0 / xr).min(MAX_PLOT.1 / yr);
    let (w, h) = ((xr * scale).max(MIN_PLOT.0), (yr * scale).max(MIN_PLOT.1));
    let grow = |lo: f64, hi: f64, len: f64, elo: f64, ehi: f64| {
        let c = 0.5 * (lo + hi);
        let (mut a, mut b) = (c - 0.5 * len, c + 0.5 * len);
        if len <= ehi - elo {
            let shift = (elo - a).max(0.0) - (b - ehi).max(0.0);
            (a, b) = (a + shift, b + shift);
        }
        (a, b)
    };
    let (x0, x1) = grow(data[0], data[1], w / scale, extent[0], extent[1]);
    let (y0, y1) = grow(data[2], data[3], h / scale, extent[2], extent[3]);
    ([x0, x1, y0, y1], (w.round() as u32, h.round() as u32))
}

/// Axes of a 2D chart in the house style.
pub(crate) fn axes<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    x_desc: &str,
    y_desc: &str,
    grid: bool,
) -> DrawResult<DB> {
    axes_with(chart, x_desc, y_desc, grid, 8)
}

/// [`axes`] with about `y_labels` labels on the y axis (fewer for a short panel).
pub(crate) fn axes_with<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    x_desc: &str,
    y_desc: &str,
    grid: bool,
    y_labels: usize,
) -> DrawResult<DB> {
    let mut mesh = chart.configure_mesh();
    if !grid {
        mesh.disable_mesh();
    }
    mesh.x_desc(x_desc)
        .y_desc(y_desc)
        .axis_desc_style(text(LABEL))
        .label_style(text(TICK))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .x_labels(9)
        .y_labels(y_labels)
        .x_label_formatter(&style::tick)
        .y_label_formatter(&style::tick)
        .draw()
}

impl Figure for Map<'_> {
    fn name(&self) -> &'static str {
        match self.kind {
            Kind::Floor => "seafloor",
            Kind::Paths(Stage::Step1) => "step1-top",
            Kind::Paths(Stage::Final) => "final-top",
            Kind::Links => "links-top",
        }
    }

    fn size(&self) -> (u32, u32) {
        let h = self.frame.height() + MARGIN * 2 + self.plot.1 + X_AREA;
        (self.frame_width(), h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, images: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let (left, right) = body.split_horizontally(self.frame_width() - BAR);
        let muted = self.kind != Kind::Floor;
        let floor = self.scene.floor;
        let mut chart = floor_chart(
            root,
            &left,
            images,
            floor,
            self.view,
            muted,
            self.contour_step,
        )?;
        match self.kind {
            Kind::Floor => self.draw_floor_marks(&mut chart)?,
            Kind::Paths(stage) => overlay::paths(&mut chart, self.scene, stage, 3)?,
            Kind::Links => {
                overlay::paths(&mut chart, self.scene, Stage::Step1, 2)?;
                overlay::links(&mut chart, self.scene)?;
            }
        }
        overlay::colour_bar(&right, floor, muted, MARGIN, X_AREA)
    }
}

/// The floor of a top view in `area` (part of `root`) over `view`: its depth raster (`muted`:
/// whitened, for paths over it), the axes and the contours every `contour_step` m. Returns the
/// chart to draw over it; the colour bar goes beside it ([`overlay::colour_bar`]).
pub(crate) fn floor_chart<'b, DB: DrawingBackend>(
    root: &Area<DB>,
    area: &'b Area<DB>,
    images: &mut Images,
    floor: &Seafloor,
    view: View,
    muted: bool,
    contour_step: f64,
) -> Result<Chart2d<'b, DB>, DrawErr<DB>> {
    let v = view;
    let mut chart = ChartBuilder::on(area)
        .margin(MARGIN)
        .x_label_area_size(X_AREA)
        .y_label_area_size(Y_AREA)
        .build_cartesian_2d(v[0]..v[1], v[2]..v[3])?;
    let plot = chart.plotting_area();
    let (pos, size) = (plot.get_base_pixel(), plot.dim_in_pixel());
    let res = match images.max_side() {
        Some(m) => shrink(size, m),
        None => size,
    };
    let r = raster::depth_raster(floor, v, res, muted);
    images.draw(root, pos, size, r)?;
    axes(&mut chart, "x, east (m)", "y, north (m)", false)?;
    draw_contours(&mut chart, floor, v, contour_step, muted)?;
    Ok(chart)
}

impl Map<'_> {
    fn frame_width(&self) -> u32 {
        MARGIN * 2 + Y_AREA + self.plot.0 + BAR
    }

    fn draw_floor_marks<DB: DrawingBackend>(&self, chart: &mut Chart2d<'_, DB>) -> DrawResult<DB> {
        let u = self.scene.plan.initial.usv;
        overlay::marker(chart, Swatch::Square(BLACK), (u[0], u[1]))?;
        let b = pad(self.scene.bbox());
        let rect = vec![
            (b[0], b[2]),
            (b[1], b[2]),
            (b[1], b[3]),
            (b[0], b[3]),
            (b[0], b[2]),
        ];
        chart.draw_series(std::iter::once(plotters::element::DashedPathElement::new(
            rect,
            10,
            6,
            BLACK.stroke_width(2),
        )))?;
        Ok(())
    }
}

/// Depth contours of `floor` over `view` every `step` m (fainter when `muted`).
fn draw_contours<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    floor: &Seafloor,
    v: View,
    step: f64,
    muted: bool,
) -> DrawResult<DB> {
    let n = 220.0;
    let (xr, yr) = (v[1] - v[0], v[3] - v[2]);
    let (nx, ny) = if xr > yr {
        (n, n * yr / xr)
    } else {
        (n * xr / yr, n)
    };
    let g = Grid::sample(floor, v, nx as usize, ny as usize);
    let (lo, hi) = floor.z_range();
    let alpha = if muted { 0.35 } else { 0.55 };
    let style = RGBColor(40, 40, 40).mix(alpha).stroke_width(1);
    let mut level = (lo / step).ceil() * step;
    while level <= hi {
        let lines = raster::contours(&g, level);
        chart.draw_series(lines.into_iter().map(|l| PathElement::new(l, style)))?;
        level += step;
    }
    Ok(())
}

fn shrink((w, h): (u32, u32), max: u32) -> (u32, u32) {
    let s = (max as f64 / w.max(h) as f64).min(1.0);
    (
        ((w as f64 * s) as u32).max(2),
        ((h as f64 * s) as u32).max(2),
    )
}
