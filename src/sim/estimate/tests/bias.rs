//! Dead-reckoning biases as unknowns: recovery, consistency (NEES), timing; the missions the
//! other bias tests (`bias_checks.rs`) use.

use nalgebra::{Matrix2, Vector2, Vector3};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;

use super::*;

/// How the estimators are told about the biases.
#[derive(Clone, Copy, PartialEq, Debug)]
pub(super) enum Model {
    /// A [`Bias`] per AUV, the odometry with its white covariance.
    Bias,
    /// No [`Bias`]; each increment's covariance inflated by the biases' prior as if they were
    /// drawn anew each cycle (the simulator's `increment_cov` rule: (σ_s·l)² along the track,
    /// (σ_β·l)² across it, (σ_s·Δz)² vertically).
    Inflated,
    /// No [`Bias`]; the white covariance alone.
    White,
}

/// A mission: AUVs 0..auvs−1 dead reckoning `step` m per epoch along +x (80 m apart across
/// track, `weave` m of sinusoidal weaving), each with a prior at epoch 0 and depths every epoch;
/// the USV (index `auvs`) with GPS every epoch circling the formation's middle 150 m out; a
/// range AUV ↔ USV every `range_every` epochs.
#[derive(Clone, Copy)]
pub(super) struct Mission {
    pub auvs: usize,
    pub epochs: usize,
    pub step: f64,
    pub weave: f64,
    pub range_every: usize,
    /// The prior standard deviations of β (rad) and s; the prior means are 0.
    pub prior_sigma: [f64; 2],
    /// The true biases of every AUV; `None`: each drawn from the prior.
    pub truth: Option<[f64; 2]>,
    pub model: Model,
}

const WHITE: Cov3 = [[0.04, 0.01, 0.0], [0.01, 0.05, 0.002], [0.0, 0.002, 0.01]];

/// (1 + s)·R_z(β)·d: what an AUV with biases b measures for a true increment d.
fn measured(b: [f64; 2], d: [f64; 3]) -> [f64; 3] {
    let (sn, cs) = b[0].sin_cos();
    let k = 1.0 + b[1];
    [
        k * (cs * d[0] - sn * d[1]),
        k * (sn * d[0] + cs * d[1]),
        k * d[2],
    ]
}

fn inflated(d: [f64; 3], sigma: [f64; 2]) -> Cov3 {
    let l = d[0].hypot(d[1]);
    let t = [d[0] / l, d[1] / l];
    let n = [-t[1], t[0]];
    let (along, across) = ((sigma[1] * l).powi(2), (sigma[0] * l).powi(2));
    let mut c = WHITE;
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] += along * t[i] * t[j] + across * n[i] * n[j];
        }
    }
    c[2][2] += (sigma[1] * d[2]).powi(2);
    c
}

/// Positions `[vehicle][epoch]`.
pub(super) type Tracks = Vec<Vec<[f64; 3]>>;

