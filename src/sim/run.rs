//! `shoal simulate`'s job: fly a plan (and its Step 1 paths), measure, estimate under every
//! policy with both estimators, and score it all.

use super::current::{mission_bounds, CurrentError, CurrentField, CURRENT_MARGIN};
use super::estimate::{self, Cov3, Estimate, EstimateError};
use super::flight::{fly, Flight};
use super::measure::{measure, Measurements};
use super::policy::{initial_start, problem, Policy};
use super::record::{
    packed, EstimateRecord, FlightMetrics, FlightRecord, NavMetrics, SimRecord, FORMAT,
};
use super::reference::{Flown, Reference};
use super::remus::Remus100;
use crate::plan::Plan;
use crate::scenario::validate_whole_multiple;
use crate::seafloor::Seafloor;
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
    /// A `--set` of a key `shoal simulate` does not read.
    #[error(
        "--set {0}: shoal simulate changes only the [current], [navigation] and [simulation] \
         keys; the plan's other keys are what it was made with (plan again to change them)"
    )]
    NotSimKey(String),
    /// A `--set` whose value is not allowed.
    #[error(transparent)]
    Scenario(#[from] crate::scenario::ScenarioError),
    /// An estimator failed.
    #[error("the {estimator} estimate under policy {policy}: {source}")]
    Estimate {
        /// Which estimator.
        estimator: &'static str,
        /// Which policy.
        policy: &'static str,
        /// Why.
        source: EstimateError,
    },
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
/// the record of the first run, with the runs' summary when `runs` > 1. The flight is the same
/// in every run (the current and the controller are deterministic); the sensor errors, the
/// noise and the packets are drawn anew.
pub fn monte_carlo(
    plan: &Plan,
    plan_name: &str,
    floor: &Seafloor,
    seed: u64,
    runs: usize,
) -> Result<SimRecord, SimError> {
    let s = &plan.scenario;
    let nav = &s.navigation;
    let window = s.horizon.steps as f64 * s.horizon.dt;
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
    let model = Remus100::default();
    // relative current grid files are found next to the plan
    let plan_dir = std::path::Path::new(plan_name)
        .parent()
        .unwrap_or(std::path::Path::new(""));
    let current = CurrentField::load(&s.current, plan_dir, mission_bounds(plan, CURRENT_MARGIN))?;
    let per_window = (window / nav.acoustic_period).round() as usize;
    let flights: Vec<(Flown, Reference, Flight)> = [Flown::Final, Flown::Step1]
        .into_iter()
        .map(|flown| {
            let reference = Reference::new(plan, flown);
            let flight = fly(
                plan,
                &reference,
                floor,
                &current,
                &model,
                s.simulation.step,
                nav.sample_period,
            );
            (flown, reference, flight)
        })
        .collect();

    let mut first: Option<SimRecord> = None;
    let mut all_runs = Vec::with_capacity(runs);
    for run in 0..runs {
        let run_seed = seed.wrapping_add(run as u64);
        let mut estimates = Vec::new();
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
                let whole = problem(
                    &m,
                    nav,
                    policy,
                    &planned,
                    0,
                    m.epochs - 1,
                    &initial_start(&m, nav),
                );
                let ekf = estimate::filter(&whole).map_err(|source| SimError::Estimate {
                    estimator: "ekf",
                    policy: policy.name(),
                    source,
                })?;
                let fg = smooth_mission(&whole, policy, &ekf)?;
                for (name, est, used) in [
                    ("factor_graph", fg.0, fg.1),
                    ("ekf", ekf, whole.ranges.len()),
                ] {
                    estimates.push(record_estimate(
                        policy, name, *flown, used, est, flight, &m, per_window,
                    ));
                }
            }
            if run == 0 {
                let metrics = flight_metrics(plan, floor, flight, &m, &planned);
                records.push(flight_record(flight, &m, metrics));
            }
        }
        all_runs.push(super::montecarlo::RunMetrics::of(run_seed, &estimates));
        if run == 0 {
            let step1_flight = records.pop().expect("two flights");
            let flight = records.pop().expect("two flights");
            let epochs = flight.usv.len();
            first = Some(SimRecord {
                format: FORMAT.into(),
                shoal_version: env!("CARGO_PKG_VERSION").into(),
                plan: plan_name.into(),
                seed,
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
                monte_carlo: None,
            });
        }
    }
    let mut record = first.expect("runs ≥ 1");
    if runs > 1 {
        record.monte_carlo = Some(super::montecarlo::MonteCarlo::of(all_runs));
    }
    Ok(record)
}

