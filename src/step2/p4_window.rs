//! P4 for a whole window: one A2A chain that every step of the window keeps
//! (`acoustic.graph = "lanes"` or `"window"`), where the paper's P4 picks a chain per step
//! (`"per_step"`, `p4_hamiltonian`).
//!
//! Why. The paper's longest Hamiltonian path of each step's positions reorders the chain from
//! one step to the next (at N = 20, seed 1, the edge set changes at 15 of the 20 steps).
//! Two things follow. P5 couples every AUV with its chain neighbours at every step, so a chain
//! that reorders couples nearly every AUV with every other over the window, and the interior-point
//! factorisation fills in: at N = 20 its cost grows 3.7× (4.4·10⁷ against 1.2·10⁷
//! multiply-adds per factorisation) and a window takes twice as long. And the longest path is a
//! zigzag: over AUVs abreast of each other, the chain joins the ones farthest apart, so its links
//! (at most d_s each) hold the team to about d_s across in all, where the same AUVs chained in
//! their cross-track order may spread to (N − 1)·d_s and sweep separate lanes.
//!
//! - [`lanes`]: the AUVs chained in the order of their mean cross-track offset
//!   from the USV's track over the window (Step 1's positions), each link joining neighbouring
//!   lanes. Over a grid with obstacles, or where a link of that order is out of range at some
//!   step, the chain is the one with the fewest such (step, edge) pairs and, among those, the
//!   smallest Σ of squared offset gaps (closest to the cross-track order).
//! - [`longest`]: the Hamiltonian path with the fewest blocked (step, edge) pairs and, among
//!   those, the largest Σ_k Σ_edges ‖P_i\[k\] − P_j\[k\]‖²: the paper's OF4 summed over the window.
//!
//! At a step where an edge of the window's chain cannot carry a link at Step 1's positions,
//! `step2::solve` keeps the step's own P4 path if it has fewer such edges.
//!
//! docs/design-decisions.md ("One chain per window") has
//! the measurements: lanes is the default since it explores more than the paper's chains at
//! every team size measured, over one window and over missions, at about half the time at
//! N = 20, and stops nearer the converged optimum.

use super::dist2;
use super::p4_hamiltonian::{longest_path_over, HamiltonianPath};
use crate::trajectory::Trajectory;

/// The USV's track over the window must be at least this long (m) for a cross-track order to
/// mean something; below it, [`lanes`] falls back to [`longest`].
const MIN_TRACK: f64 = 1.0;

/// The steps P5 constrains the links at: k = 1..=K.
fn steps(t: &Trajectory) -> std::ops::Range<usize> {
    1..t.usv_p.len()
}

/// The (step, edge) pairs of edge i–j that cannot carry a link: `blocked(k, i, j)`.
fn blocked_steps(
    t: &Trajectory,
    blocked: &dyn Fn(usize, usize, usize) -> bool,
    i: usize,
    j: usize,
) -> usize {
    steps(t).filter(|&k| blocked(k, i, j)).count()
}

/// The longest chain over the window (see the module's documentation).
pub fn longest(t: &Trajectory, blocked: &dyn Fn(usize, usize, usize) -> bool) -> HamiltonianPath {
    longest_path_over(
        t.auv_p.len(),
        |i, j| steps(t).map(|k| dist2(t.auv_p[i][k], t.auv_p[j][k])).sum(),
        |i, j| blocked_steps(t, blocked, i, j),
    )
}

/// The chain in cross-track order (see the module's documentation).
pub fn lanes(t: &Trajectory, blocked: &dyn Fn(usize, usize, usize) -> bool) -> HamiltonianPath {
    let Some(offset) = cross_track(t) else {
        return longest(t, blocked);
    };
    let n = offset.len();
    let mut order: Vec<usize> = (0..n).collect();
    // stable: equal offsets keep index order
    order.sort_by(|&a, &b| offset[a].total_cmp(&offset[b]));
    let clear = order
        .windows(2)
        .all(|e| blocked_steps(t, blocked, e[0], e[1]) == 0);
    let path = if clear {
        oriented(order, true)
    } else {
        // fewest blocked (step, edge) pairs first, then the smallest Σ (gap)²
        let p = longest_path_over(
            n,
            |i, j| -(offset[i] - offset[j]).powi(2),
            |i, j| blocked_steps(t, blocked, i, j),
        );
        oriented(p.order, p.exact)
    };
    HamiltonianPath {
        weight: path
            .order
            .windows(2)
            .map(|e| (offset[e[0]] - offset[e[1]]).powi(2))
            .sum(),
        ..path
    }
}

