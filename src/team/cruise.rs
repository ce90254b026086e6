//! The cruise floor (ours; the paper has none): from step 1 on every AUV's horizontal speed
//! through the water stays at least v_c = `auv.min_speed`. A REMUS 100 cruises at ~1.5 m/s and
//! its fins lose authority below ~1 m/s: flown by `shoal simulate`, plans that let AUVs stop
//! mid-window (C1_14's "slow" alternatives did) or creep at 0.6–1.1 m/s sank into the floor.
//!
//! ‖V_h‖ ≥ v_c is not convex. About the reference the model keeps the convex restriction
//! d̂·V_h ≥ v̂ (d̂·V_h ≤ ‖V_h‖), d̂ the direction of the reference's V̄_h\[k\] (`direction`), as
//! C1_14's rows are built about a reference; its slack ν_c ≥ 0 is priced by the SCP's penalty
//! (per m/s, times δ, as the heading slacks). At the reference the row charges exactly the
//! true shortfall.
//!
//! The floor holds along each segment too: under the zero-order hold V_h(t) runs along the
//! straight line from V_h\[k−1\] to V_h\[k\] (`vehicle`), and between two velocities of speed at
//! least v̂ that turn by at most θ = ψ̇_max·δ (C1_14) the speed stays at least v̂·cos(θ/2). So
//! the waypoints keep v̂ = v_c / cos(θ/2). The first segment of a window that starts slower
//! (the mission's start, at rest) is the ramp up to cruise: V\[0\] is data, only V\[1\] is held.
//! V is the velocity through the water: the current (`team::drift`) moves the position only.

use super::heading::h2;
use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;

/// Relative margin by which the model raises the floor, so that the solver's tolerance cannot
/// leave a speed a hair below it.
const CRUISE_MARGIN: f64 = 1e-4;

/// Below this speed (m/s) a reference velocity has no direction to linearise about.
const NO_DIRECTION: f64 = 1e-6;

/// The cruise floor of one scenario.
#[derive(Debug, Clone, Copy)]
pub struct CruiseRule {
    /// v_c, m/s (0: no floor).
    pub min_speed: f64,
    /// θ = ψ̇_max·δ, the largest turn per step (rad).
    pub turn: f64,
}

impl CruiseRule {
    /// Whether the floor applies.
    pub fn on(&self) -> bool {
        self.min_speed > 0.0
    }

    /// v̂ = v_c / cos(θ/2), tightened by the margin: what the waypoints keep so that every
    /// point of a segment keeps v_c (module documentation). θ is taken at most π/2, beyond
    /// which C1_14 bounds nothing the floor could use.
    pub fn waypoint_floor(&self) -> f64 {
        let half = (0.5 * self.turn).min(std::f64::consts::FRAC_PI_4);
        self.min_speed / half.cos() * (1.0 + CRUISE_MARGIN)
    }

    /// The shortfall (m/s) of a horizontal velocity `v` below v̂: 0 when it keeps it.
    pub fn violation(&self, v: [f64; 2]) -> f64 {
        if !self.on() {
            return 0.0;
        }
        (self.waypoint_floor() - v[0].hypot(v[1])).max(0.0)
    }

    /// The model's row about the unit direction `d`: −d·V_h − ν ≤ −v̂, as (coefficients on
    /// V_h, right-hand side).
    pub fn row(&self, d: [f64; 2]) -> ([f64; 2], f64) {
        ([-d[0], -d[1]], -self.waypoint_floor())
    }
}

/// The rule of `p`'s scenario.
pub(super) fn rule(p: &TeamProblem) -> CruiseRule {
    let s = p.scenario;
    CruiseRule {
        min_speed: s.auv.min_speed,
        turn: s.auv.max_heading_rate * s.horizon.dt,
    }
}

fn unit(v: [f64; 2]) -> Option<[f64; 2]> {
    let n = v[0].hypot(v[1]);
    (n >= NO_DIRECTION && n.is_finite()).then(|| [v[0] / n, v[1] / n])
}

/// d̂ for AUV n at step k about the reference `r`: the direction of V̄_h\[k\]; where that is
/// (nearly) zero, of V̄_h\[k−1\], then of the USV's velocity over step k, then east.
pub(super) fn direction(r: &Trajectory, n: usize, k: usize) -> [f64; 2] {
    unit(h2(r.auv_v[n][k]))
        .or_else(|| unit(h2(r.auv_v[n][k - 1])))
        .or_else(|| unit(r.usv_u[k - 1]))
        .unwrap_or([1.0, 0.0])
}

