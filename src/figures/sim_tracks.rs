//! `sim-tracks`: a top view of a simulated mission over the floor, as the plan's `final-top`:
//! the planned paths (thin, light), the executed paths (each AUV's colour), one estimate's
//! positions as dots with their 2-σ horizontal uncertainty ellipses every few epochs, and the
//! USV's path.

use super::canvas::{Area, DrawResult, Figure, Images};
use super::map::{self, Chart2d, BAR, MARGIN, X_AREA, Y_AREA};
use super::overlay;
use super::raster::View;
use super::scene::Scene;
use super::sim::{estimator_label, fitting_title, policy_label};
use super::style::{self, outline, vehicle_colour, Entry, Frame, Swatch};
use crate::sim::record::{EstimateRecord, SimRecord};
use plotters::prelude::*;

type Xy = (f64, f64);

/// At most about this many ellipses per AUV (every 10th epoch of 201).
const ELLIPSES: f64 = 25.0;
/// When the typical ellipse's semi-major axis would be under half this many pixels, every
/// ellipse is drawn enlarged, by a factor of 1, 2 or 5 × 10ⁿ (stated in the legend) that
/// brings it to this size at least.
const MIN_ELLIPSE_PX: f64 = 6.0;

pub(crate) struct Tracks<'a> {
    scene: &'a Scene<'a>,
    sim: &'a SimRecord,
    est: &'a EstimateRecord,
    view: View,
    plot: (u32, u32),
    frame: Frame,
    contour_step: f64,
    /// An ellipse every `stride` epochs, drawn `scale` times its size.
    stride: usize,
    scale: f64,
}

/// The 2-σ ellipse of the horizontal block [xx, xy; xy, yy] of a packed covariance
/// [xx, xy, xz, yy, yz, zz]: semi-axes (major, minor) and the major axis' angle from x, rad.
fn ellipse(c: &[f64; 6]) -> (f64, f64, f64) {
    let (a, b, d) = (c[0], c[1], c[3]);
    let mean = 0.5 * (a + d);
    let r = (0.25 * (a - d) * (a - d) + b * b).sqrt();
    let sd = |l: f64| 2.0 * l.max(0.0).sqrt();
    (sd(mean + r), sd(mean - r), 0.5 * (2.0 * b).atan2(a - d))
}

/// Points around an ellipse centred at `p`.
fn ellipse_points(p: Xy, (major, minor, angle): (f64, f64, f64)) -> Vec<Xy> {
    let (s, c) = angle.sin_cos();
    (0..=48)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / 48.0;
            let (u, v) = (major * t.cos(), minor * t.sin());
            (p.0 + c * u - s * v, p.1 + s * u + c * v)
        })
        .collect()
}

/// The smallest of 1, 2, 5, 10, 20, … at least `x` (1 for x ≤ 1).
fn nice_at_least(x: f64) -> f64 {
    if !x.is_finite() || x <= 1.0 {
        return 1.0;
    }
    let mut p = 1.0;
    loop {
        for m in [1.0, 2.0, 5.0] {
            if m * p >= x {
                return m * p;
            }
        }
        p *= 10.0;
    }
}

