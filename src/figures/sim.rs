//! Figures of a simulated mission (`shoal simulate`, a [`SimRecord`]): the team's position error
//! against time under every navigation policy (`sim-error`), and a top view of the planned,
//! executed and estimated paths with their uncertainty (`sim-tracks`, in [`super::sim_tracks`]).
//!
//! Both follow the plan's figures: the same frame (title and legend), fonts, axes and vehicle
//! colours; the navigation policies have colours of their own, listed in the legend.

use super::canvas::{self, Area, DrawResult, Figure, Images};
use super::map::{axes, axes_with};
use super::scene::Scene;
use super::series::window_marks;
use super::sim_tracks::Tracks;
use super::style::{self, Entry, Frame, Swatch};
use super::FigureError;
use crate::plan::Plan;
use crate::seafloor::Seafloor;
use crate::sim::policy::Policy;
use crate::sim::record::{EstimateRecord, FlightRecord, SimRecord};
use crate::sim::reference::{Flown, Reference};
use plotters::prelude::*;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// The figures [`write_sim`] writes, by file stem; each as `STEM.png` and `STEM.svg`.
pub const SIM_FIGURES: [&str; 2] = ["sim-error", "sim-tracks"];

/// Write the figures of `sim`, a simulation of `plan` over `floor`, into `dir` (created if
/// needed): `sim-error` (the team's position error against time under every policy and both
/// estimators) and `sim-tracks` (the paths over the floor, with the planned-chain factor-graph
/// estimate, or when that estimator failed the next of
/// [`SHOWN_ESTIMATES`](crate::viewer::data::SHOWN_ESTIMATES) the record holds). Returns the paths written: `STEM.png` and `STEM.svg` for every stem of
/// [`SIM_FIGURES`].
pub fn write_sim(
    plan: &Plan,
    floor: &Seafloor,
    sim: &SimRecord,
    dir: &Path,
) -> Result<Vec<PathBuf>, FigureError> {
    // the first estimate the record holds, as the viewer picks it (a failed estimator leaves
    // its estimate out)
    let (policy, estimator, _) = crate::viewer::data::SHOWN_ESTIMATES
        .into_iter()
        .find(|&(p, e, f)| estimate(sim, f, p, e).is_some())
        .unwrap_or(crate::viewer::data::DEFAULT_ESTIMATE);
    write_sim_with(plan, floor, sim, dir, policy, estimator)
}

/// [`write_sim`], with `sim-tracks` showing the estimate of `policy` by `estimator`
/// ("factor_graph" or "ekf") on the final plan's flight.
pub fn write_sim_with(
    plan: &Plan,
    floor: &Seafloor,
    sim: &SimRecord,
    dir: &Path,
    policy: Policy,
    estimator: &str,
) -> Result<Vec<PathBuf>, FigureError> {
    let scene = Scene::new(plan, floor)?;
    check(&scene, sim)?;
    let shown = estimate(sim, "final", policy, estimator).ok_or_else(|| {
        FigureError::Sim(format!(
            "it has no {estimator} estimate of policy {} on the final plan's flight",
            policy.name()
        ))
    })?;
    let mut written = canvas::write(&ErrorPlot::new(&scene, sim), dir)?;
    written.extend(canvas::write(&Tracks::new(&scene, sim, shown), dir)?);
    Ok(written)
}

/// The estimate of `policy` by `estimator` on the `flown` ("final" or "step1") flight.
pub(crate) fn estimate<'a>(
    sim: &'a SimRecord,
    flown: &str,
    policy: Policy,
    estimator: &str,
) -> Option<&'a EstimateRecord> {
    sim.estimates
        .iter()
        .find(|e| e.flown == flown && e.policy == policy && e.estimator == estimator)
}

/// The colour of a policy's lines in `sim-error` (which draws no vehicle, so these may repeat
/// vehicle colours).
pub(crate) fn policy_colour(p: Policy) -> RGBColor {
    match p {
        Policy::DeadReckoning => RGBColor(0xe6, 0x55, 0x0d),
        Policy::A2u => RGBColor(0x1f, 0x77, 0xb4),
        Policy::Chain => RGBColor(0x2c, 0xa0, 0x2c),
        Policy::AllLinks => RGBColor(0x94, 0x67, 0xbd),
    }
}

/// A policy's name in the legends.
pub(crate) fn policy_label(p: Policy) -> &'static str {
    match p {
        Policy::DeadReckoning => "dead reckoning",
        Policy::A2u => "A2U only",
        Policy::Chain => "planned chain",
        Policy::AllLinks => "all links",
    }
}

/// An estimator's name in the legends.
pub(crate) fn estimator_label(e: &str) -> &str {
    match e {
        "factor_graph" => "factor graph",
        "ekf" => "EKF",
        other => other,
    }
}

