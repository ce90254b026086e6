//! Problem P4, the A2A consensus graph of one step, as the longest Hamiltonian path over the
//! AUVs: the problem P4 stands for (below), solved exactly by Held–Karp (`held_karp`) up to
//! [`EXACT_MAX`] AUVs and by a greedy construction with local search beyond (`heuristic`).
//!
//! **P4** (OF4 with C4_1–C4_3) maximises Σ_{i<j} σ_ij ‖P_i − P_j‖² subject to 0 ≤ σ_ij ≤ 1 (C4_1),
//! Σ σ_ij = N − 1 (C4_2) and 1 ≤ deg(i) ≤ 2 (C4_3). Definition IV.1 and Lemma IV.2 say the wanted
//! graph is a "tree" that is a simple path through every AUV exactly once — a Hamiltonian path —
//! and the paper's "longest tree" is the one with the maximum total *squared* edge length (the OF4
//! weights). Lemma IV.3 argues that this longest path cannot split the AUVs into clusters.
//!
//! **Why we do not solve the paper's LP.** C4_1–C4_3 do not characterise Hamiltonian paths. Even
//! with 0/1 values they admit cycles plus disconnected pieces: for N = 5, a triangle {0, 1, 2}
//! plus a separate edge {3, 4} has N − 1 = 4 edges and every degree in 1..=2, yet it is neither
//! connected nor acyclic — the very clustering Lemma IV.3 is meant to exclude. And C4_1 only
//! bounds σ to [0, 1]; nothing in C4 forces 0/1 values (for N = 3, σ ≡ 2/3 is feasible). So we
//! solve the combinatorial problem P4 stands for, the maximum-weight Hamiltonian path (NP-hard):
//!
//! - N ≤ [`EXACT_MAX`]: Held–Karp dynamic programming over subsets, exact, O(2^N N²) time and
//!   O(2^N N) memory; any start node, any end node (a path, not a cycle).
//! - N > [`EXACT_MAX`]: [`heuristic_path`], deterministic greedy constructions followed by 2-opt
//!   and or-opt local search; the result is always a valid Hamiltonian path, `exact: false`.
//!
//! **Determinism and ties.** No randomness. Candidates are scanned in increasing index order and
//! replaced only on strict improvement, so among equal weights the first one found wins; the
//! returned order is then oriented so that `order[0] < order[N − 1]`. Non-finite coordinates
//! never cause a panic: the result is still a valid path (its weight may be NaN or infinite).

mod held_karp;
mod heuristic;
#[cfg(test)]
mod tests;

use held_karp::held_karp;
#[cfg(test)]
use heuristic::greedy;
use heuristic::heuristic;
pub use heuristic::heuristic_path;

/// Largest N solved exactly by Held–Karp (2^12 · 12 states, about 0.4 MB of tables).
pub const EXACT_MAX: usize = 12;

/// A Hamiltonian path over the AUVs: the A2A graph of P4.
#[derive(Debug, Clone, PartialEq)]
pub struct HamiltonianPath {
    /// Visiting sequence (every index once); edges are consecutive pairs. `order[0] < order[N−1]`.
    pub order: Vec<usize>,
    /// Sum of squared 3D edge lengths (OF4 without the sign).
    pub weight: f64,
    /// `true` if proven optimal (Held–Karp), `false` if from the heuristic.
    pub exact: bool,
}

impl HamiltonianPath {
    /// The N − 1 edges, each as `[min, max]`, in path order (σ_ij = 1 exactly for these).
    pub fn edges(&self) -> Vec<[usize; 2]> {
        self.order
            .windows(2)
            .map(|e| [e[0].min(e[1]), e[0].max(e[1])])
            .collect()
    }
}

/// P4: the longest Hamiltonian path (maximum Σ ‖P_i − P_j‖² over its edges). Exact for
/// N ≤ [`EXACT_MAX`], [`heuristic_path`] beyond. N = 0 → empty order, N = 1 → `[0]`.
pub fn longest_path(points: &[[f64; 3]]) -> HamiltonianPath {
    longest_path_avoiding(points, |_, _| false)
}

/// P4 among the paths with the fewest `blocked` edges (`blocked(i, j)`, i < j: an edge that
/// cannot carry a link, e.g. across an obstacle), the longest of those: each blocked edge
/// weighs N·(largest squared length + 1) less, more than any path's total length. The
/// recorded weight is the true Σ ‖P_i − P_j‖².
pub fn longest_path_avoiding(
    points: &[[f64; 3]],
    blocked: impl Fn(usize, usize) -> bool,
) -> HamiltonianPath {
    let w = Weights::avoiding(points, blocked);
    if points.len() <= EXACT_MAX {
        held_karp(&w)
    } else {
        heuristic(&w)
    }
}

