//! Navigation estimators over one set of measurements: where every vehicle was at every epoch,
//! from dead reckoning (DVL + heading + depth), GPS on the USV and acoustic ranges.
//!
//! - [`smooth`] / [`smooth_with`]: the batch factor-graph estimate (all measurements, past and
//!   future) with each node's marginal covariance, by Levenberg–Marquardt in factrs
//!   (`graph.rs`; the marginals by a sparse Cholesky and the Takahashi recurrence, `marginal.rs`).
//! - [`filter`]: an extended Kalman filter, each node from the measurements up to and including
//!   its epoch (what a vehicle knows on board; `ekf.rs`).
//! - [`dead_reckoning`]: each vehicle from its priors and odometry alone.
//!
//! A vehicle may carry a [`Bias`]: its dead reckoning's constant heading bias β and DVL
//! scale-factor error s become unknowns of both estimators (`bias.rs`), so that errors which
//! persist over the whole mission are estimated instead of treated as fresh noise every cycle.
//!
//! Both estimators first validate the problem (`validate.rs`): every vehicle needs a prior at
//! epoch 0 and, at every later epoch, odometry from the previous one or a prior; node indices
//! must be in range, values finite, standard deviations between [`SIGMA_MIN`] and [`SIGMA_MAX`],
//! covariances symmetric positive definite with variances between their squares and no
//! correlation within ~1e-12 of ±1; at most one [`Bias`] per vehicle, with |β| < 0.5 rad and
//! |s| < 0.1 and prior standard deviations of at most 1 (rad, per unit). That makes every system
//! the smoother solves full rank.
//! A problem with no nodes (0 epochs or 0 vehicles) and no measurements has an empty estimate:
//! `vehicles` empty tracks, 0 iterations, cost 0.

use thiserror::Error;

mod bias;
mod ekf;
mod factors;
mod graph;
mod marginal;
#[cfg(test)]
mod tests;
mod validate;

pub use validate::{SIGMA_MAX, SIGMA_MIN};

/// A 3×3 covariance, row-major, m².
pub type Cov3 = [[f64; 3]; 3];

/// A 2×2 covariance, row-major (of a [`Bias`]: [rad², rad; rad, 1]).
pub type Cov2 = [[f64; 2]; 2];

/// A vehicle's estimated biases [β (rad), s] and their marginal covariance.
pub type BiasEstimate = ([f64; 2], Cov2);

/// One unknown: the position of `vehicle` (0..N−1 the AUVs, N the USV) at `epoch`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Node {
    /// Vehicle index.
    pub vehicle: usize,
    /// Epoch index.
    pub epoch: usize,
}

/// An absolute position measurement (a GPS fix, a known start).
#[derive(Debug, Clone, PartialEq)]
pub struct Prior {
    /// The node measured.
    pub node: Node,
    /// Measured position, m.
    pub mean: [f64; 3],
    /// Its covariance, m².
    pub cov: Cov3,
}

/// Dead reckoning of one vehicle from `epoch` to `epoch + 1`: p\[e+1\] − p\[e\] = delta, or, for a
/// vehicle with a [`Bias`] b = [β, s], p\[e+1\] − p\[e\] = g(b, delta) with
/// g = [R_z(−β)·delta_xy / (1 + s); delta_z / (1 + s)] (the measured increment is
/// (1 + s)·R_z(β) times the true one plus white noise; R_z(β) turns [x, y] from +x towards +y).
#[derive(Debug, Clone, PartialEq)]
pub struct Odometry {
    /// Vehicle index.
    pub vehicle: usize,
    /// The epoch the increment starts at.
    pub epoch: usize,
    /// Measured displacement, m (world frame).
    pub delta: [f64; 3],
    /// Its covariance, m² (for a vehicle with a [`Bias`], of the white noise only).
    pub cov: Cov3,
}

/// A vehicle's dead-reckoning biases as unknowns b = [β, s] with a Gaussian prior: β the compass
/// heading bias (rad), s the DVL scale-factor error (fraction), both constant over the problem.
/// They turn every [`Odometry`] of the vehicle into p\[e+1\] − p\[e\] = g(b, delta).
#[derive(Debug, Clone, PartialEq)]
pub struct Bias {
    /// Vehicle index.
    pub vehicle: usize,
    /// Prior mean [β (rad), s]; |β| < 0.5 and |s| < 0.1.
    pub mean: [f64; 2],
    /// Prior covariance.
    pub cov: Cov2,
}

