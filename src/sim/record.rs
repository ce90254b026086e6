//! `sim.json`, format `shoal-sim/1` (documented field by field in docs/simulation.md): what
//! was flown, what was measured, what each estimator made of it, and the metrics.

use super::estimate::Cov3;
use super::measure::{Ping, SensorErrors};
use super::policy::Policy;
use crate::scenario::{Current, Navigation, Simulation};
use serde::{Deserialize, Serialize};

/// Value of the `format` field of every sim.json this version writes.
pub const FORMAT: &str = "shoal-sim/1";

/// A simulated mission as `shoal simulate` writes it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimRecord {
    /// Always [`FORMAT`].
    pub format: String,
    /// Version of shoal that wrote it.
    pub shoal_version: String,
    /// The plan file flown.
    pub plan: String,
    /// Seed of every draw of the simulation (sensor errors, noise, packets).
    pub seed: u64,
    /// The `[current]` flown in.
    pub current: Current,
    /// The `[navigation]` sensors.
    pub navigation: Navigation,
    /// The `[simulation]` settings.
    pub simulation: Simulation,
    /// The plan's floor clearance ε (`auv.floor_clearance`), m.
    pub floor_clearance: f64,
    /// Number of AUVs; the USV is vehicle index `auvs` in links and pings.
    pub auvs: usize,
    /// Time of each epoch (acoustic cycle), s.
    pub times: Vec<f64>,
    /// The flight of the plan's final stages (Step 3, the chain).
    pub flight: FlightRecord,
    /// The flight of the plan's Step 1 paths (no chain), for comparison.
    pub step1_flight: FlightRecord,
    /// Each estimate: per policy and estimator on the final stages' flight, and the
    /// `all_links` policy on Step 1's; those that failed are in `failed_estimates` instead.
    pub estimates: Vec<EstimateRecord>,
    /// The estimates of the first run that failed (an estimator that did not converge, say),
    /// each with why.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub failed_estimates: Vec<EstimateFailure>,
    /// The families the plan's check failed when it was flown all the same (`shoal simulate
    /// --unchecked`); empty for a plan that passed (or was not checked).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub check_failures: Vec<String>,
    /// Set when the runs were stopped before all were done (Ctrl-C): the record and the
    /// summary hold the runs that finished.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub incomplete: Option<Incomplete>,
    /// With `--runs R` > 1: each run's metrics and their mean and spread.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub monte_carlo: Option<super::montecarlo::MonteCarlo>,
}

/// An estimate that could not be made.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EstimateFailure {
    /// Which ranges it would have used.
    pub policy: Policy,
    /// "factor_graph" or "ekf".
    pub estimator: String,
    /// "final" or "step1".
    pub flown: String,
    /// Ranges it would have used.
    pub ranges_used: usize,
    /// For an estimator that did not converge, the iterations it took before it stopped.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub iterations: Option<usize>,
    /// Why, in full.
    pub error: String,
}

impl EstimateFailure {
    /// Why, in a few words: "did not converge after 200 iterations", or the error.
    pub fn brief(&self) -> String {
        match self.iterations {
            Some(n) => format!("did not converge after {n} iterations"),
            None => self.error.clone(),
        }
    }
}

/// Runs stopped before all were done.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Incomplete {
    /// Runs asked for (`--runs`).
    pub runs_asked: usize,
    /// Runs finished, whose metrics the record holds.
    pub runs_finished: usize,
    /// Why: "interrupted".
    pub reason: String,
}

/// One flight: the executed and planned positions at each epoch, what was measured, and how
/// well the plan was kept.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FlightRecord {
    /// `[auv][epoch]`: executed positions, m.
    pub executed: Vec<Vec<[f64; 3]>>,
    /// `[auv][epoch]`: planned positions at the same instants, m.
    pub planned: Vec<Vec<[f64; 3]>>,
    /// `[epoch]`: the USV's position, m.
    pub usv: Vec<[f64; 3]>,
    /// `[auv]`: the sensor errors drawn.
    pub sensor_errors: Vec<SensorErrorsRecord>,
    /// `[auv][epoch]`: dead-reckoning increments from epoch e to e + 1 (e = 0..E−1), m.
    pub odometry: Vec<Vec<[f64; 3]>>,
    /// `[auv][epoch]`: fraction of each increment's samples with DVL bottom lock.
    pub bottom_lock: Vec<Vec<f64>>,
    /// `[auv][epoch]`: measured z, m.
    pub depth: Vec<Vec<f64>>,
    /// `[epoch]`: the USV's GPS fixes, m.
    pub gps: Vec<[f64; 2]>,
    /// Every ping: epoch, pair, distance, line of sight, received, measured range.
    pub pings: Vec<Ping>,
    /// Tracking, floor clearance and connectivity of the executed path.
    pub metrics: FlightMetrics,
}

