//! `shoal simulate`'s job: fly a plan (and its Step 1 paths), measure, estimate under every
//! policy with both estimators, and score it all.
//!
//! Before anything is flown, [`fly_plan`] validates the plan's scenario, counts the cost
//! ([`super::budget`]) and runs the plan's check (as its [`Gate`] says). An estimator that fails
//! (Levenberg–Marquardt that does not converge, say) does not stop the simulation: it is
//! recorded for its policy in [`SimRecord::failed_estimates`], and the others are kept.

use super::budget::Cost;
use super::current::{mission_bounds, CurrentError, CurrentField, CURRENT_MARGIN};
use super::estimate::{self, Cov3, Estimate, EstimateError};
use super::flight::{fly, Flight, Stopped};
use super::measure::{measure, Measurements};
use super::policy::{initial_start, problem, Policy};
use super::record::{
    packed, EstimateFailure, EstimateRecord, FlightMetrics, FlightRecord, Incomplete, NavMetrics,
    SimRecord, FORMAT,
};
use super::reference::{Flown, Reference};
use super::remus::Remus100;
use crate::plan::Plan;
use crate::scenario::validate_whole_multiple;
use crate::seafloor::Seafloor;
use std::sync::atomic::{AtomicBool, Ordering};
use thiserror::Error;

/// Why a plan could not be simulated.
#[derive(Debug, Error)]
pub enum SimError {
    /// A setting that does not fit the plan.
    #[error("{key} = {value}: {why}")]
    Setting {
        /// The dotted scenario key.
        key: String,
        /// Its value.
        value: String,
        /// What is allowed.
        why: String,
    },
    /// A setting of the plan file's own scenario outside its allowed range (a plan file edited
    /// by hand, or written by another version).
    #[error("{plan}: {key} = {value}: {allowed}")]
    PlanSetting {
        /// The plan file.
        plan: String,
        /// The dotted scenario key.
        key: String,
        /// Its value.
        value: String,
        /// What is allowed.
        allowed: String,
    },
    /// A count of the simulation (steps, samples, positions) above its limit.
    #[error("{plan}; {what}, above the {limit} allowed ({instead})")]
    TooLong {
        /// The plan file and how long it lasts.
        plan: String,
        /// The count, and the setting that makes it.
        what: String,
        /// The limit.
        limit: String,
        /// What would bring the count down.
        instead: String,
    },
    /// `--runs` times the positions of a run above [`super::budget::MAX_RUN_POSITIONS`].
    #[error(
        "--runs {runs}: {runs} runs × {positions} positions per run = {work} positions to \
         estimate, above the {limit} allowed (at most {most} runs of this plan)"
    )]
    TooManyRuns {
        /// The runs asked for.
        runs: usize,
        /// The positions of one run.
        positions: String,
        /// Their product.
        work: String,
        /// The limit.
        limit: String,
        /// The most runs allowed for this plan.
        most: usize,
    },
    /// The plan fails its check ([`crate::check::check_plan`]).
    #[error(
        "{plan} fails its check ({}): simulate flies only plans that pass; add --unchecked to \
         fly it anyway",
        failing.join(", ")
    )]
    FailsCheck {
        /// The plan file.
        plan: String,
        /// The failing families.
        failing: Vec<String>,
    },
    /// The plan's structure is broken: it cannot be flown even unchecked.
    #[error("{plan} is malformed ({problem}): it cannot be flown, even with --unchecked")]
    Malformed {
        /// The plan file.
        plan: String,
        /// The check's first structural problem.
        problem: String,
    },
    /// The 6-DoF model diverged.
    #[error(
        "flying {flown} of {plan}: AUV {auv}'s 6-DoF state stopped being finite after t = {time} \
         s, in a current of {speed:.2} m/s (a REMUS 100 flies at up to about 2.5 m/s through \
         the water; a current it cannot stem, or a simulation.step too coarse for the model)"
    )]
    Diverged {
        /// The plan file.
        plan: String,
        /// Which flight: "its final stages" or "its Step 1 paths".
        flown: &'static str,
        /// The AUV.
        auv: usize,
        /// The last time its state was finite, s.
        time: f64,
        /// The current's speed there, m/s.
        speed: f64,
    },
    /// Cancelled before any run had finished: there is nothing to record.
    #[error("interrupted before the first run finished")]
    Interrupted,
    /// A `--set` of a key `shoal simulate` does not read.
    #[error(
        "--set {0}: shoal simulate changes only the [current], [navigation] and [simulation] \
         keys; the plan's other keys are what it was made with (plan again to change them)"
    )]
    NotSimKey(String),
    /// A `--set` whose value is not allowed.
    #[error(transparent)]
    Scenario(#[from] crate::scenario::ScenarioError),
    /// The current's grid files could not be used.
    #[error(transparent)]
    Current(#[from] CurrentError),
}

/// Sections of the scenario `shoal simulate` reads, and the only ones `--set` may change.
pub const SIM_SECTIONS: [&str; 3] = ["current", "navigation", "simulation"];

/// `plan` with `overrides` (`--set key=value`) applied to its scenario's [`SIM_SECTIONS`];
/// errors name the override or `plan_name`.
pub fn with_settings(plan: &Plan, plan_name: &str, overrides: &[String]) -> Result<Plan, SimError> {
    for o in overrides {
        let key = o.split('=').next().unwrap_or("").trim();
        let section = key.split('.').next().unwrap_or("");
        if !SIM_SECTIONS.contains(&section) {
            return Err(SimError::NotSimKey(o.clone()));
        }
    }
    let mut p = plan.clone();
    p.scenario = crate::scenario::with_overrides(
        &plan.scenario,
        &format!("the scenario of {plan_name}"),
        overrides,
    )?;
    Ok(p)
}

/// Whether [`fly_plan`] checks the plan ([`crate::check::check_plan`]) before flying it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Gate {
    /// Fly it unchecked: the caller has checked it (or made it).
    Trust,
    /// Refuse a plan that fails its check ([`SimError::FailsCheck`]).
    Check,
    /// Fly a plan that fails its check all the same, and record the failing families in
    /// [`SimRecord::check_failures`]; a plan whose structure is broken is still refused
    /// ([`SimError::Malformed`]).
    Unchecked,
}