impl<'a> Tracks<'a> {
    pub fn new(scene: &'a Scene<'a>, sim: &'a SimRecord, est: &'a EstimateRecord) -> Tracks<'a> {
        let epochs = sim.times.len();
        let stride = nice_at_least(epochs as f64 / ELLIPSES) as usize;
        let f = &sim.flight;
        // The data: every path, and every ellipse drawn at its size.
        let mut points: Vec<[f64; 2]> = Vec::new();
        let mut add = |x: f64, y: f64| points.push([x, y]);
        for p in f.executed.iter().chain(&f.planned).flatten() {
            add(p[0], p[1]);
        }
        for p in &f.usv {
            add(p[0], p[1]);
        }
        let mut majors = Vec::new();
        for (pos, cov) in est.position.iter().zip(&est.covariance) {
            for (e, (p, c)) in pos.iter().zip(cov).enumerate() {
                add(p[0], p[1]);
                if e % stride == 0 {
                    let (major, _, _) = ellipse(c);
                    if major.is_finite() {
                        add(p[0] - major, p[1] - major);
                        add(p[0] + major, p[1] + major);
                        majors.push(major);
                    }
                }
            }
        }
        let e = scene.floor.extent();
        let extent = [e.x_min, e.x_max, e.y_min, e.y_max];
        let data = crate::plan::bbox(points).map_or(extent, map::pad);
        let (view, plot) = map::fit(data, extent);
        // Enlarge the ellipses when the typical one would be a speck.
        majors.sort_by(f64::total_cmp);
        let px_per_m = f64::from(plot.0) / (view[1] - view[0]);
        let typical = majors.get(majors.len() / 2).copied().unwrap_or(0.0) * px_per_m;
        let scale = if typical > 0.0 && typical < MIN_ELLIPSE_PX / 2.0 {
            nice_at_least(MIN_ELLIPSE_PX / typical)
        } else {
            1.0
        };

        let contour_step = map::contour_step(scene.floor);
        let dark = RGBColor(40, 40, 40);
        let mut entries = style::vehicles(scene.n, true);
        entries.extend([
            Entry::new("planned path", Swatch::Line(RGBColor(170, 170, 170), 2)),
            Entry::new("executed path", Swatch::Line(dark, 3)),
            Entry::new(
                format!(
                    "estimate: {}, {}",
                    policy_label(est.policy),
                    estimator_label(&est.estimator)
                ),
                Swatch::Dot(dark),
            ),
            Entry::new(ellipse_label(stride, scale), Swatch::Ring(dark)),
            Entry::new("end", Swatch::Square(BLACK)),
            map::contour_entry(contour_step),
        ]);
        let width = MARGIN * 2 + Y_AREA + plot.0 + BAR;
        let seed = sim.seed;
        let title = fitting_title(
            scene,
            &[
                format!("Executed and estimated paths, simulation seed {seed}, top view"),
                format!("Executed and estimated paths, simulation seed {seed}"),
                format!("Executed and estimated paths, sim seed {seed}"),
                format!("Simulated paths, sim seed {seed}"),
            ],
            width,
        );
        Tracks {
            scene,
            sim,
            est,
            view,
            plot,
            frame: Frame::new(title, entries, width),
            contour_step,
            stride,
            scale,
        }
    }

    fn frame_width(&self) -> u32 {
        MARGIN * 2 + Y_AREA + self.plot.0 + BAR
    }

    fn draw_paths<DB: DrawingBackend>(&self, chart: &mut Chart2d<'_, DB>) -> DrawResult<DB> {
        let f = &self.sim.flight;
        let xy = |p: &Vec<[f64; 3]>| p.iter().map(|q| (q[0], q[1])).collect::<Vec<Xy>>();
        for (n, p) in f.planned.iter().enumerate() {
            let c = light(vehicle_colour(Some(n)));
            chart.draw_series(LineSeries::new(xy(p), c.stroke_width(2)))?;
        }
        for (n, p) in f.executed.iter().enumerate() {
            let c = vehicle_colour(Some(n));
            chart.draw_series(LineSeries::new(xy(p), c.stroke_width(3)))?;
        }
        let usv = f.usv.iter().map(|q| (q[0], q[1]));
        chart.draw_series(LineSeries::new(usv, vehicle_colour(None).stroke_width(3)))?;
        Ok(())
    }

    fn draw_estimate<DB: DrawingBackend>(&self, chart: &mut Chart2d<'_, DB>) -> DrawResult<DB> {
        let est = self.est;
        for (n, (pos, cov)) in est.position.iter().zip(&est.covariance).enumerate() {
            let c = vehicle_colour(Some(n));
            let rings = pos
                .iter()
                .zip(cov)
                .step_by(self.stride)
                .map(|(p, cv)| {
                    let (a, b, angle) = ellipse(cv);
                    ellipse_points((p[0], p[1]), (a * self.scale, b * self.scale, angle))
                })
                .filter(|r| r.iter().all(|q| q.0.is_finite() && q.1.is_finite()))
                .collect::<Vec<_>>();
            chart.draw_series(rings.iter().map(|r| Polygon::new(r.clone(), c.mix(0.15))))?;
            chart.draw_series(
                rings
                    .iter()
                    .map(|r| PathElement::new(r.clone(), c.stroke_width(2))),
            )?;
            let dot = |p: &[f64; 3]| Circle::new((p[0], p[1]), 2, outline(c).filled());
            chart.draw_series(pos.iter().map(dot))?;
        }
        Ok(())
    }
}