/// The heaviest Hamiltonian path in `length2(i, j)` (i < j; any sign) among those with the
/// fewest `blocked(i, j)` counts summed over their edges: P4 over a window (`p4_window`), where
/// the count is the steps at which edge i–j cannot carry a link. The recorded weight is the sum
/// of `length2` over the path's edges.
pub fn longest_path_over(
    n: usize,
    length2: impl Fn(usize, usize) -> f64,
    blocked: impl Fn(usize, usize) -> usize,
) -> HamiltonianPath {
    let w = Weights::over(n, length2, blocked);
    if n <= EXACT_MAX {
        held_karp(&w)
    } else {
        heuristic(&w)
    }
}

/// `true` iff `edges` form a Hamiltonian path on nodes 0..n: exactly n − 1 distinct edges with
/// valid, distinct endpoints, every degree ≤ 2 and no cycle (hence connected). n = 0 and n = 1
/// accept only the empty edge list.
pub fn is_hamiltonian_path(n: usize, edges: &[[usize; 2]]) -> bool {
    if edges.len() != n.saturating_sub(1) {
        return false;
    }
    fn find(root: &mut [usize], mut x: usize) -> usize {
        while root[x] != x {
            root[x] = root[root[x]];
            x = root[x];
        }
        x
    }
    let mut deg = vec![0u8; n];
    let mut root: Vec<usize> = (0..n).collect();
    for &[a, b] in edges {
        if a >= n || b >= n || a == b {
            return false;
        }
        deg[a] += 1;
        deg[b] += 1;
        let (ra, rb) = (find(&mut root, a), find(&mut root, b));
        // Same component: a repeated edge or a cycle.
        if deg[a] > 2 || deg[b] > 2 || ra == rb {
            return false;
        }
        root[ra] = rb;
    }
    // n − 1 edges and no cycle: a spanning tree; with degrees ≤ 2 it is a path.
    true
}

/// Dense matrix of edge weights: squared 3D distances, less a penalty on blocked edges.
struct Weights {
    n: usize,
    w: Vec<f64>,
    /// The squared distances themselves.
    d: Vec<f64>,
    max: f64,
}

impl Weights {
    #[cfg(test)]
    fn new(p: &[[f64; 3]]) -> Self {
        Self::avoiding(p, |_, _| false)
    }
    fn avoiding(p: &[[f64; 3]], blocked: impl Fn(usize, usize) -> bool) -> Self {
        Self::over(
            p.len(),
            |i, j| (0..3).map(|c| (p[i][c] - p[j][c]).powi(2)).sum::<f64>(),
            |i, j| usize::from(blocked(i, j)),
        )
    }
    /// Weights `length2(i, j)` (of any sign) less a penalty per count of `blocked(i, j)`
    /// (i < j), N·(largest |weight| + 1) each: fewest blocked counts first.
    fn over(
        n: usize,
        length2: impl Fn(usize, usize) -> f64,
        blocked: impl Fn(usize, usize) -> usize,
    ) -> Self {
        let mut d = vec![0.0; n * n];
        let mut max = 0.0f64;
        for i in 0..n {
            for j in i + 1..n {
                let v = length2(i, j);
                d[i * n + j] = v;
                d[j * n + i] = v;
                max = max.max(v.abs());
            }
        }
        let penalty = n as f64 * (max + 1.0);
        let mut w = d.clone();
        for i in 0..n {
            for j in i + 1..n {
                let count = blocked(i, j) as f64;
                w[i * n + j] -= penalty * count;
                w[j * n + i] -= penalty * count;
            }
        }
        Weights { n, w, d, max }
    }
    fn at(&self, i: usize, j: usize) -> f64 {
        self.w[i * self.n + j]
    }
    /// Σ of the (penalised) weights of the path's edges.
    fn total(&self, order: &[usize]) -> f64 {
        order.windows(2).map(|e| self.at(e[0], e[1])).sum()
    }
    /// Weight of edge x–y, or 0 if an endpoint is absent (beyond an end of the path).
    fn edge(&self, x: Option<usize>, y: Option<usize>) -> f64 {
        x.zip(y).map_or(0.0, |(x, y)| self.at(x, y))
    }
}

/// Orients the order (`order[0] < order[N−1]`) and sums its weight.
fn finish(mut order: Vec<usize>, w: &Weights, exact: bool) -> HamiltonianPath {
    if order.first() > order.last() {
        order.reverse();
    }
    let weight = order.windows(2).map(|e| w.d[e[0] * w.n + e[1]]).sum();
    HamiltonianPath {
        order,
        weight,
        exact,
    }
}
