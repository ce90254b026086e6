//! Bridges of P5 (Step 3): the acoustic chain where Step 2's path cannot be in range yet.
//!
//! The paper's graph is a path USV–a₁–…–a_N at every step, each link in range (C5_2/C5_3).
//! But the window starts where it starts: Algorithm 1 (line 5) draws the AUVs anywhere within
//! d_s of the USV, so two path neighbours can start up to 2·d_s apart, and a later window starts
//! where the last one ended, every AUV within d_s of the USV (C1_6) but not of its neighbours.
//! Such a link cannot be in range until both ends have closed the distance, and the soft band
//! of `links` only prices it; meanwhile nothing kept the far end in reach of anyone, and the
//! chain broke (issue 13's draw 1016: two AUVs, the far one left out of range of the USV at
//! step 3, the window refused).
//!
//! At every step k < K at which a planned link cannot be in range — its ends start farther
//! apart than d_s plus what both close at [`CLOSING_FRACTION`] of their speed limits in k steps
//! — the path splits into pieces; each piece cut off from the USV gets a bridge: its AUV that
//! starts nearest the USV keeps an A2U link in range and in line of sight at that step. Every
//! AUV starts within d_s of the USV (C1_6 at k = 0, `mission::check_start`), so a bridge can
//! always hold. At k = K C1_6 keeps every AUV in range of the USV already.
//!
//! A bridge is a constraint of P5, not a planned link: its range is a second-order cone
//! ‖P_a − P_USV‖ ≤ d_s + σ_b and its line of sight the linearised rows of `keep_out` with slack
//! ν_b, both slacks priced by the SCP's penalty and their true violations part of the SCP's
//! measure. The plan's links stay Step 2's path (and `shoal check` verifies connectivity
//! through any links in range and in sight, as it always has).

use super::keep_out::{link_rows, link_violation};
use super::links::{cone, dist2, ends, LinkSet};
use super::model::Assembly;
use super::ranges::RANGE_MARGIN;
use super::TeamProblem;
use crate::error::PlanError;
use crate::plan::Link;
use crate::scenario::Scenario;
use crate::trajectory::{Start, Trajectory};

/// The fraction of its ends' combined top speed at which a link is taken to close when the
/// bridges are placed: the AUVs start at rest, and P5 closes a link as fast as its band's price
/// against the other terms asks, not at its speed limits. (A grace of two steps instead put
/// bridges on links 5 m out of range with δ = 100 s, and cost seed 8 at N = 5 5.7 % of its
/// objective; with none, draw 1016 would still lose its chain at the last steps before the
/// edge closes.)
pub const CLOSING_FRACTION: f64 = 0.5;

/// An A2U link that P5 keeps in range and in sight at step `k`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bridge {
    pub k: usize,
    /// The AUV (`a`) and the USV (`b` = None).
    pub link: Link,
}

/// The start position of node `i` (0 the USV at z = 0, i + 1 AUV i).
fn node(start: &Start, i: usize) -> [f64; 3] {
    match i {
        0 => [start.usv[0], start.usv[1], 0.0],
        _ => start.auvs[i - 1].position,
    }
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    dist2(a, b).sqrt()
}

/// The nodes (0 the USV, i + 1 AUV i) at the ends of a link.
fn nodes(l: Link) -> (usize, usize) {
    (l.a + 1, l.b.map_or(0, |b| b + 1))
}

/// The least length of `link` after `time` seconds: its ends' start distance less what both
/// can close at their speed limits (C1_7, the USV's limit), never below 0.
fn least_length(s: &Scenario, start: &Start, link: Link, time: f64) -> f64 {
    let (i, j) = nodes(link);
    let speed = |i: usize| {
        if i == 0 {
            s.usv.max_speed
        } else {
            s.auv.max_speed
        }
    };
    let closing = (speed(i) + speed(j)) * time;
    (distance(node(start, i), node(start, j)) - closing).max(0.0)
}

