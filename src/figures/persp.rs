//! 3D perspective views (the paper's Fig. 4(b)–(d)): the floor as a shaded surface, the paths
//! of Step 1 or of the final plan, or Step 2's links, above it. The vertical axis is stretched
//! so the floor's relief and the AUVs' height above it show.

use super::canvas::{Area, DrawResult, Figure, Images};
use super::raster::{depth_colour, hillshade, rgb, whiten, Grid, View};
use super::scene::{Scene, Stage};
use super::style::{self, outline, text, vehicle_colour, Entry, Frame, Swatch, LABEL, TICK};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const WIDTH: u32 = 1280;
const BODY_H: u32 = 720;
/// Floor cells along the longer horizontal side.
const CELLS: f64 = 64.0;

pub(crate) struct Persp<'a> {
    scene: &'a Scene<'a>,
    stage: Stage,
    links: bool,
    frame: Frame,
    view: View,
}

impl<'a> Persp<'a> {
    pub fn new(scene: &'a Scene<'a>, stage: Stage, links: bool) -> Persp<'a> {
        let b = scene.bbox();
        let m = 0.08 * (b[1] - b[0]).max(b[3] - b[2]) + 100.0;
        let e = scene.floor.extent();
        let view = [
            (b[0] - m).max(e.x_min),
            (b[1] + m).min(e.x_max),
            (b[2] - m).max(e.y_min),
            (b[3] + m).min(e.y_max),
        ];
        let mut entries = style::vehicles(scene.n, true);
        let title = if links {
            entries.push(Entry::new("A2U link (P3)", Swatch::Link(style::A2U)));
            if scene.n > 1 {
                entries.push(Entry::new("A2A link (P4)", Swatch::Link(style::A2A)));
            }
            format!("{}, 3D", scene.links_name())
        } else {
            entries.push(Entry::new("start", Swatch::Dot(BLACK)));
            entries.push(Entry::new("end", Swatch::Square(BLACK)));
            format!("{}, 3D", scene.paths_name(stage))
        };
        let frame = Frame::new(scene.title(&title), entries, WIDTH);
        Persp {
            scene,
            stage,
            links,
            frame,
            view,
        }
    }
}

type Pt = (f64, f64, f64);

