//! Step 2 of Section IV-A: the acoustic graph of every step, from Step 1's positions
//! (Algorithm 1, lines 13–16): P3 picks the A2U link (the AUV nearest the USV), P4 the A2A
//! graph (the longest Hamiltonian path, `graph::longest_path`).

use crate::graph::{a2u_link, longest_path};
use crate::plan::Graph;
use crate::trajectory::Trajectory;
use std::time::Instant;

/// P3 and P4 at every step k = 0..=K of `t`.
pub fn solve(t: &Trajectory) -> Graph {
    let clock = Instant::now();
    let steps = t.usv_p.len();
    let mut g = Graph {
        a2u: Vec::with_capacity(steps),
        a2a: Vec::with_capacity(steps),
        exact: true,
        solve_time_s: 0.0,
    };
    for k in 0..steps {
        let points: Vec<[f64; 3]> = t.auv_p.iter().map(|p| p[k]).collect();
        // a team has at least one AUV (scenario validation), so there is a nearest one
        g.a2u.push(a2u_link(t.usv_p[k], &points).unwrap_or(0));
        let path = longest_path(&points);
        g.exact &= path.exact;
        g.a2a.push(path.edges());
    }
    g.solve_time_s = clock.elapsed().as_secs_f64();
    g
}
