//! The batch estimate (smoother): one factor graph over every node and every measurement, past
//! and future, solved by Levenberg–Marquardt, with each node's marginal covariance.
//!
//! Built on factrs: its variables and residuals are typed (a `VectorVar3` per node; prior,
//! between, depth and range residuals), it solves by Levenberg–Marquardt over faer's sparse
//! Cholesky, it differentiates custom residuals (depth, range) by forward-mode dual numbers
//! instead of hand-written Jacobians, and its API (`Values`, `Graph`, `PriorResidual`,
//! `BetweenResidual`, noise models, `LevenMarquardt`) is GTSAM's, which navigation researchers
//! know.
//!
//! factrs's linear solver panics on a singular system (`expect("Cholesky decomp failed")`);
//! [`validate`](super::validate) makes every system full rank before anything is solved, and the
//! solve runs inside `catch_unwind` only as a last line of defence, so that a panic that
//! validation failed to prevent becomes [`EstimateError::Solver`] instead of aborting `shoal`.
//!
//! Convergence ([`SmoothOptions`]): Levenberg–Marquardt iterates until an iteration lowers the
//! cost ½‖r‖² (whitened residuals) by at most `tolerance`, until it cannot find a step that
//! lowers the cost at all, or until `max_iterations`. Unless it ran out of iterations, up to
//! three Gauss–Newton steps then polish the result (LM's damping leaves a relative error of
//! about λ, and its last step may fail on rounding); they reuse the factorisation the marginals
//! need anyway and make a linear problem exact. The result is accepted if and only if the
//! Gauss–Newton decrement ½ gᵀΛ⁻¹g (the cost decrease one more step would predict) is at most
//! `acceptance`; otherwise the smoother returns [`EstimateError::Solver`] with the reason LM
//! stopped. The decrement is half the squared Mahalanobis length of that step, which bounds
//! every coordinate's remaining error relative to its own marginal standard deviation.
//!
//! Gauss–Newton converges only linearly where ranges are short compared with the residuals'
//! effect on their curvature (closely spaced vehicles, large range noise); the iteration count
//! is then what the time depends on.

use std::panic::{catch_unwind, AssertUnwindSafe};

use factrs::{
    assign_symbols,
    containers::{FactorBuilder, Graph, Values, ValuesOrder},
    linalg::{vectorx, Const, DiffResult, ForwardProp, Numeric, VectorX},
    noise::GaussianNoise,
    optimizers::{LevenMarquardt, LevenParams, OptError, Optimizer},
    residuals::{BetweenResidual, PriorResidual, Residual1, Residual2},
    variables::VectorVar3,
};

use super::marginal::Cholesky;
use super::validate::{cov_factor, index, Checked};
use super::{Cov3, Estimate, EstimateError, Problem, SmoothOptions};

assign_symbols!(X: VectorVar3);

/// A depth gauge: r = z − z_measured.
#[derive(Clone, Debug)]
struct DepthResidual {
    z: f64,
}

#[factrs::mark]
impl Residual1 for DepthResidual {
    type Differ = ForwardProp<Const<3>>;
    type V1 = VectorVar3;
    type DimIn = Const<3>;
    type DimOut = Const<1>;

    fn residual1<T: Numeric>(&self, p: VectorVar3<T>) -> VectorX<T> {
        vectorx![p.0[2] - T::from(self.z)]
    }
}

/// The square of the length below which a range's Jacobian fades to zero, m².
const RANGE_EPS2: f64 = 1e-12;

/// An acoustic range: r = √(‖a − b‖² + ε²) − range, ε = 1 µm. The ε keeps the autodiff
/// derivative finite (zero) when the two positions coincide, where ‖·‖ has none; it biases a
/// range of d metres by ε²/2d, 5·10⁻¹³ m at 1 m.
#[derive(Clone, Debug)]
struct RangeResidual {
    range: f64,
}

#[factrs::mark]
impl Residual2 for RangeResidual {
    type Differ = ForwardProp<Const<6>>;
    type V1 = VectorVar3;
    type V2 = VectorVar3;
    type DimIn = Const<6>;
    type DimOut = Const<1>;

    fn residual2<T: Numeric>(&self, a: VectorVar3<T>, b: VectorVar3<T>) -> VectorX<T> {
        let d = a.0 - b.0;
        vectorx![(d.norm_squared() + T::from(RANGE_EPS2)).sqrt() - T::from(self.range)]
    }
}

