//! Step 2 of Section IV-A: the acoustic graph of every step, from Step 1's positions
//! (Algorithm 1, lines 13–16): P3 picks the A2U link (the AUV nearest the USV, `p3_a2u`), P4
//! the A2A graph, a Hamiltonian path: by default the paper's longest path of each step
//! (`p4_hamiltonian`), or one chain for the window (`p4_window`, `acoustic.graph = "lanes"` or
//! `"window"`).
//!
//! Departure: over a grid with obstacles, P4 avoids A2A edges that cross an obstacle cell
//! (NODATA or land, `Seafloor::segment_obstacle`): among the Hamiltonian paths with the fewest
//! such edges it takes the longest (`p4_hamiltonian::longest_path_avoiding`). No link sees through an
//! obstacle, and P5 cannot make two AUVs on either side of one see each other by pulling them
//! together (they would have to go round it).
//!
//! Departure: an A2A edge longer than d_s at Step 1's positions counts as blocked too, so P4
//! takes the longest of the paths with the fewest out-of-range edges. The longest path alone
//! can join the two AUVs farthest apart (230 m with d_s = 155 m, from a start where each AUV
//! was in range of another), and P5, whose bands are soft, then stalled with the edge 75 m out
//! of range and the chain broken (issue 13's property test: N = 4, δ = 25 s). Where every
//! Hamiltonian path has an edge out of range, P4 is as before.

pub mod p3_a2u;
pub mod p4_hamiltonian;
pub mod p4_window;

use crate::plan::Graph;
use crate::scenario::A2aGraph;
use crate::seafloor::Seafloor;
use crate::trajectory::Trajectory;
use p3_a2u::a2u_link;
use p4_hamiltonian::longest_path_avoiding;
use std::time::Instant;

/// P3 and P4 at every step k = 0..=K of `t`, over `floor` sampled at `resolution` (𝓛_r), with
/// sonar range d_s = `sonar_range`; P4 per step or once for the window (`policy`).
pub fn solve(
    t: &Trajectory,
    floor: &Seafloor,
    resolution: f64,
    sonar_range: f64,
    policy: A2aGraph,
) -> Graph {
    let clock = Instant::now();
    let steps = t.usv_p.len();
    let mut g = Graph {
        a2u: Vec::with_capacity(steps),
        a2a: Vec::with_capacity(steps),
        exact: true,
        solve_time_s: 0.0,
    };
    // an A2A edge a–b that cannot carry a link: longer than d_s, or across an obstacle cell
    let blocked = |a: [f64; 3], b: [f64; 3]| {
        dist2(a, b).sqrt() > sonar_range
            || floor.has_obstacles()
                && matches!(floor.segment_obstacle(a, b, resolution), Ok(Some(_)))
    };
    let blocked_at = |k: usize, i: usize, j: usize| blocked(t.auv_p[i][k], t.auv_p[j][k]);
    let chain = match policy {
        A2aGraph::PerStep => None,
        A2aGraph::Window => Some(p4_window::longest(t, &blocked_at)),
        A2aGraph::Lanes => Some(p4_window::lanes(t, &blocked_at)),
    };
    if let Some(path) = &chain {
        g.exact = path.exact;
    }
    for k in 0..steps {
        let points: Vec<[f64; 3]> = t.auv_p.iter().map(|p| p[k]).collect();
        // a team has at least one AUV (scenario validation), so there is a nearest one
        g.a2u.push(a2u_link(t.usv_p[k], &points).unwrap_or(0));
        let count =
            |edges: &[[usize; 2]]| edges.iter().filter(|e| blocked_at(k, e[0], e[1])).count();
        // the window's chain, unless an edge of it cannot carry a link at this step (the first
        // steps of a later window, whose positions the last window's momentum fixes) and the
        // step's own P4 path has fewer such edges
        let window = chain.as_ref().map(|c| c.edges());
        let clear = window.as_ref().is_some_and(|w| count(w) == 0);
        let edges = match window {
            Some(w) if clear => w,
            _ => {
                let path = longest_path_avoiding(&points, |i, j| blocked(points[i], points[j]));
                let own = path.edges();
                match window {
                    Some(w) if count(&w) <= count(&own) => w,
                    _ => {
                        g.exact &= path.exact;
                        own
                    }
                }
            }
        };
        g.a2a.push(edges);
    }
    g.solve_time_s = clock.elapsed().as_secs_f64();
    g
}

/// ‖a − b‖².
pub(crate) fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}
