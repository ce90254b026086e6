//! Each AUV's depth against the floor under it (C2_2), one panel per AUV: the final path's z
//! between waypoints, the floor Z(x, y) sampled along the same straight segments, and the
//! clearance floor + ε.

use super::canvas::{Area, DrawResult, Figure, Images};
use super::map::Chart2d;
use super::raster::elevation;
use super::scene::{Scene, Stage};
use super::series::window_marks;
use super::style::{self, text, vehicle_colour, vehicle_name, Entry, Frame, Swatch, LABEL, TICK};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const WIDTH: u32 = 1280;
/// Samples of the floor per step, along the segment between waypoints.
const SUB: usize = 10;
const FLOOR: RGBColor = RGBColor(0xa0, 0x7a, 0x4c);

pub(crate) struct Depth<'a> {
    scene: &'a Scene<'a>,
    frame: Frame,
    cols: usize,
    rows: usize,
    panel_h: u32,
}

impl<'a> Depth<'a> {
    pub fn new(scene: &'a Scene<'a>) -> Depth<'a> {
        let n = scene.n.max(1);
        let cols = match n {
            1 => 1,
            2..=4 => 2,
            5..=9 => 3,
            _ => 4,
        };
        let rows = n.div_ceil(cols);
        let panel_h = if rows <= 3 { 300 } else { 250 };
        let eps = scene.plan.scenario.auv.floor_clearance;
        let mut entries = style::vehicles(scene.n, false);
        entries.push(Entry::new("floor under the AUV", Swatch::Area(FLOOR)));
        entries.push(Entry::new(
            format!("floor + ε = {eps} m clearance"),
            Swatch::Dashed(FLOOR, 2),
        ));
        if scene.plan.windows.len() > 1 {
            entries.push(Entry::new("window start", Swatch::Dashed(style::WINDOW, 2)));
        }
        let title = scene.title("AUV depth over the floor (final plan)");
        Depth {
            scene,
            frame: Frame::new(title, entries, WIDTH),
            cols,
            rows,
            panel_h,
        }
    }

    /// The AUV's z and the floor under it, at SUB points per step: (t, z, floor).
    fn profile(&self, n: usize) -> Vec<(f64, f64, f64)> {
        let s = self.scene;
        let p = s.auv_path(Stage::Final, n);
        let t = s.times();
        let mut out = Vec::with_capacity(p.len() * SUB);
        for i in 0..p.len() {
            let subs = if i + 1 < p.len() { SUB } else { 1 };
            for j in 0..subs {
                let f = j as f64 / SUB as f64;
                let q = |c: usize| {
                    let next = p.get(i + 1).map_or(p[i][c], |b| b[c]);
                    p[i][c] + f * (next - p[i][c])
                };
                let tt = t[i] + f * t.get(i + 1).map_or(0.0, |b| b - t[i]);
                out.push((tt, q(2), elevation(s.floor, q(0), q(1))));
            }
        }
        out
    }

    fn panel<DB: DrawingBackend>(&self, area: &Area<DB>, n: usize) -> DrawResult<DB> {
        let prof = self.profile(n);
        let eps = self.scene.plan.scenario.auv.floor_clearance;
        let ys = prof
            .iter()
            .flat_map(|p| [p.1, p.2])
            .filter(|v| v.is_finite());
        let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
            (a.min(y), b.max(y))
        });
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (-1.0, 0.0) };
        let m = 0.1 * (hi - lo).max(10.0);
        let (lo, hi) = (lo - m, hi + m);
        let (t0, t1) = (prof[0].0, prof.last().map_or(prof[0].0 + 1.0, |p| p.0));
        let col = n % self.cols;
        let bottom = n + self.cols >= self.scene.n;
        let mut chart: Chart2d<DB> = ChartBuilder::on(area)
            .margin(8)
            .margin_right(24)
            .x_label_area_size(if bottom { 64 } else { 34 })
            .y_label_area_size(if col == 0 { 100 } else { 70 })
            .build_cartesian_2d(t0..t1.max(t0 + 1.0), lo..hi)?;
        let mut mesh = chart.configure_mesh();
        if bottom {
            mesh.x_desc("time t (s)");
        }
        if col == 0 {
            mesh.y_desc("z (m)");
        }
        mesh.axis_desc_style(text(LABEL))
            .label_style(text(TICK))
            .light_line_style(RGBColor(240, 240, 240))
            .bold_line_style(RGBColor(215, 215, 215))
            .x_labels(if self.cols >= 4 { 3 } else { 5 })
            .y_labels(5)
            .x_label_formatter(&style::tick)
            .y_label_formatter(&style::tick)
            .draw()?;
        let floor: Vec<(f64, f64)> = prof
            .iter()
            .filter(|p| p.2.is_finite())
            .map(|p| (p.0, p.2))
            .collect();
        chart.draw_series(AreaSeries::new(floor.iter().copied(), lo, FLOOR.mix(0.55)))?;
        chart.draw_series(LineSeries::new(
            floor.iter().copied(),
            FLOOR.stroke_width(2),
        ))?;
        chart.draw_series(std::iter::once(plotters::element::DashedPathElement::new(
            floor.iter().map(|p| (p.0, p.1 + eps)),
            6,
            4,
            FLOOR.stroke_width(2),
        )))?;
        window_marks(&mut chart, self.scene, (lo, hi), false)?;
        let c = vehicle_colour(Some(n));
        chart.draw_series(LineSeries::new(
            prof.iter().map(|p| (p.0, p.1)),
            c.stroke_width(3),
        ))?;
        let label = text(LABEL).color(&c).pos(Pos::new(HPos::Right, VPos::Top));
        chart.plotting_area().draw(
            &(EmptyElement::at((t1, hi)) + Text::new(vehicle_name(Some(n)), (-10, 6), label)),
        )?;
        Ok(())
    }
}

impl Figure for Depth<'_> {
    fn name(&self) -> &'static str {
        "depth"
    }

    fn size(&self) -> (u32, u32) {
        (
            WIDTH,
            self.frame.height() + self.rows as u32 * self.panel_h + 30,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let (body, _) = body.split_vertically(self.rows as u32 * self.panel_h + 10);
        let panels = body.split_evenly((self.rows, self.cols));
        for n in 0..self.scene.n {
            self.panel(&panels[n], n)?;
        }
        Ok(())
    }
}
