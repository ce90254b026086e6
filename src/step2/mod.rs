//! Step 2 of Section IV-A: the acoustic graph of every step, from Step 1's positions
//! (Algorithm 1, lines 13–16): P3 picks the A2U link (the AUV nearest the USV, `p3_a2u`), P4
//! the A2A graph (the longest Hamiltonian path, `p4_hamiltonian`).
//!
//! Departure: over a grid with obstacles, P4 avoids A2A edges that cross an obstacle cell
//! (NODATA or land, `Seafloor::segment_obstacle`): among the Hamiltonian paths with the fewest
//! such edges it takes the longest (`p4_hamiltonian::longest_path_avoiding`). No link sees through an
//! obstacle, and P5 cannot make two AUVs on either side of one see each other by pulling them
//! together (they would have to go round it). Over a grid without obstacles nothing changes.

pub mod p3_a2u;
pub mod p4_hamiltonian;

use crate::plan::Graph;
use crate::seafloor::Seafloor;
use crate::trajectory::Trajectory;
use p3_a2u::a2u_link;
use p4_hamiltonian::longest_path_avoiding;
use std::time::Instant;

/// P3 and P4 at every step k = 0..=K of `t`, over `floor` sampled at `resolution` (𝓛_r).
pub fn solve(t: &Trajectory, floor: &Seafloor, resolution: f64) -> Graph {
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
        let crosses = |i: usize, j: usize| {
            floor.has_obstacles()
                && matches!(
                    floor.segment_obstacle(points[i], points[j], resolution),
                    Ok(Some(_))
                )
        };
        let path = longest_path_avoiding(&points, crosses);
        g.exact &= path.exact;
        g.a2a.push(path.edges());
    }
    g.solve_time_s = clock.elapsed().as_secs_f64();
    g
}
