//! The flight-path angle (ours; the paper has none): every AUV climbs or dives through the
//! water at most γ_max = `auv.max_flight_path_angle` from the horizontal, |V_z| ≤ tan(γ_max)·‖V_h‖,
//! at every step k = 1..=K. A REMUS keeps its pitch within about ±15–20°; plans without the
//! rule climbed 88 m in 100 s and dived 44–189 m in the first 100 s from rest, which the
//! simulated vehicle could not follow.
//!
//! The rule is not convex (‖V_h‖ on the larger side). About the reference the model keeps the
//! convex restriction |V_z| ≤ t·d̂·V_h (d̂·V_h ≤ ‖V_h‖), d̂ the reference's horizontal direction
//! (`cruise::direction`), as two linear rows sharing a slack ν_γ ≥ 0 priced by the SCP's
//! penalty (per m/s, times δ):  ±V_z − t·d̂·V_h − ν_γ ≤ 0. At the reference the rows charge
//! exactly the true excess. V is the velocity through the water.
//!
//! A climb also needs speed: below `auv.level_speed` a REMUS 100 cannot even hold its depth,
//! and the climb it can sustain grows with the speed above it (docs/simulation.md, "What the
//! vehicle can fly": +4.8° at 1.25 m/s, +27° at 1.5 m/s). So from step 1 on the rule also
//! keeps V_z ≤ c·(‖V_h‖ − v_l), c = `auv.climb_per_speed`, v_l = `auv.level_speed`, a line below
//! the vehicle's sustained climbs; its convex restriction about the reference is the third row
//! V_z − c·d̂·V_h − ν_γ ≤ −c·v_l, on the same slack.

use super::cruise::direction;
use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;

/// Relative margin by which the model tightens tan(γ_max).
const CLIMB_MARGIN: f64 = 1e-4;

/// The flight-path angle rule of one scenario.
#[derive(Debug, Clone, Copy)]
pub struct ClimbRule {
    /// γ_max, rad.
    pub max_angle: f64,
    /// v_l, m/s: the slowest level flight.
    pub level_speed: f64,
    /// c: climb rate per m/s above v_l.
    pub climb_per_speed: f64,
    /// Whether the cruise floor is on (`auv.min_speed` > 0): the climb line belongs to a vehicle
    /// that flies on its fins; with the floor off (a vehicle that can hover) only the angle holds.
    pub cruising: bool,
}

impl ClimbRule {
    /// Whether the angle is limited at all (`auv.max_flight_path_angle` below
    /// [`NO_ANGLE_LIMIT`](crate::scenario::NO_ANGLE_LIMIT)).
    pub fn limited(&self) -> bool {
        self.max_angle < crate::scenario::NO_ANGLE_LIMIT
    }

    /// tan(γ_max) as the model holds it (tightened); infinite without a limit.
    pub fn slope(&self) -> f64 {
        if self.limited() {
            self.max_angle.tan() * (1.0 - CLIMB_MARGIN)
        } else {
            f64::INFINITY
        }
    }

    /// c as the model holds it (tightened).
    pub fn climb_slope(&self) -> f64 {
        self.climb_per_speed * (1.0 - CLIMB_MARGIN)
    }

    /// The excess (m/s) of |V_z| over tan(γ_max)·‖V_h‖ and of V_z over c·(‖V_h‖ − v_l)
    /// (tightened), the larger: 0 when the rule holds.
    pub fn violation(&self, v: [f64; 3]) -> f64 {
        let h = v[0].hypot(v[1]);
        let angle = if self.limited() {
            v[2].abs() - self.slope() * h
        } else {
            0.0
        };
        let climb = if self.cruising {
            v[2] - self.climb_slope() * (h - self.level_speed)
        } else {
            0.0
        };
        angle.max(climb).max(0.0)
    }

    /// The three rows a·V ≤ b + ν about the unit direction `d`: ±V_z − t·d̂·V_h ≤ ν and
    /// V_z − c·d̂·V_h ≤ −c·v_l + ν, as (coefficients on (V_x, V_y, V_z), b).
    pub fn rows(&self, d: [f64; 2]) -> [([f64; 3], f64); 3] {
        // without an angle limit its rows are empty (0 ≤ ν), the pattern kept
        let t = self.slope();
        let c = self.climb_slope();
        let none = ([0.0; 3], 0.0);
        if !self.limited() {
            let line = ([-c * d[0], -c * d[1], 1.0], -c * self.level_speed);
            return [none, none, if self.cruising { line } else { none }];
        }
        // with the cruise floor off the third row repeats the first
        if !self.cruising {
            let up = ([-t * d[0], -t * d[1], 1.0], 0.0);
            return [up, ([-t * d[0], -t * d[1], -1.0], 0.0), up];
        }
        [
            ([-t * d[0], -t * d[1], 1.0], 0.0),
            ([-t * d[0], -t * d[1], -1.0], 0.0),
            ([-c * d[0], -c * d[1], 1.0], -c * self.level_speed),
        ]
    }
}

