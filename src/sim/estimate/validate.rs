//! The checks both estimators make before they touch a number, so that every system they solve
//! is full rank and no user input can make them panic.
//!
//! - Every vehicle has a prior at epoch 0, and at every epoch e > 0 odometry from e − 1 or a
//!   prior at e: each node is then pinned by its own chain, whatever the ranges and depths do.
//! - Every node index is inside the problem (odometry's `epoch + 1` too).
//! - Every value is finite, every range ≥ 0 and between two different nodes.
//! - Every standard deviation lies in [`SIGMA_MIN`, `SIGMA_MAX`]; every covariance is symmetric
//!   (to 1e-9 of its largest variance), has variances in [`SIGMA_MIN`², `SIGMA_MAX`²] and
//!   correlations far enough from ±1 that its correlation matrix's Cholesky pivots are ≥ 1e-6
//!   (condition of the correlation matrix ≲ 1e12).
//! - Every [`Bias`](super::Bias) names a vehicle of the problem, at most one per vehicle, with a
//!   finite mean of |β| < [`MAX_HEADING_BIAS`] rad and |s| < [`MAX_SCALE_ERROR`], and a covariance
//!   held to the same standard as the others (standard deviations in [`SIGMA_MIN`,
//!   [`MAX_BIAS_SIGMA`]] rad and per unit).

use nalgebra::{Matrix2, Matrix3};

use super::{Cov2, Cov3, EstimateError, Node, Problem};

/// The smallest standard deviation accepted, m.
pub const SIGMA_MIN: f64 = 1e-9;
/// The largest standard deviation accepted, m.
pub const SIGMA_MAX: f64 = 1e9;
/// The largest |β| of a bias's prior mean (exclusive), rad.
pub(super) const MAX_HEADING_BIAS: f64 = 0.5;
/// The largest |s| of a bias's prior mean (exclusive).
pub(super) const MAX_SCALE_ERROR: f64 = 0.1;
/// The largest prior standard deviation of β (rad) or s accepted.
pub(super) const MAX_BIAS_SIGMA: f64 = 1.0;

/// What validation learned about the problem's structure, indexed by node `v · epochs + e`.
pub(super) struct Checked {
    /// The priors on each node, in input order.
    pub priors: Vec<Vec<usize>>,
    /// The odometry arriving at each node (from epoch e − 1 to e), in input order.
    pub odometry_into: Vec<Vec<usize>>,
    /// Per vehicle, the index of its bias in `problem.biases`.
    pub bias: Vec<Option<usize>>,
}

/// The index of a node among `vehicles · epochs`.
pub(super) fn index(problem: &Problem, node: Node) -> usize {
    node.vehicle * problem.epochs + node.epoch
}

fn bad(what: String, why: impl Into<String>) -> EstimateError {
    EstimateError::BadMeasurement {
        what,
        why: why.into(),
    }
}

fn node_in(problem: &Problem, node: Node, what: &str) -> Result<(), EstimateError> {
    if node.vehicle >= problem.vehicles || node.epoch >= problem.epochs {
        return Err(bad(
            what.to_string(),
            format!(
                "node (vehicle {}, epoch {}) is outside the problem: vehicles are 0..{} and epochs \
                 0..{}",
                node.vehicle, node.epoch, problem.vehicles, problem.epochs
            ),
        ));
    }
    Ok(())
}

fn finite(values: &[f64], what: &str, name: &str) -> Result<(), EstimateError> {
    if values.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(bad(
            what.to_string(),
            format!("{name} {values:?} is not finite (NaN or infinite)"),
        ))
    }
}

fn sigma_ok(sigma: f64, what: &str) -> Result<(), EstimateError> {
    if (SIGMA_MIN..=SIGMA_MAX).contains(&sigma) {
        Ok(())
    } else {
        Err(bad(
            what.to_string(),
            format!("standard deviation {sigma} m is not in [{SIGMA_MIN:e}, {SIGMA_MAX:e}] m"),
        ))
    }
}