/// The problem, the true positions and the true biases `[auv]`.
pub(super) fn mission(m: &Mission, seed: u64) -> (Problem, Tracks, Vec<[f64; 2]>) {
    let mut r = rng(seed);
    let usv = m.auvs;
    let sd = |r: &mut ChaCha8Rng, s: f64| s * r.sample::<f64, _>(StandardNormal);
    let biases: Vec<[f64; 2]> = (0..m.auvs)
        .map(|_| {
            m.truth.unwrap_or_else(|| {
                let b = sd(&mut r, m.prior_sigma[0]);
                [b, sd(&mut r, m.prior_sigma[1])]
            })
        })
        .collect();
    let truth: Vec<Vec<[f64; 3]>> = (0..=m.auvs)
        .map(|v| {
            (0..m.epochs)
                .map(|e| {
                    let t = e as f64;
                    if v == usv {
                        let middle = 80.0 * (m.auvs as f64 - 1.0) / 2.0;
                        let x = m.step * t + 150.0 * (t / 8.0).cos();
                        [x, middle + 150.0 * (t / 8.0).sin(), 0.0]
                    } else {
                        let y = 80.0 * v as f64 + m.weave * (t / 15.0 + v as f64).sin();
                        [m.step * t, y, -30.0 - 4.0 * v as f64 - 0.02 * t]
                    }
                })
                .collect()
        })
        .collect();
    let mut p = Problem {
        vehicles: m.auvs + 1,
        epochs: m.epochs,
        ..Default::default()
    };
    if m.model == Model::Bias {
        let [sb, ss] = m.prior_sigma;
        p.biases = (0..m.auvs)
            .map(|vehicle| Bias {
                vehicle,
                mean: [0.0; 2],
                cov: [[sb * sb, 0.0], [0.0, ss * ss]],
            })
            .collect();
    }
    let (gps, start) = (diag(2.0, 2.0, 0.1), diag(1.0, 1.0, 0.2));
    for e in 0..m.epochs {
        p.priors.push(Prior {
            node: node(usv, e),
            mean: add(truth[usv][e], sample(&mut r, &gps)),
            cov: gps,
        });
        for v in 0..usv {
            if e == 0 {
                p.priors.push(Prior {
                    node: node(v, 0),
                    mean: add(truth[v][0], sample(&mut r, &start)),
                    cov: start,
                });
            } else {
                let d = sub(truth[v][e], truth[v][e - 1]);
                let delta = add(measured(biases[v], d), sample(&mut r, &WHITE));
                let cov = match m.model {
                    Model::Inflated => inflated(delta, m.prior_sigma),
                    Model::Bias | Model::White => WHITE,
                };
                p.odometry.push(Odometry {
                    vehicle: v,
                    epoch: e - 1,
                    delta,
                    cov,
                });
            }
            let z = truth[v][e][2] + sd(&mut r, 0.1);
            p.depths.push(Depth {
                node: node(v, e),
                z,
                sigma: 0.1,
            });
            if e % m.range_every == 0 {
                let d = sub(truth[v][e], truth[usv][e]);
                let range = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() + sd(&mut r, 1.0);
                p.ranges.push(Range {
                    a: node(v, e),
                    b: node(usv, e),
                    range,
                    sigma: 1.0,
                });
            }
        }
    }
    (p, truth, biases)
}

fn nees3(est: &Estimate, truth: &[Vec<[f64; 3]>], v: usize, e: usize) -> f64 {
    let err = Vector3::from(sub(est.position[v][e], truth[v][e]));
    let cov = m3(&est.covariance[v][e]);
    (err.transpose() * cov.try_inverse().unwrap() * err)[0]
}

fn nees2(est: &Estimate, truth: [f64; 2], v: usize) -> f64 {
    let (b, c) = est.bias[v].unwrap();
    let err = Vector2::new(b[0] - truth[0], b[1] - truth[1]);
    let cov = Matrix2::from_fn(|i, j| c[i][j]);
    (err.transpose() * cov.try_inverse().unwrap() * err)[0]
}

fn rmse(track: &[[f64; 3]], truth: &[[f64; 3]]) -> f64 {
    let s: f64 = track
        .iter()
        .zip(truth)
        .map(|(a, b)| sub(*a, *b).iter().map(|x| x * x).sum::<f64>())
        .sum();
    (s / track.len() as f64).sqrt()
}

/// The biases' prior standard deviations: 1° and 0.002.
pub(super) const PRIOR: [f64; 2] = [0.017_453_292_519_943_295, 0.002];

