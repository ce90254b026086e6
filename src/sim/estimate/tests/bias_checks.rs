//! Dead-reckoning biases: the linearisations against finite differences, the marginals against a
//! dense inverse, validation.

use std::ops::AddAssign;

use factrs::{
    containers::{Key, Values},
    residuals::Residual3,
    variables::{VectorVar2, VectorVar3},
};
use nalgebra::{DMatrix, DVector, Matrix2};
use rand::Rng;

use super::super::bias::{g, prediction, BiasedOdometry};
use super::super::graph::{B, X};
use super::bias::{mission, Mission, Model, PRIOR};
use super::ranges::information;
use super::*;

/// Central differences of `f` at `x` with steps `h`, as columns.
fn central(f: &dyn Fn(&[f64]) -> Vec<f64>, x: &[f64], h: f64) -> Vec<Vec<f64>> {
    (0..x.len())
        .map(|j| {
            let (mut a, mut b) = (x.to_vec(), x.to_vec());
            a[j] += h;
            b[j] -= h;
            let (fa, fb) = (f(&a), f(&b));
            fa.iter()
                .zip(&fb)
                .map(|(p, q)| (p - q) / (2.0 * h))
                .collect()
        })
        .collect()
}

fn assert_close(what: &str, analytic: impl Fn(usize, usize) -> f64, numeric: &[Vec<f64>]) {
    for (j, col) in numeric.iter().enumerate() {
        for (i, &n) in col.iter().enumerate() {
            let a = analytic(i, j);
            let err = (a - n).abs() / a.abs().max(n.abs()).max(1.0);
            assert!(err < 1e-6, "{what}[{i}][{j}]: {a} vs finite difference {n}");
        }
    }
}

/// The smoother's biased odometry residual differentiated by factrs's forward-mode autodiff, and
/// the filter's ∂g/∂b and ∂g/∂delta, against central differences (relative 1e-6), at a few
/// points far from zero bias; and the residual vanishes on p1 = p0 + g(b, delta).
#[test]
fn bias_linearisations_match_finite_differences() {
    let mut r = rng(31);
    for _ in 0..5 {
        let mut u = |s: f64| r.gen_range(-s..s);
        let p0 = [u(100.0), u(100.0), -u(50.0).abs()];
        let delta = [u(20.0), u(20.0), u(2.0)];
        let b = [u(0.45), u(0.09)];
        let p1 = add(p0, add(g(b, delta), [u(1.0), u(1.0), u(0.3)]));
        let res = BiasedOdometry { delta };
        let eval = |x: &[f64]| -> Vec<f64> {
            let v = res.residual3(
                VectorVar3::new(x[0], x[1], x[2]),
                VectorVar3::new(x[3], x[4], x[5]),
                VectorVar2::new(x[6], x[7]),
            );
            v.iter().copied().collect()
        };
        let x: Vec<f64> = p0.iter().chain(&p1).chain(&b).copied().collect();
        let mut values = Values::new();
        values.insert(X(0), VectorVar3::new(p0[0], p0[1], p0[2]));
        values.insert(X(1), VectorVar3::new(p1[0], p1[1], p1[2]));
        values.insert(B(0), VectorVar2::new(b[0], b[1]));
        let keys: [Key; 3] = [X(0).into(), X(1).into(), B(0).into()];
        let jac = res.residual3_jacobian(&values, &keys);
        assert_eq!((jac.diff.nrows(), jac.diff.ncols()), (3, 8));
        let value: Vec<f64> = jac.value.iter().copied().collect();
        assert_eq!(value, eval(&x));
        assert_close(
            "residual",
            |i, j| jac.diff[(i, j)],
            &central(&eval, &x, 1e-5),
        );
        let on = add(p0, g(b, delta));
        let zero = eval(&[p0[0], p0[1], p0[2], on[0], on[1], on[2], b[0], b[1]]);
        assert!(zero.iter().all(|z| z.abs() < 1e-12), "{zero:?}");

        let (jb, jd) = prediction(b, delta);
        let gb = |x: &[f64]| g([x[0], x[1]], delta).to_vec();
        assert_close("∂g/∂b", |i, j| jb[(i, j)], &central(&gb, &b, 1e-6));
        let gd = |x: &[f64]| g(b, [x[0], x[1], x[2]]).to_vec();
        assert_close("∂g/∂delta", |i, j| jd[(i, j)], &central(&gd, &delta, 1e-4));
    }
}

