//! Time series over the whole mission, window starts marked: every planned link's length against
//! its band, each vehicle's speed and each AUV's heading rate against their limits.

use super::canvas::{Area, DrawResult, Figure, Images};
use super::map::{axes, Chart2d};
use super::scene::{Scene, Stage};
use super::style::{self, outline, text, vehicle_colour, Entry, Frame, Swatch, TICK};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const WIDTH: u32 = 1280;
const PLOT_H: u32 = 620;

/// A polyline; `outlined` draws it over a dark outline (links).
struct Line {
    colour: RGBColor,
    width: u32,
    outlined: bool,
    points: Vec<(f64, f64)>,
}

pub(crate) struct Series<'a> {
    scene: &'a Scene<'a>,
    name: &'static str,
    frame: Frame,
    y_desc: String,
    y_range: (f64, f64),
    band: Option<(f64, f64)>,
    /// Horizontal limit lines: value and colour.
    limits: Vec<(f64, RGBColor)>,
    lines: Vec<Line>,
    /// A2A link lengths, drawn as yellow dots.
    dots: Vec<(f64, f64)>,
    /// Short red ticks (lowered band tops) and red rings (links outside their band).
    ticks: Vec<(f64, f64)>,
    rings: Vec<(f64, f64)>,
}

impl<'a> Series<'a> {
    fn new(scene: &'a Scene<'a>, name: &'static str, title: &str, entries: Vec<Entry>) -> Self {
        let mut entries = entries;
        if scene.plan.windows.len() > 1 {
            entries.push(Entry::new("window start", Swatch::Dashed(style::WINDOW, 2)));
        }
        Series {
            scene,
            name,
            frame: Frame::new(scene.title(title), entries, WIDTH),
            y_desc: String::new(),
            y_range: (0.0, 1.0),
            band: None,
            limits: Vec::new(),
            lines: Vec::new(),
            dots: Vec::new(),
            ticks: Vec::new(),
            rings: Vec::new(),
        }
    }

    /// The y range: every value and limit, with a margin.
    fn fit_y(&mut self, floor_zero: bool) {
        let ys = self.lines.iter().flat_map(|l| l.points.iter().map(|p| p.1));
        let ys = ys.chain(self.dots.iter().map(|p| p.1));
        let ys = ys.chain(self.limits.iter().map(|l| l.0));
        let ys = ys.chain(self.band.iter().flat_map(|b| [b.0, b.1]));
        let (lo, hi) = ys
            .filter(|y| y.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), y| {
                (a.min(y), b.max(y))
            });
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 1.0) };
        let m = 0.08 * (hi - lo).max(1e-9);
        let lo = if floor_zero {
            (lo - m).max(0.0)
        } else {
            lo - m
        };
        self.y_range = (lo, hi + m);
    }
}

/// Every planned link's length in the final plan (A2U: to the USV at the surface) against the
/// band [ρ·d_s − d_t, ρ·d_s] (ρ = 1: the paper's); lowered band tops and links outside their
/// band marked.
pub(crate) fn links<'a>(scene: &'a Scene<'a>) -> Series<'a> {
    let a = &scene.plan.scenario.acoustic;
    let top = a.link_margin * a.sonar_range;
    let (lo, hi) = (top - a.band_tolerance, top);
    // The A2U link (whichever AUV holds it) as one line; the A2A links as dots.
    let (mut a2u, mut a2a) = (Vec::new(), Vec::new());
    let (mut ticks, mut rings) = (Vec::new(), Vec::new());
    for &(w, k, t) in &scene.steps {
        let report = &scene.plan.windows[w].links;
        let (Some(links), Some(bands)) = (report.links.get(k), report.bands.get(k)) else {
            continue;
        };
        for (&l, b) in links.iter().zip(bands) {
            let len = scene.link_length(Stage::Final, w, k, l);
            if l.b.is_none() {
                a2u.push((t, len))
            } else {
                a2a.push((t, len))
            }
            if b.hi < hi - 1e-9 {
                ticks.push((t, b.hi));
            }
        }
        let oob = report.out_of_band.iter().filter(|o| o.k == k && k > 0);
        rings.extend(oob.map(|o| (t, o.length)));
    }
    let mut entries = vec![Entry::new("A2U link (AUV–USV)", Swatch::Link(style::A2U))];
    if scene.n > 1 {
        // one AUV has no A2A link to show
        entries.push(Entry::new("A2A link (AUV–AUV)", Swatch::Dot(style::A2A)));
    }
    entries.push(Entry::new(
        format!("band d_s − d_t … d_s = {lo:.0} … {hi:.0} m"),
        Swatch::Area(style::BAND),
    ));
    if !ticks.is_empty() {
        entries.push(Entry::new(
            "band top lowered (line of sight)",
            Swatch::Line(style::LIMIT, 3),
        ));
    }
    if !rings.is_empty() {
        entries.push(Entry::new("outside its band", Swatch::Ring(style::LIMIT)));
    }
    let mut s = Series::new(
        scene,
        "link-lengths",
        "Planned link lengths (final plan)",
        entries,
    );
    s.y_desc = "link length (m)".into();
    s.band = Some((lo, hi));
    s.lines.push(Line {
        colour: style::A2U,
        width: 3,
        outlined: true,
        points: a2u,
    });
    s.dots = a2a;
    s.ticks = ticks;
    s.rings = rings;
    s.fit_y(true);
    s
}

