//! Speed limits, second-order cones: the USV's ‖U_USV[k]‖ ≤ its top speed (its input is a
//! velocity, eq. (9)), and C1_7, ‖V_n[k]‖ ≤ V_max for every AUV. Both are convex and hard in
//! the model, tightened by [`SPEED_MARGIN`].

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

/// Relative margin by which the model tightens the speed limits, so that the solver's own
/// residuals cannot leave a limit violated beyond the checker's 1e-6 tolerance.
const SPEED_MARGIN: f64 = 1e-6;

/// How an infeasible USV speed limit is named.
const USV_SPEED: &str = "the USV speed limit of eq. (9)";
/// How an infeasible C1_7 is named.
const AUV_SPEED: &str = "C1_7 (AUV speed limit)";

/// The true violations at step k: the USV's speed beyond its limit (its input k − 1) and each
/// AUV's beyond V_max (C1_7), m/s, the largest. The model holds both hard, so only a first
/// guess can violate them.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, k: usize) -> f64 {
    let s = p.scenario;
    let u = t.usv_u[k - 1];
    let mut worst = (u[0].hypot(u[1]) - s.usv.max_speed).max(0.0);
    for v in &t.auv_v {
        let v = v[k];
        let speed = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        worst = worst.max(speed - s.auv.max_speed);
    }
    worst
}

/// ‖U_USV[k]‖ ≤ the USV's top speed, k = 0..K.
pub(super) fn usv(p: &TeamProblem, m: &mut Assembly, k: usize) {
    let l = p.layout;
    let row = m.row(p.scenario.usv.max_speed * (1.0 - SPEED_MARGIN));
    m.group(USV_SPEED, row);
    for i in 0..2 {
        let row = m.row(0.0);
        m.a.push(row, l.usv_u(k) + i, 1.0);
    }
    m.cones.push(SecondOrderConeT(3));
}

/// C1_7: ‖V_n[k]‖ ≤ V_max, k = 1..=K.
pub(super) fn auv(p: &TeamProblem, m: &mut Assembly, n: usize, k: usize) {
    let l = p.layout;
    let row = m.row(p.scenario.auv.max_speed * (1.0 - SPEED_MARGIN));
    m.group(AUV_SPEED, row);
    for i in 0..3 {
        let row = m.row(0.0);
        m.a.push(row, l.auv_v(n, k) + i, 1.0);
    }
    m.cones.push(SecondOrderConeT(4));
}