/// Each broken bias gives a `BadMeasurement` naming it, from both estimators.
#[test]
fn validation_names_the_bias() {
    let (mut p, _, _) = mission(
        &Mission {
            auvs: 2,
            epochs: 4,
            step: 15.0,
            weave: 0.0,
            range_every: 1,
            prior_sigma: PRIOR,
            truth: Some([0.0; 2]),
            model: Model::Bias,
        },
        41,
    );
    // Also a bias on the USV: allowed (its odometry-free track leaves b at its prior).
    p.biases.push(Bias {
        vehicle: 2,
        mean: [0.1, 0.01],
        cov: [[1e-4, 1e-6], [1e-6, 1e-6]],
    });
    let s = smooth(&p, &[]).unwrap();
    assert!(filter(&p).is_ok());
    let (b, c) = s.bias[2].unwrap();
    assert!((b[0] - 0.1).abs() < 1e-9 && (c[0][1] - 1e-6).abs() < 1e-12);
    type Edit = fn(&mut Problem);
    let cases: Vec<(Edit, &str)> = vec![
        (|p| p.biases[1].vehicle = 3, "bias #1 (vehicle 3)"),
        (|p| p.biases[2].vehicle = 0, "bias #2 (vehicle 0)"),
        (|p| p.biases[0].mean[0] = f64::NAN, "bias #0 (vehicle 0)"),
        (|p| p.biases[0].mean[0] = 0.5, "bias #0 (vehicle 0)"),
        (|p| p.biases[1].mean[0] = -0.6, "bias #1 (vehicle 1)"),
        (|p| p.biases[1].mean[1] = 0.1, "bias #1 (vehicle 1)"),
        (
            |p| p.biases[0].mean[1] = f64::INFINITY,
            "bias #0 (vehicle 0)",
        ),
        (|p| p.biases[0].cov[0][1] = 1e-6, "bias #0 (vehicle 0)"),
        (
            |p| p.biases[0].cov = [[1e-4, 1e-3], [1e-3, 1e-4]],
            "bias #0",
        ),
        (
            |p| p.biases[0].cov = [[1e-4, 1e-5], [1e-5, 1e-6]],
            "bias #0",
        ),
        (|p| p.biases[0].cov[1][1] = 0.0, "bias #0 (vehicle 0)"),
        (|p| p.biases[0].cov[0][0] = -1e-4, "bias #0 (vehicle 0)"),
        (|p| p.biases[2].cov[1][1] = f64::NAN, "bias #2 (vehicle 2)"),
        (|p| p.biases[2].cov[0][0] = 4.0, "bias #2 (vehicle 2)"),
    ];
    for (edit, name) in cases {
        let mut q = p.clone();
        edit(&mut q);
        for result in [
            smooth(&q, &[]),
            filter(&q),
            dead_reckoning(&q).map(|_| s.clone()),
        ] {
            match result {
                Err(EstimateError::BadMeasurement { what, why }) => {
                    assert!(what.starts_with(name), "{name}: got {what}: {why}");
                    assert!(!why.is_empty());
                }
                other => panic!("{name}: expected BadMeasurement, got {other:?}"),
            }
        }
    }
    // No epochs: each bias's estimate is its prior.
    let mut empty = p.clone();
    empty.epochs = 0;
    empty.priors.clear();
    empty.odometry.clear();
    empty.depths.clear();
    empty.ranges.clear();
    for est in [smooth(&empty, &[]).unwrap(), filter(&empty).unwrap()] {
        assert_eq!(est.bias[2], Some((p.biases[2].mean, p.biases[2].cov)));
        assert_eq!(est.bias.len(), 3);
    }
}