/// The rule of `p`'s scenario.
pub(super) fn rule(p: &TeamProblem) -> ClimbRule {
    let auv = &p.scenario.auv;
    ClimbRule {
        max_angle: auv.max_flight_path_angle,
        // level flight is always allowed at the cruise floor: a floor below v_l (another
        // vehicle's) lowers v_l to it
        level_speed: auv.level_speed.min(auv.min_speed),
        climb_per_speed: auv.climb_per_speed,
        cruising: auv.min_speed > 0.0,
    }
}

/// The slacks' price: the SCP's penalty λ per m/s, times δ (m/s → m over one step).
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    let dt = p.scenario.horizon.dt;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.penalise(l.climb_slack(n, k), dt, penalty);
        }
    }
}

/// ±V_z − t·d̂·V_h − ν_γ ≤ 0 about `r` for every AUV and step k = 1..=K, and ν_γ ≥ 0
/// (nonnegative cone).
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let l = p.layout;
    let rule = rule(p);
    for n in 0..l.n {
        for k in 1..=l.k {
            for (c, b) in rule.rows(direction(r, n, k)) {
                let row = m.row(b);
                for (i, ci) in c.into_iter().enumerate() {
                    m.a.push(row, l.auv_v(n, k) + i, ci);
                }
                m.a.push(row, l.climb_slack(n, k), -1.0);
            }
            m.nonnegative(l.climb_slack(n, k));
        }
    }
}

/// The true violation of AUV n at step k, m/s of vertical speed beyond the angle.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> f64 {
    rule(p).violation(t.auv_v[n][k])
}

/// The message of AUV n at step k, `excess` m/s beyond the angle.
pub(super) fn detail(p: &TeamProblem, t: &Trajectory, n: usize, k: usize, excess: f64) -> String {
    let v = t.auv_v[n][k];
    let angle = v[2].atan2(v[0].hypot(v[1])).to_degrees();
    let auv = &p.scenario.auv;
    format!(
        "flight-path angle: AUV {n} at step {k} climbs or dives at {angle:.1}° through the \
         water at {:.2} m/s ({excess:.3} m/s of vertical speed beyond auv.max_flight_path_angle \
         = {} rad, or beyond the climb auv.climb_per_speed = {} × (speed − auv.level_speed = \
         {} m/s))",
        v[0].hypot(v[1]),
        auv.max_flight_path_angle,
        auv.climb_per_speed,
        auv.level_speed
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// About any reference, the rows (slack at its least) charge at least the true
        /// violation at any point (a restriction), and exactly it at the reference.
        #[test]
        fn the_rows_are_a_restriction_exact_at_the_reference(
            rs in 0.01..2.0f64, rpsi in -3.2..3.2f64, rz in -1.0..1.0f64,
            s in 0.0..2.0f64, psi in -3.2..3.2f64, z in -1.0..1.0f64,
            angle in 0.05..1.4f64, level in 0.0..1.5f64, per in 0.1..3.0f64,
        ) {
            let r = ClimbRule {
                max_angle: angle, level_speed: level, climb_per_speed: per, cruising: true,
            };
            let reference = [rs * rpsi.cos(), rs * rpsi.sin(), rz];
            let d = [rpsi.cos(), rpsi.sin()];
            let rows = r.rows(d);
            let charge = |v: [f64; 3]| {
                rows.iter()
                    .map(|(c, b)| c[0] * v[0] + c[1] * v[1] + c[2] * v[2] - b)
                    .fold(0.0f64, f64::max)
            };
            let v = [s * psi.cos(), s * psi.sin(), z];
            prop_assert!(charge(v) >= r.violation(v) - 1e-12);
            prop_assert!((charge(reference) - r.violation(reference)).abs() < 1e-12);
            // the rule holds exactly when |γ| ≤ γ_max and the climb is within the line
            // (tightened)
            let gamma = z.atan2(s).abs();
            let limit = r.slope().atan();
            let climb = z - r.climb_slope() * (s - level);
            if (gamma - limit).abs() > 1e-9 && climb.abs() > 1e-9 {
                prop_assert_eq!(r.violation(v) == 0.0, gamma < limit && climb < 0.0);
            }
        }
    }
}
