//! OF1_5 of P5 (Step 3): non-adjacent AUVs spread out, rewarded as −w5·Σ_k Σ ‖P_i − P_j‖² over
//! the pairs of AUVs not joined by a planned A2A edge at step k. The reward is concave, so the
//! model linearises it about the reference: −w5·(‖d̄‖² + 2d̄ᵀ(d − d̄)) per pair, d = P_i − P_j.

use super::links::{dist2, LinkSet};
use super::model::Assembly;
use super::TeamProblem;
use crate::linearise::spread;
use crate::trajectory::Trajectory;

/// The unweighted OF1_5 of a trajectory, m²: Σ_k Σ ‖P_i − P_j‖² over the pairs not joined by an
/// A2A edge at k, k = 1..=K.
pub fn value(set: &LinkSet, t: &Trajectory) -> f64 {
    let mut total = 0.0;
    let n = t.auv_p.len();
    for k in 1..set.links.len().min(t.auv_p.first().map_or(0, Vec::len)) {
        for i in 0..n {
            for j in i + 1..n {
                if !set.adjacent(k, i, j) {
                    total += dist2(t.auv_p[i][k], t.auv_p[j][k]);
                }
            }
        }
    }
    total
}

/// −w5·OF1_5 linearised about the reference `r` (after P2's terms: q entries add up).
pub(super) fn objective(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let Some(set) = &p.links else { return };
    let l = p.layout;
    let w = &p.scenario.weights;
    let w5 = w.w5 * w.per_auv(l.n); // weights.scaling: each AUV's share
    for k in 1..=l.k {
        for i in 0..l.n {
            for j in i + 1..l.n {
                if set.adjacent(k, i, j) {
                    continue;
                }
                let (pi, pj) = (r.auv_p[i][k], r.auv_p[j][k]);
                let d: [f64; 3] = std::array::from_fn(|c| pi[c] - pj[c]);
                // w5·(value + g·(d − d̄)) with d = P_i − P_j
                let (value, g) = spread(d);
                for c in 0..3 {
                    m.q[l.auv_p(i, k) + c] += w5 * g[c];
                    m.q[l.auv_p(j, k) + c] -= w5 * g[c];
                }
                m.constant += w5 * (value - (g[0] * d[0] + g[1] * d[1] + g[2] * d[2]));
            }
        }
    }
}
