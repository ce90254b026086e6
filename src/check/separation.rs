//! AUV–AUV separation: every pair of AUVs at least `auv.min_separation` apart at every
//! waypoint and along the straight segment between consecutive waypoints (both AUVs moving
//! at constant velocity over the segment, the relative position moves on a line), in both
//! stages. Re-evaluated from the plan's positions alone: the least distance of a line segment
//! from the origin, in closed form.

use super::run::{diff, seg, Checker, Family};
use super::{FamilyResult, SEPARATION_TOL};

/// The least Euclidean distance between two points moving on straight lines from a0 to a1
/// and from b0 to b1 over the same interval, metres.
pub(super) fn least_gap(a0: [f64; 3], a1: [f64; 3], b0: [f64; 3], b1: [f64; 3]) -> f64 {
    // gap(s) = g0 + s·v, s ∈ [0, 1]; the unconstrained minimiser of ‖gap‖² is −g0·v / v·v
    let g0: [f64; 3] = std::array::from_fn(|c| a0[c] - b0[c]);
    let v: [f64; 3] = std::array::from_fn(|c| (a1[c] - a0[c]) - (b1[c] - b0[c]));
    let vv: f64 = v.iter().map(|x| x * x).sum();
    let at_start = diff(a0, b0);
    let at_end = diff(a1, b1);
    let mut best = at_start.min(at_end);
    if vv > 0.0 {
        let s = -(0..3).map(|c| g0[c] * v[c]).sum::<f64>() / vv;
        if s > 0.0 && s < 1.0 {
            let p: [f64; 3] = std::array::from_fn(|c| g0[c] + s * v[c]);
            best = best.min(diff(p, [0.0; 3]));
        }
    }
    // a non-finite position gives NaN, which the family counts as a failure
    if a0
        .iter()
        .chain(&a1)
        .chain(&b0)
        .chain(&b1)
        .all(|x| x.is_finite())
    {
        best
    } else {
        f64::NAN
    }
}

impl Checker<'_> {
    // ------------------------------------------------------------------------------------
    // AUV–AUV separation, at waypoints and along segments
    // ------------------------------------------------------------------------------------
    pub(super) fn separation(&self) -> FamilyResult {
        let mut f = Family::new("AUV separation", "m", SEPARATION_TOL);
        let d = self.limits.auv.min_separation;
        if d.is_nan() || d <= 0.0 {
            return f.finish();
        }
        for (w, pre, st) in self.stages() {
            let n = st.auvs.len();
            for i in 0..n {
                for j in i + 1..n {
                    let (pi, pj) = (&st.auvs[i].position, &st.auvs[j].position);
                    for k in 1..=self.k.min(pi.len().min(pj.len()).saturating_sub(1)) {
                        let gap = least_gap(pi[k - 1], pi[k], pj[k - 1], pj[k]);
                        f.record(gap - d, || {
                            seg(
                                w,
                                k,
                                &format!(
                                    "{pre}AUVs {i} and {j} come within {gap:.4} m, \
                                     auv.min_separation = {d} m"
                                ),
                            )
                        });
                    }
                }
            }
        }
        f.finish()
    }
}

#[cfg(test)]
mod tests {
    use super::least_gap;

    /// Head-on past each other 4 m apart sideways: the least gap is 4 m at mid-segment, though
    /// both ends are 100 m apart; parallel at constant offset: the offset; crossing: 0.
    #[test]
    fn the_least_gap_is_found_between_the_ends() {
        let g = least_gap(
            [0.0, 0.0, -50.0],
            [100.0, 0.0, -50.0],
            [100.0, 4.0, -50.0],
            [0.0, 4.0, -50.0],
        );
        assert!((g - 4.0).abs() < 1e-12, "{g}");
        let g = least_gap(
            [0.0, 0.0, -50.0],
            [100.0, 0.0, -50.0],
            [0.0, 0.0, -62.0],
            [100.0, 0.0, -62.0],
        );
        assert!((g - 12.0).abs() < 1e-12, "{g}");
        let g = least_gap(
            [0.0; 3],
            [10.0, 10.0, 0.0],
            [10.0, 0.0, 0.0],
            [0.0, 10.0, 0.0],
        );
        assert!(g.abs() < 1e-12, "{g}");
        assert!(least_gap([f64::NAN; 3], [0.0; 3], [1.0; 3], [2.0; 3]).is_nan());
    }
}
