//! Algorithm 1's outer loop: for each window, Step 1 (P2, line 9), Step 2 (P3 and P4 per step,
//! lines 13–16), Step 3 (P5 with the line-of-sight loop, lines 17–22), the acoustic chain
//! verified at every step, and the next window starting where the last one ended (line 7).
//! The set-up around it (the initial state, the floor, each window's start) is `mission`.
//!
//! ```no_run
//! let scenario = shoal::Scenario::default();
//! let floor = shoal::Seafloor::synthetic(&scenario.seafloor.synthetic, scenario.seed)?;
//! let plan = shoal::Planner::new(&scenario, &floor).run()?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use crate::conic::SolveReport;
use crate::error::PlanError;
use crate::metrics::{first_cut_off, mission_metrics, window_metrics, MetricParams};
use crate::mission::{check_start, initial_state, next_window, FloorSource};
use crate::plan::{
    Course, Graph, LinkReport, Metrics, ModelRecord, ObjectiveTerms, Plan, ScpIteration, Stage,
    Window, FORMAT, METHOD_MPC,
};
use crate::scenario::Scenario;
use crate::scp::{Iteration, ScpOutcome};
use crate::seafloor::Seafloor;
use crate::team::{LinkSet, TeamProblem};
use crate::trajectory::{Start, Trajectory};
use crate::vehicle::{AuvModel, Damping, UsvModel};
use crate::{step1, step2, step3};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// What the planner reports as it goes (the CLI prints a line per step on stderr).
#[derive(Debug, Clone, Copy)]
pub enum Progress<'a> {
    /// An SCP iteration of Step 1 (`step` 1) or Step 3 (`step` 3) has ended.
    Iteration {
        /// The window (0-based).
        window: usize,
        /// 1 or 3.
        step: u8,
        /// The iteration, as the plan records it.
        iteration: &'a ScpIteration,
    },
    /// Step 1 has ended.
    Step1 {
        /// The window (0-based).
        window: usize,
        /// Step 1's plan and its SCP record.
        stage: &'a Stage,
        /// The first courses tried before it (`usv.courses` > 1, first window; else empty).
        courses: &'a [Course],
    },
    /// Step 2 has ended.
    Step2 {
        /// The window (0-based).
        window: usize,
        /// The acoustic graph of every step.
        graph: &'a Graph,
    },
    /// A window failed from one first guess and is planned again from another.
    Retry {
        /// The window (0-based).
        window: usize,
        /// The next first guess's course turn, rad.
        turn: f64,
        /// Why the window failed.
        why: &'a PlanError,
    },
    /// Step 3 has ended.
    Step3 {
        /// The window (0-based).
        window: usize,
        /// The window's final plan and its SCP record.
        stage: &'a Stage,
        /// Rounds of the line-of-sight loop.
        los_rounds: usize,
        /// Link-steps left outside their band.
        out_of_band: usize,
        /// P5's bridges (`LinkReport::bridges`).
        bridges: usize,
    },
}

/// Where a plan's inputs came from, as the plan file records them.
#[derive(Debug, Clone, PartialEq)]
pub struct Provenance {
    /// "embedded default", the scenario file's path, or "in memory" (the default).
    pub scenario_source: String,
    /// The `--set key=value` overrides applied to it.
    pub overrides: Vec<String>,
    /// Where the floor came from.
    pub seafloor: FloorSource,
}

impl Provenance {
    /// A scenario built in memory over the floor it names ([`FloorSource::of_scenario`]).
    pub fn in_memory(scenario: &Scenario) -> Provenance {
        Provenance {
            scenario_source: "in memory".into(),
            overrides: Vec::new(),
            seafloor: FloorSource::of_scenario(scenario),
        }
    }
}

type Listener<'a> = Box<dyn FnMut(Progress) + 'a>;

/// Plans every window of a scenario over a floor (Algorithm 1).
pub struct Planner<'a> {
    scenario: &'a Scenario,
    floor: &'a Seafloor,
    provenance: Provenance,
    progress: Option<Listener<'a>>,
    stop: Option<&'a AtomicBool>,
}

