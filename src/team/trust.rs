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

use super::layout::Layout;
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
/// segment 1. `bent[s]` says whether segment s (`segment(layout, n, k)`) has a floor row with a
/// curvature term: a segment without one leaves its pair of τ unbound from the step (τ ≥ 0,
/// its entries in the cone zero, so that the pattern stays), and [`proximal`] prices the step
/// in P instead.
pub(super) fn squared_steps(
    p: &TeamProblem,
    m: &mut Assembly,
    r: &Trajectory,
    bent: &[bool],
    n: usize,
    k: usize,
) {
    let l = p.layout;
    let of = |s: usize| Some((r, n, k, bent[segment(l, n, s)]));
    square(p, m, l.end_square(n, k), of(k));
    if k < l.k {
        square(p, m, l.start_square(n, k + 1), of(k + 1));
    }
    if k == 1 {
        square(p, m, l.start_square(n, 1), None);
    }
}

/// The index of segment k − 1 → k of AUV n (k = 1..=K) in the flags `floor::rows` returns.
pub(super) fn segment(l: Layout, n: usize, k: usize) -> usize {
    n * l.k + (k - 1)
}

/// τ (column `tau`) ≥ ‖P_n,xy[k] − P̄_n,xy[k]‖² / d_s for `of` = (r, n, k, true), τ ≥ 0 for
/// None or (…, false), as the second-order cone ‖(2·(P_xy − P̄_xy), τ − d_s)‖ ≤ τ + d_s.
fn square(
    p: &TeamProblem,
    m: &mut Assembly,
    tau: usize,
    of: Option<(&Trajectory, usize, usize, bool)>,
) {
    let l = p.layout;
    let c = p.scenario.acoustic.sonar_range;
    let row = m.row(c);
    m.a.push(row, tau, -1.0);
    for i in 0..2 {
        match of {
            Some((r, n, k, bound)) => {
                let row = m.row(if bound { -2.0 * r.auv_p[n][k][i] } else { 0.0 });
                m.a.push(row, l.auv_p(n, k) + i, if bound { -2.0 } else { 0.0 });
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

/// For every τ that [`squared_steps`] leaves unbound (a segment without a bent floor row), its
/// price in P instead: TAU_PRICE·‖P_n,xy[k] − P̄_n,xy[k]‖²/d_s, what the price of τ at its
/// bound would be. The entries are in P's pattern for every waypoint (zero where both of a
/// waypoint's τ are bound).
///
/// Why not leave τ bound and priced everywhere: where nothing else needs τ, the solver meets the
/// cone ‖(2d, τ − d_s)‖ ≤ τ + d_s near d = 0, τ = 0, and resolves d only to about the square
/// root of its tolerance (on a flat floor, horizontal inputs of 4·10⁻⁷ m/s² where the optimum
/// has none). Why not drop the price with the binding: the proximal pull kept the SCP's steps
/// short where the floor is flat, and without it the median gap to the converged optimum at
/// N = 5 was 1.63 % against 0.81 % (docs/design-decisions.md, "The floor rows").
pub(super) fn proximal(p: &TeamProblem, m: &mut Assembly, r: &Trajectory, bent: &[bool]) {
    let l = p.layout;
    let per_tau = TAU_PRICE / p.scenario.acoustic.sonar_range;
    for n in 0..l.n {
        for k in 1..=l.k {
            // the waypoint's τ: segment k's end, and segment k + 1's start
            let mut unbound = usize::from(!bent[segment(l, n, k)]);
            if k < l.k {
                unbound += usize::from(!bent[segment(l, n, k + 1)]);
            }
            let w = unbound as f64 * per_tau;
            for i in 0..2 {
                let (col, at) = (l.auv_p(n, k) + i, r.auv_p[n][k][i]);
                // w·(x − x̄)² = ½(2w)x² − 2w·x̄·x + w·x̄²
                m.p.push(col, col, 2.0 * w);
                m.q[col] -= 2.0 * w * at;
                m.constant += w * at * at;
            }
        }
    }
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

    /// `f` of one AUV's problem (K = 3, the default scenario's first window) and its first
    /// guess, the reference.
    fn with_problem<R>(f: impl FnOnce(&TeamProblem, Trajectory) -> R) -> R {
        let mut s = Scenario::default();
        s.team.auvs = 1;
        s.horizon.steps = 3;
        let (floor, _) = scenario_floor(&s, std::path::Path::new("")).unwrap();
        let keep_out = floor.keep_out();
        let p = TeamProblem::first_window(&s, &floor, &keep_out).unwrap();
        let r = p.initial_guess(None);
        f(&p, r)
    }

    /// Where no floor row is bent, τ is bound to nothing (its cone's step entries zero) and the
    /// step's price is in P: at a waypoint moved by d, ½xᵀPx + qᵀx + constant is
    /// TAU_PRICE·‖d‖²/d_s per unbound τ (two at an inner waypoint, one at the last).
    #[test]
    fn an_unbound_squared_step_is_priced_in_p() {
        with_problem(|p, r| unbound_priced_in_p(p, &r));
    }

    fn unbound_priced_in_p(p: &TeamProblem, r: &Trajectory) {
        let l = p.layout;
        let mut m = super::super::model::Assembly::new(l.variables());
        // segment 3 bent, segments 1 and 2 not
        let bent = vec![false, false, true];
        squared_steps(p, &mut m, r, &bent, 0, 1);
        // segment 1's end and segment 2's start: no step entry holds a value
        for i in 0..m.a.len() {
            let col = m.a.cols[i];
            if col == l.auv_p(0, 1) || col == l.auv_p(0, 1) + 1 {
                assert_eq!(m.a.vals[i], 0.0);
            }
        }
        proximal(p, &mut m, r, &bent);
        let (dx, dy) = (30.0, -40.0);
        let value = |k: usize| {
            let mut x = vec![0.0; l.variables()];
            for kk in 1..=l.k {
                x[l.auv_p(0, kk)] = r.auv_p[0][kk][0];
                x[l.auv_p(0, kk) + 1] = r.auv_p[0][kk][1];
            }
            x[l.auv_p(0, k)] += dx;
            x[l.auv_p(0, k) + 1] += dy;
            let mut v = m.constant;
            for i in 0..m.p.len() {
                v += 0.5 * m.p.vals[i] * x[m.p.rows[i]] * x[m.p.cols[i]];
            }
            v + m.q.iter().zip(&x).map(|(q, x)| q * x).sum::<f64>()
        };
        let per_tau = TAU_PRICE * (dx * dx + dy * dy) / p.scenario.acoustic.sonar_range;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
        // waypoint 1: segment 1's end and segment 2's start, both unbound
        assert!(close(value(1), 2.0 * per_tau), "{}", value(1));
        // waypoint 2: segment 2's end unbound, segment 3's start bound
        assert!(close(value(2), per_tau), "{}", value(2));
        // waypoint 3 (the last): segment 3's end, bound
        assert!(close(value(3), 0.0), "{}", value(3));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The rows of `squared_steps`, evaluated (s = b − A·x) at a waypoint moved by d from the
        /// reference, lie on each cone's boundary at τ = ‖d‖²/d_s and outside it below.
        #[test]
        fn the_squared_step_cone_holds_tau_at_the_square(
            dx in -500.0..500.0f64, dy in -500.0..500.0f64, below in 0.0..0.999f64,
        ) {
            with_problem(|p, r| square_at(p, &r, dx, dy, below))?;
        }
    }

    /// The body of `the_squared_step_cone_holds_tau_at_the_square`.
    fn square_at(
        p: &TeamProblem,
        r: &Trajectory,
        dx: f64,
        dy: f64,
        below: f64,
    ) -> Result<(), TestCaseError> {
        let s = p.scenario;
        let l = p.layout;
        let mut m = super::super::model::Assembly::new(l.variables());
        let bent = vec![true; l.n * l.k];
        squared_steps(p, &mut m, r, &bent, 0, 2);
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
        Ok(())
    }
}