/// How [`fly_plan`] flies a plan.
#[derive(Debug, Clone, Copy)]
pub struct Options<'a> {
    /// The seed of the first run; run i has seed + i.
    pub seed: u64,
    /// Monte Carlo runs (≥ 1).
    pub runs: usize,
    /// Whether the plan is checked first.
    pub gate: Gate,
    /// Raised to stop: checked at every sample of the flights and between estimates. The runs
    /// finished by then are returned, marked [`SimRecord::incomplete`]; with none finished,
    /// [`SimError::Interrupted`].
    pub cancel: Option<&'a AtomicBool>,
    /// The factor graph's Levenberg–Marquardt iteration limit ([`FACTOR_GRAPH_ITERATIONS`]).
    pub max_iterations: usize,
}

/// The factor graph's Levenberg–Marquardt iteration limit in `shoal simulate`.
pub const FACTOR_GRAPH_ITERATIONS: usize = 200;

impl Options<'_> {
    /// `runs` runs from `seed`, the plan trusted, no cancel flag, the factor graph's usual
    /// iteration limit.
    pub fn new(seed: u64, runs: usize) -> Options<'static> {
        Options {
            seed,
            runs,
            gate: Gate::Trust,
            cancel: None,
            max_iterations: FACTOR_GRAPH_ITERATIONS,
        }
    }
}