/// "its 2-σ ellipse every 10th epoch, drawn ×5".
fn ellipse_label(stride: usize, scale: f64) -> String {
    let mut s = "its 2-σ ellipse".to_string();
    if stride > 1 {
        let th = match (stride % 10, stride % 100) {
            (1, r) if r != 11 => "st",
            (2, r) if r != 12 => "nd",
            (3, r) if r != 13 => "rd",
            _ => "th",
        };
        s += &format!(" every {stride}{th} epoch");
    }
    if scale > 1.0 {
        s += &format!(", drawn ×{scale}");
    }
    s
}

/// A vehicle's colour, 55 % of the way to white: its planned path.
fn light(c: RGBColor) -> RGBColor {
    let w = |v: u8| (f64::from(v) + 0.55 * (255.0 - f64::from(v))).round() as u8;
    RGBColor(w(c.0), w(c.1), w(c.2))
}

impl Figure for Tracks<'_> {
    fn name(&self) -> &'static str {
        super::sim::SIM_FIGURES[1]
    }

    fn size(&self) -> (u32, u32) {
        let h = self.frame.height() + MARGIN * 2 + self.plot.1 + X_AREA;
        (self.frame_width(), h)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, images: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let (left, right) = body.split_horizontally(self.frame_width() - BAR);
        let floor = self.scene.floor;
        let mut chart = map::floor_chart(
            root,
            &left,
            images,
            floor,
            self.view,
            true,
            self.contour_step,
        )?;
        self.draw_paths(&mut chart)?;
        self.draw_estimate(&mut chart)?;
        let f = &self.sim.flight;
        let ends = f
            .executed
            .iter()
            .enumerate()
            .map(|(n, p)| (Some(n), p.last()));
        let usv_end = f.usv.last();
        for (v, end) in ends.chain(std::iter::once((None, usv_end))) {
            if let Some(q) = end {
                overlay::marker(&chart, Swatch::Square(vehicle_colour(v)), (q[0], q[1]))?;
            }
        }
        overlay::colour_bar(&right, floor, true, MARGIN, X_AREA)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ellipses_have_two_sigma_axes_along_the_covariance() {
        // σx = 3, σy = 1, no correlation: 2σ semi-axes 6 and 2 along x
        let (a, b, angle) = ellipse(&[9.0, 0.0, 0.0, 1.0, 0.0, 4.0]);
        assert!((a - 6.0).abs() < 1e-12 && (b - 2.0).abs() < 1e-12 && angle.abs() < 1e-12);
        // the same, turned 90°
        let (a, b, angle) = ellipse(&[1.0, 0.0, 0.0, 9.0, 0.0, 4.0]);
        assert!((a - 6.0).abs() < 1e-12 && (b - 2.0).abs() < 1e-12);
        assert!((angle.abs() - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        // perfectly correlated along the diagonal: a line at 45°
        let (a, b, angle) = ellipse(&[1.0, 1.0, 0.0, 1.0, 0.0, 1.0]);
        assert!((a - 2.0 * 2f64.sqrt()).abs() < 1e-12 && b.abs() < 1e-6);
        assert!((angle - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    }

    #[test]
    fn nice_factors_are_1_2_5_times_powers_of_ten() {
        let got: Vec<f64> = [0.3, 1.0, 1.5, 2.0, 3.0, 7.0, 10.0, 11.0, 40.0]
            .iter()
            .map(|&x| nice_at_least(x))
            .collect();
        assert_eq!(got, [1.0, 1.0, 2.0, 2.0, 5.0, 10.0, 10.0, 20.0, 50.0]);
    }
}
