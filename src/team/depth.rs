//! The depth rating (ours; the paper has none): every AUV keeps z ≥ −D, D = `auv.max_depth`
//! (a REMUS 100 is rated to 100 m), one linear row per AUV and step k = 1..=K with its slack
//! ν_d ≥ 0 priced by the SCP's penalty: −z − ν_d ≤ D.
//!
//! Rows at the waypoints suffice: the plan's path between two waypoints is the straight segment
//! (as the floor rows, the checker and the simulator's guidance take it), whose points are
//! convex combinations of its ends, and the half-space z ≥ −D is convex. (The ZOH state
//! between waypoints departs from the segment by less than a metre at the default δ = 100 s:
//! the heave settles within 1/e_z ≈ 2.5 s.) The slack lets a reference that breaks the rating
//! (a window starting deeper, a first guess over a deep floor) still give a model that solves.

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;

/// Metres by which the model keeps the rating tightened, so that the solver's tolerance cannot
/// leave a waypoint a hair below it.
pub(super) const DEPTH_MARGIN: f64 = 1e-3;

/// The depth rating's rows and their violation for one AUV waypoint: z ≥ −D.
#[derive(Debug, Clone, Copy)]
pub struct DepthRule {
    /// D, metres.
    pub max_depth: f64,
}

impl DepthRule {
    /// How far below the rating (m) a waypoint at height `z` is: 0 when it keeps it.
    pub fn violation(&self, z: f64) -> f64 {
        (-z - self.max_depth).max(0.0)
    }

    /// The model's row, −z − ν ≤ b: its right-hand side.
    pub fn bound(&self) -> f64 {
        self.max_depth - DEPTH_MARGIN
    }
}

/// The rule of `p`'s scenario.
pub(super) fn rule(p: &TeamProblem) -> DepthRule {
    DepthRule {
        max_depth: p.scenario.auv.max_depth,
    }
}

/// The slacks' price: the SCP's penalty λ per metre.
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.penalise(l.depth_slack(n, k), 1.0, penalty);
        }
    }
}

/// −z_n\[k\] − ν_d\[n\]\[k\] ≤ D − margin, and ν_d ≥ 0 (nonnegative cone), k = 1..=K.
pub(super) fn rows(p: &TeamProblem, m: &mut Assembly) {
    let l = p.layout;
    let b = rule(p).bound();
    for n in 0..l.n {
        for k in 1..=l.k {
            let row = m.row(b);
            m.a.push(row, l.auv_p(n, k) + 2, -1.0);
            m.a.push(row, l.depth_slack(n, k), -1.0);
            m.nonnegative(l.depth_slack(n, k));
        }
    }
}

/// The true violation of AUV n at step k, metres below the rating.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> f64 {
    rule(p).violation(t.auv_p[n][k][2])
}

/// The message of AUV n at step k, `excess` metres below the rating.
pub(super) fn detail(p: &TeamProblem, n: usize, k: usize, excess: f64) -> String {
    format!(
        "depth rating: AUV {n} at step {k} is {excess:.3} m below auv.max_depth = {} m",
        p.scenario.auv.max_depth
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The row (with its slack at its least, max(0, row)) charges exactly the true
        /// violation, up to the margin, at any point: the rule is linear.
        #[test]
        fn the_row_charges_the_true_violation(d in 1.0..500.0f64, z in -1000.0..0.0f64) {
            let r = DepthRule { max_depth: d };
            let slack = (-z - r.bound()).max(0.0);
            prop_assert!((slack - r.violation(z)).abs() <= DEPTH_MARGIN + 1e-12);
            prop_assert!(slack >= r.violation(z));
            prop_assert_eq!(r.violation(z) == 0.0, z >= -d);
        }
    }
}