/// What [`fly_plan`] is doing, for a progress display.
#[derive(Debug, Clone, PartialEq)]
pub enum Progress<'a> {
    /// The plan fails its check and is flown all the same ([`Gate::Unchecked`]).
    Unchecked {
        /// The failing families.
        failing: &'a [String],
    },
    /// The cost is counted and flying starts.
    Counted(&'a Cost),
    /// A flight starts: "its final stages" or "its Step 1 paths".
    Flying(&'static str),
    /// A run's estimates start.
    Estimating {
        /// The run, from 0.
        run: usize,
    },
    /// A run has finished.
    RunDone {
        /// Runs finished so far.
        finished: usize,
        /// Runs asked for.
        runs: usize,
    },
}

/// Simulate `plan` (read from `plan_name`) over `floor` with every draw from `seed`.
pub fn simulate(
    plan: &Plan,
    plan_name: &str,
    floor: &Seafloor,
    seed: u64,
) -> Result<SimRecord, SimError> {
    monte_carlo(plan, plan_name, floor, seed, 1)
}

/// Fly `plan` once and measure and estimate it `runs` times, with seeds `seed`, `seed + 1`, …:
/// [`fly_plan`] with the plan trusted, no cancel flag and no progress.
pub fn monte_carlo(
    plan: &Plan,
    plan_name: &str,
    floor: &Seafloor,
    seed: u64,
    runs: usize,
) -> Result<SimRecord, SimError> {
    fly_plan(
        plan,
        plan_name,
        floor,
        &Options::new(seed, runs),
        &mut |_| {},
    )
}

/// The check's verdict for [`fly_plan`]: the failing families (empty when it passes), or why
/// the plan may not be flown.
fn gate(
    plan: &Plan,
    plan_name: &str,
    floor: &Seafloor,
    gate: Gate,
) -> Result<Vec<String>, SimError> {
    if gate == Gate::Trust {
        return Ok(Vec::new());
    }
    let report = crate::check::check_plan(plan, floor);
    if report.passed() {
        return Ok(Vec::new());
    }
    if let Some(problem) = report.problems.first() {
        return Err(SimError::Malformed {
            plan: plan_name.into(),
            problem: problem.clone(),
        });
    }
    let failing: Vec<String> = report
        .failures()
        .iter()
        .map(|f| f.name.to_string())
        .collect();
    match gate {
        Gate::Unchecked => Ok(failing),
        _ => Err(SimError::FailsCheck {
            plan: plan_name.into(),
            failing,
        }),
    }
}

/// The scenario's own rules on `plan`'s scenario (a plan file is read without them).
fn validated(plan: &Plan, plan_name: &str) -> Result<(), SimError> {
    match crate::scenario::validate(&plan.scenario) {
        Ok(()) => Ok(()),
        Err(v) => {
            let v = &v[0];
            Err(SimError::PlanSetting {
                plan: plan_name.into(),
                key: v.key.clone(),
                value: v.value.clone(),
                allowed: v.allowed.clone(),
            })
        }
    }
}

/// The name of a flight in messages.
fn flight_name(flown: Flown) -> &'static str {
    match flown {
        Flown::Final => "its final stages",
        Flown::Step1 => "its Step 1 paths",
    }
}