/// One AUV 200 epochs × 15 m on a straight line with β = 2° (2σ of its prior) and s = 0.003,
/// ranges to the USV every 4 epochs: both biases recovered within 3σ, σ below the prior's, and
/// the track better than with the biases folded into each increment's covariance (the
/// simulator's rule) or ignored (white covariance only).
#[test]
fn smoother_recovers_the_biases_on_a_straight_line() {
    let truth_b = [2f64.to_radians(), 0.003];
    let mut m = Mission {
        auvs: 1,
        epochs: 200,
        step: 15.0,
        weave: 0.0,
        range_every: 4,
        prior_sigma: PRIOR,
        truth: Some(truth_b),
        model: Model::Bias,
    };
    let (p, truth, _) = mission(&m, 21);
    let s = smooth(&p, &[]).unwrap();
    let f = filter(&p).unwrap();
    let (b, c) = s.bias[0].unwrap();
    let sigma = [c[0][0].sqrt(), c[1][1].sqrt()];
    let (bf, cf) = f.bias[0].unwrap();
    println!(
        "smoother: β = {:.4}° ± {:.4}° (truth 2°), s = {:.5} ± {:.5} (truth 0.003); \
         filter: β = {:.4}° ± {:.4}°, s = {:.5} ± {:.5}",
        b[0].to_degrees(),
        sigma[0].to_degrees(),
        b[1],
        sigma[1],
        bf[0].to_degrees(),
        cf[0][0].sqrt().to_degrees(),
        bf[1],
        cf[1][1].sqrt()
    );
    for i in 0..2 {
        assert!(
            (b[i] - truth_b[i]).abs() < 3.0 * sigma[i],
            "bias component {i}: {} ± {} vs truth {}",
            b[i],
            sigma[i],
            truth_b[i]
        );
        assert!(sigma[i] < PRIOR[i], "σ {} not below the prior's", sigma[i]);
    }
    assert!(s.bias[1].is_none() && f.bias[1].is_none());
    let with = rmse(&s.position[0], &truth[0]);
    let mut without = Vec::new();
    for model in [Model::Inflated, Model::White] {
        m.model = model;
        let (q, _, _) = mission(&m, 21);
        assert!(q.biases.is_empty());
        let est = smooth(&q, &[]).unwrap();
        without.push(rmse(&est.position[0], &truth[0]));
    }
    println!(
        "smoothed RMSE: with bias states {with:.3} m, without (inflated covariance) {:.3} m, \
         without (white covariance) {:.3} m",
        without[0], without[1]
    );
    assert!(
        with < without[0] && with < without[1],
        "{with} m vs {without:?} m"
    );
}

/// 20 seeds (1000–1019), β and s drawn from their prior, one weaving AUV over 100 epochs:
/// Σ NEES of the last AUV node ~ χ²(60) (mean in [2.024, 4.165] with probability 95 %), of the
/// smoother's b ~ χ²(40) (mean in [1.222, 2.967]), for both estimators.
#[test]
fn biased_estimators_are_consistent() {
    let (lo3, hi3) = (40.482 / 20.0, 83.298 / 20.0);
    let (lo2, hi2) = (24.433 / 20.0, 59.342 / 20.0);
    let m = Mission {
        auvs: 1,
        epochs: 100,
        step: 15.0,
        weave: 20.0,
        range_every: 3,
        prior_sigma: PRIOR,
        truth: None,
        model: Model::Bias,
    };
    let (mut ns, mut nf, mut nbs, mut nbf) = (0.0, 0.0, 0.0, 0.0);
    for seed in 1000..1020 {
        let (p, truth, b) = mission(&m, seed);
        let s = smooth(&p, &[]).unwrap();
        let f = filter(&p).unwrap();
        ns += nees3(&s, &truth, 0, 99) / 20.0;
        nf += nees3(&f, &truth, 0, 99) / 20.0;
        nbs += nees2(&s, b[0], 0) / 20.0;
        nbf += nees2(&f, b[0], 0) / 20.0;
    }
    println!(
        "average NEES: last AUV node smoother {ns:.3}, filter {nf:.3}; \
         b smoother {nbs:.3}, filter {nbf:.3}"
    );
    for (what, v, lo, hi) in [
        ("smoother's node", ns, lo3, hi3),
        ("filter's node", nf, lo3, hi3),
        ("smoother's bias", nbs, lo2, hi2),
        ("filter's bias", nbf, lo2, hi2),
    ] {
        assert!(
            (lo..=hi).contains(&v),
            "{what}: NEES {v} not in [{lo}, {hi}]"
        );
    }
}

/// Timing (never asserted): `cargo test --release --lib sim::estimate -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing_with_biases() {
    for auvs in [5, 20] {
        let mut m = Mission {
            auvs,
            epochs: 200,
            step: 10.0,
            weave: 20.0,
            range_every: 1,
            prior_sigma: PRIOR,
            truth: None,
            model: Model::Bias,
        };
        for model in [Model::Bias, Model::Inflated] {
            m.model = model;
            let (p, _, _) = mission(&m, 11);
            let t = std::time::Instant::now();
            let s = smooth(&p, &[]).unwrap();
            let ts = t.elapsed();
            let t = std::time::Instant::now();
            filter(&p).unwrap();
            let tf = t.elapsed();
            println!(
                "{} vehicles × 200 epochs, {model:?}: smoother {ts:?} ({} iterations, cost \
                 {:.1}), filter {tf:?}",
                auvs + 1,
                s.iterations,
                s.cost
            );
        }
    }
}