/// Each AUV's mean cross-track offset (m, positive to the left) from the USV over k = 1..=K,
/// across the direction from the USV's first to its last position; `None` when the USV moves
/// less than 1 m (`MIN_TRACK`) or a position is not finite.
pub fn cross_track(t: &Trajectory) -> Option<Vec<f64>> {
    let (first, last) = (t.usv_p.first()?, t.usv_p.last()?);
    let d = [last[0] - first[0], last[1] - first[1]];
    let norm = d[0].hypot(d[1]);
    if norm.is_nan() || norm < MIN_TRACK || steps(t).is_empty() {
        return None;
    }
    let u = [d[0] / norm, d[1] / norm];
    let count = steps(t).len() as f64;
    let offset: Vec<f64> = t
        .auv_p
        .iter()
        .map(|p| {
            steps(t)
                .map(|k| u[0] * (p[k][1] - t.usv_p[k][1]) - u[1] * (p[k][0] - t.usv_p[k][0]))
                .sum::<f64>()
                / count
        })
        .collect();
    offset.iter().all(|o| o.is_finite()).then_some(offset)
}

/// `order` as a path with `order[0] < order[N − 1]` (weight 0, set by the caller).
fn oriented(mut order: Vec<usize>, exact: bool) -> HamiltonianPath {
    if order.first() > order.last() {
        order.reverse();
    }
    HamiltonianPath {
        order,
        weight: 0.0,
        exact,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::step2::p4_hamiltonian::is_hamiltonian_path;

    /// N AUVs abreast of a USV that runs east 100 m per step for `k` steps: AUV i at
    /// cross-track offset `y[i]` (north positive = left of an eastward track), 20 m behind.
    fn abreast(y: &[f64], k: usize) -> Trajectory {
        Trajectory {
            usv_p: (0..=k).map(|s| [100.0 * s as f64, 0.0]).collect(),
            usv_u: vec![[0.0; 2]; k],
            auv_p: y
                .iter()
                .map(|&yi| {
                    (0..=k)
                        .map(|s| [100.0 * s as f64 - 20.0, yi, -50.0])
                        .collect()
                })
                .collect(),
            auv_v: vec![vec![[0.0; 3]; k + 1]; y.len()],
            auv_u: vec![vec![[0.0; 3]; k]; y.len()],
        }
    }

    const NONE: &dyn Fn(usize, usize, usize) -> bool = &|_, _, _| false;

    #[test]
    fn lanes_chain_the_auvs_in_cross_track_order() {
        let t = abreast(&[100.0, -200.0, 0.0, 200.0, -100.0], 4);
        let off = cross_track(&t).unwrap();
        assert!((off[0] - 100.0).abs() < 1e-9 && (off[1] + 200.0).abs() < 1e-9);
        let path = lanes(&t, NONE);
        assert_eq!(path.order, vec![1, 4, 2, 0, 3]);
        assert!(path.exact);
        assert!(is_hamiltonian_path(5, &path.edges()));
        assert!((path.weight - 4.0 * 100.0f64.powi(2)).abs() < 1e-6);
    }

    #[test]
    fn the_longest_window_chain_is_the_zigzag_over_auvs_abreast() {
        // offsets 0, 100, 200: the longest path joins 0 and 200 m with 100 m at one end
        let t = abreast(&[0.0, 100.0, 200.0], 3);
        let path = longest(&t, NONE);
        assert!(
            path.order == vec![0, 2, 1] || path.order == vec![1, 0, 2],
            "{:?}",
            path.order
        );
        assert!((path.weight - 3.0 * (200.0f64.powi(2) + 100.0f64.powi(2))).abs() < 1e-6);
    }

    #[test]
    fn lanes_go_round_an_edge_blocked_at_one_step() {
        // order by offset would be 0–1–2–3; edge 1–2 is blocked at step 2 only
        let t = abreast(&[0.0, 100.0, 200.0, 300.0], 3);
        let blocked = |k: usize, i: usize, j: usize| k == 2 && (i, j) == (1, 2);
        let path = lanes(&t, &blocked);
        assert!(is_hamiltonian_path(4, &path.edges()));
        assert!(!path.edges().contains(&[1, 2]), "{:?}", path.order);
        // the two closest orders to 0–1–2–3 without 1–2 (Σ gap² = 6·10⁴ m² each)
        assert!(
            path.order == vec![1, 0, 2, 3] || path.order == vec![0, 1, 3, 2],
            "{:?}",
            path.order
        );
    }

    #[test]
    fn a_usv_that_stays_put_falls_back_to_the_longest_chain() {
        let mut t = abreast(&[0.0, 100.0, 200.0], 3);
        let p0 = t.usv_p[0];
        t.usv_p.iter_mut().for_each(|p| *p = p0);
        assert!(cross_track(&t).is_none());
        assert_eq!(lanes(&t, NONE).order, longest(&t, NONE).order);
    }

    #[test]
    fn one_and_zero_auvs_give_the_empty_chain() {
        for y in [&[][..], &[5.0][..]] {
            let t = abreast(y, 2);
            assert!(lanes(&t, NONE).edges().is_empty());
            assert!(longest(&t, NONE).edges().is_empty());
        }
    }
}