/// One AUV's sensor errors.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SensorErrorsRecord {
    /// DVL scale-factor error (fraction).
    pub dvl_scale: f64,
    /// Compass heading bias, rad.
    pub heading_bias: f64,
}

impl From<SensorErrors> for SensorErrorsRecord {
    fn from(e: SensorErrors) -> Self {
        SensorErrorsRecord {
            dvl_scale: e.dvl_scale,
            heading_bias: e.heading_bias,
        }
    }
}

/// How the executed path kept the plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FlightMetrics {
    /// `[auv]`: RMS distance between executed and planned positions over the samples, m.
    pub tracking_rms_m: Vec<f64>,
    /// `[auv]`: largest such distance, m.
    pub tracking_max_m: Vec<f64>,
    /// Lowest height above the floor over every AUV and sample, m.
    pub min_altitude_m: f64,
    /// Samples (all AUVs) below the floor clearance ε (`auv.floor_clearance`).
    pub samples_below_clearance: usize,
    /// Samples (all AUVs) below the floor itself (a collision).
    pub samples_below_floor: usize,
    /// Samples (all AUVs) outside the grid.
    pub samples_off_grid: usize,
    /// Epochs at which every AUV has a path of links (in range and in line of sight, executed
    /// positions) to the USV, as a fraction.
    pub connected_fraction: f64,
    /// Planned link-epochs (Step 2's links) in range and in line of sight, as a fraction (0
    /// for Step 1's flight, which has no plan of links).
    pub planned_links_up: f64,
    /// Planned link-epochs whose ping was received, as a fraction.
    pub planned_links_received: f64,
    /// Epochs at which every AUV reaches the USV through links whose pings were received
    /// (on the executed positions, with the drawn packet losses), as a fraction.
    #[serde(default)]
    pub linked_fraction: f64,
    /// Closest approach of two AUVs over the samples, flown, m (0 with one AUV).
    #[serde(default)]
    pub min_separation_m: f64,
    /// Closest approach of two AUVs' references (the plan in time) at the same samples, m.
    #[serde(default)]
    pub min_separation_planned_m: f64,
    /// The references' samples (all AUVs) below the floor clearance ε: what the plan itself
    /// asks for, measured as the flight is.
    #[serde(default)]
    pub planned_samples_below_clearance: usize,
    /// The references' samples (all AUVs) below the floor.
    #[serde(default)]
    pub planned_samples_below_floor: usize,
    /// The references' lowest height above the floor, m.
    #[serde(default)]
    pub planned_min_altitude_m: f64,
    /// The reception the plan expects of its links: the mean of p(d) over the planned
    /// link-epochs at the planned positions (0 where out of range or out of sight).
    #[serde(default)]
    pub planned_links_expected: f64,
    /// Epochs at which every AUV reaches the USV through links in range and in line of sight
    /// at the planned positions, as a fraction.
    #[serde(default)]
    pub planned_connected_fraction: f64,
    /// Distance each AUV travelled, m.
    pub distance_m: Vec<f64>,
}

/// One estimator's run under one policy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EstimateRecord {
    /// Which ranges it used.
    pub policy: Policy,
    /// "factor_graph" (batch per window, all of the window's measurements) or "ekf" (causal).
    pub estimator: String,
    /// "final" (Step 3's plan) or "step1" (Step 1's paths).
    pub flown: String,
    /// Ranges used.
    pub ranges_used: usize,
    /// `[auv][epoch]`: estimated positions, m.
    pub position: Vec<Vec<[f64; 3]>>,
    /// `[auv][epoch]`: their covariances [xx, xy, xz, yy, yz, zz], m².
    pub covariance: Vec<Vec<[f64; 6]>>,
    /// Errors against the executed positions.
    pub metrics: NavMetrics,
}

/// Position errors of one estimate (3-D distance to the executed position).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NavMetrics {
    /// RMS over every AUV and epoch, m.
    pub team_rmse_m: f64,
    /// Largest over every AUV and epoch, m.
    pub team_max_m: f64,
    /// `[auv]`: RMS over the epochs, m.
    pub rmse_m: Vec<f64>,
    /// `[auv]`: largest over the epochs, m.
    pub max_m: Vec<f64>,
    /// `[epoch]`: RMS over the AUVs, m.
    pub team_rmse_over_time_m: Vec<f64>,
    /// `[window]`: RMS over the AUVs at each window's last epoch, m.
    pub window_end_rmse_m: Vec<f64>,
    /// The team's RMS error at the end of the mission as a percentage of the mean distance
    /// travelled.
    pub end_percent_of_distance: f64,
    /// Mean normalised estimation error squared (3 for a consistent estimator).
    pub mean_nees: f64,
}

/// [xx, xy, xz, yy, yz, zz] of a covariance.
pub fn packed(c: &Cov3) -> [f64; 6] {
    [c[0][0], c[0][1], c[0][2], c[1][1], c[1][2], c[2][2]]
}