/// The lower Cholesky factor of a covariance that passes the module's checks, else why not.
pub(super) fn cov_factor(c: &Cov3) -> Result<Matrix3<f64>, String> {
    const ALLOWED: &str = "a covariance must be finite, symmetric and positive definite";
    if !c.iter().flatten().all(|v| v.is_finite()) {
        return Err(format!("covariance {c:?} is not finite; {ALLOWED}"));
    }
    let scale = (0..3).map(|i| c[i][i].abs()).fold(0.0, f64::max);
    for i in 0..3 {
        for j in 0..i {
            if (c[i][j] - c[j][i]).abs() > 1e-9 * scale {
                return Err(format!(
                    "covariance {c:?} is not symmetric ([{i}][{j}] ≠ [{j}][{i}]); {ALLOWED}"
                ));
            }
        }
    }
    let (lo, hi) = (SIGMA_MIN * SIGMA_MIN, SIGMA_MAX * SIGMA_MAX);
    for i in 0..3 {
        if !(lo..=hi).contains(&c[i][i]) {
            return Err(format!(
                "covariance {c:?} has variance {} m² on axis {i}, not in [{lo:e}, {hi:e}] m²; \
                 {ALLOWED}",
                c[i][i]
            ));
        }
    }
    let m = Matrix3::from_fn(|i, j| 0.5 * (c[i][j] + c[j][i]));
    let d = Matrix3::from_diagonal(&m.diagonal().map(|v| 1.0 / v.sqrt()));
    let corr = d * m * d;
    let Some(chol) = corr.cholesky() else {
        return Err(format!(
            "covariance {c:?} is not positive definite; {ALLOWED}"
        ));
    };
    let pivot = chol.l().diagonal().min();
    if pivot.is_nan() || pivot < 1e-6 {
        return Err(format!(
            "covariance {c:?} is singular to working precision (correlations within 1e-12 of ±1); \
             {ALLOWED}"
        ));
    }
    m.cholesky()
        .map(|ch| ch.l())
        .ok_or_else(|| format!("covariance {c:?}: {ALLOWED}"))
}

/// The lower Cholesky factor of a bias's prior covariance that passes the module's checks,
/// else why not.
pub(super) fn cov2_factor(c: &Cov2) -> Result<Matrix2<f64>, String> {
    const ALLOWED: &str = "a covariance must be finite, symmetric and positive definite";
    if !c.iter().flatten().all(|v| v.is_finite()) {
        return Err(format!("covariance {c:?} is not finite; {ALLOWED}"));
    }
    let scale = c[0][0].abs().max(c[1][1].abs());
    if (c[1][0] - c[0][1]).abs() > 1e-9 * scale {
        return Err(format!(
            "covariance {c:?} is not symmetric ([1][0] ≠ [0][1]); {ALLOWED}"
        ));
    }
    let (lo, hi) = (SIGMA_MIN * SIGMA_MIN, MAX_BIAS_SIGMA * MAX_BIAS_SIGMA);
    for (i, unit) in [(0, "rad²"), (1, "")] {
        if !(lo..=hi).contains(&c[i][i]) {
            return Err(format!(
                "covariance {c:?} has variance {} {unit} on axis {i}, not in [{lo:e}, {hi:e}]; \
                 {ALLOWED}",
                c[i][i]
            ));
        }
    }
    let rho = 0.5 * (c[0][1] + c[1][0]) / (c[0][0] * c[1][1]).sqrt();
    // The second pivot of the correlation matrix's Cholesky factor.
    let pivot = (1.0 - rho * rho).max(0.0).sqrt();
    if pivot.is_nan() || pivot < 1e-6 {
        return Err(format!(
            "covariance {c:?} is not positive definite or is singular to working precision \
             (correlation within 1e-12 of ±1); {ALLOWED}"
        ));
    }
    let m = Matrix2::new(c[0][0], c[0][1], c[0][1], c[1][1]);
    m.cholesky()
        .map(|ch| ch.l())
        .ok_or_else(|| format!("covariance {c:?}: {ALLOWED}"))
}

