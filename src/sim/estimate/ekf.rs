//! The causal estimate: an extended Kalman filter over all vehicles' positions at once, what
//! the team knows on board at each epoch from the measurements up to and including it.
//!
//! State: the 3·V positions of the current epoch, then b = [β, s] of each vehicle with a
//! [`Bias`](super::Bias) (in vehicle order, from its prior; constant, no process noise),
//! covariance P dense (V ≤ 65 gives ≤ 325 unknowns; at most [`MAX_VEHICLES`] vehicles). At
//! epoch 0 each vehicle starts from its first prior there. At e > 0 each vehicle is predicted
//! with its odometry e − 1 → e (several increments for the same interval are first fused in
//! information form, as the smoother's factors would be): without a bias, mean += delta and
//! P_vv += cov; with one, mean += g(b̂, delta) and P ← F P Fᵀ + G cov Gᵀ, F the identity but for
//! ∂g/∂b in the vehicle's rows and its bias's columns, G = ∂g/∂delta (`bias.rs`). Without
//! odometry a vehicle is restarted from its first prior at e (its block of P replaced, its
//! cross-covariances, also with its bias, zeroed). Then the remaining priors at e, the
//! depths at e and the ranges with both ends at e update the state, one scalar at a time (a
//! prior's three components after whitening by its Cholesky factor), in the Joseph form,
//! linearised at the current mean; a range whose two estimates coincide has no direction and is
//! skipped. The estimate of epoch e is recorded after its updates.

use std::ops::AddAssign;

use nalgebra::{DMatrix, DVector, Matrix2, Matrix3, Matrix3x2, Vector3};

use super::bias::{g, prediction};
use super::validate::{cov_factor, Checked};
use super::{Cov3, Estimate, EstimateError, Problem};

/// The most vehicles the filter takes (its covariance is dense, (3·V)² numbers).
pub(super) const MAX_VEHICLES: usize = 1000;

fn mat(c: &Cov3) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| 0.5 * (c[i][j] + c[j][i]))
}

fn solver(what: &str, why: impl std::fmt::Display) -> EstimateError {
    EstimateError::Solver(format!("{what}: {why}"))
}

/// The filter's state and the running ½ Σ (normalised innovation)².
struct Ekf {
    x: DVector<f64>,
    p: DMatrix<f64>,
    cost: f64,
}

impl Ekf {
    /// One scalar measurement z = h(x) + noise with Jacobian row `h` (sparse: (index, value)),
    /// innovation `nu` = z − h(x̂) and variance `r`, in the Joseph form
    /// P ← (I − k hᵀ) P (I − k hᵀ)ᵀ + r k kᵀ.
    fn update(&mut self, h: &[(usize, f64)], nu: f64, r: f64) {
        let n = self.x.len();
        let ph = DVector::from_fn(n, |i, _| {
            h.iter().map(|&(j, c)| self.p[(i, j)] * c).sum::<f64>()
        });
        let s = h.iter().map(|&(j, c)| c * ph[j]).sum::<f64>() + r;
        let k = &ph / s;
        self.x += &k * nu;
        self.cost += 0.5 * nu * nu / s;
        // A = (I − k hᵀ) P = P − k (P h)ᵀ, then A (I − k hᵀ)ᵀ = A − (A h) kᵀ.
        let mut a = self.p.clone();
        a.ger(-1.0, &k, &ph, 1.0);
        let ah = DVector::from_fn(n, |i, _| h.iter().map(|&(j, c)| a[(i, j)] * c).sum::<f64>());
        a.ger(-1.0, &ah, &k, 1.0);
        a.ger(r, &k, &k, 1.0);
        self.p = (&a + a.transpose()) * 0.5;
    }

    /// P ← F P Fᵀ with F = I + (`jb` at rows `r..r+3`, columns `c..c+2`): the rows of a vehicle
    /// whose prediction depends on the bias at `c`, then its columns.
    fn propagate_bias(&mut self, r: usize, c: usize, jb: &Matrix3x2<f64>) {
        let rows = jb * self.p.rows(c, 2);
        self.p.rows_mut(r, 3).add_assign(&rows);
        let cols = self.p.columns(c, 2) * jb.transpose();
        self.p.columns_mut(r, 3).add_assign(&cols);
    }

