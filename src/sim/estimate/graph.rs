//! The batch estimate (smoother): one factor graph over every node and every measurement, past
//! and future, solved by Levenberg–Marquardt, with each node's marginal covariance.
//!
//! Built on factrs: its variables and residuals are typed (a `VectorVar3` per node, a
//! `VectorVar2` per vehicle with biases; prior, between, biased odometry, depth and range
//! residuals), it solves by Levenberg–Marquardt over faer's sparse Cholesky, it differentiates
//! custom residuals (depth, range in `factors.rs`; biased odometry in `bias.rs`) by forward-mode
//! dual numbers instead of hand-written Jacobians, and its API (`Values`, `Graph`, `PriorResidual`,
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
//! `acceptance`; otherwise the smoother returns [`EstimateError::NotConverged`] with the reason LM
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
    linalg::{DiffResult, VectorX},
    linear::LinearValues,
    noise::GaussianNoise,
    optimizers::{LevenMarquardt, LevenParams, OptError, Optimizer},
    residuals::{BetweenResidual, PriorResidual},
    variables::{VectorVar2, VectorVar3},
};

use super::bias::{g, BiasedOdometry};
use super::factors::{noise2, noise3, DepthResidual, RangeResidual};
use super::marginal::Cholesky;
use super::validate::{index, Checked};
use super::{Estimate, EstimateError, Problem, SmoothOptions};

assign_symbols!(X: VectorVar3; B: VectorVar2);

fn key(k: usize) -> X {
    // validate() bounds the node count by u32::MAX / 3.
    X(k as u32)
}

/// The bias variable of vehicle `v` (v < nodes ≤ u32::MAX / 3 in a non-empty problem).
fn bias_key(v: usize) -> B {
    B(v as u32)
}

