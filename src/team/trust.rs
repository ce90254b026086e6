//! The SCvx trust region (`scp`): the model is trusted only within Δ of the reference, on each
//! AUV's horizontal position per step, ‖P_n,xy[k] − P̄_n,xy[k]‖ ≤ Δ, and over a grid with
//! obstacles, whose USV keep-out rows are linearised too, on the USV's.
//!
//! Each segment k − 1 → k of an AUV also has the squared steps of its ends,
//! τ ≥ ‖P_xy − P̄_xy‖²/d_s (second-order cones, [`squared_steps`]), which its floor rows price
//! (their curvature term, `floor::rows`). Each segment has its own pair: one τ per waypoint,
//! shared by the rows of the two segments that meet there, made the interior-point method's
//! factor fill in (at N = 5, P5's multiply-adds per factorisation 2.61·10⁶ against 1.29·10⁶
//! without τ; with a pair per segment, 1.31·10⁶). (The trust region held as τ ≤ Δ²/d_s
//! instead of its own cone saved a cone, but at the largest radii a solve then took 52–85
//! interior-point iterations instead of 31–35.)

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

/// How an infeasible trust region is named.
const TRUST: &str = "the trust region about the previous iterate";

/// Price of τ per metre: only enough that the solver keeps τ at ‖P_xy − P̄_xy‖²/d_s where no
/// floor row needs more (10⁻³ per metre: 0.07 for a step of 100 m at d_s = 150 m, against
/// objectives of 10³–10⁴): no other term bounds it from above.
const TAU_PRICE: f64 = 1e-3;

/// τ's price (see `TAU_PRICE`).
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly) {
    let l = p.layout;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.q[l.end_square(n, k)] = TAU_PRICE;
            m.q[l.start_square(n, k)] = TAU_PRICE;
        }
    }
}

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

/// The squared step of P_n[k], τ ≥ ‖P_n,xy[k] − P̄_n,xy[k]‖² / d_s, for the rows of segment k
/// (its end) and of segment k + 1 (its start, k < K); at k = 1 also the fixed start's (0) for
/// segment 1.
pub(super) fn squared_steps(p: &TeamProblem, m: &mut Assembly, r: &Trajectory, n: usize, k: usize) {
    let l = p.layout;
    square(p, m, l.end_square(n, k), Some((r, n, k)));
    if k < l.k {
        square(p, m, l.start_square(n, k + 1), Some((r, n, k)));
    }
    if k == 1 {
        square(p, m, l.start_square(n, 1), None);
    }
}

/// τ (column `tau`) ≥ ‖P_n,xy[k] − P̄_n,xy[k]‖² / d_s for `of` = (r, n, k), τ ≥ 0 for None, as
/// the second-order cone ‖(2·(P_xy − P̄_xy), τ − d_s)‖ ≤ τ + d_s.
fn square(p: &TeamProblem, m: &mut Assembly, tau: usize, of: Option<(&Trajectory, usize, usize)>) {
    let l = p.layout;
    let c = p.scenario.acoustic.sonar_range;
    let row = m.row(c);
    m.a.push(row, tau, -1.0);
    for i in 0..2 {
        match of {
            Some((r, n, k)) => {
                let row = m.row(-2.0 * r.auv_p[n][k][i]);
                m.a.push(row, l.auv_p(n, k) + i, -2.0);
            }
            None => {
                m.row(0.0);
            }
        }
    }
    let row = m.row(-c);
    m.a.push(row, tau, -1.0);
    m.cones.push(SecondOrderConeT(4));
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mission::scenario_floor;
    use crate::scenario::Scenario;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The rows of `squared_steps`, evaluated (s = b − A·x) at a waypoint moved by d from the
        /// reference, lie on each cone's boundary at τ = ‖d‖²/d_s and outside it below.
        #[test]
        fn the_squared_step_cone_holds_tau_at_the_square(
            dx in -500.0..500.0f64, dy in -500.0..500.0f64, below in 0.0..0.999f64,
        ) {
            let mut s = Scenario::default();
            s.team.auvs = 1;
            s.horizon.steps = 3;
            let (floor, _) = scenario_floor(&s, std::path::Path::new("")).unwrap();
            let keep_out = floor.keep_out();
            let p = TeamProblem::first_window(&s, &floor, &keep_out).unwrap();
            let r = p.initial_guess(None);
            let l = p.layout;
            let mut m = super::super::model::Assembly {
                p: Default::default(),
                q: vec![0.0; l.variables()],
                a: Default::default(),
                b: Vec::new(),
                cones: Vec::new(),
                constant: 0.0,
                groups: Vec::new(),
            };
            squared_steps(&p, &mut m, &r, 0, 2);
            // two cones: segment 2's end (τ) and segment 3's start (τ'), the same square
            assert_eq!(m.b.len(), 8);
            let mut x = vec![0.0; l.variables()];
            let c = s.acoustic.sonar_range;
            let at = |x: &mut Vec<f64>, tau: f64, cone: usize| {
                x[l.auv_p(0, 2)] = r.auv_p[0][2][0] + dx;
                x[l.auv_p(0, 2) + 1] = r.auv_p[0][2][1] + dy;
                x[l.end_square(0, 2)] = tau;
                x[l.start_square(0, 3)] = tau;
                let mut slack = m.b.clone();
                for i in 0..m.a.len() {
                    slack[m.a.rows[i]] -= m.a.vals[i] * x[m.a.cols[i]];
                }
                let s = &slack[4 * cone..4 * cone + 4];
                s[0] - (s[1].powi(2) + s[2].powi(2) + s[3].powi(2)).sqrt()
            };
            let tau = (dx * dx + dy * dy) / c;
            for cone in 0..2 {
                prop_assert!(at(&mut x, tau, cone).abs() <= 1e-9 * (tau + c));
                if tau > 1e-3 {
                    prop_assert!(at(&mut x, below * tau, cone) < 0.0);
                }
            }
        }
    }
}