/// Fly `plan` (read from `plan_name`; relative current grid files are found beside it) over
/// `floor`, then measure and estimate it `options.runs` times with seeds `options.seed`,
/// `options.seed + 1`, …: the record of the first run, with the runs' summary when more than
/// one was asked for. The flight is the same in every run (the current and the controller are
/// deterministic); the sensor errors, the noise and the packets are drawn anew.
///
/// First the plan's scenario is validated, the cost counted ([`Cost::of`]) and the plan
/// checked as `options.gate` says; each refusal is a [`SimError`] naming the setting.
pub fn fly_plan(
    plan: &Plan,
    plan_name: &str,
    floor: &Seafloor,
    options: &Options,
    on_progress: &mut dyn FnMut(Progress),
) -> Result<SimRecord, SimError> {
    let s = &plan.scenario;
    let nav = &s.navigation;
    let runs = options.runs.max(1);
    validated(plan, plan_name)?;
    if !validate_whole_multiple(s.horizon.dt, nav.acoustic_period) {
        return Err(SimError::Setting {
            key: "navigation.acoustic_period".into(),
            value: format!("{}", nav.acoustic_period),
            why: format!(
                "must divide the plan's step horizon.dt = {} s into a whole number of acoustic \
                 cycles",
                s.horizon.dt
            ),
        });
    }
    if plan.windows.is_empty() {
        return Err(SimError::Setting {
            key: "windows".into(),
            value: "0".into(),
            why: "the plan has no window to fly".into(),
        });
    }
    let cost = Cost::of(plan, plan_name, runs)?;
    let check_failures = gate(plan, plan_name, floor, options.gate)?;
    if !check_failures.is_empty() {
        on_progress(Progress::Unchecked {
            failing: &check_failures,
        });
    }
    on_progress(Progress::Counted(&cost));
    let cancelled = || options.cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let window = s.horizon.steps as f64 * s.horizon.dt;
    let model = Remus100::default();
    let plan_dir = std::path::Path::new(plan_name)
        .parent()
        .unwrap_or(std::path::Path::new(""));
    let current = CurrentField::load(&s.current, plan_dir, mission_bounds(plan, CURRENT_MARGIN))?;
    let per_window = ((window / nav.acoustic_period).round() as usize).max(1);
    let mut flights: Vec<(Flown, Reference, Flight)> = Vec::with_capacity(2);
    for flown in [Flown::Final, Flown::Step1] {
        on_progress(Progress::Flying(flight_name(flown)));
        let reference = Reference::new(plan, flown);
        let flight = fly(
            plan,
            &reference,
            floor,
            &current,
            &model,
            &cost,
            options.cancel,
        )
        .map_err(|stop| match stop {
            Stopped::Cancelled => SimError::Interrupted,
            Stopped::Diverged { auv, time, current } => SimError::Diverged {
                plan: plan_name.into(),
                flown: flight_name(flown),
                auv,
                time,
                speed: current[0].hypot(current[1]),
            },
        })?;
        flights.push((flown, reference, flight));
    }

    let mut first: Option<SimRecord> = None;
    let mut all_runs = Vec::with_capacity(runs);
    'runs: for run in 0..runs {
        if cancelled() {
            break;
        }
        on_progress(Progress::Estimating { run });
        let run_seed = options.seed.wrapping_add(run as u64);
        let mut estimates = Vec::new();
        let mut failures = Vec::new();
        let mut records = Vec::new();
        for (flown, reference, flight) in &flights {
            let m = measure(
                flight,
                floor,
                nav,
                s.acoustic.sonar_range,
                s.acoustic.resolution,
                run_seed,
            );
            let planned = |e: usize| -> Vec<(usize, usize)> {
                if *flown == Flown::Step1 {
                    return Vec::new();
                }
                let (w, k) = reference.nearest_step(e as f64 * m.period);
                Reference::links(plan, w, k)
                    .into_iter()
                    .map(|(a, b)| (a.min(b), a.max(b)))
                    .collect()
            };
            let policies: &[Policy] = match flown {
                Flown::Final => &Policy::EVERY,
                Flown::Step1 => &[Policy::AllLinks],
            };
            for &policy in policies {
                if cancelled() {
                    break 'runs;
                }
                let whole = problem(
                    &m,
                    nav,
                    policy,
                    &planned,
                    0,
                    m.epochs - 1,
                    &initial_start(&m, nav),
                );
                let used = whole.ranges.len();
                let failed = |estimator: &str, e: EstimateError| EstimateFailure {
                    policy,
                    estimator: estimator.into(),
                    flown: flown_name(*flown).into(),
                    ranges_used: used,
                    iterations: match e {
                        EstimateError::NotConverged { iterations, .. } => Some(iterations),
                        _ => None,
                    },
                    error: e.to_string(),
                };
                let ekf = estimate::filter(&whole).and_then(finite);
                // from the filter's estimate, or from dead reckoning when the filter failed
                let guess = ekf.as_ref().map_or(&[][..], |e| &e.position[..]);
                let fg = smooth_mission(&whole, guess, options.max_iterations).and_then(finite);
                match fg {
                    Ok(fg) => estimates.push(record_estimate(
                        policy,
                        "factor_graph",
                        *flown,
                        used,
                        fg,
                        flight,
                        &m,
                        per_window,
                    )),
                    Err(e) => failures.push(failed("factor_graph", e)),
                }
                match ekf {
                    Ok(ekf) => estimates.push(record_estimate(
                        policy, "ekf", *flown, used, ekf, flight, &m, per_window,
                    )),
                    Err(e) => failures.push(failed("ekf", e)),
                }
            }
            if run == 0 {
                let metrics = flight_metrics(plan, floor, flight, &m, &planned);
                records.push(flight_record(flight, &m, metrics));
            }
        }
        all_runs.push(super::montecarlo::RunMetrics::of(
            run_seed, &estimates, &failures,
        ));
        if run == 0 {
            let (Some(step1_flight), Some(flight)) = (records.pop(), records.pop()) else {
                unreachable!("two flights are flown");
            };
            let epochs = flight.usv.len();
            first = Some(SimRecord {
                format: FORMAT.into(),
                shoal_version: env!("CARGO_PKG_VERSION").into(),
                plan: plan_name.into(),
                seed: options.seed,
                current: s.current.clone(),
                navigation: nav.clone(),
                simulation: s.simulation.clone(),
                floor_clearance: s.auv.floor_clearance,
                auvs: s.team.auvs,
                times: (0..epochs)
                    .map(|e| e as f64 * nav.acoustic_period)
                    .collect(),
                flight,
                step1_flight,
                estimates,
                failed_estimates: failures,
                check_failures: check_failures.clone(),
                incomplete: None,
                monte_carlo: None,
            });
        }
        on_progress(Progress::RunDone {
            finished: run + 1,
            runs,
        });
    }
    let Some(mut record) = first else {
        return Err(SimError::Interrupted);
    };
    let finished = all_runs.len();
    if finished < runs {
        record.incomplete = Some(Incomplete {
            runs_asked: runs,
            runs_finished: finished,
            reason: "interrupted".into(),
        });
    }
    if runs > 1 {
        record.monte_carlo = Some(super::montecarlo::MonteCarlo::of(all_runs));
    }
    Ok(record)
}