impl Figure for Persp<'_> {
    fn name(&self) -> &'static str {
        match (self.links, self.stage) {
            (true, _) => "links-3d",
            (false, Stage::Step1) => "step1-3d",
            (false, Stage::Final) => "final-3d",
        }
    }

    fn size(&self) -> (u32, u32) {
        (WIDTH, self.frame.height() + BODY_H)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let v = self.view;
        let (xr, yr) = (v[1] - v[0], v[3] - v[2]);
        let (gx, gy) = if xr >= yr {
            (CELLS, (CELLS * yr / xr).max(8.0))
        } else {
            ((CELLS * xr / yr).max(8.0), CELLS)
        };
        let g = Grid::sample(self.scene.floor, v, gx as usize + 1, gy as usize + 1);
        let floor_lo =
            g.z.iter()
                .copied()
                .filter(|z| z.is_finite())
                .fold(0.0, f64::min);
        let (zlo, zhi) = (floor_lo - 0.05 * floor_lo.abs(), 0.0);
        let mut chart = ChartBuilder::on(&body).margin(30).build_cartesian_3d(
            v[0]..v[1],
            zlo..zhi,
            -v[3]..-v[2],
        )?;
        // Horizontal sides in proportion (within 1 : 3), the height 0.3 of the longer; then
        // the whole box scaled to fill the area, leaving room for the tick labels and titles.
        let ratio = (yr / xr).clamp(1.0 / 3.0, 3.0);
        let unit = if ratio <= 1.0 {
            (1.0, ratio)
        } else {
            (1.0 / ratio, 1.0)
        };
        let set = |chart: &mut Chart3d<DB>, side: f64| {
            let (px, pz) = (side * unit.0, side * unit.1);
            chart.set_3d_pixel_range((px as i32, (side * 0.3) as i32, pz as i32));
            chart.with_projection(|mut p| {
                p.yaw = 0.55;
                p.pitch = 0.5;
                p.into_matrix()
            });
        };
        let mut side = 800.0;
        for _ in 0..2 {
            set(&mut chart, side);
            let spec = chart.as_coord_spec();
            let corners = [v[0], v[1]].into_iter().flat_map(|x| {
                [zlo, zhi]
                    .into_iter()
                    .flat_map(move |z| [-v[3], -v[2]].map(|y| (x, z, y)))
            });
            let (mut lo, mut hi) = ((i32::MAX, i32::MAX), (i32::MIN, i32::MIN));
            for c in corners {
                let (sx, sy) = spec.translate(&c);
                (lo, hi) = ((lo.0.min(sx), lo.1.min(sy)), (hi.0.max(sx), hi.1.max(sy)));
            }
            let (aw, ah) = chart.plotting_area().dim_in_pixel();
            let fit = ((aw as f64 - 300.0) / f64::from(hi.0 - lo.0).max(1.0))
                .min((ah as f64 - 140.0) / f64::from(hi.1 - lo.1).max(1.0));
            side *= fit;
        }
        set(&mut chart, side);
        let (px, pz) = (side * unit.0, side * unit.1);
        let fmt = style::tick;
        // The third axis is −y, so that the view is not a mirror image of the map.
        let north = |y: &f64| style::tick(&-y);
        chart
            .configure_axes()
            .label_style(text(TICK))
            .tick_size(8)
            .x_labels(6)
            .y_labels(4)
            .z_labels(4)
            .max_light_lines(1)
            .axis_panel_style(RGBColor(246, 246, 246))
            .bold_grid_style(RGBColor(200, 200, 200))
            .light_grid_style(RGBColor(230, 230, 230))
            .x_formatter(&fmt)
            .y_formatter(&fmt)
            .z_formatter(&north)
            .draw()?;
        // Axis titles: just outside the middle of each labelled edge.
        let (xm, ym) = (0.5 * (v[0] + v[1]), 0.5 * (v[2] + v[3]));
        for (s, at, off, h) in [
            ("x, east (m)", (xm, zlo, -v[2]), (-50, 64), HPos::Center),
            ("y, north (m)", (v[1], zlo, -ym), (70, 10), HPos::Left),
            ("z (m)", (v[1], zhi, -v[3]), (0, -36), HPos::Left),
        ] {
            let style = text(LABEL).pos(Pos::new(h, VPos::Center));
            chart
                .plotting_area()
                .draw(&(EmptyElement::at(at) + Text::new(s, off, style)))?;
        }
        self.surface(&mut chart, &g, (px / xr, 0.3 * side / (zhi - zlo), pz / yr))?;
        // Paths, then the links over them: the links are what Fig. 4(c) shows.
        self.draw_paths(&mut chart)?;
        if self.links {
            self.draw_links(&mut chart)?;
        }
        Ok(())
    }
}

type Chart3d<'a, DB> = ChartContext<
    'a,
    DB,
    plotters::coord::cartesian::Cartesian3d<
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
        plotters::coord::types::RangedCoordf64,
    >,
>;