/// Per step k and planned link, the least length the link can have at k from `start`: no
/// plan can bring it below (`links::priced_band` prices only the metres beyond it).
pub fn least_lengths(s: &Scenario, start: &Start, set: &LinkSet) -> Vec<Vec<f64>> {
    set.links
        .iter()
        .enumerate()
        .map(|(k, links)| {
            links
                .iter()
                .map(|&l| least_length(s, start, l, k as f64 * s.horizon.dt))
                .collect()
        })
        .collect()
}

/// The bridges of the window starting at `start` with the planned links `set` (see the module
/// docs), step by step.
pub fn needed(s: &Scenario, start: &Start, set: &LinkSet) -> Vec<Bridge> {
    let n = start.auvs.len();
    let ds = s.acoustic.sonar_range;
    let mut out = Vec::new();
    // k = K is C1_6's
    for k in 1..set.links.len().saturating_sub(1) {
        let time = CLOSING_FRACTION * k as f64 * s.horizon.dt;
        let reachable = |l: &Link| least_length(s, start, *l, time) <= ds;
        if set.links[k].iter().all(reachable) {
            continue;
        }
        let mut parent: Vec<usize> = (0..=n).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        for l in set.links[k].iter().filter(|l| reachable(l)) {
            let (i, j) = nodes(*l);
            let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
            parent[ri] = rj;
        }
        let usv = root(&mut parent, 0);
        // per piece cut off from the USV, its AUV nearest the USV at the start
        let mut nearest: Vec<Option<(f64, usize)>> = vec![None; n + 1];
        for i in 1..=n {
            let r = root(&mut parent, i);
            if r == usv {
                continue;
            }
            let d = distance(node(start, i), node(start, 0));
            // (a start beyond d_s of the USV, which `mission::check_start` refuses, gets none)
            if d <= ds && nearest[r].map_or(true, |(best, _)| d < best) {
                nearest[r] = Some((d, i));
            }
        }
        let mut auvs: Vec<usize> = nearest.iter().flatten().map(|&(_, i)| i - 1).collect();
        auvs.sort_unstable();
        out.extend(auvs.into_iter().map(|a| Bridge {
            k,
            link: Link { a, b: None },
        }));
    }
    out
}

/// The bridges' slacks, priced by the SCP's penalty λ per metre.
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    for b in 0..p.bridges.len() {
        m.penalise(l.bridge_slack(b), 1.0, penalty);
        m.penalise(l.bridge_los_slack(b), 1.0, penalty);
    }
}

/// Nonnegative-cone rows: each bridge's line of sight (linearised about the reference, as a
/// planned link's in `keep_out`) and its slacks σ_b, ν_b ≥ 0.
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) -> Result<(), PlanError> {
    let l = p.layout;
    for (bi, bridge) in p.bridges.iter().enumerate() {
        link_rows(p, r, m, bridge.k, bridge.link, l.bridge_los_slack(bi))?;
        m.nonnegative(l.bridge_slack(bi));
        m.nonnegative(l.bridge_los_slack(bi));
    }
    Ok(())
}

/// Second-order cones: ‖P_a − P_USV‖ ≤ d_s + σ_b, tightened by `RANGE_MARGIN` like C1_6.
pub(super) fn cones(p: &TeamProblem, m: &mut Assembly) {
    let l = p.layout;
    let ds = p.scenario.acoustic.sonar_range;
    for (bi, bridge) in p.bridges.iter().enumerate() {
        let hi = ds - RANGE_MARGIN;
        cone(l, m, bridge.k, bridge.link, hi, l.bridge_slack(bi));
    }
}

/// Per bridge, its true violation in metres (beyond d_s less `RANGE_MARGIN`, as the model's
/// cone: the model and the measure agree at the reference, as SCvx needs; plus the line of
/// sight's shortfall) and the point where the sight is worst.
pub(super) fn violations(p: &TeamProblem, t: &Trajectory) -> Vec<(f64, [f64; 3])> {
    let hi = p.scenario.acoustic.sonar_range - RANGE_MARGIN;
    p.bridges
        .iter()
        .map(|bridge| {
            let (a, b) = ends(t, bridge.k, bridge.link);
            let (sight, at) = link_violation(p, a, b);
            ((distance(a, b) - hi).max(0.0) + sight.max(0.0), at)
        })
        .collect()
}