/// The smoother's estimate with biases is a stationary point of the cost (the Gauss–Newton step
/// from it is below 1e-6 of each coordinate's standard deviation) and its covariance blocks, of
/// the nodes and of the biases, are those of the dense inverse of the information matrix there
/// (1e-9 relative to the block's largest entry). The dense matrix takes the unbiased factors
/// from `ranges::information` and adds the biased odometry (factrs's Jacobian, checked above
/// against finite differences) and the biases' priors.
#[test]
fn smoother_bias_marginals_equal_dense_inverse() {
    let m = Mission {
        auvs: 3,
        epochs: 30,
        step: 15.0,
        weave: 20.0,
        range_every: 2,
        prior_sigma: PRIOR,
        truth: None,
        model: Model::Bias,
    };
    let (mut p, _, _) = mission(&m, 51);
    // A vehicle without a bias keeps its plain odometry.
    p.biases.remove(1);
    let est = smooth(&p, &[]).unwrap();
    let plain = Problem {
        odometry: p
            .odometry
            .iter()
            .filter(|o| est.bias[o.vehicle].is_none())
            .cloned()
            .collect(),
        biases: Vec::new(),
        ..p.clone()
    };
    let (info0, grad0) = information(&plain, &est.position);
    let nodes = 3 * p.vehicles * p.epochs;
    let n = nodes + 2 * p.biases.len();
    let (mut info, mut grad) = (DMatrix::zeros(n, n), DVector::zeros(n));
    info.view_mut((0, 0), (nodes, nodes)).copy_from(&info0);
    grad.rows_mut(0, nodes).copy_from(&grad0);
    let bias_col = |v: usize| nodes + 2 * p.biases.iter().position(|b| b.vehicle == v).unwrap();
    let mut add_factor =
        |cols: &[(usize, usize)], j: &DMatrix<f64>, r: &DVector<f64>, w: &DMatrix<f64>| {
            let (jtw, mut at) = (j.transpose() * w, 0);
            for &(c, len) in cols {
                let rows = jtw.rows(at, len);
                grad.rows_mut(c, len).add_assign(&(rows * r));
                let mut bt = 0;
                for &(d, dlen) in cols {
                    let mut blk = info.view_mut((c, d), (len, dlen));
                    blk += rows * j.columns(bt, dlen);
                    bt += dlen;
                }
                at += len;
            }
        };
    for b in &p.biases {
        let (mean, c) = est.bias[b.vehicle].unwrap();
        let r = DVector::from_vec(vec![mean[0] - b.mean[0], mean[1] - b.mean[1]]);
        let w = DMatrix::from_fn(2, 2, |i, j| b.cov[i][j])
            .try_inverse()
            .unwrap();
        add_factor(
            &[(bias_col(b.vehicle), 2)],
            &DMatrix::identity(2, 2),
            &r,
            &w,
        );
        assert!(c[0][0] < b.cov[0][0] && c[1][1] < b.cov[1][1]);
    }
    for o in p.odometry.iter().filter(|o| est.bias[o.vehicle].is_some()) {
        let (p0, p1) = (
            est.position[o.vehicle][o.epoch],
            est.position[o.vehicle][o.epoch + 1],
        );
        let b = est.bias[o.vehicle].unwrap().0;
        let mut values = Values::new();
        values.insert(X(0), VectorVar3::new(p0[0], p0[1], p0[2]));
        values.insert(X(1), VectorVar3::new(p1[0], p1[1], p1[2]));
        values.insert(B(0), VectorVar2::new(b[0], b[1]));
        let keys: [Key; 3] = [X(0).into(), X(1).into(), B(0).into()];
        let jac = BiasedOdometry { delta: o.delta }.residual3_jacobian(&values, &keys);
        let j = DMatrix::from_fn(3, 8, |i, k| jac.diff[(i, k)]);
        let r = DVector::from_iterator(3, jac.value.iter().copied());
        let w = DMatrix::from_fn(3, 3, |i, k| m3(&o.cov).try_inverse().unwrap()[(i, k)]);
        let c0 = 3 * (o.vehicle * p.epochs + o.epoch);
        add_factor(
            &[(c0, 3), (c0 + 3, 3), (bias_col(o.vehicle), 2)],
            &j,
            &r,
            &w,
        );
    }
    let cov = info.try_inverse().unwrap();
    let step = &cov * grad;
    let worst_step = (0..n)
        .map(|i| step[i].abs() / cov[(i, i)].sqrt())
        .fold(0.0, f64::max);
    assert!(worst_step < 1e-6, "Gauss–Newton step {worst_step:e} σ");
    let mut worst = 0.0f64;
    let mut compare = |c: usize, block: &[&[f64]]| {
        let dense = cov.view((c, c), (block.len(), block.len()));
        let scale = dense.amax();
        for (i, row) in block.iter().enumerate() {
            for (j, &x) in row.iter().enumerate() {
                worst = worst.max((x - dense[(i, j)]).abs() / scale);
            }
        }
    };
    for v in 0..p.vehicles {
        for e in 0..p.epochs {
            let c = &est.covariance[v][e];
            compare(3 * (v * p.epochs + e), &[&c[0], &c[1], &c[2]]);
        }
        if let Some((_, c)) = est.bias[v] {
            compare(bias_col(v), &[&c[0], &c[1]]);
        }
    }
    assert!(worst < 1e-9, "relative covariance error {worst:e}");
    // The filter's final bias covariance: the same information (every measurement up to the
    // last epoch), linearised along the way instead of at the end.
    let f = filter(&p).unwrap();
    for v in [0, 2] {
        let (cs, cf) = (est.bias[v].unwrap().1, f.bias[v].unwrap().1);
        let (ms, mf) = (
            Matrix2::from_fn(|i, j| cs[i][j]),
            Matrix2::from_fn(|i, j| cf[i][j]),
        );
        let rel = (ms - mf).abs().max() / ms.abs().max();
        assert!(rel < 0.02, "vehicle {v}: filter {cf:?} vs smoother {cs:?}");
    }
}