impl Persp<'_> {
    /// The floor as shaded quadrilaterals, farthest first. `scale`: pixels per metre along x,
    /// z and y, for shading the relief as drawn.
    fn surface<DB: DrawingBackend>(
        &self,
        chart: &mut Chart3d<'_, DB>,
        g: &Grid,
        scale: (f64, f64, f64),
    ) -> DrawResult<DB> {
        let range = self.scene.floor.z_range();
        let (cx, cy) = (
            (g.view[1] - g.view[0]) / (g.nx - 1) as f64,
            (g.view[3] - g.view[2]) / (g.ny - 1) as f64,
        );
        let mut cells = Vec::new();
        for (i, j, z) in g.cells() {
            // Each cell a little larger than its share, so anti-aliased SVG edges leave
            // no hairline seams between neighbours.
            let p = |di: usize, dj: usize, z: f64| {
                let grow = |d: usize| if d == 0 { -0.12 } else { 1.12 };
                let (x, y) = g.point(i as f64 + grow(di), j as f64 + grow(dj));
                (x, z, -y)
            };
            let corners = vec![p(0, 0, z[0]), p(1, 0, z[1]), p(1, 1, z[2]), p(0, 1, z[3])];
            let mean = z.iter().sum::<f64>() / 4.0;
            // Slope as drawn: vertical pixels per horizontal pixel.
            let gx = (z[1] + z[2] - z[0] - z[3]) / (2.0 * cx) * scale.1 / scale.0;
            let gy = (z[2] + z[3] - z[0] - z[1]) / (2.0 * cy) * scale.1 / scale.2;
            let c = depth_colour(mean, range).map(|c| c * hillshade(gx, gy));
            let (x, y) = g.point(i as f64 + 0.5, j as f64 + 0.5);
            let depth = chart.as_coord_spec().projected_depth(&x, &mean, &-y);
            cells.push((depth, corners, rgb(whiten(c, 0.25))));
        }
        cells.sort_by_key(|c| std::cmp::Reverse(c.0));
        chart.draw_series(
            cells
                .into_iter()
                .map(|(_, corners, c)| Polygon::new(corners, c.filled())),
        )?;
        Ok(())
    }

    fn draw_paths<DB: DrawingBackend>(&self, chart: &mut Chart3d<'_, DB>) -> DrawResult<DB> {
        let s = self.scene;
        let width = if self.links { 2 } else { 3 };
        let mut all: Vec<(Option<usize>, Vec<Pt>)> = (0..s.n)
            .map(|n| {
                let p = s.auv_path(self.stage, n);
                (Some(n), p.iter().map(|q| (q[0], q[2], -q[1])).collect())
            })
            .collect();
        let usv = s
            .usv_path(self.stage)
            .iter()
            .map(|q| (q[0], 0.0, -q[1]))
            .collect();
        all.push((None, usv));
        for (v, p) in &all {
            let c = vehicle_colour(*v);
            chart.draw_series(LineSeries::new(p.iter().copied(), c.stroke_width(width)))?;
            if self.links {
                continue;
            }
            if let (Some(&a), Some(&b)) = (p.first(), p.last()) {
                let area = chart.plotting_area();
                area.draw(
                    &(EmptyElement::at(a)
                        + Circle::new((0, 0), 7, c.filled())
                        + Circle::new((0, 0), 7, BLACK.stroke_width(1))),
                )?;
                area.draw(
                    &(EmptyElement::at(b)
                        + Rectangle::new([(-7, -7), (7, 7)], c.filled())
                        + Rectangle::new([(-7, -7), (7, 7)], BLACK.stroke_width(1))),
                )?;
            }
        }
        Ok(())
    }

    fn draw_links<DB: DrawingBackend>(&self, chart: &mut Chart3d<'_, DB>) -> DrawResult<DB> {
        let s = self.scene;
        let mut segs: Vec<(RGBColor, Pt, Pt)> = Vec::new();
        for (&(w, k, _), links) in s.steps.iter().zip(s.graph_links()) {
            let st = s.stage(w, Stage::Step1);
            for l in links {
                let a = st.auvs[l.a].position[k];
                let (b, c) = match l.b {
                    Some(b) => (st.auvs[b].position[k], style::A2A),
                    None => {
                        let u = st.usv.position[k];
                        ([u[0], u[1], 0.0], style::A2U)
                    }
                };
                segs.push((c, (a[0], a[2], -a[1]), (b[0], b[2], -b[1])));
            }
        }
        for (w, dark) in [(4, true), (2, false)] {
            chart.draw_series(segs.iter().map(|&(c, a, b)| {
                let c = if dark { outline(c) } else { c };
                PathElement::new(vec![a, b], c.stroke_width(w))
            }))?;
        }
        Ok(())
    }
}