/// The whitening of a validated covariance: R = L⁻¹ with L Lᵀ = cov, so RᵀR = cov⁻¹.
fn noise3(cov: &Cov3) -> Result<GaussianNoise<3>, EstimateError> {
    let l = cov_factor(cov).map_err(|why| EstimateError::Solver(format!("covariance: {why}")))?;
    let r = l
        .try_inverse()
        .ok_or_else(|| EstimateError::Solver("covariance inverse".into()))?;
    Ok(GaussianNoise::<3>::from_matrix_sqrt_inf(r))
}

fn key(k: usize) -> X {
    // validate() bounds the node count by u32::MAX / 3.
    X(k as u32)
}

fn build(problem: &Problem) -> Result<Graph, EstimateError> {
    let mut graph = Graph::with_capacity(
        problem.priors.len() + problem.odometry.len() + problem.depths.len() + problem.ranges.len(),
    );
    for p in &problem.priors {
        let [x, y, z] = p.mean;
        let res = PriorResidual::new(VectorVar3::new(x, y, z));
        let k = key(index(problem, p.node));
        graph.add_factor(
            FactorBuilder::<3>::new1(res, k)
                .noise(noise3(&p.cov)?)
                .build(),
        );
    }
    for o in &problem.odometry {
        let [x, y, z] = o.delta;
        let res = BetweenResidual::new(VectorVar3::new(x, y, z));
        let k0 = o.vehicle * problem.epochs + o.epoch;
        let f = FactorBuilder::<3>::new2(res, key(k0), key(k0 + 1)).noise(noise3(&o.cov)?);
        graph.add_factor(f.build());
    }
    for d in &problem.depths {
        let res = DepthResidual { z: d.z };
        let noise = GaussianNoise::<1>::from_scalar_sigma(d.sigma);
        let k = key(index(problem, d.node));
        graph.add_factor(FactorBuilder::<1>::new1(res, k).noise(noise).build());
    }
    for r in &problem.ranges {
        let res = RangeResidual { range: r.range };
        let noise = GaussianNoise::<1>::from_scalar_sigma(r.sigma);
        let (a, b) = (key(index(problem, r.a)), key(index(problem, r.b)));
        graph.add_factor(FactorBuilder::<1>::new2(res, a, b).noise(noise).build());
    }
    Ok(graph)
}

/// Each vehicle from its priors and odometry alone (see [`super::dead_reckoning`]).
pub(super) fn dead_reckoning(problem: &Problem, checked: &Checked) -> Vec<Vec<[f64; 3]>> {
    let mut out: Vec<Vec<[f64; 3]>> = vec![Vec::with_capacity(problem.epochs); problem.vehicles];
    for (v, track) in out.iter_mut().enumerate() {
        for e in 0..problem.epochs {
            let k = v * problem.epochs + e;
            let p = match (checked.priors[k].first(), track.last()) {
                (Some(&i), _) => problem.priors[i].mean,
                (None, Some(prev)) => {
                    // validate() guarantees odometry into every node without a prior.
                    let d = checked.odometry_into[k]
                        .first()
                        .map_or([0.0; 3], |&i| problem.odometry[i].delta);
                    [prev[0] + d[0], prev[1] + d[1], prev[2] + d[2]]
                }
                (None, None) => [0.0; 3],
            };
            track.push(p);
        }
    }
    out
}

/// Why Levenberg–Marquardt stopped.
enum Stop {
    Converged,
    Stalled,
    MaxIterations,
}

/// The smoother on a validated, non-empty problem from a validated initial guess.
pub(super) fn smooth(
    problem: &Problem,
    initial: &[Vec<[f64; 3]>],
    options: &SmoothOptions,
) -> Result<Estimate, EstimateError> {
    let graph = build(problem)?;
    let mut values = Values::new();
    for (v, track) in initial.iter().enumerate() {
        for (e, p) in track.iter().enumerate() {
            values.insert(
                key(v * problem.epochs + e),
                VectorVar3::new(p[0], p[1], p[2]),
            );
        }
    }
    // Last line of defence only: validation makes every system this solves full rank.
    match catch_unwind(AssertUnwindSafe(|| solve(problem, graph, values, options))) {
        Ok(result) => result,
        Err(panic) => {
            let msg = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(EstimateError::Solver(format!("factrs panicked: {msg}")))
        }
    }
}

