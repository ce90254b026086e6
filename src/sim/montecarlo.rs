//! Monte Carlo over the simulation's draws (`shoal simulate --runs R`): each run's error
//! metrics per estimate, and their mean and spread.

use super::policy::Policy;
use super::record::EstimateRecord;
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

/// One run's metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunMetrics {
    /// The run's seed.
    pub seed: u64,
    /// One per estimate, in the order of `SimRecord::estimates`.
    pub entries: Vec<RunEntry>,
}

impl RunMetrics {
    /// The metrics of a run's `estimates`.
    pub fn of(seed: u64, estimates: &[EstimateRecord]) -> RunMetrics {
        RunMetrics {
            seed,
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
    /// Summarise `runs` (every run lists the same estimates in the same order).
    pub fn of(runs: Vec<RunMetrics>) -> MonteCarlo {
        let summary = match runs.first() {
            None => Vec::new(),
            Some(first) => (0..first.entries.len())
                .map(|i| {
                    let col = |f: &dyn Fn(&RunEntry) -> f64| -> Stat {
                        Stat::of(&runs.iter().map(|r| f(&r.entries[i])).collect::<Vec<_>>())
                    };
                    let e = &first.entries[i];
                    Summary {
                        flown: e.flown.clone(),
                        policy: e.policy,
                        estimator: e.estimator.clone(),
                        team_rmse_m: col(&|x| x.team_rmse_m),
                        team_max_m: col(&|x| x.team_max_m),
                        window_end_rmse_m: (0..e.window_end_rmse_m.len())
                            .map(|w| col(&|x| x.window_end_rmse_m[w]))
                            .collect(),
                        mean_nees: col(&|x| x.mean_nees),
                    }
                })
                .collect(),
        };
        MonteCarlo {
            runs: runs.len(),
            summary,
            each: runs,
        }
    }
}
