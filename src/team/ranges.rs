//! Acoustic ranges to the USV, second-order cones: C1_5, ‖P_n[k] − P_USV[k]‖ ≤ d_max for
//! k < K, and C1_6, ≤ d_s at k = K (the USV at z = 0). C1_6 at k = 0 is the start's, checked
//! before the window (`mission::check_start`). Convex and hard in the model, tightened by
//! [`RANGE_MARGIN`].

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

/// Margin (m) by which the convex model tightens the range bounds and the surface bound, so
/// that the solver's own residuals (up to about 1e-4 m on positions of a few km, once the plan
/// is re-simulated from its inputs) cannot leave a bound violated beyond the checker's 1e-6
/// tolerance.
pub(crate) const RANGE_MARGIN: f64 = 1e-3;

/// How an infeasible C1_5 is named.
const RANGE_MAX: &str = "C1_5 (every AUV within d_max of the USV)";
/// How an infeasible C1_6 is named.
const RANGE_END: &str = "C1_6 (every AUV within d_s of the USV at k = K)";

/// The true violation of C1_5 (k < K) or C1_6 (k = K) by AUV n at step k: metres beyond the
/// range. The model holds it hard, so only a first guess can violate it.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> f64 {
    let acoustic = &p.scenario.acoustic;
    let range = if k == p.layout.k {
        acoustic.sonar_range
    } else {
        acoustic.max_range
    };
    let (a, u) = (t.auv_p[n][k], t.usv_p[k]);
    let d = ((a[0] - u[0]).powi(2) + (a[1] - u[1]).powi(2) + a[2] * a[2]).sqrt();
    (d - range).max(0.0)
}

/// C1_5 (k < K) or C1_6 (k = K) for AUV n.
pub(super) fn auv(p: &TeamProblem, m: &mut Assembly, n: usize, k: usize) {
    let l = p.layout;
    let acoustic = &p.scenario.acoustic;
    let (range, group) = if k == l.k {
        (acoustic.sonar_range, RANGE_END)
    } else {
        (acoustic.max_range, RANGE_MAX)
    };
    let row = m.row(range - RANGE_MARGIN);
    m.group(group, row);
    for i in 0..3 {
        let row = m.row(0.0);
        m.a.push(row, l.auv_p(n, k) + i, 1.0);
        if i < 2 {
            m.a.push(row, l.usv_p(k) + i, -1.0);
        }
    }
    m.cones.push(SecondOrderConeT(4));
}