fn solve(
    problem: &Problem,
    graph: Graph,
    mut values: Values,
    options: &SmoothOptions,
) -> Result<Estimate, EstimateError> {
    let mut lm = LevenMarquardt::new(LevenParams::default(), graph);
    lm.init(&values);
    let mut cost = lm.graph().error(&values);
    let mut iterations = 0;
    let mut stop = Stop::Converged;
    if cost > 0.0 {
        stop = Stop::MaxIterations;
        for i in 1..=options.max_iterations {
            match lm.step(values.clone(), i) {
                Ok((next, _)) => {
                    iterations = i;
                    let next_cost = lm.graph().error(&next);
                    let decrease = cost - next_cost;
                    values = next;
                    cost = next_cost;
                    if decrease <= options.tolerance {
                        stop = Stop::Converged;
                        break;
                    }
                }
                Err(OptError::FailedToStep) => {
                    stop = Stop::Stalled;
                    break;
                }
                Err(e) => return Err(EstimateError::Solver(format!("Levenberg–Marquardt: {e:?}"))),
            }
        }
    }
    if !cost.is_finite() {
        return Err(EstimateError::Solver(format!(
            "the cost is {cost} after {iterations} iterations"
        )));
    }

    // Polish (see the module documentation); each step is kept unless it raises the cost
    // beyond rounding.
    let nodes = problem.vehicles * problem.epochs;
    let graph = lm.graph();
    let mut linear = linearise(graph, &values, nodes)?;
    if !matches!(stop, Stop::MaxIterations) {
        for _ in 0..3 {
            let decrement = linear.chol.newton_decrement(&linear.g);
            if decrement.is_nan() || decrement <= f64::EPSILON * f64::EPSILON * cost.max(1.0) {
                break;
            }
            let dx = linear.chol.solve(&linear.g);
            let mut next = Values::new();
            for (k, &c) in linear.cols.iter().enumerate() {
                let p: &VectorVar3 = values.get(key(k)).ok_or_else(|| lost(k))?;
                next.insert(
                    key(k),
                    VectorVar3::new(p.0[0] + dx[c], p.0[1] + dx[c + 1], p.0[2] + dx[c + 2]),
                );
            }
            let next_cost = graph.error(&next);
            if next_cost.is_nan() || next_cost > cost + 1e-12 * cost.max(1.0) {
                break;
            }
            values = next;
            cost = next_cost;
            iterations += 1;
            linear = linearise(graph, &values, nodes)?;
        }
    }
    let Linear { chol, cols, g } = linear;
    let decrement = chol.newton_decrement(&g);
    if decrement.is_nan() || decrement > options.acceptance {
        let why = match stop {
            Stop::Converged => "its cost decrease fell below the tolerance",
            Stop::Stalled => "it found no step that lowers the cost",
            Stop::MaxIterations => "it reached the iteration limit",
        };
        return Err(EstimateError::Solver(format!(
            "Levenberg–Marquardt did not converge: it stopped after {iterations} iterations \
             because {why}, at cost {cost:.6e}, but a Gauss–Newton step would still lower the \
             cost by {decrement:.3e}"
        )));
    }

    let z = chol.selected_inverse();
    let mut position = vec![Vec::with_capacity(problem.epochs); problem.vehicles];
    let mut covariance = vec![Vec::with_capacity(problem.epochs); problem.vehicles];
    for v in 0..problem.vehicles {
        for e in 0..problem.epochs {
            let k = v * problem.epochs + e;
            let p: &VectorVar3 = values.get(key(k)).ok_or_else(|| lost(k))?;
            position[v].push([p.0[0], p.0[1], p.0[2]]);
            let block = chol.block(&z, cols[k]).ok_or_else(|| {
                EstimateError::Solver(format!("node {k}'s block is not in the factor's pattern"))
            })?;
            covariance[v].push(block);
        }
    }
    Ok(Estimate {
        position,
        covariance,
        iterations,
        cost,
    })
}

fn lost(k: usize) -> EstimateError {
    EstimateError::Solver(format!("node {k} is missing from the solver's values"))
}

/// The problem linearised at some values: the factorised information matrix JᵀJ, each node's
/// first column in it, and the gradient Jᵀb (b = −r, whitened).
struct Linear {
    chol: Cholesky,
    cols: Vec<usize>,
    g: Vec<f64>,
}

fn linearise(graph: &Graph, values: &Values, nodes: usize) -> Result<Linear, EstimateError> {
    let order = ValuesOrder::from_values(values);
    let mut cols = Vec::with_capacity(nodes);
    for k in 0..nodes {
        cols.push(order.get(key(k)).ok_or_else(|| lost(k))?.idx);
    }
    let linear = graph.linearize(values);
    let graph_order = linear.sparsity_pattern(order);
    let DiffResult { value: b, diff: j } = linear.residual_jacobian(&graph_order);
    let jt = j
        .as_ref()
        .transpose()
        .to_col_major()
        .map_err(|e| EstimateError::Solver(format!("transposing the Jacobian: {e:?}")))?;
    let info = &jt * &j;
    let g = &jt * &b;
    let chol = Cholesky::new(info.as_ref()).map_err(EstimateError::Solver)?;
    let g = (0..g.nrows()).map(|i| g[(i, 0)]).collect();
    Ok(Linear { chol, cols, g })
}