/// A depth (pressure) measurement: z of `node` = `z`.
#[derive(Debug, Clone, PartialEq)]
pub struct Depth {
    /// The node measured.
    pub node: Node,
    /// Measured z, m (negative under water).
    pub z: f64,
    /// Standard deviation, m.
    pub sigma: f64,
}

/// An acoustic range between two nodes: ‖p_a − p_b‖ = range.
#[derive(Debug, Clone, PartialEq)]
pub struct Range {
    /// One end.
    pub a: Node,
    /// The other end.
    pub b: Node,
    /// Measured range, m.
    pub range: f64,
    /// Standard deviation, m.
    pub sigma: f64,
}

/// Everything measured over a stretch of epochs.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Problem {
    /// Number of vehicles (AUVs and the USV).
    pub vehicles: usize,
    /// Number of epochs.
    pub epochs: usize,
    /// Absolute position measurements.
    pub priors: Vec<Prior>,
    /// Dead-reckoning increments.
    pub odometry: Vec<Odometry>,
    /// Depth measurements.
    pub depths: Vec<Depth>,
    /// Acoustic ranges.
    pub ranges: Vec<Range>,
    /// Dead-reckoning biases, at most one per vehicle (a vehicle without one has unbiased
    /// odometry).
    pub biases: Vec<Bias>,
}

/// Estimated positions and their marginal covariances, indexed `[vehicle][epoch]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Position estimates, m.
    pub position: Vec<Vec<[f64; 3]>>,
    /// Marginal covariance of each estimate, m².
    pub covariance: Vec<Vec<Cov3>>,
    /// Nonlinear iterations taken (0 for the filter).
    pub iterations: usize,
    /// The smoother: its final cost ½ Σ ‖whitened residual‖² (its expectation is half the number
    /// of scalar measurements, a bias's prior counting 2, minus 3 per node and 2 per bias). The
    /// filter: ½ Σ of its squared normalised innovations ν²/s.
    pub cost: f64,
    /// Per vehicle, its estimated biases b = [β, s] and their marginal covariance (the filter:
    /// after the last epoch), or `None` for a vehicle without a [`Bias`].
    pub bias: Vec<Option<BiasEstimate>>,
}

/// Settings of the smoother's Levenberg–Marquardt solve.
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothOptions {
    /// The most iterations (default 100).
    pub max_iterations: usize,
    /// Stop once an iteration lowers the cost (½χ²) by at most this (default 1e-5).
    pub tolerance: f64,
    /// Accept the result only if one more Gauss–Newton step would lower the cost by at most
    /// this (default 1e-3, a step of at most √(2·1e-3) ≈ 0.045 posterior standard deviations in
    /// Mahalanobis length, so no coordinate is further than 0.045 of its own marginal standard
    /// deviation from where that step leads); otherwise [`EstimateError::NotConverged`].
    pub acceptance: f64,
}

impl Default for SmoothOptions {
    fn default() -> Self {
        Self {
            max_iterations: 100,
            tolerance: 1e-5,
            acceptance: 1e-3,
        }
    }
}

/// Why an estimate could not be made.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum EstimateError {
    /// A node no measurement determines.
    #[error("vehicle {vehicle} at epoch {epoch} is not determined by any measurement: {why}")]
    Unobservable {
        /// Vehicle index.
        vehicle: usize,
        /// Epoch index.
        epoch: usize,
        /// What is missing.
        why: String,
    },
    /// A measurement that names a node outside the problem or has a non-positive noise.
    #[error("measurement {what}: {why}")]
    BadMeasurement {
        /// Which measurement.
        what: String,
        /// What is wrong.
        why: String,
    },
    /// Levenberg–Marquardt stopped short of the standard of [`SmoothOptions::acceptance`].
    #[error(
        "the factor graph solver failed: Levenberg–Marquardt did not converge: it stopped after \
         {iterations} iterations because {reason}, at cost {cost:.6e}, but a Gauss–Newton step \
         would still lower the cost by {decrement:.3e}"
    )]
    NotConverged {
        /// Iterations taken (the Gauss–Newton polish included).
        iterations: usize,
        /// Why it stopped: "it reached the iteration limit", …
        reason: &'static str,
        /// Its final cost ½χ².
        cost: f64,
        /// The decrease one more Gauss–Newton step would predict.
        decrement: f64,
    },
    /// The solver failed.
    #[error("the factor graph solver failed: {0}")]
    Solver(String),
}