/// The error text of a violated bridge.
pub(super) fn detail(p: &TeamProblem, bi: usize, at: [f64; 3]) -> String {
    let bridge = p.bridges[bi];
    format!(
        "the acoustic chain at step {}: AUV {} cannot reach the planned path's links yet and must \
         keep the USV in range (d_s = {} m) and in line of sight (worst at ({:.1}, {:.1}, {:.1}))",
        bridge.k, bridge.link.a, p.scenario.acoustic.sonar_range, at[0], at[1], at[2]
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::AuvState;
    use crate::plan::Graph;

    fn start(auvs: &[[f64; 3]]) -> Start {
        Start {
            usv: [0.0, 0.0],
            auvs: auvs
                .iter()
                .map(|&position| AuvState {
                    position,
                    velocity: [0.0; 3],
                })
                .collect(),
        }
    }

    /// The chain USV–AUV 0–AUV 1 for K steps.
    fn chain(k: usize) -> LinkSet {
        let graph = Graph {
            a2u: vec![0; k + 1],
            a2a: vec![vec![[0, 1]]; k + 1],
            exact: true,
            solve_time_s: 0.0,
        };
        LinkSet::from_graph(&graph, 100.0, 20.0)
    }

    fn scenario(k: usize) -> Scenario {
        let mut s = Scenario::default();
        s.horizon.steps = k;
        s.horizon.dt = 10.0;
        s.acoustic.sonar_range = 100.0;
        s.auv.max_speed = 1.0;
        s.usv.max_speed = 1.0;
        s
    }

    /// Two AUVs on either side of the USV, 180 m apart: the edge between them closes at 2 m/s
    /// at most, taken as 1 m/s (10 m per step), so it is in range from step 8; until then AUV 1
    /// keeps the USV.
    #[test]
    fn the_far_end_keeps_the_usv_until_its_edge_can_close() {
        let s = scenario(20);
        let bridges = needed(
            &s,
            &start(&[[-90.0, 0.0, -1.0], [90.0, 0.0, -1.0]]),
            &chain(20),
        );
        let steps: Vec<usize> = bridges.iter().map(|b| b.k).collect();
        assert_eq!(steps, (1..8).collect::<Vec<_>>());
        assert!(bridges.iter().all(|b| b.link == Link { a: 1, b: None }));
    }

    /// A chain whose links are all in range at the start needs none, and none is put at k = K.
    #[test]
    fn a_chain_in_range_needs_no_bridge() {
        let s = scenario(3);
        assert!(needed(
            &s,
            &start(&[[-40.0, 0.0, -1.0], [40.0, 0.0, -1.0]]),
            &chain(3)
        )
        .is_empty());
        // far apart, but K = 1: only k = K, which C1_6 holds
        let s = scenario(1);
        assert!(needed(
            &s,
            &start(&[[-90.0, 0.0, -1.0], [90.0, 0.0, -1.0]]),
            &chain(1)
        )
        .is_empty());
    }

    /// A link's least length falls by what its ends close at their speed limits per step, to
    /// 0; the band OF1_3/OF1_4 price starts there when that is above d_s.
    #[test]
    fn least_lengths_fall_at_the_closing_speed() {
        let s = scenario(12);
        let start = start(&[[-90.0, 0.0, 0.0], [90.0, 0.0, 0.0]]);
        let least = least_lengths(&s, &start, &chain(12));
        for (k, l) in least.iter().enumerate() {
            // A2U link AUV 0–USV: 90 m, closing at 2 m/s; A2A edge: 180 m
            assert!(
                (l[0] - (90.0 - 20.0 * k as f64).max(0.0)).abs() < 1e-9,
                "k = {k}"
            );
            assert!(
                (l[1] - (180.0 - 20.0 * k as f64).max(0.0)).abs() < 1e-9,
                "k = {k}"
            );
        }
        let band = crate::plan::Band {
            lo: 80.0,
            hi: 100.0,
        };
        assert_eq!(super::super::priced_band(band, least[2][1]).hi, 140.0);
        assert_eq!(super::super::priced_band(band, least[5][1]), band);
    }
}