/// The factor graph over the whole mission from the filter's estimate `guess`: every
/// measurement, past and future (what the team's data tell after the mission). Solved window
/// by window, handing each window's last epoch on as independent marginals, it crept up over
/// windows (2.8, 3.9, 5.7 m at the ends of three windows against 2.2, 2.2, 2.3 m in one
/// batch, for the same time): the marginals drop the correlations of each AUV's position with
/// its own biases. Returns the estimate and the ranges used.
fn smooth_mission(
    whole: &estimate::Problem,
    policy: Policy,
    guess: &Estimate,
) -> Result<(Estimate, usize), SimError> {
    // a result one Gauss–Newton step could still improve by up to ½ in ½χ² (a step of one
    // posterior standard deviation in Mahalanobis length, spread over thousands of
    // coordinates) is kept: the estimators are judged on metres of error
    let options = estimate::SmoothOptions {
        max_iterations: 200,
        acceptance: 0.5,
        ..estimate::SmoothOptions::default()
    };
    // from the filter's estimate: with few ranges, from dead reckoning tens of metres off,
    // Levenberg–Marquardt can settle in a range-only problem's mirror solution
    let est = estimate::smooth_with(whole, &guess.position, &options).map_err(|source| {
        SimError::Estimate {
            estimator: "factor_graph",
            policy: policy.name(),
            source,
        }
    })?;
    Ok((est, whole.ranges.len()))
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// eᵀ C⁻¹ e for a 3×3 covariance (∞ when C is singular).
fn nees(e: [f64; 3], c: &Cov3) -> f64 {
    let m = nalgebra::Matrix3::from_fn(|i, j| c[i][j]);
    let v = nalgebra::Vector3::from(e);
    m.cholesky()
        .map(|ch| v.dot(&ch.solve(&v)))
        .unwrap_or(f64::INFINITY)
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
    let mut nees_sum = 0.0;
    for v in 0..n {
        for e in 0..m.epochs {
            let p = est.position[v][e];
            let t = truth(v, e);
            let d = dist(p, t);
            sq[e] += d * d / n as f64;
            rmse[v] += d * d / m.epochs as f64;
            max[v] = max[v].max(d);
            nees_sum += nees(
                [p[0] - t[0], p[1] - t[1], p[2] - t[2]],
                &est.covariance[v][e],
            );
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
        flown: match flown {
            Flown::Final => "final",
            Flown::Step1 => "step1",
        }
        .into(),
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
            mean_nees: nees_sum / (n * m.epochs) as f64,
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
    _floor: &Seafloor,
    flight: &Flight,
    m: &Measurements,
    planned: &dyn Fn(usize) -> Vec<(usize, usize)>,
) -> FlightMetrics {
    let n = flight.auvs.len();
    let eps = plan.scenario.auv.floor_clearance;
    let mut min_alt = f64::INFINITY;
    let (mut below_eps, mut below_floor, mut off) = (0, 0, 0);
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
        }
        travelled[v] = samples
            .windows(2)
            .map(|w| dist(w[0].position, w[1].position))
            .sum();
    }
    // connectivity on the executed geometry: links in range and in line of sight
    let per_epoch = (n + 1) * n / 2;
    let (mut connected, mut planned_total, mut planned_up, mut planned_rx) = (0, 0, 0, 0);
    for e in 0..m.epochs {
        let pings = &m.pings[e * per_epoch..(e + 1) * per_epoch];
        let up = |a: usize, b: usize| {
            pings
                .iter()
                .find(|p| p.a == a.min(b) && p.b == a.max(b))
                .filter(|p| p.line_of_sight)
        };
        // breadth-first from the USV (index n)
        let mut seen = vec![false; n + 1];
        let mut queue = vec![n];
        seen[n] = true;
        while let Some(x) = queue.pop() {
            for y in 0..=n {
                if !seen[y] && y != x && up(x, y).is_some() {
                    seen[y] = true;
                    queue.push(y);
                }
            }
        }
        connected += usize::from(seen.iter().all(|&s| s));
        for (a, b) in planned(e) {
            planned_total += 1;
            if let Some(p) = up(a, b) {
                planned_up += 1;
                planned_rx += usize::from(p.received);
            }
        }
    }
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
        distance_m: travelled,
    }
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