/// The estimate of a problem with no nodes: empty tracks, and each bias its prior.
fn empty(problem: &Problem) -> Estimate {
    let mut bias = vec![None; problem.vehicles];
    for b in &problem.biases {
        if let Some(slot) = bias.get_mut(b.vehicle) {
            *slot = Some((b.mean, b.cov));
        }
    }
    Estimate {
        position: vec![Vec::new(); problem.vehicles],
        covariance: vec![Vec::new(); problem.vehicles],
        iterations: 0,
        cost: 0.0,
        bias,
    }
}

/// The batch factor-graph estimate (smoother) of every node, from `initial` guesses
/// (`[vehicle][epoch]`); with `initial` empty, from [`dead_reckoning`]. Each [`Bias`] starts
/// from its prior mean. Default options.
///
/// Errors: [`EstimateError::Unobservable`] or [`EstimateError::BadMeasurement`] from
/// validation (an `initial` of the wrong shape or not finite is a `BadMeasurement` of "initial
/// guess"); [`EstimateError::NotConverged`] if Levenberg–Marquardt does not converge by the
/// standard of [`SmoothOptions::acceptance`]; [`EstimateError::Solver`] if the linear algebra
/// fails (which validation is meant to make impossible).
pub fn smooth(problem: &Problem, initial: &[Vec<[f64; 3]>]) -> Result<Estimate, EstimateError> {
    smooth_with(problem, initial, &SmoothOptions::default())
}

/// [`smooth`] with explicit solver settings.
pub fn smooth_with(
    problem: &Problem,
    initial: &[Vec<[f64; 3]>],
    options: &SmoothOptions,
) -> Result<Estimate, EstimateError> {
    let checked = validate::validate(problem)?;
    if problem.vehicles * problem.epochs == 0 {
        return Ok(empty(problem));
    }
    let guess;
    let initial = if initial.is_empty() {
        guess = graph::dead_reckoning(problem, &checked);
        &guess[..]
    } else {
        let bad = |why: String| EstimateError::BadMeasurement {
            what: "initial guess".into(),
            why,
        };
        if initial.len() != problem.vehicles {
            return Err(bad(format!(
                "it has {} vehicles, the problem {}",
                initial.len(),
                problem.vehicles
            )));
        }
        for (v, track) in initial.iter().enumerate() {
            if track.len() != problem.epochs {
                return Err(bad(format!(
                    "vehicle {v} has {} epochs, the problem {}",
                    track.len(),
                    problem.epochs
                )));
            }
            if let Some(e) = track.iter().position(|p| !p.iter().all(|c| c.is_finite())) {
                return Err(bad(format!("vehicle {v} at epoch {e} is not finite")));
            }
        }
        initial
    };
    graph::smooth(problem, &checked, initial, options)
}

/// Each vehicle's position from its priors and odometry alone: a node's first prior where it
/// has one, else the previous position plus the (first) odometry increment into it (for a vehicle
/// with a [`Bias`], g(b, delta) at the bias's prior mean). This is the
/// smoother's default initial guess; for an AUV with a single prior at epoch 0 it is pure dead
/// reckoning.
pub fn dead_reckoning(problem: &Problem) -> Result<Vec<Vec<[f64; 3]>>, EstimateError> {
    let checked = validate::validate(problem)?;
    Ok(graph::dead_reckoning(problem, &checked))
}

/// The EKF estimate of every node from the measurements up to its epoch (causal). Ranges must
/// join two nodes of the same epoch, and there may be at most 1000 vehicles (the covariance is
/// dense); otherwise [`EstimateError::BadMeasurement`].
pub fn filter(problem: &Problem) -> Result<Estimate, EstimateError> {
    let checked = validate::validate(problem)?;
    if problem.vehicles * problem.epochs == 0 {
        return Ok(empty(problem));
    }
    ekf::filter(problem, &checked)
}