/// Each AUV's speed ‖V‖ against V_max (C1_7), and the USV's speed against its limit.
pub(crate) fn speed<'a>(scene: &'a Scene<'a>) -> Series<'a> {
    let sc = &scene.plan.scenario;
    let mut entries = style::vehicles(scene.n, true);
    entries.push(Entry::new(
        format!("AUV limit V_max = {} m/s", sc.auv.max_speed),
        Swatch::Dashed(style::LIMIT, 3),
    ));
    entries.push(Entry::new(
        format!("USV limit {} m/s", sc.usv.max_speed),
        Swatch::Dashed(BLACK, 3),
    ));
    let mut s = Series::new(scene, "speed", "Speeds (final plan)", entries);
    s.y_desc = "speed (m/s)".into();
    s.limits = vec![(sc.auv.max_speed, style::LIMIT), (sc.usv.max_speed, BLACK)];
    for n in 0..scene.n {
        let points = scene.steps.iter().map(|&(w, k, t)| {
            let v = scene.stage(w, Stage::Final).auvs[n].velocity[k];
            (t, (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt())
        });
        s.lines.push(vehicle_line(Some(n), points.collect()));
    }
    // The USV's input is its velocity, held from step k to k + 1.
    let mut usv = Vec::new();
    for &(w, k, t) in &scene.steps {
        let st = scene.stage(w, Stage::Final);
        if let Some(u) = st.usv.input.get(k) {
            let v = u[0].hypot(u[1]);
            usv.extend([(t, v), (t + sc.horizon.dt, v)]);
        }
    }
    s.lines.push(vehicle_line(None, usv));
    s.fit_y(true);
    s
}

/// Each AUV's heading rate wrap(ψ[k] − ψ[k−1]) / δ against ±ψ̇_max (C1_14), in mrad/s; gaps
/// where the heading is undefined (horizontal speed below auv.min_heading_speed).
pub(crate) fn heading_rate<'a>(scene: &'a Scene<'a>) -> Series<'a> {
    let sc = &scene.plan.scenario;
    let max = 1e3 * sc.auv.max_heading_rate;
    let mut entries = style::vehicles(scene.n, false);
    entries.push(Entry::new(
        format!("limit ±ψ̇_max = ±{max} mrad/s"),
        Swatch::Dashed(style::LIMIT, 3),
    ));
    let dt = sc.horizon.dt;
    let mut lines = Vec::new();
    for n in 0..scene.n {
        let heading =
            |&(w, k, _): &(usize, usize, f64)| scene.stage(w, Stage::Final).auvs[n].heading[k];
        let mut run = Vec::new();
        for pair in scene.steps.windows(2) {
            match (heading(&pair[0]), heading(&pair[1])) {
                (Some(h0), Some(h1)) => {
                    let d = (h1 - h0 + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                        - std::f64::consts::PI;
                    run.push((pair[1].2, 1e3 * d / dt));
                }
                _ if !run.is_empty() => lines.push(vehicle_line(Some(n), std::mem::take(&mut run))),
                _ => {}
            }
        }
        lines.push(vehicle_line(Some(n), run));
    }
    // a rate needs two consecutive steps with a heading: say why the plot is empty
    let title = if lines.iter().all(|l| l.points.is_empty()) {
        "AUV heading rates: none (no two steps with a heading)"
    } else {
        "AUV heading rates (final plan)"
    };
    let mut s = Series::new(scene, "heading-rate", title, entries);
    s.y_desc = "heading rate ψ̇ (mrad/s)".into();
    s.limits = vec![(max, style::LIMIT), (-max, style::LIMIT)];
    s.lines = lines;
    s.fit_y(false);
    let m = s.y_range.0.abs().max(s.y_range.1.abs());
    s.y_range = (-m, m);
    s
}

fn vehicle_line(v: Option<usize>, points: Vec<(f64, f64)>) -> Line {
    Line {
        colour: vehicle_colour(v),
        width: if v.is_none() { 3 } else { 2 },
        outlined: false,
        points,
    }
}

/// Dashed vertical lines at the start of windows 1, 2, …, labelled at the top.
pub(crate) fn window_marks<DB: DrawingBackend>(
    chart: &mut Chart2d<'_, DB>,
    scene: &Scene,
    (lo, hi): (f64, f64),
    label: bool,
) -> DrawResult<DB> {
    for (w, t) in scene.window_starts() {
        chart.draw_series(std::iter::once(plotters::element::DashedPathElement::new(
            vec![(t, lo), (t, hi)],
            8,
            6,
            style::WINDOW.stroke_width(2),
        )))?;
        if label {
            let style = text(TICK)
                .color(&style::WINDOW)
                .pos(Pos::new(HPos::Left, VPos::Top));
            chart.plotting_area().draw(
                &(EmptyElement::at((t, hi)) + Text::new(format!("window {w}"), (6, 6), style)),
            )?;
        }
    }
    Ok(())
}

impl Figure for Series<'_> {
    fn name(&self) -> &'static str {
        self.name
    }

    fn size(&self) -> (u32, u32) {
        (WIDTH, self.frame.height() + PLOT_H)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let t = self.scene.times();
        let (t0, t1) = (t[0], *t.last().unwrap_or(&t[0]));
        let (y0, y1) = self.y_range;
        let mut chart = ChartBuilder::on(&body)
            .margin(20)
            .margin_right(40)
            .x_label_area_size(70)
            .y_label_area_size(110)
            .build_cartesian_2d(t0..t1.max(t0 + 1.0), y0..y1)?;
        axes(&mut chart, "time t (s)", &self.y_desc, true)?;
        if let Some((lo, hi)) = self.band {
            chart.draw_series(std::iter::once(Rectangle::new(
                [(t0, lo), (t1, hi)],
                style::BAND.mix(0.45).filled(),
            )))?;
        }
        window_marks(&mut chart, self.scene, (y0, y1), true)?;
        for l in self.lines.iter().filter(|l| l.outlined) {
            let style = outline(l.colour).stroke_width(l.width + 2);
            chart.draw_series(LineSeries::new(l.points.iter().copied(), style))?;
        }
        for l in &self.lines {
            let style = l.colour.stroke_width(l.width);
            chart.draw_series(LineSeries::new(l.points.iter().copied(), style))?;
        }
        let dot = |&p: &(f64, f64)| {
            EmptyElement::at(p)
                + Circle::new((0, 0), 5, style::A2A.filled())
                + Circle::new((0, 0), 5, outline(style::A2A).stroke_width(1))
        };
        chart.draw_series(self.dots.iter().map(dot))?;
        // Limits over the data, so a value at its limit shows both.
        for &(v, c) in &self.limits {
            chart.draw_series(std::iter::once(plotters::element::DashedPathElement::new(
                vec![(t0, v), (t1, v)],
                12,
                7,
                c.stroke_width(3),
            )))?;
        }

        let area = chart.plotting_area();
        for &p in &self.ticks {
            area.draw(
                &(EmptyElement::at(p)
                    + PathElement::new(vec![(-9, 0), (9, 0)], style::LIMIT.stroke_width(3))),
            )?;
        }
        for &p in &self.rings {
            area.draw(
                &(EmptyElement::at(p) + Circle::new((0, 0), 8, style::LIMIT.stroke_width(3))),
            )?;
        }
        Ok(())
    }
}
