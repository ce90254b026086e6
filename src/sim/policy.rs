//! Navigation policies: which of a flight's measurements each estimator may use. All of them
//! see the same dead reckoning, depths and GPS fixes; they differ in the acoustic ranges.

use super::estimate::{Bias, BiasEstimate, Cov3, Depth, Node, Odometry, Prior, Problem, Range};
use super::measure::{Measurements, Ping};
use crate::scenario::Navigation;
use serde::{Deserialize, Serialize};

/// Which acoustic ranges an estimator uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Policy {
    /// None: dead reckoning and depth alone.
    DeadReckoning,
    /// Only ranges to the USV (an AUV corrects itself only when it is linked to the USV).
    A2u,
    /// The planned consensus chain: each step's A2U link and A2A path (Step 2's graph).
    Chain,
    /// Every range received, planned or not.
    AllLinks,
}

impl Policy {
    /// Every policy, in the order reports list them.
    pub const EVERY: [Policy; 4] = [
        Policy::DeadReckoning,
        Policy::A2u,
        Policy::Chain,
        Policy::AllLinks,
    ];

    /// The name used in sim.json and the reports.
    pub fn name(self) -> &'static str {
        match self {
            Policy::DeadReckoning => "dead_reckoning",
            Policy::A2u => "a2u",
            Policy::Chain => "chain",
            Policy::AllLinks => "all_links",
        }
    }

    /// Whether this policy uses `ping` (received), given the links `planned` at its epoch as
    /// pairs (a, b) with a < b, the USV being index `usv`.
    pub fn uses(self, ping: &Ping, planned: &[(usize, usize)], usv: usize) -> bool {
        ping.received
            && match self {
                Policy::DeadReckoning => false,
                Policy::A2u => ping.b == usv,
                Policy::Chain => planned.contains(&(ping.a, ping.b)),
                Policy::AllLinks => true,
            }
    }
}

fn diag(s: [f64; 3]) -> Cov3 {
    [
        [s[0] * s[0], 0.0, 0.0],
        [0.0, s[1] * s[1], 0.0],
        [0.0, 0.0, s[2] * s[2]],
    ]
}

/// Standard deviation of the USV's z (it is on the surface), m.
const USV_Z_SIGMA: f64 = 0.01;

/// What the estimators know of each vehicle where a stretch of epochs starts: its position
/// and, when the biases are estimated, each AUV's biases [β, s], each as a mean and a
/// covariance.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    /// `[auv]`: position mean and covariance.
    pub positions: Vec<([f64; 3], Cov3)>,
    /// `[auv]`: bias mean and covariance (None: the biases are not estimated).
    pub biases: Vec<Option<BiasEstimate>>,
}

/// The estimation problem of `policy` over epochs `first..=last` of `m` (renumbered from 0):
/// the AUVs' start priors `start` (at `first`), the USV's GPS fixes, every AUV's dead
/// reckoning and depth, and the ranges the policy uses (`planned(e)`: the planned links at
/// epoch e, pairs a < b). With bias priors in `start`, each AUV's biases are unknowns and its
/// increments carry their white noise alone.
pub fn problem(
    m: &Measurements,
    nav: &Navigation,
    policy: Policy,
    planned: &dyn Fn(usize) -> Vec<(usize, usize)>,
    first: usize,
    last: usize,
    start: &Start,
) -> Problem {
    let n = m.errors.len();
    let usv = n;
    let mut p = Problem {
        vehicles: n + 1,
        epochs: last - first + 1,
        ..Problem::default()
    };
    for (v, (mean, cov)) in start.positions.iter().enumerate() {
        p.priors.push(Prior {
            node: Node {
                vehicle: v,
                epoch: 0,
            },
            mean: *mean,
            cov: *cov,
        });
    }
    for (v, b) in start.biases.iter().enumerate() {
        if let Some((mean, cov)) = b {
            p.biases.push(Bias {
                vehicle: v,
                mean: *mean,
                cov: *cov,
            });
        }
    }
    for e in first..=last {
        let g = m.gps[e];
        p.priors.push(Prior {
            node: Node {
                vehicle: usv,
                epoch: e - first,
            },
            mean: [g[0], g[1], 0.0],
            cov: diag([nav.gps_noise, nav.gps_noise, USV_Z_SIGMA]),
        });
        for v in 0..n {
            p.depths.push(Depth {
                node: Node {
                    vehicle: v,
                    epoch: e - first,
                },
                z: m.depth[v][e],
                sigma: nav.depth_noise.max(1e-3),
            });
            if e < last {
                let inc = &m.odometry[v][e];
                p.odometry.push(Odometry {
                    vehicle: v,
                    epoch: e - first,
                    delta: inc.delta,
                    cov: if start.biases[v].is_some() {
                        inc.white
                    } else {
                        inc.cov
                    },
                });
            }
        }
    }
    if policy != Policy::DeadReckoning {
        let per_epoch = (n + 1) * n / 2;
        for e in first..=last {
            let links = planned(e);
            for ping in &m.pings[e * per_epoch..(e + 1) * per_epoch] {
                if policy.uses(ping, &links, usv) {
                    p.ranges.push(Range {
                        a: Node {
                            vehicle: ping.a,
                            epoch: e - first,
                        },
                        b: Node {
                            vehicle: ping.b,
                            epoch: e - first,
                        },
                        range: ping.range,
                        sigma: nav.range_noise,
                    });
                }
            }
        }
    }
    p
}

/// What the estimators know at the mission's start: each AUV's fix before the dive and, when
/// `navigation.estimate_biases`, the biases' prior (zero mean, the sensors' 1σ).
pub fn initial_start(m: &Measurements, nav: &Navigation) -> Start {
    let s = nav.initial_noise;
    // a prior standard deviation the estimators accept even for ideal sensors
    let beta = nav.heading_bias.max(1e-6);
    let scale = nav.dvl_scale.max(1e-6);
    Start {
        positions: m.initial.iter().map(|p| (*p, diag([s, s, s]))).collect(),
        biases: m
            .initial
            .iter()
            .map(|_| {
                nav.estimate_biases
                    .then_some(([0.0, 0.0], [[beta * beta, 0.0], [0.0, scale * scale]]))
            })
            .collect(),
    }
}
