//! Monte Carlo over the simulation's draws (`shoal simulate --runs R`): each run's error
//! metrics per estimate, and their mean and spread.

use super::policy::Policy;
use super::record::{EstimateFailure, EstimateRecord};
use serde::{Deserialize, Serialize};

/// Mean, standard deviation (n − 1) and range of one metric over the runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Stat {
    /// Mean.
    pub mean: f64,
    /// Sample standard deviation (0 for one run).
    pub std: f64,
    /// Smallest.
    pub min: f64,
    /// Largest.
    pub max: f64,
}

impl Stat {
    /// The statistics of `xs` (all zero when empty).
    pub fn of(xs: &[f64]) -> Stat {
        if xs.is_empty() {
            return Stat {
                mean: 0.0,
                std: 0.0,
                min: 0.0,
                max: 0.0,
            };
        }
        let n = xs.len() as f64;
        let mean = xs.iter().sum::<f64>() / n;
        let var = if xs.len() > 1 {
            xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)
        } else {
            0.0
        };
        Stat {
            mean,
            std: var.sqrt(),
            min: xs.iter().copied().fold(f64::INFINITY, f64::min),
            max: xs.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        }
    }
}

/// One estimate's metrics in one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunEntry {
    /// "final" or "step1".
    pub flown: String,
    /// The policy.
    pub policy: Policy,
    /// "factor_graph" or "ekf".
    pub estimator: String,
    /// RMS error over every AUV and epoch, m.
    pub team_rmse_m: f64,
    /// Largest error, m.
    pub team_max_m: f64,
    /// RMS over the AUVs at each window's end, m.
    pub window_end_rmse_m: Vec<f64>,
    /// Mean NEES.
    pub mean_nees: f64,
}

/// An estimate that failed in one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunFailure {
    /// "final" or "step1".
    pub flown: String,
    /// The policy.
    pub policy: Policy,
    /// "factor_graph" or "ekf".
    pub estimator: String,
    /// Why, in a few words ([`EstimateFailure::brief`]).
    pub error: String,
}

/// One run's metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunMetrics {
    /// The run's seed.
    pub seed: u64,
    /// One per estimate made, in the order of `SimRecord::estimates`.
    pub entries: Vec<RunEntry>,
    /// The estimates that failed in this run.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub failed: Vec<RunFailure>,
}

impl RunMetrics {
    /// The metrics of a run's `estimates`, and its `failures`.
    pub fn of(seed: u64, estimates: &[EstimateRecord], failures: &[EstimateFailure]) -> RunMetrics {
        RunMetrics {
            seed,
            failed: failures
                .iter()
                .map(|f| RunFailure {
                    flown: f.flown.clone(),
                    policy: f.policy,
                    estimator: f.estimator.clone(),
                    error: f.brief(),
                })
                .collect(),
            entries: estimates
                .iter()
                .map(|e| RunEntry {
                    flown: e.flown.clone(),
                    policy: e.policy,
                    estimator: e.estimator.clone(),
                    team_rmse_m: e.metrics.team_rmse_m,
                    team_max_m: e.metrics.team_max_m,
                    window_end_rmse_m: e.metrics.window_end_rmse_m.clone(),
                    mean_nees: e.metrics.mean_nees,
                })
                .collect(),
        }
    }
}

/// The summary of one estimate over the runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// "final" or "step1".
    pub flown: String,
    /// The policy.
    pub policy: Policy,
    /// "factor_graph" or "ekf".
    pub estimator: String,
    /// RMS error over every AUV and epoch, m.
    pub team_rmse_m: Stat,
    /// Largest error, m.
    pub team_max_m: Stat,
    /// `[window]`: RMS over the AUVs at the window's end, m.
    pub window_end_rmse_m: Vec<Stat>,
    /// Mean NEES.
    pub mean_nees: Stat,
    /// Runs in which this estimate failed; the statistics are over the others (all zero when
    /// it failed in every run).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub failed_runs: usize,
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

/// Where an estimate comes in the reports: the final stages' flight first, the policies in
/// [`Policy::EVERY`]'s order, the factor graph before the EKF.
fn rank(flown: &str, policy: Policy, estimator: &str) -> (usize, usize, usize, String) {
    let f = match flown {
        "final" => 0,
        "step1" => 1,
        _ => 2,
    };
    let p = Policy::EVERY
        .iter()
        .position(|&x| x == policy)
        .unwrap_or(Policy::EVERY.len());
    let e = match estimator {
        "factor_graph" => 0,
        "ekf" => 1,
        _ => 2,
    };
    (f, p, e, format!("{flown}/{estimator}"))
}

/// Every run and the summary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MonteCarlo {
    /// Number of runs.
    pub runs: usize,
    /// One summary per estimate.
    pub summary: Vec<Summary>,
    /// Each run's metrics.
    pub each: Vec<RunMetrics>,
}

impl MonteCarlo {
    /// Summarise `runs`: one summary per estimate made or failed in any run, in the order of
    /// the reports, over the runs in which it was made.
    pub fn of(runs: Vec<RunMetrics>) -> MonteCarlo {
        let mut keys: Vec<(String, Policy, String)> = Vec::new();
        for r in &runs {
            let made = r.entries.iter().map(|e| (&e.flown, e.policy, &e.estimator));
            let failed = r.failed.iter().map(|e| (&e.flown, e.policy, &e.estimator));
            for (f, p, e) in made.chain(failed) {
                if !keys.iter().any(|k| &k.0 == f && k.1 == p && &k.2 == e) {
                    keys.push((f.clone(), p, e.clone()));
                }
            }
        }
        keys.sort_by_key(|(f, p, e)| rank(f, *p, e));
        let summary = keys
            .into_iter()
            .map(|(flown, policy, estimator)| {
                let made: Vec<&RunEntry> = runs
                    .iter()
                    .filter_map(|r| {
                        r.entries.iter().find(|x| {
                            x.flown == flown && x.policy == policy && x.estimator == estimator
                        })
                    })
                    .collect();
                let failed_runs = runs
                    .iter()
                    .filter(|r| {
                        r.failed.iter().any(|x| {
                            x.flown == flown && x.policy == policy && x.estimator == estimator
                        })
                    })
                    .count();
                let col = |f: &dyn Fn(&RunEntry) -> Option<f64>| -> Stat {
                    Stat::of(&made.iter().filter_map(|x| f(x)).collect::<Vec<_>>())
                };
                let windows = made.first().map_or(0, |x| x.window_end_rmse_m.len());
                Summary {
                    team_rmse_m: col(&|x| Some(x.team_rmse_m)),
                    team_max_m: col(&|x| Some(x.team_max_m)),
                    window_end_rmse_m: (0..windows)
                        .map(|w| col(&|x| x.window_end_rmse_m.get(w).copied()))
                        .collect(),
                    mean_nees: col(&|x| Some(x.mean_nees)),
                    failed_runs,
                    flown,
                    policy,
                    estimator,
                }
            })
            .collect();
        MonteCarlo {
            runs: runs.len(),
            summary,
            each: runs,
        }
    }
}
