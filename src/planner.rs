//! Algorithm 1's outer loop: the initial state (line 5), then for each window Step 1 (P2, line 9),
//! Step 2 (P3 and P4 per step, lines 13–16), Step 3 (P5 with the line-of-sight loop, lines
//! 17–22), the acoustic chain verified at every step, and the next window starting where the last
//! one ended (line 7).

use crate::conic::ConicError;
use crate::metrics::{first_cut_off, mission_metrics, window_metrics, MetricParams};
use crate::plan::{
    AuvState, Graph, InitialState, LinkReport, Metrics, ModelRecord, ObjectiveTerms, Plan,
    SeafloorRecord, Stage, Window, FORMAT,
};
use crate::scenario::Scenario;
use crate::scp::ScpOutcome;
use crate::seafloor::{GridFormat, LoadOptions, Region, Seafloor, SeafloorError, Values};
use crate::step3::LinkSet;
use crate::team::TeamProblem;
use crate::trajectory::Start;
use crate::trajectory::Trajectory;
use crate::vehicle::{AuvModel, Damping, UsvModel, VehicleError};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;
use thiserror::Error;

/// Errors of planning.
#[derive(Debug, Error)]
pub enum PlanError {
    #[error(transparent)]
    Seafloor(#[from] SeafloorError),
    #[error(transparent)]
    Vehicle(#[from] VehicleError),
    #[error(transparent)]
    Conic(#[from] ConicError),
    #[error("the start of window {window} is infeasible: {why}")]
    InvalidStart { window: usize, why: String },
    #[error("no initial AUV position can be drawn (Algorithm 1, line 5): {0}")]
    NoInitialPosition(String),
    #[error("{stage}: the convex subproblem failed: Clarabel status {status} after {iterations} interior-point iterations")]
    Solver {
        stage: &'static str,
        status: String,
        iterations: u32,
    },
    #[error("{stage}: the convex subproblem is infeasible (Clarabel status {status}); {}", culprit_text(.culprit))]
    ConvexInfeasible {
        stage: &'static str,
        status: String,
        /// The first constraint group without which it becomes feasible, if one is.
        culprit: Option<String>,
    },
    #[error("{stage}: a constraint cannot hold: {detail}")]
    Infeasible { stage: &'static str, detail: String },
    #[error("step3: the {link} has no line of sight at step {k} after {rounds} rounds of lowering its range (C1_13): {why}")]
    LineOfSight {
        link: String,
        k: usize,
        rounds: usize,
        why: String,
    },
    #[error("the acoustic chain breaks at window {window}, step {k}: {why}")]
    Disconnected {
        window: usize,
        k: usize,
        why: String,
    },
    #[error(transparent)]
    Scp(#[from] crate::scp::ScpFailure),
}

fn culprit_text(c: &Option<String>) -> String {
    match c {
        Some(c) => format!("it becomes feasible without {c}, so that constraint cannot hold"),
        None => "no single constraint group is to blame: several conflict".into(),
    }
}

fn metric_params(s: &Scenario) -> MetricParams {
    MetricParams {
        dt: s.horizon.dt,
        sonar_range: s.acoustic.sonar_range,
        resolution: s.acoustic.resolution,
        swath_width: s.auv.swath_width,
    }
}

/// Metrics over every window of the mission.
fn mission(windows: &[Window], floor: &Seafloor, s: &Scenario) -> Metrics {
    let parts: Vec<(&Stage, &[Vec<crate::plan::Link>])> = windows
        .iter()
        .map(|w| (&w.final_, w.links.links.as_slice()))
        .collect();
    let times: Vec<[f64; 3]> = windows
        .iter()
        .map(|w| {
            [
                w.step1.solve_time_s,
                w.graph.solve_time_s,
                w.final_.solve_time_s,
            ]
        })
        .collect();
    mission_metrics(&parts, floor, &metric_params(s), &times)
}

/// Everything the planner needs besides the scenario: the floor and where things came from.
pub struct PlanInput<'a> {
    pub scenario: &'a Scenario,
    pub floor: &'a Seafloor,
    /// "embedded default" or the scenario file's path.
    pub scenario_source: String,
    pub overrides: Vec<String>,
    /// Where the floor came from.
    pub seafloor_source: FloorSource,
}

/// Where a floor came from, as the plan records it, and what the loader had to say.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorSource {
    /// "synthetic" or "file".
    pub source: String,
    /// The file's path (absolute when the planner loaded it).
    pub path: Option<String>,
    /// "synthetic", "esri-ascii" or "geotiff".
    pub format: String,
    /// The file's CRS ("none", "EPSG:4326", …).
    pub crs: String,
    pub values: Values,
    /// [lat, lon] of the local frame's origin for a geographic grid.
    pub origin: Option<[f64; 2]>,
    /// Warnings of the loader (likely sign-convention mistakes, datum assumptions), for the
    /// user; not recorded in the plan.
    pub warnings: Vec<String>,
}

impl FloorSource {
    /// The synthetic floor.
    pub fn synthetic() -> FloorSource {
        FloorSource {
            source: "synthetic".into(),
            path: None,
            format: "synthetic".into(),
            crs: "none".into(),
            values: Values::Elevation,
            origin: None,
            warnings: Vec::new(),
        }
    }

    /// An ESRI ASCII grid file of elevations in metres (no CRS).
    pub fn file(path: Option<String>) -> FloorSource {
        FloorSource {
            source: "file".into(),
            path,
            format: GridFormat::EsriAscii.name().into(),
            ..FloorSource::synthetic()
        }
    }

    /// The plan's record of `floor` loaded from this source: where it came from, its grid and
    /// its fingerprint.
    pub fn record(&self, floor: &Seafloor) -> SeafloorRecord {
        let (z_min, z_max) = floor.z_range();
        SeafloorRecord {
            source: self.source.clone(),
            path: self.path.clone(),
            format: self.format.clone(),
            crs: self.crs.clone(),
            values: self.values,
            origin: self.origin,
            nx: floor.nx(),
            ny: floor.ny(),
            x0: floor.x0(),
            y0: floor.y0(),
            dx: floor.dx(),
            dy: floor.dy(),
            z_min,
            z_max,
            fingerprint: floor.fingerprint(),
        }
    }
}

/// The window's start must satisfy the constraints that no input can change at k = 0, over the
/// floor and over its keep-out field `keep_out` (`Seafloor::keep_out`).
pub fn check_start(
    s: &Scenario,
    floor: &Seafloor,
    keep_out: &Seafloor,
    start: &Start,
    window: usize,
) -> Result<(), PlanError> {
    let bad = |why: String| Err(PlanError::InvalidStart { window, why });
    if start.auvs.len() != s.team.auvs {
        return bad(format!(
            "{} AUV states for team.auvs = {}",
            start.auvs.len(),
            s.team.auvs
        ));
    }
    let tol = s.scp.feasibility_tol;
    if let Some(why) = position_problem(floor, start.usv[0], start.usv[1]) {
        return bad(format!("the USV {why}"));
    }
    let [x, y] = start.usv;
    let field = keep_out.elevation(x, y)?;
    if field > tol {
        return bad(format!(
            "the USV at ({x:.1}, {y:.1}) is {}",
            next_to_obstacle(field, floor.elevation(x, y)?)
        ));
    }
    for (n, a) in start.auvs.iter().enumerate() {
        let p = a.position;
        let d =
            ((p[0] - start.usv[0]).powi(2) + (p[1] - start.usv[1]).powi(2) + p[2] * p[2]).sqrt();
        if d > s.acoustic.sonar_range + 1e-9 {
            return bad(format!(
                "AUV {n} is {d:.1} m from the USV, beyond the sonar range d_s = {} m (C1_6 at k = 0)",
                s.acoustic.sonar_range
            ));
        }
        if p[2] > -s.auv.surface_clearance + 1e-9 {
            return bad(format!(
                "AUV {n} is at z = {:.2} m, above −surface_clearance = {} m (C1_4)",
                p[2], -s.auv.surface_clearance
            ));
        }
        if let Some(why) = position_problem(floor, p[0], p[1]) {
            return bad(format!("AUV {n} {why}"));
        }
        let z = floor.elevation(p[0], p[1])?;
        if p[2] < z + s.auv.floor_clearance - tol {
            return bad(format!(
                "AUV {n} at z = {:.2} m is less than ε = {} m above the floor (z = {z:.2} m) (C2_2)",
                p[2], s.auv.floor_clearance
            ));
        }
        let field = keep_out.elevation(p[0], p[1])?;
        if p[2] < field + s.auv.floor_clearance - tol {
            return bad(format!(
                "AUV {n} at ({:.1}, {:.1}, {:.1}) is {}; it needs ε = {} m of clearance above it",
                p[0],
                p[1],
                p[2],
                next_to_obstacle(field, z),
                s.auv.floor_clearance
            ));
        }
        let v = (a.velocity.iter().map(|c| c * c).sum::<f64>()).sqrt();
        if v > s.auv.max_speed + 1e-6 {
            return bad(format!(
                "AUV {n} moves at {v:.3} m/s, above V_max = {} (C1_7)",
                s.auv.max_speed
            ));
        }
    }
    Ok(())
}

/// Why a point off every obstacle cell is kept out of all the same: `field` is the keep-out
/// field there and `z` the floor.
fn next_to_obstacle(field: f64, z: f64) -> String {
    format!(
        "next to an obstacle cell (NODATA or land): the planner keeps every vehicle out of \
         obstacle cells with a keep-out field that rises from the floor (here z = {z:.1} m) \
         to above the surface over them, here z = {field:.1} m (at most one cell of margin; \
         move the start away from the obstacle)"
    )
}

/// Why a vehicle cannot start at (x, y): outside the grid, or in an obstacle cell (NODATA,
/// land). The text starts with the position.
fn position_problem(floor: &Seafloor, x: f64, y: f64) -> Option<String> {
    let at = format!("at ({x:.1}, {y:.1})");
    if !floor.contains(x, y) {
        return Some(format!(
            "{at} is outside the seafloor grid, which covers {}",
            floor.extent()
        ));
    }
    match floor.obstacle(x, y) {
        Ok(None) => None,
        Ok(Some(o)) => Some(format!("{at} is {o}")),
        Err(e) => Some(format!("{at}: {e}")),
    }
}

/// Algorithm 1, line 5: USV at the origin; AUVs at seeded random points in the half ball of
/// radius d_s below it, at least surface_clearance below the surface and ε above the floor's
/// keep-out field `keep_out` (`Seafloor::keep_out`: the floor itself away from obstacles), at
/// rest. Or the explicit `[initial]` of the scenario.
pub fn initial_state(
    s: &Scenario,
    floor: &Seafloor,
    keep_out: &Seafloor,
) -> Result<InitialState, PlanError> {
    if let Some(init) = &s.initial {
        return Ok(InitialState {
            origin: "explicit".into(),
            usv: init.usv,
            auvs: init
                .auvs
                .iter()
                .map(|p| AuvState {
                    position: *p,
                    velocity: [0.0; 3],
                })
                .collect(),
        });
    }
    if let Some(why) = position_problem(floor, 0.0, 0.0) {
        return Err(PlanError::InvalidStart {
            window: 0,
            why: format!(
                "the USV {why} (without [initial] the USV starts at the origin of the frame; \
                 give [initial] positions inside the grid)"
            ),
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
    let ds = s.acoustic.sonar_range;
    let mut auvs = Vec::with_capacity(s.team.auvs);
    const TRIES: usize = 100_000;
    for n in 0..s.team.auvs {
        let mut found = None;
        for _ in 0..TRIES {
            let p = [
                rng.gen_range(-ds..ds),
                rng.gen_range(-ds..ds),
                rng.gen_range(-ds..0.0),
            ];
            if p.iter().map(|c| c * c).sum::<f64>() > ds * ds || p[2] > -s.auv.surface_clearance {
                continue;
            }
            if !floor.contains(p[0], p[1]) || floor.is_obstacle(p[0], p[1])? {
                continue;
            }
            if p[2] >= keep_out.elevation(p[0], p[1])? + s.auv.floor_clearance {
                found = Some(p);
                break;
            }
        }
        let Some(p) = found else {
            let z0 = floor.elevation(0.0, 0.0).unwrap_or(f64::NAN);
            return Err(PlanError::NoInitialPosition(format!(
                "no point for AUV {n} in {TRIES} draws within d_s = {ds} m of the USV, at least \
                 {} m below the surface and {} m above the floor (floor under the USV: z = {z0:.1} m)",
                s.auv.surface_clearance, s.auv.floor_clearance
            )));
        };
        auvs.push(AuvState {
            position: p,
            velocity: [0.0; 3],
        });
    }
    Ok(InitialState {
        origin: "seeded".into(),
        usv: [0.0, 0.0],
        auvs,
    })
}

/// The rectangle of the planner's frame that the mission can reach, [x_min, x_max, y_min,
/// y_max], metres: the bounding box of the start (the explicit `[initial]` positions, or the
/// USV at the origin with the AUVs within d_s of it), widened by twice the distance the fastest
/// vehicle covers at its speed limit over every window (speed limits hold at the samples; the
/// factor 2 covers the path between samples), plus d_max and the swath width.
pub fn mission_area(s: &Scenario) -> [f64; 4] {
    let mut pts: Vec<[f64; 2]> = Vec::new();
    match &s.initial {
        Some(init) => {
            pts.push(init.usv);
            pts.extend(init.auvs.iter().map(|p| [p[0], p[1]]));
        }
        None => {
            let d = s.acoustic.sonar_range;
            pts.extend([[-d, -d], [d, d]]);
        }
    }
    let span = (s.windows * s.horizon.steps) as f64 * s.horizon.dt;
    let reach = 2.0 * span * s.auv.max_speed.max(s.usv.max_speed)
        + s.acoustic.max_range.max(s.acoustic.sonar_range)
        + s.auv.swath_width;
    let fold = |f: fn(f64, f64) -> f64, d: usize, init: f64| pts.iter().map(|p| p[d]).fold(init, f);
    [
        fold(f64::min, 0, f64::INFINITY) - reach,
        fold(f64::max, 0, f64::NEG_INFINITY) + reach,
        fold(f64::min, 1, f64::INFINITY) - reach,
        fold(f64::max, 1, f64::NEG_INFINITY) + reach,
    ]
}

/// The seafloor a scenario names: the grid file (a relative path is taken from `base_dir`, the
/// scenario file's directory), cut to the [`mission_area`], or the synthetic floor. Returns it
/// with its source record (and the loader's warnings).
pub fn scenario_floor(
    s: &Scenario,
    base_dir: &std::path::Path,
) -> Result<(Seafloor, FloorSource), PlanError> {
    match &s.seafloor.file {
        Some(f) => {
            let path = base_dir.join(f);
            let [x_min, x_max, y_min, y_max] = mission_area(s);
            let opts = LoadOptions {
                values: s.seafloor.values,
                origin: s.seafloor.origin,
                crs: s.seafloor.crs.clone(),
                region: Region::Area {
                    x_min,
                    x_max,
                    y_min,
                    y_max,
                },
            };
            let l = crate::seafloor::load(&path, &opts)?;
            // recorded absolute, so that `shoal check` finds it from any working directory
            let recorded = std::fs::canonicalize(&path).unwrap_or(path);
            let source = FloorSource {
                source: "file".into(),
                path: Some(recorded.display().to_string()),
                format: l.format.name().into(),
                crs: l.crs.to_string(),
                values: l.values,
                origin: l.origin,
                warnings: l.warnings,
            };
            Ok((l.floor, source))
        }
        None => Ok((
            Seafloor::synthetic(&s.seafloor.synthetic, s.seed)?,
            FloorSource::synthetic(),
        )),
    }
}

/// Plan every window of the scenario.
pub fn plan(input: &PlanInput) -> Result<Plan, PlanError> {
    plan_with_progress(input, |_| {})
}

/// What the planner reports as it goes (the CLI prints a line per event on stderr).
#[derive(Debug, Clone, Copy)]
pub enum Progress<'a> {
    Step1 {
        window: usize,
        stage: &'a Stage,
    },
    Step2 {
        window: usize,
        graph: &'a Graph,
    },
    Step3 {
        window: usize,
        stage: &'a Stage,
        los_rounds: usize,
        out_of_band: usize,
    },
}

/// A stage record of the plan from a solved team problem.
fn stage_record(
    problem: &TeamProblem,
    out: &ScpOutcome<Trajectory>,
    iterations: usize,
    seconds: f64,
) -> Stage {
    let t = &out.iterate;
    let terms = problem.terms(t);
    Stage {
        status: out.status.as_str().into(),
        iterations,
        solve_time_s: seconds,
        objective: ObjectiveTerms {
            energy: terms.energy,
            depth: terms.depth,
            height: terms.height,
            usv: terms.usv,
            spread: terms.spread,
            band: terms.band_a2u + terms.band_a2a,
            total: problem.objective(&terms),
        },
        max_violation: out.evaluation.max_violation,
        usv: t.usv_path(),
        auvs: t.auv_paths(problem.scenario.auv.min_heading_speed),
        scp: out.trace.clone(),
    }
}

/// Plan every window (Algorithm 1): Step 1, Step 2, Step 3 with its line-of-sight loop, then
/// the next window from the last state. `progress` hears of each step as it ends.
pub fn plan_with_progress(
    input: &PlanInput,
    mut progress: impl FnMut(Progress),
) -> Result<Plan, PlanError> {
    let s = input.scenario;
    let floor = input.floor;
    let damping = Damping::from_params(&s.auv)?;
    let auv = AuvModel::new(&s.auv, s.horizon.dt)?;
    let usv = UsvModel {
        dt: s.horizon.dt,
        max_speed: s.usv.max_speed,
    };
    // what the constraints see: every obstacle cell above the surface (built once per plan)
    let keep_out = floor.keep_out();
    let initial = initial_state(s, floor, &keep_out)?;
    let mut start = Start {
        usv: initial.usv,
        auvs: initial.auvs.clone(),
    };
    let mut windows = Vec::with_capacity(s.windows);
    let mut heading = None;
    for w in 0..s.windows {
        check_start(s, floor, &keep_out, &start, w)?;
        // Step 1 (P2), Algorithm 1 line 9
        let clock = Instant::now();
        let mut p2 = TeamProblem::new(s, floor, &keep_out, auv, usv, start.clone());
        let out1 = crate::step1::solve(&mut p2, heading)?;
        let step1 = stage_record(&p2, &out1, out1.trace.len(), clock.elapsed().as_secs_f64());
        progress(Progress::Step1 {
            window: w,
            stage: &step1,
        });
        // Step 2 (P3, P4), lines 13–16
        let graph = crate::step2::solve(&out1.iterate, floor, s.acoustic.resolution);
        progress(Progress::Step2 {
            window: w,
            graph: &graph,
        });
        // Step 3 (P5) and line of sight, lines 17–22
        let clock = Instant::now();
        let links = LinkSet::from_graph(&graph, s.acoustic.sonar_range, s.acoustic.band_tolerance);
        let mut p5 =
            TeamProblem::new(s, floor, &keep_out, auv, usv, start.clone()).with_links(links);
        let out3 = crate::step3::solve(&mut p5, &out1.iterate)?;
        let final_ = stage_record(
            &p5,
            &out3.outcome,
            out3.iterations,
            clock.elapsed().as_secs_f64(),
        );
        progress(Progress::Step3 {
            window: w,
            stage: &final_,
            los_rounds: out3.los_rounds,
            out_of_band: out3.out_of_band.len(),
        });
        let t = &out3.outcome.iterate;
        let last = t.usv_u.last().copied().unwrap_or([0.0; 2]);
        if last[0].hypot(last[1]) > 1e-6 {
            heading = Some(last[1].atan2(last[0]));
        }
        start = t.end();
        let report = LinkReport {
            links: out3.links.links,
            bands: out3.links.bands,
            out_of_band: out3.out_of_band,
            los_rounds: out3.los_rounds,
        };
        let times = [step1.solve_time_s, graph.solve_time_s, final_.solve_time_s];
        let params = metric_params(s);
        if let Some((k, n)) = first_cut_off(&final_, floor, &params) {
            let p = final_.auvs[n].position[k];
            return Err(PlanError::Disconnected {
                window: w,
                k,
                why: format!(
                    "AUV {n} at ({:.1}, {:.1}, {:.1}) reaches the USV through no chain of links \
                     within d_s = {} m with line of sight",
                    p[0], p[1], p[2], s.acoustic.sonar_range
                ),
            });
        }
        let metrics = window_metrics(&final_, &report.links, floor, &params, times);
        windows.push(Window {
            index: w,
            start_time: w as f64 * s.horizon.steps as f64 * s.horizon.dt,
            step1,
            graph,
            final_,
            links: report,
            metrics,
        });
    }
    Ok(Plan {
        format: FORMAT.into(),
        shoal_version: env!("CARGO_PKG_VERSION").into(),
        scenario_source: input.scenario_source.clone(),
        overrides: input.overrides.clone(),
        scenario: s.clone(),
        seafloor: input.seafloor_source.record(floor),
        model: ModelRecord { damping, auv, usv },
        metrics: mission(&windows, floor, s),
        initial,
        windows,
    })
}
