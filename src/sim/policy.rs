//! Navigation policies: which of a flight's measurements each estimator may use. All of them
//! see the same dead reckoning, depths and GPS fixes; they differ in the acoustic ranges.

use super::estimate::{Cov3, Depth, Node, Odometry, Prior, Problem, Range};
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

/// The estimation problem of `policy` over epochs `first..=last` of `m` (renumbered from 0):
/// the AUVs' start priors `start` (one per AUV, at `first`), the USV's GPS fixes, every AUV's
/// dead reckoning and depth, and the ranges the policy uses (`planned(e)`: the planned links at
/// epoch e, pairs a < b).
pub fn problem(
    m: &Measurements,
    nav: &Navigation,
    policy: Policy,
    planned: &dyn Fn(usize) -> Vec<(usize, usize)>,
    first: usize,
    last: usize,
    start: &[(/* mean */ [f64; 3], Cov3)],
) -> Problem {
    let n = m.errors.len();
    let usv = n;
    let mut p = Problem {
        vehicles: n + 1,
        epochs: last - first + 1,
        ..Problem::default()
    };
    for (v, (mean, cov)) in start.iter().enumerate() {
        p.priors.push(Prior {
            node: Node {
                vehicle: v,
                epoch: 0,
            },
            mean: *mean,
            cov: *cov,
        });
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
                    cov: inc.cov,
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

/// The start priors of window 0: each AUV's fix before the dive.
pub fn initial_priors(m: &Measurements, nav: &Navigation) -> Vec<([f64; 3], Cov3)> {
    let s = nav.initial_noise;
    m.initial.iter().map(|p| (*p, diag([s, s, s]))).collect()
}
