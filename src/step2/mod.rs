//! Step 2 of Section IV-A: the acoustic graph of every step, from Step 1's positions
//! (Algorithm 1, lines 13–16): P3 picks the A2U link (the AUV nearest the USV, `p3_a2u`), P4
//! the A2A graph, a Hamiltonian path: by default one chain for the window in lane order
//! (`p4_window`, `acoustic.graph = "lanes"`, or the longest, `"window"`), or the paper's
//! longest path of each step (`p4_hamiltonian`, `"per_step"`).
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seafloor::Lattice;

    /// A flat floor at −100 m, 2 km across.
    fn flat() -> Seafloor {
        let (n, c, x0) = (41usize, 50.0, -1000.0);
        Seafloor::from_nodes(
            Lattice::new(n, n, x0, x0, c, c),
            vec![-100.0; n * n],
            vec![false; n * n],
        )
        .unwrap()
    }

    /// Three AUVs over k = 0..=3 with the USV running east 100 m per step: at k = 2, 3 they are
    /// abreast at y = 0, 100, 200 m; at k = 1 AUVs 1 and 2 have swapped sides (y = 260 and 130).
    fn swapped_at_step_one() -> Trajectory {
        let y = [
            [0.0, 0.0, 0.0, 0.0],
            [100.0, 260.0, 100.0, 100.0],
            [200.0, 130.0, 200.0, 200.0],
        ];
        Trajectory {
            usv_p: (0..4).map(|k| [100.0 * k as f64, -50.0]).collect(),
            usv_u: vec![[0.0; 2]; 3],
            auv_p: y
                .iter()
                .map(|yn| (0..4).map(|k| [100.0 * k as f64, yn[k], -50.0]).collect())
                .collect(),
            auv_v: vec![vec![[0.0; 3]; 4]; 3],
            auv_u: vec![vec![[0.0; 3]; 3]; 3],
        }
    }

    /// The lanes chain 0–1–2 holds at k = 2, 3; at k = 1 its edge 0–1 is 260 m > d_s, and the
    /// step keeps its own P4 path 0–2–1, whose links are all in range there.
    #[test]
    fn a_step_where_the_window_chain_is_out_of_range_keeps_its_own_path() {
        let t = swapped_at_step_one();
        let g = solve(&t, &flat(), 5.0, 150.0, A2aGraph::Lanes);
        assert_eq!(g.a2a[2], vec![[0, 1], [1, 2]]);
        assert_eq!(g.a2a[3], vec![[0, 1], [1, 2]]);
        let mut at_one = g.a2a[1].clone();
        at_one.sort();
        assert_eq!(at_one, vec![[0, 2], [1, 2]]);
        // the paper's P4 at every step picks the same path at k = 1
        let paper = solve(&t, &flat(), 5.0, 150.0, A2aGraph::PerStep);
        let mut own = paper.a2a[1].clone();
        own.sort();
        assert_eq!(own, at_one);
    }
}
