//! Tests of the estimators: exactness against closed-form least squares in the linear case,
//! filter ≡ smoother where theory says so, consistency (NEES) with ranges, validation, edges.

use nalgebra::{DMatrix, DVector, Matrix3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::*;

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// A random full (correlated) covariance with standard deviations around `sigma`.
fn random_cov(rng: &mut ChaCha8Rng, sigma: f64) -> Cov3 {
    let a = Matrix3::from_fn(|_, _| rng.gen_range(-1.0..1.0));
    let c = (a * a.transpose() + Matrix3::identity() * 0.3) * (sigma * sigma);
    let c = (c + c.transpose()) * 0.5;
    [
        [c[(0, 0)], c[(0, 1)], c[(0, 2)]],
        [c[(1, 0)], c[(1, 1)], c[(1, 2)]],
        [c[(2, 0)], c[(2, 1)], c[(2, 2)]],
    ]
}

fn diag(sx: f64, sy: f64, sz: f64) -> Cov3 {
    [
        [sx * sx, 0.0, 0.0],
        [0.0, sy * sy, 0.0],
        [0.0, 0.0, sz * sz],
    ]
}

fn m3(c: &Cov3) -> Matrix3<f64> {
    Matrix3::from_fn(|i, j| c[i][j])
}

/// A draw from N(0, cov).
fn sample(rng: &mut ChaCha8Rng, cov: &Cov3) -> [f64; 3] {
    let l = m3(cov).cholesky().expect("test covariance").l();
    let n = Vector3::from_fn(|_, _| rng.sample::<f64, _>(StandardNormal));
    let s = l * n;
    [s[0], s[1], s[2]]
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn node(vehicle: usize, epoch: usize) -> Node {
    Node { vehicle, epoch }
}

/// x̂ = (AᵀWA)⁻¹AᵀWb and (AᵀWA)⁻¹ for a problem without ranges, A, W, b built densely.
fn weighted_least_squares(p: &Problem) -> (DVector<f64>, DMatrix<f64>) {
    let n = 3 * p.vehicles * p.epochs;
    let rows = 3 * p.priors.len() + 3 * p.odometry.len() + p.depths.len();
    let (mut a, mut w, mut b) = (
        DMatrix::zeros(rows, n),
        DMatrix::zeros(rows, rows),
        DVector::zeros(rows),
    );
    let col = |nd: Node| 3 * (nd.vehicle * p.epochs + nd.epoch);
    let mut r = 0;
    for pr in &p.priors {
        let c = col(pr.node);
        let inv = m3(&pr.cov).try_inverse().unwrap();
        for i in 0..3 {
            a[(r + i, c + i)] = 1.0;
            b[r + i] = pr.mean[i];
            for j in 0..3 {
                w[(r + i, r + j)] = inv[(i, j)];
            }
        }
        r += 3;
    }
    for o in &p.odometry {
        let c = col(node(o.vehicle, o.epoch));
        let inv = m3(&o.cov).try_inverse().unwrap();
        for i in 0..3 {
            a[(r + i, c + i)] = -1.0;
            a[(r + i, c + 3 + i)] = 1.0;
            b[r + i] = o.delta[i];
            for j in 0..3 {
                w[(r + i, r + j)] = inv[(i, j)];
            }
        }
        r += 3;
    }
    for d in &p.depths {
        a[(r, col(d.node) + 2)] = 1.0;
        b[r] = d.z;
        w[(r, r)] = 1.0 / (d.sigma * d.sigma);
        r += 1;
    }
    let info = a.transpose() * &w * &a;
    let cov = info.try_inverse().expect("full rank");
    let x = &cov * (a.transpose() * &w * b);
    (x, cov)
}

/// max |estimate − closed form| over positions and covariance blocks.
fn compare(est: &Estimate, p: &Problem, x: &DVector<f64>, cov: &DMatrix<f64>) -> (f64, f64) {
    let (mut dx, mut dc) = (0.0f64, 0.0f64);
    for v in 0..p.vehicles {
        for e in 0..p.epochs {
            let c = 3 * (v * p.epochs + e);
            for i in 0..3 {
                dx = dx.max((est.position[v][e][i] - x[c + i]).abs());
                for j in 0..3 {
                    dc = dc.max((est.covariance[v][e][i][j] - cov[(c + i, c + j)]).abs());
                }
            }
        }
    }
    (dx, dc)
}

/// One vehicle's noisy linear chain: prior at 0, full-covariance odometry, depths, extra priors.
fn chain(
    p: &mut Problem,
    rng: &mut ChaCha8Rng,
    v: usize,
    gaps: &[usize],
    extra: &[usize],
) -> Vec<[f64; 3]> {
    let truth: Vec<[f64; 3]> = (0..p.epochs)
        .map(|e| {
            let t = e as f64;
            [
                5.0 * t + 10.0 * v as f64,
                40.0 * (t / 9.0).sin(),
                -20.0 - 3.0 * v as f64 - 0.05 * t,
            ]
        })
        .collect();
    let odo = random_cov(rng, 0.3);
    for e in 0..p.epochs {
        let fix = e == 0 || gaps.contains(&(e)) || extra.contains(&e);
        if fix {
            let cov = random_cov(rng, 1.5);
            p.priors.push(Prior {
                node: node(v, e),
                mean: add(truth[e], sample(rng, &cov)),
                cov,
            });
        }
        if e > 0 && !gaps.contains(&e) {
            let delta = add(sub(truth[e], truth[e - 1]), sample(rng, &odo));
            p.odometry.push(Odometry {
                vehicle: v,
                epoch: e - 1,
                delta,
                cov: odo,
            });
        }
        let sigma = 0.1 + 0.05 * v as f64;
        let z = truth[e][2] + sigma * rng.sample::<f64, _>(StandardNormal);
        p.depths.push(Depth {
            node: node(v, e),
            z,
            sigma,
        });
    }
    truth
}

#[test]
fn smoother_equals_weighted_least_squares_one_vehicle() {
    let mut r = rng(1);
    let mut p = Problem {
        vehicles: 1,
        epochs: 50,
        ..Default::default()
    };
    chain(&mut p, &mut r, 0, &[], &[17, 33, 41]);
    let est = smooth(&p, &[]).unwrap();
    let (x, cov) = weighted_least_squares(&p);
    let (dx, dc) = compare(&est, &p, &x, &cov);
    assert!(
        dx < 1e-9 && dc < 1e-9,
        "position error {dx:e} m, covariance error {dc:e} m²"
    );
}

fn two_chains(seed: u64) -> Problem {
    let mut r = rng(seed);
    let mut p = Problem {
        vehicles: 2,
        epochs: 40,
        ..Default::default()
    };
    chain(&mut p, &mut r, 0, &[], &[25]);
    // Vehicle 1 loses its dead reckoning at epoch 12 and restarts from a fix there.
    chain(&mut p, &mut r, 1, &[12], &[30, 31]);
    // A second, independent increment for vehicle 0 over 7 → 8.
    let mut second = p
        .odometry
        .iter()
        .find(|o| o.vehicle == 0 && o.epoch == 7)
        .unwrap()
        .clone();
    second.cov = random_cov(&mut r, 0.5);
    second.delta = add(second.delta, sample(&mut r, &second.cov));
    p.odometry.push(second);
    p
}

#[test]
fn smoother_equals_weighted_least_squares_two_vehicles() {
    let p = two_chains(2);
    let est = smooth(&p, &[]).unwrap();
    let (x, cov) = weighted_least_squares(&p);
    let (dx, dc) = compare(&est, &p, &x, &cov);
    assert!(
        dx < 1e-9 && dc < 1e-9,
        "position error {dx:e} m, covariance error {dc:e} m²"
    );
}

fn truncate(p: &Problem, last: usize) -> Problem {
    Problem {
        vehicles: p.vehicles,
        epochs: last + 1,
        priors: p
            .priors
            .iter()
            .filter(|x| x.node.epoch <= last)
            .cloned()
            .collect(),
        odometry: p
            .odometry
            .iter()
            .filter(|o| o.epoch < last)
            .cloned()
            .collect(),
        depths: p
            .depths
            .iter()
            .filter(|d| d.node.epoch <= last)
            .cloned()
            .collect(),
        ranges: p
            .ranges
            .iter()
            .filter(|r| r.a.epoch.max(r.b.epoch) <= last)
            .cloned()
            .collect(),
        biases: p.biases.clone(),
    }
}

#[test]
fn filter_equals_smoother_at_the_last_epoch_linear() {
    let p = two_chains(3);
    let f = filter(&p).unwrap();
    let (mut dx, mut dc) = (0.0f64, 0.0f64);
    for e in 0..p.epochs {
        let s = smooth(&truncate(&p, e), &[]).unwrap();
        for v in 0..p.vehicles {
            for i in 0..3 {
                dx = dx.max((f.position[v][e][i] - s.position[v][e][i]).abs());
                for j in 0..3 {
                    dc = dc.max((f.covariance[v][e][i][j] - s.covariance[v][e][i][j]).abs());
                }
            }
        }
    }
    assert!(
        dx < 1e-9 && dc < 1e-9,
        "position error {dx:e} m, covariance error {dc:e} m²"
    );
}

#[test]
fn edge_sizes() {
    let cov = random_cov(&mut rng(4), 2.0);
    let one = Problem {
        vehicles: 1,
        epochs: 1,
        priors: vec![Prior {
            node: node(0, 0),
            mean: [1.0, 2.0, -3.0],
            cov,
        }],
        ..Default::default()
    };
    for est in [smooth(&one, &[]).unwrap(), filter(&one).unwrap()] {
        assert_eq!(est.position, vec![vec![[1.0, 2.0, -3.0]]]);
        let c = est.covariance[0][0];
        let worst = (0..9)
            .map(|k| (c[k / 3][k % 3] - cov[k / 3][k % 3]).abs())
            .fold(0.0, f64::max);
        assert!(worst < 1e-12, "{worst:e}");
    }
    let mut with_depth = one.clone();
    with_depth.depths.push(Depth {
        node: node(0, 0),
        z: -2.5,
        sigma: 0.3,
    });
    let (x, c) = weighted_least_squares(&with_depth);
    for est in [
        smooth(&with_depth, &[]).unwrap(),
        filter(&with_depth).unwrap(),
    ] {
        let (dx, dc) = compare(&est, &with_depth, &x, &c);
        assert!(dx < 1e-12 && dc < 1e-12, "{dx:e} {dc:e}");
    }
    // No epochs (or no vehicles): an empty estimate, one empty track per vehicle.
    let empty = Problem {
        vehicles: 3,
        epochs: 0,
        ..Default::default()
    };
    for est in [smooth(&empty, &[]).unwrap(), filter(&empty).unwrap()] {
        assert_eq!(est.position, vec![Vec::<[f64; 3]>::new(); 3]);
        assert_eq!(est.covariance.len(), 3);
        assert_eq!(est.iterations, 0);
    }
    let none = Problem {
        vehicles: 0,
        epochs: 5,
        ..Default::default()
    };
    assert!(smooth(&none, &[]).unwrap().position.is_empty());
    let mut stray = empty.clone();
    stray.depths.push(Depth {
        node: node(0, 0),
        z: 0.0,
        sigma: 1.0,
    });
    assert!(matches!(
        smooth(&stray, &[]),
        Err(EstimateError::BadMeasurement { .. })
    ));
}

mod bias;
mod bias_checks;
mod ranges;
mod validation;
