//! Held–Karp dynamic programming for the longest Hamiltonian path: exact, O(2^N N²) time and
//! O(2^N N) memory.

use super::{finish, HamiltonianPath, Weights};

/// Held–Karp: `dp[S][j]` = heaviest path visiting exactly the set S and ending at j (starting
/// anywhere in S), `dp[{j}][j] = 0`; the answer is max_j dp[all][j], rebuilt from `parent`.
/// Only meant for N ≤ [`EXACT_MAX`] (memory grows as 2^N N).
pub(super) fn held_karp(w: &Weights) -> HamiltonianPath {
    let n = w.n;
    if n <= 2 {
        return finish((0..n).collect(), w, true);
    }
    let full = 1usize << n;
    let mut dp = vec![0.0f64; full * n];
    let mut parent = vec![0u8; full * n];
    for mask in 1..full {
        if mask.is_power_of_two() {
            continue; // dp[{j}][j] = 0 already
        }
        for j in (0..n).filter(|&j| mask & (1 << j) != 0) {
            let prev = mask ^ (1 << j);
            let mut best: Option<(usize, f64)> = None;
            for i in (0..n).filter(|&i| prev & (1 << i) != 0) {
                let c = dp[prev * n + i] + w.at(i, j);
                if best.map_or(true, |(_, b)| c > b) {
                    best = Some((i, c));
                }
            }
            if let Some((i, c)) = best {
                dp[mask * n + j] = c;
                parent[mask * n + j] = i as u8;
            }
        }
    }
    let all = full - 1;
    let row = &dp[all * n..];
    // Heaviest end; `rev` + `max_by` (last maximum) gives ties to the lowest index.
    let end = (0..n)
        .rev()
        .max_by(|&a, &b| row[a].total_cmp(&row[b]))
        .unwrap_or(0);
    let mut order = Vec::with_capacity(n);
    let (mut mask, mut j) = (all, end);
    order.push(j);
    while !mask.is_power_of_two() {
        let i = parent[mask * n + j] as usize;
        mask ^= 1 << j;
        j = i;
        order.push(j);
    }
    finish(order, w, true)
}