/// The first of `whats` whose title ([`Scene::title`]) fits a figure `width` pixels wide, or
/// the last.
pub(crate) fn fitting_title(scene: &Scene, whats: &[String], width: u32) -> String {
    style::register_font();
    let font = style::text(style::TITLE);
    let fits = |t: &String| {
        font.font
            .box_size(t)
            .is_ok_and(|b| b.0 + 2 * TITLE_SIDE <= width)
    };
    let titles: Vec<String> = whats.iter().map(|w| scene.title(w)).collect();
    let last = titles.last().cloned().unwrap_or_default();
    titles.into_iter().find(fits).unwrap_or(last)
}

/// Room left of and right of a title, pixels.
const TITLE_SIDE: u32 = 20;

/// The Step 1 flight's estimate: grey.
const STEP1: RGBColor = RGBColor(0x8a, 0x8a, 0x8a);
const STEP1_LABEL: &str = "Step 1 paths (no chain), all links";

/// Checks that the record fits the plan and that every array the figures index has one entry
/// per AUV and per epoch.
fn check(scene: &Scene, sim: &SimRecord) -> Result<(), FigureError> {
    let bad = |why: String| Err(FigureError::Sim(why));
    let (n, epochs) = (scene.n, sim.times.len());
    if sim.auvs != n {
        return bad(format!("it has {} AUVs, the plan {n}", sim.auvs));
    }
    if epochs == 0 {
        return bad("it has no epochs".into());
    }
    let per_auv = |a: &[Vec<[f64; 3]>]| a.len() == n && a.iter().all(|p| p.len() == epochs);
    let flight_ok =
        |f: &FlightRecord| per_auv(&f.executed) && per_auv(&f.planned) && f.usv.len() == epochs;
    for (name, f) in [("flight", &sim.flight), ("step1_flight", &sim.step1_flight)] {
        if !flight_ok(f) {
            return bad(format!(
                "{name} has not {n} AUVs and a USV of {epochs} epochs each"
            ));
        }
    }
    for e in &sim.estimates {
        let ok = per_auv(&e.position)
            && e.covariance.len() == n
            && e.covariance.iter().all(|c| c.len() == epochs)
            && e.metrics.team_rmse_over_time_m.len() == epochs;
        if !ok {
            return bad(format!(
                "the {} estimate of policy {} ({}) has not {n} AUVs of {epochs} epochs each",
                e.estimator,
                e.policy.name(),
                e.flown
            ));
        }
    }
    Ok(())
}

const WIDTH: u32 = 1280;
/// Height of the error plot, and of the links panel below it.
const ERROR_H: u32 = 600;
const LINKS_H: u32 = 250;

struct Trace {
    colour: RGBColor,
    width: u32,
    dashed: bool,
    points: Vec<(f64, f64)>,
}

/// `sim-error`: the team's RMS position error against time, one colour per policy (factor graph
/// solid, EKF dashed) and the Step 1 flight's all-links estimate in grey; below it, the
/// fraction of the planned links up and received at each epoch.
struct ErrorPlot<'a> {
    scene: &'a Scene<'a>,
    frame: Frame,
    t_range: (f64, f64),
    y_max: f64,
    /// Drawn in order.
    traces: Vec<Trace>,
    /// At each epoch with planned links: time, % of them up (in range, line of sight), %
    /// received.
    links: Vec<(f64, f64, f64)>,
}

/// Colours of the links panel: A2U's light blue, paler (45 % of it over white), and a dark
/// blue.
const LINKS_UP: RGBColor = RGBColor(0xb0, 0xdf, 0xf8);
const LINKS_RX: RGBColor = RGBColor(0x1a, 0x3a, 0x6e);

