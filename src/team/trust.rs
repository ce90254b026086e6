//! The SCvx trust region (`scp`): the model is trusted only within Δ of the reference, as a
//! second-order cone on each AUV's horizontal position per step, ‖P_n,xy[k] − P̄_n,xy[k]‖ ≤ Δ,
//! and over a grid with obstacles, whose USV keep-out rows are linearised too, on the USV's.

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

/// How an infeasible trust region is named.
const TRUST: &str = "the trust region about the previous iterate";

/// ‖P_n,xy[k] − P̄_n,xy[k]‖ ≤ Δ.
pub(super) fn auv(
    p: &TeamProblem,
    m: &mut Assembly,
    r: &Trajectory,
    radius: f64,
    n: usize,
    k: usize,
) {
    let row = m.row(radius);
    m.group(TRUST, row);
    for i in 0..2 {
        let row = m.row(r.auv_p[n][k][i]);
        m.a.push(row, p.layout.auv_p(n, k) + i, 1.0);
    }
    m.cones.push(SecondOrderConeT(3));
}

/// ‖P_USV[k] − P̄_USV[k]‖ ≤ Δ.
pub(super) fn usv(p: &TeamProblem, m: &mut Assembly, r: &Trajectory, radius: f64, k: usize) {
    let row = m.row(radius);
    m.group(TRUST, row);
    for i in 0..2 {
        let row = m.row(r.usv_p[k][i]);
        m.a.push(row, p.layout.usv_p(k) + i, 1.0);
    }
    m.cones.push(SecondOrderConeT(3));
}