/// Checks the biases and indexes them by vehicle.
fn biases(problem: &Problem) -> Result<Vec<Option<usize>>, EstimateError> {
    let mut by_vehicle = vec![None; problem.vehicles];
    for (i, b) in problem.biases.iter().enumerate() {
        let what = format!("bias #{i} (vehicle {})", b.vehicle);
        let Some(slot) = by_vehicle.get_mut(b.vehicle) else {
            return Err(bad(
                what,
                format!(
                    "vehicle {} is outside the problem: vehicles are 0..{}",
                    b.vehicle, problem.vehicles
                ),
            ));
        };
        if let Some(j) = *slot {
            return Err(bad(
                what,
                format!("the vehicle already has bias #{j}: at most one bias per vehicle"),
            ));
        }
        finite(&b.mean, &what, "mean")?;
        let [beta, s] = b.mean;
        if beta.abs() >= MAX_HEADING_BIAS {
            return Err(bad(
                what,
                format!("heading bias {beta} rad: |β| must be < {MAX_HEADING_BIAS} rad"),
            ));
        }
        if s.abs() >= MAX_SCALE_ERROR {
            return Err(bad(
                what,
                format!("scale-factor error {s}: |s| must be < {MAX_SCALE_ERROR}"),
            ));
        }
        cov2_factor(&b.cov).map_err(|why| bad(what, why))?;
        *slot = Some(i);
    }
    Ok(by_vehicle)
}

/// Checks `problem` (see the module documentation) and indexes its priors and odometry by node.
pub(super) fn validate(problem: &Problem) -> Result<Checked, EstimateError> {
    let (vehicles, epochs) = (problem.vehicles, problem.epochs);
    let nodes = vehicles
        .checked_mul(epochs)
        .filter(|&n| n <= u32::MAX as usize / 3);
    let Some(nodes) = nodes else {
        return Err(bad(
            "problem".into(),
            format!("{vehicles} vehicles × {epochs} epochs is too many nodes (at most 2³²/3)"),
        ));
    };
    let mut priors = vec![Vec::new(); nodes];
    let mut odometry_into = vec![Vec::new(); nodes];
    for (i, p) in problem.priors.iter().enumerate() {
        let what = format!("prior #{i}");
        node_in(problem, p.node, &what)?;
        let what = format!(
            "prior #{i} (vehicle {}, epoch {})",
            p.node.vehicle, p.node.epoch
        );
        finite(&p.mean, &what, "mean")?;
        cov_factor(&p.cov).map_err(|why| bad(what, why))?;
        priors[index(problem, p.node)].push(i);
    }
    for (i, o) in problem.odometry.iter().enumerate() {
        let to = Node {
            vehicle: o.vehicle,
            epoch: o.epoch.saturating_add(1),
        };
        let what = format!(
            "odometry #{i} (vehicle {}, epoch {} → {})",
            o.vehicle, o.epoch, to.epoch
        );
        node_in(problem, to, &what)?;
        finite(&o.delta, &what, "delta")?;
        cov_factor(&o.cov).map_err(|why| bad(what, why))?;
        odometry_into[index(problem, to)].push(i);
    }
    for (i, d) in problem.depths.iter().enumerate() {
        let what = format!("depth #{i}");
        node_in(problem, d.node, &what)?;
        let what = format!(
            "depth #{i} (vehicle {}, epoch {})",
            d.node.vehicle, d.node.epoch
        );
        finite(&[d.z], &what, "z")?;
        sigma_ok(d.sigma, &what)?;
    }
    for (i, r) in problem.ranges.iter().enumerate() {
        let what = format!("range #{i}");
        node_in(problem, r.a, &what)?;
        node_in(problem, r.b, &what)?;
        let what = format!(
            "range #{i} (vehicle {} epoch {} ↔ vehicle {} epoch {})",
            r.a.vehicle, r.a.epoch, r.b.vehicle, r.b.epoch
        );
        if r.a == r.b {
            return Err(bad(what, "a range must join two different nodes"));
        }
        if !(r.range.is_finite() && r.range >= 0.0) {
            return Err(bad(
                what,
                format!("range {} m must be finite and ≥ 0", r.range),
            ));
        }
        sigma_ok(r.sigma, &what)?;
    }
    let bias = biases(problem)?;
    for vehicle in 0..vehicles {
        for epoch in 0..epochs {
            let k = vehicle * epochs + epoch;
            if !priors[k].is_empty() || (epoch > 0 && !odometry_into[k].is_empty()) {
                continue;
            }
            let why = if epoch == 0 {
                "every vehicle needs a prior (absolute position) at epoch 0".to_string()
            } else {
                format!(
                    "every vehicle needs odometry from epoch {} or a prior at epoch {epoch}",
                    epoch - 1
                )
            };
            return Err(EstimateError::Unobservable {
                vehicle,
                epoch,
                why,
            });
        }
    }
    Ok(Checked {
        priors,
        odometry_into,
        bias,
    })
}