/// "final" or "step1", as sim.json names a flight.
fn flown_name(flown: Flown) -> &'static str {
    match flown {
        Flown::Final => "final",
        Flown::Step1 => "step1",
    }
}

/// The factor graph over the whole mission from the filter's estimate `guess` (from dead
/// reckoning when empty): every measurement, past and future (what the team's data tell after
/// the mission). Solved window by window, handing each window's last epoch on as independent
/// marginals, it crept up over windows (2.8, 3.9, 5.7 m at the ends of three windows against
/// 2.2, 2.2, 2.3 m in one batch, for the same time): the marginals drop the correlations of
/// each AUV's position with its own biases.
fn smooth_mission(
    whole: &estimate::Problem,
    guess: &[Vec<[f64; 3]>],
    max_iterations: usize,
) -> Result<Estimate, EstimateError> {
    // a result one Gauss–Newton step could still improve by up to ½ in ½χ² (a step of one
    // posterior standard deviation in Mahalanobis length, spread over thousands of
    // coordinates) is kept: the estimators are judged on metres of error
    let options = estimate::SmoothOptions {
        max_iterations,
        acceptance: 0.5,
        ..estimate::SmoothOptions::default()
    };
    // from the filter's estimate: with few ranges, from dead reckoning tens of metres off,
    // Levenberg–Marquardt can settle in a range-only problem's mirror solution
    estimate::smooth_with(whole, guess, &options)
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// eᵀ C⁻¹ e for a 3×3 covariance; None when C is not positive definite (rounding can leave
/// a marginal of a nearly singular problem so).
fn nees(e: [f64; 3], c: &Cov3) -> Option<f64> {
    let m = nalgebra::Matrix3::from_fn(|i, j| c[i][j]);
    let v = nalgebra::Vector3::from(e);
    m.cholesky()
        .map(|ch| v.dot(&ch.solve(&v)))
        .filter(|x| x.is_finite())
}

/// `est`, if every position and covariance of it is finite.
fn finite(est: Estimate) -> Result<Estimate, EstimateError> {
    let positions = est.position.iter().flatten().flatten();
    let covariances = est.covariance.iter().flatten().flatten().flatten();
    if positions.chain(covariances).all(|x| x.is_finite()) {
        Ok(est)
    } else {
        Err(EstimateError::Solver(
            "its estimate holds a non-finite number".into(),
        ))
    }
}

#[allow(clippy::too_many_arguments)]
fn record_estimate(
    policy: Policy,
    estimator: &str,
    flown: Flown,
    ranges_used: usize,
    est: Estimate,
    flight: &Flight,
    m: &Measurements,
    per_window: usize,
) -> EstimateRecord {
    let n = m.errors.len();
    let per = flight.times.len().saturating_sub(1) / (m.epochs - 1).max(1);
    let truth = |v: usize, e: usize| flight.auvs[v][e * per].position;
    let mut sq = vec![0.0; m.epochs];
    let mut rmse = vec![0.0; n];
    let mut max = vec![0.0_f64; n];
    let (mut nees_sum, mut nees_count) = (0.0, 0);
    for v in 0..n {
        for e in 0..m.epochs {
            let p = est.position[v][e];
            let t = truth(v, e);
            let d = dist(p, t);
            sq[e] += d * d / n as f64;
            rmse[v] += d * d / m.epochs as f64;
            max[v] = max[v].max(d);
            if let Some(x) = nees(
                [p[0] - t[0], p[1] - t[1], p[2] - t[2]],
                &est.covariance[v][e],
            ) {
                nees_sum += x;
                nees_count += 1;
            }
        }
    }
    let over_time: Vec<f64> = sq.iter().map(|x| x.sqrt()).collect();
    let travelled: f64 = (0..n)
        .map(|v| {
            flight.auvs[v]
                .windows(2)
                .map(|w| dist(w[0].position, w[1].position))
                .sum::<f64>()
        })
        .sum::<f64>()
        / n as f64;
    let end = *over_time.last().unwrap_or(&0.0);
    let team = (sq.iter().sum::<f64>() / m.epochs as f64).sqrt();
    EstimateRecord {
        policy,
        estimator: estimator.into(),
        flown: flown_name(flown).into(),
        ranges_used,
        metrics: NavMetrics {
            team_rmse_m: team,
            team_max_m: max.iter().copied().fold(0.0, f64::max),
            rmse_m: rmse.iter().map(|x| x.sqrt()).collect(),
            max_m: max,
            window_end_rmse_m: (1..m.epochs)
                .filter(|e| e % per_window == 0)
                .map(|e| over_time[e])
                .collect(),
            team_rmse_over_time_m: over_time,
            end_percent_of_distance: if travelled > 0.0 {
                100.0 * end / travelled
            } else {
                0.0
            },
            mean_nees: nees_sum / nees_count.max(1) as f64,
        },
        position: est.position[..n].to_vec(),
        covariance: est.covariance[..n]
            .iter()
            .map(|cs| cs.iter().map(packed).collect())
            .collect(),
    }
}

fn flight_metrics(
    plan: &Plan,
    floor: &Seafloor,
    flight: &Flight,
    m: &Measurements,
    planned: &dyn Fn(usize) -> Vec<(usize, usize)>,
) -> FlightMetrics {
    let n = flight.auvs.len();
    let eps = plan.scenario.auv.floor_clearance;
    let mut min_alt = f64::INFINITY;
    let (mut below_eps, mut below_floor, mut off) = (0, 0, 0);
    let mut planned_min_alt = f64::INFINITY;
    let (mut planned_below_eps, mut planned_below_floor) = (0, 0);
    let mut rms = vec![0.0; n];
    let mut mx = vec![0.0_f64; n];
    let mut travelled = vec![0.0; n];
    for (v, samples) in flight.auvs.iter().enumerate() {
        for s in samples {
            let d = dist(s.position, s.reference);
            rms[v] += d * d / samples.len() as f64;
            mx[v] = mx[v].max(d);
            match s.altitude {
                Some(a) => {
                    min_alt = min_alt.min(a);
                    below_eps += usize::from(a < eps);
                    below_floor += usize::from(a < 0.0);
                }
                None => off += 1,
            }
            if let Ok(z) = floor.elevation(s.reference[0], s.reference[1]) {
                let a = s.reference[2] - z;
                planned_min_alt = planned_min_alt.min(a);
                planned_below_eps += usize::from(a < eps);
                planned_below_floor += usize::from(a < 0.0);
            }
        }
        travelled[v] = samples
            .windows(2)
            .map(|w| dist(w[0].position, w[1].position))
            .sum();
    }
    // closest approach of two AUVs, flown and planned, over the samples
    let (mut sep, mut sep_planned) = (f64::INFINITY, f64::INFINITY);
    for i in 0..flight.times.len() {
        for a in 0..n {
            for b in a + 1..n {
                let (x, y) = (&flight.auvs[a][i], &flight.auvs[b][i]);
                sep = sep.min(dist(x.position, y.position));
                sep_planned = sep_planned.min(dist(x.reference, y.reference));
            }
        }
    }
    let finite_or_zero = |x: f64| if x.is_finite() { x } else { 0.0 };
    // connectivity on the executed geometry: links in range and in line of sight, and links
    // whose pings were received
    let per_epoch = (n + 1) * n / 2;
    let (mut connected, mut linked) = (0, 0);
    let (mut planned_total, mut planned_up, mut planned_rx) = (0, 0, 0);
    for e in 0..m.epochs {
        let pings = &m.pings[e * per_epoch..(e + 1) * per_epoch];
        let up = |a: usize, b: usize| {
            pings
                .iter()
                .find(|p| p.a == a.min(b) && p.b == a.max(b))
                .filter(|p| p.line_of_sight)
        };
        connected += usize::from(reaches_usv(n, &|a, b| up(a, b).is_some()));
        linked += usize::from(reaches_usv(n, &|a, b| up(a, b).is_some_and(|p| p.received)));
        for (a, b) in planned(e) {
            planned_total += 1;
            if let Some(p) = up(a, b) {
                planned_up += 1;
                planned_rx += usize::from(p.received);
            }
        }
    }
    let (planned_expected, planned_connected) = planned_links(plan, floor, flight, m, planned);
    let frac = |x: usize, of: usize| if of > 0 { x as f64 / of as f64 } else { 0.0 };
    FlightMetrics {
        tracking_rms_m: rms.iter().map(|x| x.sqrt()).collect(),
        tracking_max_m: mx,
        min_altitude_m: if min_alt.is_finite() { min_alt } else { 0.0 },
        samples_below_clearance: below_eps,
        samples_below_floor: below_floor,
        samples_off_grid: off,
        connected_fraction: frac(connected, m.epochs),
        planned_links_up: frac(planned_up, planned_total),
        planned_links_received: frac(planned_rx, planned_total),
        linked_fraction: frac(linked, m.epochs),
        min_separation_m: finite_or_zero(sep),
        min_separation_planned_m: finite_or_zero(sep_planned),
        planned_samples_below_clearance: planned_below_eps,
        planned_samples_below_floor: planned_below_floor,
        planned_min_altitude_m: finite_or_zero(planned_min_alt),
        planned_links_expected: planned_expected,
        planned_connected_fraction: planned_connected,
        distance_m: travelled,
    }
}

/// What the plan itself promises of its links, on the planned positions at each acoustic
/// epoch (the references, and the USV, which flies its plan): the mean reception p(d) of the
/// planned link-epochs (0 out of range or out of sight), and the share of epochs at which every
/// AUV reaches the USV through links in range and in sight.
fn planned_links(
    plan: &Plan,
    floor: &Seafloor,
    flight: &Flight,
    m: &Measurements,
    planned: &dyn Fn(usize) -> Vec<(usize, usize)>,
) -> (f64, f64) {
    let s = &plan.scenario;
    let (nav, range, resolution) = (&s.navigation, s.acoustic.sonar_range, s.acoustic.resolution);
    let n = flight.auvs.len();
    let per = flight.times.len().saturating_sub(1) / (m.epochs - 1).max(1);
    let (mut expected, mut links, mut connected) = (0.0, 0usize, 0usize);
    for e in 0..m.epochs {
        let at = |v: usize| {
            if v == n {
                flight.usv[e * per]
            } else {
                flight.auvs[v][e * per].reference
            }
        };
        let reception = |a: usize, b: usize| {
            let (pa, pb) = (at(a), at(b));
            let d = dist(pa, pb);
            let sight = d < range
                && floor
                    .segment_clearance(pa, pb, resolution)
                    .is_ok_and(|c| c.min_clearance >= 0.0);
            sight.then(|| nav.packet_success * (1.0 - (d / range).powf(nav.range_falloff)))
        };
        for (a, b) in planned(e) {
            links += 1;
            expected += reception(a, b).unwrap_or(0.0);
        }
        connected += usize::from(reaches_usv(n, &|a, b| reception(a, b).is_some()));
    }
    let frac = |x: f64, of: usize| if of > 0 { x / of as f64 } else { 0.0 };
    (frac(expected, links), frac(connected as f64, m.epochs))
}

/// Whether every one of `n` AUVs reaches the USV (vehicle `n`) through pairs `linked` joins
/// (breadth-first from the USV).
fn reaches_usv(n: usize, linked: &dyn Fn(usize, usize) -> bool) -> bool {
    let mut seen = vec![false; n + 1];
    let mut queue = vec![n];
    seen[n] = true;
    while let Some(x) = queue.pop() {
        for y in 0..=n {
            if !seen[y] && y != x && linked(x, y) {
                seen[y] = true;
                queue.push(y);
            }
        }
    }
    seen.iter().all(|&s| s)
}

fn flight_record(flight: &Flight, m: &Measurements, metrics: FlightMetrics) -> FlightRecord {
    let per = flight.times.len().saturating_sub(1) / (m.epochs - 1).max(1);
    let at = |samples: &Vec<super::flight::Sample>,
              f: &dyn Fn(&super::flight::Sample) -> [f64; 3]| {
        (0..m.epochs)
            .map(|e| f(&samples[e * per]))
            .collect::<Vec<_>>()
    };
    FlightRecord {
        executed: flight.auvs.iter().map(|s| at(s, &|x| x.position)).collect(),
        planned: flight
            .auvs
            .iter()
            .map(|s| at(s, &|x| x.reference))
            .collect(),
        usv: (0..m.epochs).map(|e| flight.usv[e * per]).collect(),
        sensor_errors: m.errors.iter().map(|&e| e.into()).collect(),
        odometry: m
            .odometry
            .iter()
            .map(|o| o.iter().map(|i| i.delta).collect())
            .collect(),
        bottom_lock: m
            .odometry
            .iter()
            .map(|o| o.iter().map(|i| i.bottom_lock).collect())
            .collect(),
        depth: m.depth.clone(),
        gps: m.gps.clone(),
        pings: m.pings.clone(),
        metrics,
    }
}
