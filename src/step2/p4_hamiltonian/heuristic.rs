//! The longest Hamiltonian path beyond Held–Karp's reach: greedy constructions from every
//! start, improved by 2-opt and or-opt local search.

use super::{finish, HamiltonianPath, Weights};
use std::collections::{HashSet, VecDeque};

/// Heuristic for P4, used beyond `EXACT_MAX` (works for any N). For each start node s, in
/// increasing order: a greedy path from s that repeatedly appends, at either end, the unvisited
/// node farthest from that end; each distinct greedy path is then improved by local search until
/// no move gains more than 1e-12 × (largest edge weight):
/// - 2-opt: reverse a segment `order[i..=j]`, including segments touching an end;
/// - or-opt: move a segment of 1–3 nodes to its best other position, possibly reversed.
///
/// The heaviest result wins (first one on ties). Deterministic; `exact: false`. Cost about
/// O(N³) for the constructions plus O(N²) per local-search sweep.
pub fn heuristic_path(points: &[[f64; 3]]) -> HamiltonianPath {
    heuristic(&Weights::avoiding(points, |_, _| false))
}

pub(super) fn heuristic(w: &Weights) -> HamiltonianPath {
    let n = w.n;
    let mut best = finish((0..n).collect(), w, false);
    if n <= 2 {
        return best;
    }
    let mut seen = HashSet::new();
    for start in 0..n {
        let mut order = finish(greedy(w, start), w, false).order;
        if !seen.insert(order.clone()) {
            continue;
        }
        local_search(w, &mut order);
        let cand = finish(order, w, false);
        if w.total(&cand.order) > w.total(&best.order) {
            best = cand;
        }
    }
    best
}

pub(super) fn greedy(w: &Weights, start: usize) -> Vec<usize> {
    let n = w.n;
    let mut used = vec![false; n];
    used[start] = true;
    let mut path = VecDeque::from([start]);
    for _ in 1..n {
        let (front, back) = (path[0], path[path.len() - 1]);
        let mut best: Option<(usize, bool, f64)> = None;
        for u in (0..n).filter(|&u| !used[u]) {
            for (at_back, end) in [(true, back), (false, front)] {
                let c = w.at(end, u);
                if best.map_or(true, |(_, _, b)| c > b) {
                    best = Some((u, at_back, c));
                }
            }
        }
        if let Some((u, at_back, _)) = best {
            used[u] = true;
            if at_back {
                path.push_back(u);
            } else {
                path.push_front(u);
            }
        }
    }
    path.into()
}

/// First-improvement 2-opt / or-opt sweeps until a sweep makes no move. Every accepted move gains
/// more than `eps` (far above the rounding error of an O(1) delta), so the weight strictly
/// increases and the search terminates; NaN or infinite weights make every test false.
fn local_search(w: &Weights, o: &mut Vec<usize>) {
    let n = o.len();
    let eps = 1e-12 * w.max;
    loop {
        let mut improved = false;
        for i in 0..n - 1 {
            for j in i + 1..n {
                if i == 0 && j == n - 1 {
                    continue; // reversing the whole path changes nothing
                }
                let (p, q) = (i.checked_sub(1).map(|k| o[k]), o.get(j + 1).copied());
                let (oi, oj) = (Some(o[i]), Some(o[j]));
                let d = w.edge(p, oj) - w.edge(p, oi) + w.edge(oi, q) - w.edge(oj, q);
                if d > eps {
                    o[i..=j].reverse();
                    improved = true;
                }
            }
        }
        for len in 1..=3.min(n - 1) {
            for i in 0..=n - len {
                improved |= or_opt(w, o, i, len, eps);
            }
        }
        if !improved {
            return;
        }
    }
}

/// Moves `o[i..i + len]` to the best gap of the remaining path (either orientation) if that
/// gains more than `eps`. Returns whether a move was made.
fn or_opt(w: &Weights, o: &mut Vec<usize>, i: usize, len: usize, eps: f64) -> bool {
    let n = o.len();
    let (s, e) = (o[i], o[i + len - 1]);
    let (a, b) = (i.checked_sub(1).map(|k| o[k]), o.get(i + len).copied());
    // Gain of cutting the segment out (and closing the gap a–b).
    let base = w.edge(a, b) - w.edge(a, Some(s)) - w.edge(Some(e), b);
    let m = n - len;
    let rest = |q: usize| if q < i { o[q] } else { o[q + len] };
    let mut best: Option<(usize, bool, f64)> = None;
    for q in 0..=m {
        // Gap q lies between rest[q − 1] and rest[q] (either may be absent at the ends).
        let x = q.checked_sub(1).map(rest);
        let y = (q < m).then(|| rest(q));
        for rev in [false, true] {
            if q == i && !rev {
                continue; // the identity move
            }
            let (f, l) = if rev { (e, s) } else { (s, e) };
            let d = base - w.edge(x, y) + w.edge(x, Some(f)) + w.edge(Some(l), y);
            if d > eps && best.map_or(true, |(_, _, bd)| d > bd) {
                best = Some((q, rev, d));
            }
        }
    }
    let Some((q, rev, _)) = best else {
        return false;
    };
    let mut seg = o[i..i + len].to_vec();
    if rev {
        seg.reverse();
    }
    let mut rest: Vec<usize> = o[..i].iter().chain(&o[i + len..]).copied().collect();
    rest.splice(q..q, seg);
    *o = rest;
    true
}