/// The slacks' price: the SCP's penalty λ per m/s, times δ (m/s → m over one step).
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    let dt = p.scenario.horizon.dt;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.penalise(l.cruise_slack(n, k), dt, penalty);
        }
    }
}

/// −d̂·V_h,n\[k\] − ν_c\[n\]\[k\] ≤ −v̂ about `r`, and ν_c ≥ 0 (nonnegative cone), k = 1..=K;
/// without a floor, the padding rows of the same pattern.
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let l = p.layout;
    let rule = rule(p);
    for n in 0..l.n {
        for k in 1..=l.k {
            let (c, b) = if rule.on() {
                rule.row(direction(r, n, k))
            } else {
                ([0.0; 2], super::model::INACTIVE)
            };
            let row = m.row(b);
            m.a.push(row, l.auv_v(n, k), c[0]);
            m.a.push(row, l.auv_v(n, k) + 1, c[1]);
            m.a.push(row, l.cruise_slack(n, k), -1.0);
            m.nonnegative(l.cruise_slack(n, k));
        }
    }
}

/// The true violation of AUV n at step k: its horizontal speed's shortfall below v̂, m/s.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> f64 {
    rule(p).violation(h2(t.auv_v[n][k]))
}

/// The message of AUV n at step k, `short` m/s below the floor.
pub(super) fn detail(p: &TeamProblem, n: usize, k: usize, short: f64) -> String {
    let rule = rule(p);
    format!(
        "cruise floor: AUV {n} at step {k} goes {short:.3} m/s slower through the water than \
         auv.min_speed = {} m/s (held at the waypoints as {:.3} m/s so that it holds between \
         them)",
        rule.min_speed,
        rule.waypoint_floor()
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn rule() -> CruiseRule {
        CruiseRule {
            min_speed: 1.0,
            turn: 0.5,
        }
    }

    fn polar(speed: f64, psi: f64) -> [f64; 2] {
        [speed * psi.cos(), speed * psi.sin()]
    }

    /// The least speed on the segment from a to b.
    fn least_on_segment(a: [f64; 2], b: [f64; 2]) -> f64 {
        let d = [b[0] - a[0], b[1] - a[1]];
        let dd = d[0] * d[0] + d[1] * d[1];
        let t = if dd > 0.0 {
            (-(a[0] * d[0] + a[1] * d[1]) / dd).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a[0] + t * d[0]).hypot(a[1] + t * d[1])
    }

    proptest! {
        /// About any reference, the row (slack at its least) charges at least the true
        /// violation at any point (a restriction), and exactly it at the reference.
        #[test]
        fn the_row_is_a_restriction_exact_at_the_reference(
            rs in 0.01..2.0f64, rpsi in -3.2..3.2f64, s in 0.0..2.0f64, psi in -3.2..3.2f64,
        ) {
            let r = rule();
            let reference = polar(rs, rpsi);
            let d = unit(reference).unwrap();
            let (c, b) = r.row(d);
            let charge = |v: [f64; 2]| (c[0] * v[0] + c[1] * v[1] - b).max(0.0);
            let v = polar(s, psi);
            prop_assert!(charge(v) >= r.violation(v) - 1e-12);
            prop_assert!((charge(reference) - r.violation(reference)).abs() < 1e-12);
        }

        /// Two waypoints that keep v̂ and turn within θ keep v_c along their whole segment.
        #[test]
        fn waypoints_at_the_floor_keep_it_along_the_segment(
            sa in 0.0..0.5f64, sb in 0.0..0.5f64, psi in -3.2..3.2f64, turn in -0.5..0.5f64,
        ) {
            let r = rule();
            let v = r.waypoint_floor();
            let (a, b) = (polar(v + sa, psi), polar(v + sb, psi + turn));
            prop_assert!(least_on_segment(a, b) >= r.min_speed);
        }
    }

    /// Without a floor nothing is charged.
    #[test]
    fn no_floor_no_violation() {
        let r = CruiseRule {
            min_speed: 0.0,
            turn: 0.5,
        };
        assert_eq!(r.violation([0.0, 0.0]), 0.0);
    }
}