impl<'a> Planner<'a> {
    /// A planner for `scenario` over `floor`, with the provenance of
    /// [`Provenance::in_memory`] and no progress listener.
    pub fn new(scenario: &'a Scenario, floor: &'a Seafloor) -> Planner<'a> {
        Planner {
            scenario,
            floor,
            provenance: Provenance::in_memory(scenario),
            progress: None,
            stop: None,
        }
    }

    /// Record where the scenario and the floor came from.
    pub fn provenance(mut self, provenance: Provenance) -> Planner<'a> {
        self.provenance = provenance;
        self
    }

    /// Hear of every SCP iteration and every step as it ends.
    pub fn on_progress(mut self, f: impl FnMut(Progress) + 'a) -> Planner<'a> {
        self.progress = Some(Box::new(f));
        self
    }

    /// Stop after the window being planned when `stop` is set (by a Ctrl-C handler): the plan
    /// then holds the windows done so far, records `windows` as their number, and says in its
    /// warnings that it was cut short. A stop before the first window ends is not seen until it
    /// does.
    pub fn stop_when(mut self, stop: &'a AtomicBool) -> Planner<'a> {
        self.stop = Some(stop);
        self
    }

    /// Plan every window.
    pub fn run(mut self) -> Result<Plan, PlanError> {
        let mut listener = self.progress.take();
        let mut report = |p: Progress| {
            if let Some(f) = listener.as_mut() {
                f(p);
            }
        };
        run(
            self.scenario,
            self.floor,
            &self.provenance,
            &mut report as &mut dyn FnMut(Progress),
            self.stop,
        )
    }
}

pub(crate) fn metric_params(s: &Scenario) -> MetricParams {
    MetricParams {
        dt: s.horizon.dt,
        sonar_range: s.acoustic.sonar_range,
        resolution: s.acoustic.resolution,
        swath_width: s.auv.swath_width,
        survey_altitude: s.auv.survey_altitude,
    }
}

/// Metrics over every window of the mission.
pub(crate) fn mission(windows: &[Window], floor: &Seafloor, s: &Scenario) -> Metrics {
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

/// The plan's record of an SCP iteration.
fn iteration_record(it: &Iteration<SolveReport>) -> ScpIteration {
    ScpIteration {
        trust_region: it.trust_region,
        merit_before: it.merit_before,
        merit_after: it.merit_after,
        predicted: it.predicted,
        ratio: it.ratio,
        accepted: it.accepted,
        violation: it.violation,
        penalty: Some(it.penalty),
        extrapolated: it.extrapolated,
        solver_status: it.solve.status.to_string(),
        solver_iterations: it.solve.iterations,
        solver_time_s: it.solve.solve_time_s,
    }
}

/// A stage record of the plan from a solved team problem.
fn stage_record(
    problem: &TeamProblem,
    out: &ScpOutcome<Trajectory>,
    trace: Vec<ScpIteration>,
    seconds: f64,
) -> Stage {
    let t = &out.iterate;
    let terms = problem.terms(t);
    Stage {
        status: out.status.as_str().into(),
        iterations: trace.len(),
        solve_time_s: seconds,
        objective: ObjectiveTerms {
            energy: terms.energy,
            depth: terms.depth,
            height: terms.height,
            usv: terms.usv,
            spread: terms.spread,
            band: terms.band_a2u + terms.band_a2a,
            lanes: terms.lanes,
            total: problem.objective(&terms),
        },
        max_violation: out.evaluation.max_violation,
        usv: t.usv_path(),
        auvs: t.auv_paths(problem.scenario().auv.min_heading_speed),
        scp: trace,
    }
}

/// What every planner of a scenario starts from: the discrete models, the keep-out field
/// (every obstacle cell above the surface, built once per plan) and the initial state
/// (Algorithm 1, line 5).
pub(crate) struct Setup {
    /// The models, as the plan records them.
    pub model: ModelRecord,
    /// `Seafloor::keep_out` of the floor.
    pub keep_out: Seafloor,
    /// The state window 0 starts from.
    pub initial: crate::plan::InitialState,
}

impl Setup {
    /// The set-up of `s` over `floor`.
    pub fn of(s: &Scenario, floor: &Seafloor) -> Result<Setup, PlanError> {
        let model = ModelRecord {
            damping: Damping::from_params(&s.auv)?,
            auv: AuvModel::new(&s.auv, s.horizon.dt)?,
            usv: UsvModel {
                dt: s.horizon.dt,
                max_speed: s.usv.max_speed,
            },
        };
        let keep_out = floor.keep_out();
        let initial = initial_state(s, floor, &keep_out)?;
        Ok(Setup {
            model,
            keep_out,
            initial,
        })
    }

    /// The state window 0 starts from, as a [`Start`].
    pub fn start(&self) -> Start {
        Start {
            usv: self.initial.usv,
            auvs: self.initial.auvs.clone(),
        }
    }

    /// The plan of `windows` made by `method`: the record of the scenario, the floor, the
    /// models and the initial state, the mission's metrics and the advice.
    pub fn plan(
        self,
        s: &Scenario,
        floor: &Seafloor,
        provenance: &Provenance,
        method: &str,
        windows: Vec<Window>,
    ) -> Plan {
        Plan {
            warnings: crate::advice::warnings(&windows, s, floor),
            format: FORMAT.into(),
            method: method.into(),
            shoal_version: env!("CARGO_PKG_VERSION").into(),
            scenario_source: provenance.scenario_source.clone(),
            overrides: provenance.overrides.clone(),
            scenario: s.clone(),
            seafloor: provenance.seafloor.record(floor),
            model: self.model,
            current: if method == METHOD_MPC {
                crate::sim::current::planned(&s.current)
            } else {
                crate::sim::current::still()
            },
            metrics: mission(&windows, floor, s),
            initial: self.initial,
            windows,
        }
    }
}

/// Algorithm 1: Step 1, Step 2, Step 3 with its line-of-sight loop, then the next window from
/// the last state. `progress` hears of each iteration and step as it ends.
fn run(
    s: &Scenario,
    floor: &Seafloor,
    provenance: &Provenance,
    progress: &mut dyn FnMut(Progress),
    stop: Option<&AtomicBool>,
) -> Result<Plan, PlanError> {
    let setup = Setup::of(s, floor)?; // line 5
    let (auv, usv, keep_out) = (setup.model.auv, setup.model.usv, &setup.keep_out);
    let mut start = setup.start();
    let mut windows = Vec::with_capacity(s.windows);
    let mut heading = None;
    // the USV's path so far, which OF1_8 measures from with usv.away_from = "track"
    let mut track: Vec<[f64; 2]> = Vec::new();
    for w in 0..s.windows {
        check_start(s, floor, keep_out, &start, w)?;
        let mut first_error = None;
        let mut tries = GUESS_TURNS.iter().peekable();
        let planned = loop {
            let turn = *tries.next().expect("at least one course");
            let ctx = WindowContext {
                s,
                floor,
                keep_out,
                auv,
                usv,
                start: &start,
                heading,
                track: &track,
            };
            match plan_window(&ctx, w, turn, progress) {
                Ok(planned) => break planned,
                Err(e) if retried(&e) && tries.peek().is_some() => {
                    let next = **tries.peek().expect("peeked");
                    progress(Progress::Retry {
                        window: w,
                        turn: next,
                        why: &e,
                    });
                    first_error.get_or_insert(e);
                }
                // the error of the course the window would take, the one a user can act on
                Err(e) => return Err(first_error.unwrap_or(e)),
            }
        };
        track.extend_from_slice(&planned.path);
        (start, heading) = planned.next;
        windows.push(planned.window);
        if w + 1 < s.windows && stop.is_some_and(|f| f.load(Ordering::SeqCst)) {
            return Ok(cut_short(setup, s, floor, provenance, windows));
        }
    }
    Ok(setup.plan(s, floor, provenance, METHOD_MPC, windows))
}

/// The first-guess course turns (rad) a window is planned from, in order: the course it would
/// take, then a quarter turn to either side. A window fails from one course and plans from
/// another where its first guess led the SCP into a corner it could not leave (a team with a
/// cruise floor turning at a grid's corner: the default scenario, 5 windows, seed 2, broke
/// its chain at window 2, step 2).
const GUESS_TURNS: [f64; 4] = [
    0.0,
    std::f64::consts::FRAC_PI_2,
    -std::f64::consts::FRAC_PI_2,
    std::f64::consts::PI,
];

/// Whether a window's failure is one another first guess may avoid: a constraint the SCP left
/// violated, a convex model with no feasible point, or a chain broken in the final plan (not
/// an iteration limit, which every course meets alike).
fn retried(e: &PlanError) -> bool {
    matches!(
        e,
        PlanError::Infeasible { .. }
            | PlanError::ConvexInfeasible { .. }
            | PlanError::Disconnected { .. }
    )
}

/// What a window is planned from (see `run`).
struct WindowContext<'a> {
    s: &'a Scenario,
    floor: &'a Seafloor,
    keep_out: &'a Seafloor,
    auv: AuvModel,
    usv: UsvModel,
    start: &'a Start,
    heading: Option<f64>,
    track: &'a [[f64; 2]],
}

/// A planned window, the USV's path over it and the next window's start and heading.
struct WindowPlan {
    window: Window,
    path: Vec<[f64; 2]>,
    next: (Start, Option<f64>),
}

/// Steps 1–3 of window `w` from `ctx`, its first guess's course turned by `turn`.
fn plan_window(
    ctx: &WindowContext,
    w: usize,
    turn: f64,
    progress: &mut dyn FnMut(Progress),
) -> Result<WindowPlan, PlanError> {
    let WindowContext {
        s,
        floor,
        keep_out,
        auv,
        usv,
        start,
        heading,
        track,
    } = *ctx;
    // Step 1 (P2), line 9
    let clock = Instant::now();
    let p2 = TeamProblem::new(s, floor, keep_out, auv, usv, start.clone()).with_guess_turn(turn);
    // another window follows: the terminal margin, if the scenario asks for it
    let more = s.horizon.terminal_margin && w + 1 < s.windows;
    let mut p2 = p2.with_track(track).with_terminal(more);
    let mut trace = Vec::new();
    let (out1, courses) = step1::solve(&mut p2, heading, &mut |it| {
        trace.push(iteration_record(it));
        progress(Progress::Iteration {
            window: w,
            step: 1,
            iteration: trace.last().expect("just pushed"),
        });
    })?;
    let step1 = stage_record(&p2, &out1, trace, clock.elapsed().as_secs_f64());
    progress(Progress::Step1 {
        window: w,
        stage: &step1,
        courses: &courses,
    });
    // Step 2 (P3, P4), lines 13–16
    let graph = step2::solve(
        &out1.iterate,
        floor,
        s.acoustic.resolution,
        s.acoustic.sonar_range,
        s.acoustic.graph,
    );
    progress(Progress::Step2 {
        window: w,
        graph: &graph,
    });
    // Step 3 (P5) and line of sight, lines 17–22
    let clock = Instant::now();
    // the band tops at ρ·d_s (`acoustic.link_margin`): links planned to be heard
    let top = s.acoustic.link_margin * s.acoustic.sonar_range;
    let links = LinkSet::from_graph(&graph, top, s.acoustic.band_tolerance);
    let p5 = TeamProblem::new(s, floor, keep_out, auv, usv, start.clone())
        .with_links(links)
        .with_lanes(&out1.iterate);
    let mut p5 = p5.with_track(track).with_terminal(more);
    let mut trace = Vec::new();
    let out3 = step3::solve(&mut p5, &out1.iterate, &mut |it| {
        trace.push(iteration_record(it));
        progress(Progress::Iteration {
            window: w,
            step: 3,
            iteration: trace.last().expect("just pushed"),
        });
    })?;
    let final_ = stage_record(&p5, &out3.outcome, trace, clock.elapsed().as_secs_f64());
    let bridges = p5.bridges();
    progress(Progress::Step3 {
        window: w,
        stage: &final_,
        los_rounds: out3.los_rounds,
        out_of_band: out3.out_of_band.len(),
        bridges: bridges.len(),
    });
    let path = out3.outcome.iterate.usv_p.clone();
    let next = next_window(&out3.outcome.iterate, heading); // line 7
    let report = LinkReport {
        links: out3.links.links,
        bands: out3.links.bands,
        out_of_band: out3.out_of_band,
        los_rounds: out3.los_rounds,
        bridges,
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
    let window = Window {
        index: w,
        start_time: w as f64 * s.horizon.steps as f64 * s.horizon.dt,
        courses,
        step1,
        graph,
        final_,
        links: report,
        metrics,
        sampling: None,
    };
    Ok(WindowPlan { window, path, next })
}

/// The plan of the first `windows` of a mission stopped by the user: the scenario it records
/// asks for those windows only (so the plan is whole and checkable as it is), and a warning
/// says how many were asked for.
fn cut_short(
    setup: Setup,
    s: &Scenario,
    floor: &Seafloor,
    provenance: &Provenance,
    windows: Vec<Window>,
) -> Plan {
    let mut done = s.clone();
    done.windows = windows.len();
    let mut plan = setup.plan(&done, floor, provenance, METHOD_MPC, windows);
    plan.warnings.insert(
        0,
        format!(
            "interrupted: {} of the {} windows asked for were planned; the plan holds those \
             and records windows = {}",
            done.windows, s.windows, done.windows
        ),
    );
    plan
}