impl<'a> ErrorPlot<'a> {
    fn new(scene: &'a Scene<'a>, sim: &'a SimRecord) -> ErrorPlot<'a> {
        let t = &sim.times;
        let series = |e: &EstimateRecord| -> Vec<(f64, f64)> {
            t.iter()
                .copied()
                .zip(e.metrics.team_rmse_over_time_m.iter().copied())
                .filter(|p| p.1.is_finite())
                .collect()
        };
        let mut traces = Vec::new();
        let mut entries = Vec::new();
        let step1 = estimate(sim, "step1", Policy::AllLinks, "factor_graph");
        if let Some(e) = step1 {
            traces.push(Trace {
                colour: STEP1,
                width: 3,
                dashed: false,
                points: series(e),
            });
        }
        let mut estimators = [false; 2];
        for p in Policy::EVERY {
            let c = policy_colour(p);
            for (i, (name, width, dashed)) in [("factor_graph", 3, false), ("ekf", 2, true)]
                .into_iter()
                .enumerate()
            {
                if let Some(e) = estimate(sim, "final", p, name) {
                    estimators[i] = true;
                    traces.push(Trace {
                        colour: c,
                        width,
                        dashed,
                        points: series(e),
                    });
                }
            }
            if sim
                .estimates
                .iter()
                .any(|e| e.flown == "final" && e.policy == p)
            {
                entries.push(Entry::new(policy_label(p), Swatch::Line(c, 4)));
            }
        }
        let dark = RGBColor(40, 40, 40);
        if estimators[0] {
            entries.push(Entry::new("factor graph", Swatch::Line(dark, 3)));
        }
        if estimators[1] {
            entries.push(Entry::new("EKF", Swatch::Dashed(dark, 2)));
        }
        if step1.is_some() {
            entries.push(Entry::new(STEP1_LABEL, Swatch::Line(STEP1, 3)));
        }
        let links = link_fractions(scene.plan, sim);
        if !links.is_empty() {
            entries.push(Entry::new(
                "planned links up (in range, line of sight)",
                Swatch::Area(LINKS_UP),
            ));
            entries.push(Entry::new(
                "planned links received",
                Swatch::Line(LINKS_RX, 3),
            ));
        }
        if scene.plan.windows.len() > 1 {
            entries.push(Entry::new("window start", Swatch::Dashed(style::WINDOW, 2)));
        }
        let y_max = traces
            .iter()
            .flat_map(|t| t.points.iter().map(|p| p.1))
            .fold(0.0, f64::max);
        let seed = sim.seed;
        let title = fitting_title(
            scene,
            &[
                format!("Team position error by policy, simulation seed {seed}"),
                format!("Team position error, sim seed {seed}"),
            ],
            WIDTH,
        );
        let (t0, t1) = (t[0], *t.last().unwrap_or(&t[0]));
        ErrorPlot {
            scene,
            frame: Frame::new(title, entries, WIDTH),
            t_range: (t0, t1.max(t0 + 1.0)),
            y_max: if y_max > 0.0 { 1.08 * y_max } else { 1.0 },
            traces,
            links,
        }
    }
}

/// Per epoch of the final plan's flight with planned links: its time, and the percentage of
/// those links up (in range and in line of sight) and received.
fn link_fractions(plan: &Plan, sim: &SimRecord) -> Vec<(f64, f64, f64)> {
    let reference = Reference::new(plan, Flown::Final);
    let mut pings: Vec<Vec<_>> = vec![Vec::new(); sim.times.len()];
    for p in &sim.flight.pings {
        if let Some(at) = pings.get_mut(p.epoch) {
            at.push(p);
        }
    }
    let mut out = Vec::new();
    for (e, &t) in sim.times.iter().enumerate() {
        let (w, k) = reference.nearest_step(t);
        let planned: HashSet<(usize, usize)> = Reference::links(plan, w, k)
            .into_iter()
            .map(|(a, b)| (a.min(b), a.max(b)))
            .collect();
        if planned.is_empty() {
            continue;
        }
        let (mut up, mut rx) = (0, 0);
        for p in &pings[e] {
            if p.line_of_sight && planned.contains(&(p.a.min(p.b), p.a.max(p.b))) {
                up += 1;
                rx += usize::from(p.received);
            }
        }
        let pc = |x: usize| 100.0 * x as f64 / planned.len() as f64;
        out.push((t, pc(up), pc(rx)));
    }
    out
}

impl Figure for ErrorPlot<'_> {
    fn name(&self) -> &'static str {
        SIM_FIGURES[0]
    }

    fn size(&self) -> (u32, u32) {
        let links = if self.links.is_empty() { 0 } else { LINKS_H };
        (WIDTH, self.frame.height() + ERROR_H + links)
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let (t0, t1) = self.t_range;
        let panel = !self.links.is_empty();
        let (top, bottom) = body.split_vertically(ERROR_H);
        let mut chart = ChartBuilder::on(&top)
            .margin(20)
            .margin_right(40)
            .margin_bottom(if panel { 0 } else { 20 })
            .x_label_area_size(if panel { 40 } else { 70 })
            .y_label_area_size(110)
            .build_cartesian_2d(t0..t1, 0.0..self.y_max)?;
        let x_desc = if panel { "" } else { "time t (s)" };
        axes(&mut chart, x_desc, "team position error (m)", true)?;
        window_marks(&mut chart, self.scene, (0.0, self.y_max), true)?;
        for tr in &self.traces {
            let style = tr.colour.stroke_width(tr.width);
            let points = tr.points.iter().copied();
            if tr.dashed {
                chart.draw_series(DashedLineSeries::new(points, 10, 6, style))?;
            } else {
                chart.draw_series(LineSeries::new(points, style))?;
            }
        }
        if !panel {
            return Ok(());
        }

        let mut chart = ChartBuilder::on(&bottom)
            .margin(20)
            .margin_right(40)
            .x_label_area_size(70)
            .y_label_area_size(110)
            .build_cartesian_2d(t0..t1, 0.0..105.0)?;
        axes_with(&mut chart, "time t (s)", "planned links (%)", true, 3)?;
        let up = self.links.iter().map(|l| (l.0, l.1));
        chart.draw_series(AreaSeries::new(up, 0.0, LINKS_UP.filled()))?;
        window_marks(&mut chart, self.scene, (0.0, 105.0), false)?;
        let rx = self.links.iter().map(|l| (l.0, l.2));
        chart.draw_series(LineSeries::new(rx, LINKS_RX.stroke_width(2)))?;
        Ok(())
    }
}