    fn block(&self, v: usize) -> Cov3 {
        let mut c = [[0.0; 3]; 3];
        for (i, row) in c.iter_mut().enumerate() {
            for (j, cell) in row.iter_mut().enumerate() {
                *cell = self.p[(3 * v + i, 3 * v + j)];
            }
        }
        c
    }
}

/// The filter on a validated, non-empty problem.
pub(super) fn filter(problem: &Problem, checked: &Checked) -> Result<Estimate, EstimateError> {
    let (vehicles, epochs) = (problem.vehicles, problem.epochs);
    if vehicles > MAX_VEHICLES {
        return Err(EstimateError::BadMeasurement {
            what: "problem".into(),
            why: format!(
                "{vehicles} vehicles: the filter's dense covariance takes at most {MAX_VEHICLES}"
            ),
        });
    }
    let mut ranges_at = vec![Vec::new(); epochs];
    for (i, r) in problem.ranges.iter().enumerate() {
        if r.a.epoch != r.b.epoch {
            return Err(EstimateError::BadMeasurement {
                what: format!(
                    "range #{i} (vehicle {} epoch {} ↔ vehicle {} epoch {})",
                    r.a.vehicle, r.a.epoch, r.b.vehicle, r.b.epoch
                ),
                why: "the filter only takes ranges between two nodes of the same epoch (the \
                      smoother takes any)"
                    .into(),
            });
        }
        ranges_at[r.a.epoch].push(i);
    }
    let mut depths_at = vec![Vec::new(); epochs];
    for (i, d) in problem.depths.iter().enumerate() {
        depths_at[d.node.epoch].push(i);
    }

    let mut bias_col = vec![None; vehicles];
    let mut n = 3 * vehicles;
    for (v, col) in bias_col.iter_mut().enumerate() {
        if checked.bias[v].is_some() {
            *col = Some(n);
            n += 2;
        }
    }
    let mut ekf = Ekf {
        x: DVector::zeros(n),
        p: DMatrix::zeros(n, n),
        cost: 0.0,
    };
    for (v, col) in bias_col.iter().enumerate() {
        if let (Some(c), Some(i)) = (*col, checked.bias[v]) {
            let b = &problem.biases[i];
            ekf.x[c] = b.mean[0];
            ekf.x[c + 1] = b.mean[1];
            let cov = Matrix2::from_fn(|i, j| 0.5 * (b.cov[i][j] + b.cov[j][i]));
            ekf.p.view_mut((c, c), (2, 2)).copy_from(&cov);
        }
    }
    let mut position = vec![Vec::with_capacity(epochs); vehicles];
    let mut covariance = vec![Vec::with_capacity(epochs); vehicles];
    let mut updates = Vec::new();
    for e in 0..epochs {
        updates.clear();
        for v in 0..vehicles {
            let k = v * epochs + e;
            let into = &checked.odometry_into[k];
            if e > 0 && !into.is_empty() {
                let (delta, cov) = fuse(problem, into)?;
                let (delta, cov) = match bias_col[v] {
                    None => (delta, cov),
                    Some(c) => {
                        let b = [ekf.x[c], ekf.x[c + 1]];
                        let (jb, jd) = prediction(b, delta);
                        ekf.propagate_bias(3 * v, c, &jb);
                        let q = jd * cov * jd.transpose();
                        (g(b, delta), (q + q.transpose()) * 0.5)
                    }
                };
                for i in 0..3 {
                    ekf.x[3 * v + i] += delta[i];
                }
                let mut block = ekf.p.view_mut((3 * v, 3 * v), (3, 3));
                block += cov;
                updates.extend(checked.priors[k].iter().copied());
            } else {
                // validate() guarantees a prior here.
                let (&first, rest) = checked.priors[k]
                    .split_first()
                    .ok_or_else(|| solver("filter", format!("no prior at node {k}")))?;
                let prior = &problem.priors[first];
                for i in 0..3 {
                    ekf.x[3 * v + i] = prior.mean[i];
                }
                ekf.p.rows_mut(3 * v, 3).fill(0.0);
                ekf.p.columns_mut(3 * v, 3).fill(0.0);
                ekf.p
                    .view_mut((3 * v, 3 * v), (3, 3))
                    .copy_from(&mat(&prior.cov));
                updates.extend(rest.iter().copied());
            }
        }
        for &i in &updates {
            let prior = &problem.priors[i];
            let v = prior.node.vehicle;
            let l = cov_factor(&prior.cov).map_err(|why| solver("prior", why))?;
            let w = l
                .try_inverse()
                .ok_or_else(|| solver("prior", "covariance inverse"))?;
            // Whitened: w·z = w·p + w·noise with unit covariance, three independent scalars.
            for r in 0..3 {
                let h: Vec<(usize, f64)> = (0..3).map(|c| (3 * v + c, w[(r, c)])).collect();
                // After earlier rows the mean has moved: recompute this row's innovation.
                let pred: f64 = h.iter().map(|&(j, c)| c * ekf.x[j]).sum();
                let zr: f64 = (0..3).map(|c| w[(r, c)] * prior.mean[c]).sum();
                ekf.update(&h, zr - pred, 1.0);
            }
        }
        for &i in &depths_at[e] {
            let d = &problem.depths[i];
            let j = 3 * d.node.vehicle + 2;
            let nu = d.z - ekf.x[j];
            ekf.update(&[(j, 1.0)], nu, d.sigma * d.sigma);
        }
        for &i in &ranges_at[e] {
            let r = &problem.ranges[i];
            let (a, b) = (3 * r.a.vehicle, 3 * r.b.vehicle);
            let d = Vector3::from_fn(|c, _| ekf.x[a + c] - ekf.x[b + c]);
            let norm = d.norm();
            if norm.is_nan() || norm <= 0.0 {
                continue;
            }
            let u = d / norm;
            let h: Vec<(usize, f64)> = (0..3)
                .map(|c| (a + c, u[c]))
                .chain((0..3).map(|c| (b + c, -u[c])))
                .collect();
            ekf.update(&h, r.range - norm, r.sigma * r.sigma);
        }
        if !ekf.x.iter().all(|v| v.is_finite()) {
            return Err(solver(
                "filter",
                format!("the state is not finite at epoch {e}"),
            ));
        }
        for v in 0..vehicles {
            let k = 3 * v;
            position[v].push([ekf.x[k], ekf.x[k + 1], ekf.x[k + 2]]);
            covariance[v].push(ekf.block(v));
        }
    }
    let bias = bias_col
        .iter()
        .map(|col| {
            col.map(|c| {
                let p = |i: usize, j: usize| ekf.p[(c + i, c + j)];
                (
                    [ekf.x[c], ekf.x[c + 1]],
                    [[p(0, 0), p(0, 1)], [p(1, 0), p(1, 1)]],
                )
            })
        })
        .collect();
    Ok(Estimate {
        position,
        covariance,
        iterations: 0,
        cost: ekf.cost,
        bias,
    })
}

/// The increments in `into` fused into one: information-weighted mean and its covariance.
fn fuse(problem: &Problem, into: &[usize]) -> Result<([f64; 3], Matrix3<f64>), EstimateError> {
    if let [only] = into {
        let o = &problem.odometry[*only];
        return Ok((o.delta, mat(&o.cov)));
    }
    let mut info = Matrix3::zeros();
    let mut vec = Vector3::zeros();
    for &i in into {
        let o = &problem.odometry[i];
        let inv = mat(&o.cov)
            .try_inverse()
            .ok_or_else(|| solver("odometry", "covariance inverse"))?;
        info += inv;
        vec += inv * Vector3::from(o.delta);
    }
    let cov = info
        .try_inverse()
        .ok_or_else(|| solver("odometry", "information inverse"))?;
    let cov = (cov + cov.transpose()) * 0.5;
    let mean = cov * vec;
    Ok(([mean[0], mean[1], mean[2]], cov))
}