fn build(problem: &Problem, checked: &Checked) -> Result<Graph, EstimateError> {
    let mut graph = Graph::with_capacity(
        problem.priors.len()
            + problem.odometry.len()
            + problem.depths.len()
            + problem.ranges.len()
            + problem.biases.len(),
    );
    for b in &problem.biases {
        let res = PriorResidual::new(VectorVar2::new(b.mean[0], b.mean[1]));
        let f = FactorBuilder::<2>::new1(res, bias_key(b.vehicle)).noise(noise2(&b.cov)?);
        graph.add_factor(f.build());
    }
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
        let k0 = o.vehicle * problem.epochs + o.epoch;
        let f = if checked.bias[o.vehicle].is_some() {
            let res = BiasedOdometry { delta: o.delta };
            FactorBuilder::<3>::new3(res, key(k0), key(k0 + 1), bias_key(o.vehicle))
        } else {
            let res = BetweenResidual::new(VectorVar3::new(x, y, z));
            FactorBuilder::<3>::new2(res, key(k0), key(k0 + 1))
        };
        graph.add_factor(f.noise(noise3(&o.cov)?).build());
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
        let bias = checked.bias[v].map(|i| problem.biases[i].mean);
        for e in 0..problem.epochs {
            let k = v * problem.epochs + e;
            let p = match (checked.priors[k].first(), track.last()) {
                (Some(&i), _) => problem.priors[i].mean,
                (None, Some(prev)) => {
                    // validate() guarantees odometry into every node without a prior.
                    let d = checked.odometry_into[k]
                        .first()
                        .map_or([0.0; 3], |&i| problem.odometry[i].delta);
                    let d = bias.map_or(d, |b| g(b, d));
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
    checked: &Checked,
    initial: &[Vec<[f64; 3]>],
    options: &SmoothOptions,
) -> Result<Estimate, EstimateError> {
    let graph = build(problem, checked)?;
    let mut values = Values::new();
    for b in &problem.biases {
        values.insert(bias_key(b.vehicle), VectorVar2::new(b.mean[0], b.mean[1]));
    }
    for (v, track) in initial.iter().enumerate() {
        for (e, p) in track.iter().enumerate() {
            values.insert(
                key(v * problem.epochs + e),
                VectorVar3::new(p[0], p[1], p[2]),
            );
        }
    }
    // Last line of defence only: validation makes every system this solves full rank.
    let solved = || solve(problem, graph, values, options);
    match catch_unwind(AssertUnwindSafe(solved)) {
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
    let biased: Vec<usize> = problem.biases.iter().map(|b| b.vehicle).collect();
    let graph = lm.graph();
    let mut linear = linearise(graph, &values, nodes, &biased)?;
    if !matches!(stop, Stop::MaxIterations) {
        for _ in 0..3 {
            let decrement = linear.chol.newton_decrement(&linear.g);
            if decrement.is_nan() || decrement <= f64::EPSILON * f64::EPSILON * cost.max(1.0) {
                break;
            }
            let dx = VectorX::from_vec(linear.chol.solve(&linear.g));
            let mut next = values.clone();
            next.oplus_mut(&LinearValues::from_order_and_vector(linear.order, dx));
            let next_cost = graph.error(&next);
            if next_cost.is_nan() || next_cost > cost + 1e-12 * cost.max(1.0) {
                break;
            }
            values = next;
            cost = next_cost;
            iterations += 1;
            linear = linearise(graph, &values, nodes, &biased)?;
        }
    }
    let Linear {
        chol,
        cols,
        bias_cols,
        g,
        ..
    } = linear;
    let decrement = chol.newton_decrement(&g);
    if decrement.is_nan() || decrement > options.acceptance {
        let why = match stop {
            Stop::Converged => "its cost decrease fell below the tolerance",
            Stop::Stalled => "it found no step that lowers the cost",
            Stop::MaxIterations => "it reached the iteration limit",
        };
        return Err(EstimateError::NotConverged {
            iterations,
            reason: why,
            cost,
            decrement,
        });
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
    let mut bias = vec![None; problem.vehicles];
    for (&v, &c) in biased.iter().zip(&bias_cols) {
        let b: &VectorVar2 = values.get(bias_key(v)).ok_or_else(|| lost_bias(v))?;
        let block = chol.block(&z, c).ok_or_else(|| {
            EstimateError::Solver(format!("bias {v}'s block is not in the factor's pattern"))
        })?;
        bias[v] = Some(([b.0[0], b.0[1]], block));
    }
    Ok(Estimate {
        position,
        covariance,
        iterations,
        cost,
        bias,
    })
}

fn lost(k: usize) -> EstimateError {
    EstimateError::Solver(format!("node {k} is missing from the solver's values"))
}

fn lost_bias(v: usize) -> EstimateError {
    EstimateError::Solver(format!(
        "vehicle {v}'s bias is missing from the solver's values"
    ))
}

/// The problem linearised at some values: the factorised information matrix JᵀJ, the values'
/// order, each node's and each bias's (in `biased` order) first column in it, and the gradient
/// Jᵀb (b = −r, whitened).
struct Linear {
    chol: Cholesky,
    order: ValuesOrder,
    cols: Vec<usize>,
    bias_cols: Vec<usize>,
    g: Vec<f64>,
}

fn linearise(
    graph: &Graph,
    values: &Values,
    nodes: usize,
    biased: &[usize],
) -> Result<Linear, EstimateError> {
    let order = ValuesOrder::from_values(values);
    let mut cols = Vec::with_capacity(nodes);
    for k in 0..nodes {
        cols.push(order.get(key(k)).ok_or_else(|| lost(k))?.idx);
    }
    let mut bias_cols = Vec::with_capacity(biased.len());
    for &v in biased {
        bias_cols.push(order.get(bias_key(v)).ok_or_else(|| lost_bias(v))?.idx);
    }
    let linear = graph.linearize(values);
    let graph_order = linear.sparsity_pattern(order.clone());
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
    Ok(Linear {
        chol,
        order,
        cols,
        bias_cols,
        g,
    })
}
