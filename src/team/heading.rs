//! C1_14 (heading rate) as a disjunction, its continuous violation and its convex model.
//!
//! The heading ψ = atan2(V_y, V_x) is defined only while the horizontal speed is at least
//! v_min (`auv.min_heading_speed`), and the checker (like the paper's recovery of ψ after
//! eq. (8)) bounds a turn only between two velocities that both have a heading. So for
//! a = V_h[k−1], b = V_h\[k\] the constraint is the disjunction
//!
//!   ‖a‖ < v_min   or   ‖b‖ < v_min   or   ∠(a, b) ≤ θ = ψ̇_max·δ.
//!
//! The SCP needs a violation that is continuous, else it cannot see that an AUV at 0.1006 m/s
//! reversing is almost feasible (slow it by 0.6 mm/s) while one at 0.0999 m/s is feasible
//! (docs/design-decisions.md, "The heading rule", has what a jumping measure did). Here the violation is
//!
//!   v(a, b) = max(0, min(g(a, b), ‖a‖ − v̲, ‖b‖ − v̲))   (m/s),
//!
//! with g = max(g₊, g₋) of `linearise::Heading`, which is positive exactly when the turn
//! exceeds θ. v is zero exactly when one of the three alternatives holds. The measure uses
//! the model's tightened θ (`HEADING_MARGIN`) and the slow bound v̲ = v_min·(1 −
//! `SLOW_MARGIN`), the rule every piece restricts to, so that the model and the measure agree
//! on which references are feasible; where ā is the window's fixed start the ‖a‖ − v̲ term
//! is left out (no step can slow it). The checker measures the true θ and v_min
//! (`HeadingRule::excess`), which the tightened rule implies.
//!
//! The convex model keeps, about the reference (ā, b̄), one alternative (`Piece`): the turn
//! (`Piece::Turn`) when the reference turns within θ and ā has a direction, otherwise
//! whichever alternative the reference is nearest to satisfying. Every piece but a turn the
//! reference breaks is a convex restriction of the disjunction, so a model solution that meets
//! it meets C1_14 (no linearisation error for the SCP to reject):
//! - Turn, k ≥ 2: both a and b within θ/2 of the bisector d̂ of (ā, b̄) (`HeadingRule::axis`),
//!   two linear rows each: ±(d̂ × v) − tan(θ/2)·(d̂·v) ≤ ν. The angle between them is then at most
//!   θ, and a reference that turns within θ meets it. (A linearisation about ā's direction is
//!   poor at low speed: at 0.1–0.3 m/s a change of a few cm/s swings it by tenths of a radian.)
//!   The rows on a and on b are weighted (`HeadingRule::turn_row_weights`) so that the slack
//!   they share charges a step at least what v measures, to first order: v grows with the
//!   sum of the two velocities' turns, the shared slack with the larger row.
//! - Turn, k = 1: a = V\[0\] is the window's fixed start, so the same rows about â with the full
//!   θ are exact.
//! - Turn, k ≥ 2, where the reference breaks it (v > 0): g₊ and g₋ linearised about (ā, b̄),
//!   value and gradient (`HeadingRule::turn_gradients`). The bisector rows are a restriction,
//!   not a model of v: at a violated reference their slope differs from v's, the model's
//!   steps raised v where it promised to lower it, the trust region shrank to centimetres and
//!   Step 3 crawled 50 iterations with the chain out of band (N = 20, lanes, seed 5, window
//!   2 of 5). Once the reference turns within θ, the restriction again.
//! - Slow: the second-order cone ‖V_h‖ ≤ v_min·(1 − SLOW_MARGIN) + ν.
//!
//! θ here is the model's, tightened by [`HEADING_MARGIN`].
//!
//! With the cruise floor (`cruise`, `auv.min_speed` > 0) every velocity from step 1 on keeps a
//! speed above v_min, so the slow alternatives are gone but where the floor does not apply, the
//! window's fixed start (the mission's start at rest: `Piece::Free`). The measure is then the
//! turn alone, v = max(0, g(a, b)), and the model keeps the Turn piece (`HeadingRule::cruise`).
//! `auv.min_heading_speed` keeps its meaning: the speed below which a velocity has no heading
//! (the checker's C1_14 and the plan's recorded heading), now met only at such a start.
//!
//! Departure: this replaces the paper's C2_3/C2_4 (eq. (11)), which bound each velocity
//! component by a multiple of the same component one step earlier: a component that is zero
//! (the AUVs start at rest) would then stay zero for ever.

use super::model::{Assembly, INACTIVE};
use super::TeamProblem;
use crate::linearise::Heading;
use crate::scenario::Scenario;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

/// Turn (rad per step) the convex model keeps below ψ̇_max·δ (constraint tightening).
const HEADING_MARGIN: f64 = 0.005;

/// The alternative of the disjunction the convex model keeps for one AUV and step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Piece {
    /// No constraint: a = V\[0\] is the window's fixed start and has no heading.
    Free,
    /// The turn: a and b within θ/2 of the bisector of the reference (b within θ of a fixed a).
    Turn,
    /// ‖a‖ stays below v_min.
    SlowBefore,
    /// ‖b‖ stays below v_min.
    SlowAfter,
}

/// Relative margin by which a "slow" piece keeps the speed under v_min, so that the solver's
/// tolerance cannot leave it a hair above (where the checker would measure the turn).
pub const SLOW_MARGIN: f64 = 1e-3;

/// Below this fraction of v_min a reference velocity's direction is not linearised about: it
/// is mostly the solver's noise.
const DIRECTION_FRACTION: f64 = 0.5;

/// C1_14 for one scenario: the true θ, the model's tightened θ and v_min.
#[derive(Debug, Clone, Copy)]
pub struct HeadingRule {
    pub truth: Heading,
    pub model: Heading,
    /// tan of half the model's θ.
    half_tan: f64,
    pub v_min: f64,
    /// Whether the cruise floor (`cruise`) holds every velocity but a slow window start above
    /// v_min: then the "slow" alternatives are no alternatives (the floor forbids them), the
    /// measure is the turn alone, and the model keeps the Turn piece.
    pub cruise: bool,
}

/// The coefficients c of the two rows ±(d̂ × v) − t·(d̂·v) ≤ ν, for the unit axis d̂: c·v is the
/// row's left side. (d̂ × v = d_x v_y − d_y v_x.)
pub fn cone_rows(axis: [f64; 2], tan: f64) -> [[f64; 2]; 2] {
    let row = |sign: f64| {
        [
            -sign * axis[1] - tan * axis[0],
            sign * axis[0] - tan * axis[1],
        ]
    };
    [row(1.0), row(-1.0)]
}

fn unit(v: [f64; 2]) -> [f64; 2] {
    let n = norm(v);
    [v[0] / n, v[1] / n]
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
}

impl HeadingRule {
    /// The scenario's rule: its ψ̇_max, δ and v_min, the model's rate tightened by
    /// [`HEADING_MARGIN`].
    pub fn of(s: &Scenario) -> HeadingRule {
        let (rate, dt) = (s.auv.max_heading_rate, s.horizon.dt);
        HeadingRule::new(
            rate,
            (rate - HEADING_MARGIN / dt).max(0.0),
            dt,
            s.auv.min_heading_speed,
        )
        .with_cruise(s.auv.min_speed > 0.0)
    }

    /// The same rule with the cruise floor on or off (see [`HeadingRule::cruise`]).
    pub fn with_cruise(mut self, cruise: bool) -> HeadingRule {
        self.cruise = cruise;
        self
    }

    /// The rule for a largest turn rate `rate` (rad/s) over steps of `dt` s, the model's rate
    /// `model_rate` (tightened), and v_min.
    pub fn new(rate: f64, model_rate: f64, dt: f64, v_min: f64) -> HeadingRule {
        let model = Heading::new(model_rate, dt);
        HeadingRule {
            truth: Heading::new(rate, dt),
            model,
            half_tan: (0.5 * model.tan.atan()).tan(),
            v_min,
            cruise: false,
        }
    }

    /// The Turn piece's rows about the reference (ā, b̄): (coefficients on a, on b), each two
    /// rows of `cone_rows`; no rows on a when it is the fixed start (`fixed_before`).
    pub fn turn_rows(
        &self,
        a: [f64; 2],
        b: [f64; 2],
        fixed_before: bool,
    ) -> (Option<[[f64; 2]; 2]>, [[f64; 2]; 2]) {
        if fixed_before {
            return (None, cone_rows(unit(a), self.model.tan));
        }
        let d = self.axis(a, b);
        let rows = cone_rows(d, self.half_tan);
        let (ca, cb) = self.turn_row_weights(a, b);
        let scale = |c: f64| rows.map(|r| [c * r[0], c * r[1]]);
        (Some(scale(ca)), scale(cb))
    }

    /// The weights (c_a, c_b) of the bisector rows on a and on b, so that the slack they share
    /// charges a step away from the reference at least what the measure v does, to first
    /// order. Turning a or b by a small angle ε beyond its half-cone raises its row by
    /// ‖·‖·ε/cos(θ/2), and raises v = ‖b‖(sin φ − tan θ·cos φ) by ‖b‖·ε/cos θ whichever of the
    /// two turns; when both turn, v grows by the sum while the shared slack takes the larger
    /// row. So each row is weighted by twice the ratio of those slopes at the reference:
    /// max(c_a·x, c_b·y) ≥ x + y. Unweighted, the rows charged a step that turned both apart
    /// 0.064 m where the merit measured 0.170 m, the model promised a decrease no step gave,
    /// and Step 3 crawled to its iteration limit (N = 20, lanes, seed 4, window 1 of 2).
    /// ‖b̄‖ is taken at least v_min (v grows with ‖b‖ once b has a heading). The weights
    /// scale rows, not the set where they hold: the piece is still a restriction.
    pub fn turn_row_weights(&self, a: [f64; 2], b: [f64; 2]) -> (f64, f64) {
        let half = 0.5 * self.model.tan.atan();
        let cb = 2.0 * half.cos() / (2.0 * half).cos();
        let ca = cb * norm(b).max(self.v_min) / norm(a).max(DIRECTION_FRACTION * self.v_min);
        (ca, cb)
    }

    /// The axis of the Turn piece: the bisector of ā and b̄ (which keeps both within θ/2 of
    /// it when they turn within θ, however slow b̄ is), or ā's direction when b̄ is zero or
    /// exactly reversed (ā has a direction: `piece` keeps Turn only then).
    pub fn axis(&self, a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
        let ua = unit(a);
        if norm(b) == 0.0 {
            return ua;
        }
        let ub = unit(b);
        let sum = [ua[0] + ub[0], ua[1] + ub[1]];
        if norm(sum) < 1e-9 {
            ua // a reversal has no bisector; any axis is as good (the rows are then violated)
        } else {
            unit(sum)
        }
    }

    /// v(a, b) in m/s, the SCP's measure (see the module documentation): measured with the
    /// model's tightened θ and the slow bound v_min·(1 − SLOW_MARGIN), the rule the model's
    /// pieces restrict to, so that a reference meeting it meets its piece and the model
    /// charges it nothing (with the true θ and v_min, a reference inside the true rule but
    /// not the tightened one was free to the measure and charged by the model: N = 20, lanes,
    /// seed 3, window 2, the model predicted −72 where the floor still needed a step, and
    /// Step 3 stalled with its penalty at its limit). With a `fixed_before` (the window's
    /// start), slowing a is not an alternative: v = min(g, ‖b‖ − bound).
    pub fn violation(&self, a: [f64; 2], b: [f64; 2], fixed_before: bool) -> f64 {
        let bound = self.slow_bound();
        let (sa, sb) = (norm(a) - bound, norm(b) - bound);
        if self.cruise {
            // only the window's slow start is exempt: the floor charges any other slow speed
            if (fixed_before && sa < 0.0) || norm(a) == 0.0 {
                return 0.0;
            }
            return self.model.violation(a, b).max(0.0);
        }
        if sa < 0.0 || sb < 0.0 {
            return 0.0;
        }
        let before = if fixed_before { f64::INFINITY } else { sa };
        self.model.violation(a, b).min(before).min(sb).max(0.0)
    }

    /// The turn beyond θ (rad) between two velocities that both have a heading, else 0: what
    /// `shoal check` measures.
    pub fn excess(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        if norm(a) < self.v_min || norm(b) < self.v_min {
            return 0.0;
        }
        let angle = (a[0] * b[1] - a[1] * b[0])
            .atan2(a[0] * b[0] + a[1] * b[1])
            .abs();
        (angle - self.truth.tan.atan()).max(0.0)
    }

    /// The alternative the model keeps about the reference (ā, b̄); `fixed_before` when ā is
    /// the window's start (not a variable).
    pub fn piece(&self, a: [f64; 2], b: [f64; 2], fixed_before: bool) -> Piece {
        let bound = self.slow_bound();
        let (sa, sb) = (norm(a) - bound, norm(b) - bound);
        if fixed_before && sa < 0.0 {
            return Piece::Free;
        }
        if self.cruise {
            // the floor leaves the turn as the only alternative; a reference velocity that is
            // exactly zero has no direction to turn about (the cruise rows lift it)
            return if norm(a) == 0.0 {
                Piece::SlowBefore
            } else {
                Piece::Turn
            };
        }
        let directed = norm(a) >= DIRECTION_FRACTION * self.v_min;
        let turn = if directed {
            self.model.violation(a, b)
        } else {
            f64::INFINITY
        };
        if turn <= 0.0 {
            return Piece::Turn;
        }
        let before = if fixed_before { f64::INFINITY } else { sa };
        if turn <= before && turn <= sb {
            Piece::Turn
        } else if before <= sb {
            Piece::SlowBefore
        } else {
            Piece::SlowAfter
        }
    }

    /// g₊ and g₋ with the model's θ at (a, b) and their gradients: [(g, ∇_a g, ∇_b g); 2],
    /// g± = (±(a × b) − t·(a·b))/‖a‖. `a` must be nonzero.
    pub fn turn_gradients(&self, a: [f64; 2], b: [f64; 2]) -> [(f64, [f64; 2], [f64; 2]); 2] {
        let t = self.model.tan;
        let na = norm(a);
        let cross = a[0] * b[1] - a[1] * b[0];
        let dot = a[0] * b[0] + a[1] * b[1];
        [1.0, -1.0].map(|s| {
            let num = s * cross - t * dot;
            let dn_da = [s * b[1] - t * b[0], -s * b[0] - t * b[1]];
            let dn_db = [-s * a[1] - t * a[0], s * a[0] - t * a[1]];
            let na3 = na * na * na;
            (
                num / na,
                [
                    dn_da[0] / na - num * a[0] / na3,
                    dn_da[1] / na - num * a[1] / na3,
                ],
                [dn_db[0] / na, dn_db[1] / na],
            )
        })
    }

    /// The speed bound of a "slow" piece.
    pub fn slow_bound(&self) -> f64 {
        self.v_min * (1.0 - SLOW_MARGIN)
    }
}

/// The horizontal part of a velocity.
pub(super) fn h2(v: [f64; 3]) -> [f64; 2] {
    [v[0], v[1]]
}

/// The heading slacks' price: the SCP's penalty λ per m/s, times δ (m/s → m over one step).
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    let dt = p.scenario.horizon.dt;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.penalise(l.heading_slack(n, k), dt, penalty); // m/s → m over one step
        }
    }
}

/// The alternative of C1_14 the model keeps for each AUV n and step k = 1..=K (index k − 1),
/// about the reference `r`.
pub(super) fn pieces(p: &TeamProblem, r: &Trajectory) -> Vec<Vec<Piece>> {
    (0..p.layout.n)
        .map(|n| {
            (1..=p.layout.k)
                .map(|k| {
                    let (a, b) = (h2(r.auv_v[n][k - 1]), h2(r.auv_v[n][k]));
                    p.heading.piece(a, b, k == 1)
                })
                .collect()
        })
        .collect()
}

/// C1_14's Turn piece where the model keeps it: per AUV and step four rows on V_h[k−1] and
/// V_h\[k\] sharing ν_h\[n\]\[k\]: the restriction (two on each velocity), or where the
/// reference breaks the turn g± linearised (two rows on both); padding rows elsewhere, so the
/// pattern is fixed.
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, pieces: &[Vec<Piece>], m: &mut Assembly) {
    let l = p.layout;
    let h = &p.heading;
    let dot = |c: [f64; 2], v: [f64; 2]| c[0] * v[0] + c[1] * v[1];
    const PAD: ([f64; 2], [f64; 2], f64) = ([0.0; 2], [0.0; 2], INACTIVE);
    for n in 0..l.n {
        for k in 1..=l.k {
            let a = h2(r.auv_v[n][k - 1]);
            let b = h2(r.auv_v[n][k]);
            // four rows (coefficients on V[k−1], on V[k], rhs) sharing ν_h[n][k]
            let mut set = [PAD; 4];
            if pieces[n][k - 1] == Piece::Turn {
                let truth = h.violation(a, b, k == 1);
                if k >= 2 && truth > 0.0 {
                    // a violated turn: g± linearised about the reference, exact to first
                    // order there (the restriction's rows charged it, and sloped, otherwise)
                    for (i, (g, ga, gb)) in h.turn_gradients(a, b).into_iter().enumerate() {
                        set[i] = (ga, gb, dot(ga, a) + dot(gb, b) - g);
                    }
                } else {
                    let (ra, rb) = h.turn_rows(a, b, k == 1);
                    for i in 0..2 {
                        if let Some(ra) = ra {
                            set[i] = (ra[i], [0.0; 2], 0.0);
                        }
                        set[2 + i] = ([0.0; 2], rb[i], 0.0);
                    }
                }
            }
            for (ca, cb, rhs) in set {
                let row = m.row(rhs);
                if k >= 2 {
                    for (j, cj) in ca.iter().enumerate() {
                        m.a.push(row, l.auv_v(n, k - 1) + j, *cj);
                    }
                }
                for (j, cj) in cb.iter().enumerate() {
                    m.a.push(row, l.auv_v(n, k) + j, *cj);
                }
                m.a.push(row, l.heading_slack(n, k), -1.0);
            }
        }
    }
}

/// C1_14's "slow" alternatives: per AUV and step k = 1..=K the cone
/// ‖V_h,n\[k\]‖ ≤ v_min·(1 − SLOW_MARGIN) + ν_h\[n\]\[k\] + ν_h\[n\]\[k+1\], where the slack of pair k
/// enters when it keeps `SlowAfter` and that of pair k + 1 when it keeps `SlowBefore`; a speed
/// bound no AUV reaches (2·V_max) where neither does.
pub(super) fn cones(p: &TeamProblem, pieces: &[Vec<Piece>], m: &mut Assembly) {
    let l = p.layout;
    let loose = 2.0 * p.scenario.auv.max_speed;
    for n in 0..l.n {
        for k in 1..=l.k {
            let after = pieces[n][k - 1] == Piece::SlowAfter;
            let before = k < l.k && pieces[n][k] == Piece::SlowBefore;
            let row = m.row(if after || before {
                p.heading.slow_bound()
            } else {
                loose
            });
            m.a.push(row, l.heading_slack(n, k), if after { -1.0 } else { 0.0 });
            if k < l.k {
                // when both pairs keep V[k] slow, the cone holds pair k's slack and
                // `shared_rows` makes pair k + 1's at least as large
                let own = before && !after;
                m.a.push(row, l.heading_slack(n, k + 1), if own { -1.0 } else { 0.0 });
            }
            for i in 0..2 {
                let row = m.row(0.0);
                m.a.push(row, l.auv_v(n, k) + i, 1.0);
            }
            m.cones.push(SecondOrderConeT(3));
        }
    }
}

/// Where both pairs (k − 1, k) and (k, k + 1) keep V\[k\] slow (`SlowAfter` then
/// `SlowBefore`), one cone bounds ‖V\[k\]‖ by v_min plus pair k's slack ν_k, and the row
/// ν_k − ν_{k+1} ≤ 0 (nonnegative cone) charges pair k + 1 as much: the true merit counts the
/// excess ‖V\[k\]‖ − v_min in both pairs, and a model that charged it once (one cone with
/// ν_k + ν_{k+1}) predicted a decrease that no step could make. The SCP then shrank its trust
/// region to nothing and named a constraint that "cannot hold" (issue 22's lanes chain found
/// it: N = 5, seed 5, window 7 of 10, a predicted decrease of 3 251 at every radius down to
/// 2 mm). One row per AUV and step k < K, padding (`INACTIVE`) elsewhere.
pub(super) fn shared_rows(p: &TeamProblem, pieces: &[Vec<Piece>], m: &mut Assembly) {
    let l = p.layout;
    for n in 0..l.n {
        for k in 1..l.k {
            let both = pieces[n][k - 1] == Piece::SlowAfter && pieces[n][k] == Piece::SlowBefore;
            let c = if both { 1.0 } else { 0.0 };
            // an unused row is padding (0 ≤ 1), never 0 ≤ 0, which leaves the interior-point
            // method no strictly feasible slack
            let row = m.row(if both { 0.0 } else { INACTIVE });
            m.a.push(row, l.heading_slack(n, k), c);
            m.a.push(row, l.heading_slack(n, k + 1), -c);
        }
    }
}

/// The true violation at step k of AUV n: (the continuous violation v in m/s for the merit, the
/// turn beyond θ in rad as the checker measures it).
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> (f64, f64) {
    let a = h2(t.auv_v[n][k - 1]);
    let b = h2(t.auv_v[n][k]);
    (p.heading.violation(a, b, k == 1), p.heading.excess(a, b))
}

/// The message of a turn of `angle` rad beyond ψ̇_max·δ by AUV n between steps k − 1 and k.
pub(super) fn detail(n: usize, k: usize, angle: f64) -> String {
    format!(
        "heading rate C1_14: AUV {n} turns {angle:.3} rad more than ψ̇_max·δ between steps {} \
         and {k}",
        k - 1
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn rule() -> HeadingRule {
        HeadingRule::new(0.005, 0.005 - 0.005 / 100.0, 100.0, 0.1) // θ = 0.5 rad
    }

    fn rows_hold(rows: &[[f64; 2]; 2], v: [f64; 2]) -> bool {
        rows.iter().all(|c| c[0] * v[0] + c[1] * v[1] <= 0.0)
    }

    fn polar(speed: f64, psi: f64) -> [f64; 2] {
        [speed * psi.cos(), speed * psi.sin()]
    }

    /// What a piece's restriction charges at the reference (ā, b̄), m/s: the largest value of
    /// its rows (Turn), or the speed above the slow bound (SlowBefore, SlowAfter); 0 for Free.
    fn charge(r: &HeadingRule, piece: Piece, a: [f64; 2], b: [f64; 2], fixed: bool) -> f64 {
        let value = |c: [f64; 2], v: [f64; 2]| c[0] * v[0] + c[1] * v[1];
        match piece {
            Piece::Free => 0.0,
            Piece::Turn => {
                let (rows_a, rows_b) = r.turn_rows(a, b, fixed);
                let on_a = rows_a.map_or(f64::NEG_INFINITY, |c| value(c[0], a).max(value(c[1], a)));
                on_a.max(value(rows_b[0], b)).max(value(rows_b[1], b))
            }
            Piece::SlowBefore => norm(a) - r.slow_bound(),
            Piece::SlowAfter => norm(b) - r.slow_bound(),
        }
    }

    /// The regression of the module documentation: a reversal at 0.1006 m/s is 0.7 mm/s from
    /// feasible (the slow bound is 0.0999 m/s), not 2.4 rad.
    #[test]
    fn a_reversal_just_above_v_min_is_nearly_feasible() {
        let r = rule();
        let (a, b) = (polar(0.1006, 0.0), polar(0.32, 2.9));
        assert!((r.violation(a, b, false) - 0.0007).abs() < 1e-9);
        assert!(r.excess(a, b) > 2.3);
        // from the window's fixed start, slowing it is no alternative: b must slow or turn
        assert!((r.violation(a, b, true) - (0.32 - 0.0999)).abs() < 1e-9);
        let a = polar(0.0998, 0.0);
        assert_eq!(r.violation(a, b, false), 0.0);
        assert_eq!(r.excess(a, b), 0.0);
        assert_eq!(r.piece(a, b, false), Piece::SlowBefore);
        assert_eq!(r.piece(a, b, true), Piece::Free);
    }

    /// Regression (found by `each_piece_implies_c1_14`): with b̄ too slow to have a direction,
    /// the axis was ā's, and a reference turning 0.32 rad (within θ, more than θ/2) broke its
    /// own rows. The bisector keeps both within θ/2.
    #[test]
    fn a_slow_reference_after_still_meets_its_turn_rows() {
        let r = rule();
        let (a, b) = (polar(0.252, 0.0), polar(0.0323, -0.3206));
        assert_eq!(r.piece(a, b, false), Piece::Turn);
        let (ra, rb) = r.turn_rows(a, b, false);
        assert!(rows_hold(&ra.unwrap(), a) && rows_hold(&rb, b));
    }

    proptest! {
        /// v is zero exactly when the tightened rule holds (both speeds above the slow bound
        /// and the turn within the model's θ, or a speed below it), and the excess (the
        /// checker's measure) is zero exactly when the true rule holds. The tightened rule
        /// implies the true one.
        #[test]
        fn violation_is_zero_exactly_when_c1_14_holds(
            sa in 0.0..2.0f64, sb in 0.0..2.0f64, psi in -3.1..3.1f64, turn in -3.1..3.1f64,
            fixed in any::<bool>(),
        ) {
            let r = rule();
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            let (bound, theta) = (r.slow_bound(), r.model.tan.atan());
            for edge in [0.1, bound] {
                prop_assume!((sa - edge).abs() > 1e-9 && (sb - edge).abs() > 1e-9);
            }
            for edge in [0.5, theta] {
                prop_assume!((turn.abs() - edge).abs() > 1e-6);
            }
            let tight = sa < bound || sb < bound || turn.abs() <= theta;
            prop_assert_eq!(r.violation(a, b, fixed) == 0.0, tight);
            let holds = sa < 0.1 || sb < 0.1 || turn.abs() <= 0.5;
            prop_assert_eq!(r.excess(a, b) == 0.0, holds);
            prop_assert!(!tight || holds);
        }

        /// v is continuous: a 1 µm/s change of either velocity moves it by at most about that.
        #[test]
        fn violation_is_continuous(
            sa in 0.0..2.0f64, sb in 0.0..2.0f64, psi in -3.1..3.1f64, turn in -3.1..3.1f64,
            dx in -1.0..1.0f64, dy in -1.0..1.0f64,
        ) {
            let r = rule();
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            let h = 1e-6;
            let (a2, b2) = ([a[0] + h * dx, a[1] + h * dy], [b[0] - h * dy, b[1] + h * dx]);
            let jump = (r.violation(a, b, false) - r.violation(a2, b2, false)).abs();
            // g is 2-Lipschitz in b (|∇_b g| ≤ 1 + tan θ) and of order ‖b‖/‖a‖ in a
            prop_assert!(jump <= 10.0 * h * (1.0 + sb / sa.max(0.05)), "jump {jump}");
        }

        /// Every piece is a restriction of C1_14: a pair that meets the piece's own convex
        /// condition (the turn cone, or the speed bound) meets the disjunction.
        #[test]
        fn each_piece_implies_c1_14(
            sa in 0.0..2.0f64, sb in 0.0..2.0f64, psi in -3.1..3.1f64, turn in -3.1..3.1f64,
            fixed in any::<bool>(),
        ) {
            let r = rule();
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            let meets = match r.piece(a, b, fixed) {
                Piece::Free => sa < 0.1,
                Piece::Turn => {
                    // a reference that turns within the model's θ meets its own rows
                    let (ra, rb) = r.turn_rows(a, b, fixed);
                    let holds = ra.map_or(true, |ra| rows_hold(&ra, a)) && rows_hold(&rb, b);
                    if r.model.violation(a, b) <= 0.0 {
                        prop_assert!(holds);
                    }
                    holds
                }
                Piece::SlowBefore => sa <= r.slow_bound(),
                Piece::SlowAfter => sb <= r.slow_bound(),
            };
            if meets {
                prop_assert_eq!(r.violation(a, b, fixed), 0.0);
            }
        }

        /// At the reference the model charges each pair what the SCP's measure does where the
        /// reference breaks C1_14 (a violated turn with both velocities free: g± linearised,
        /// whose larger value is v; the fixed start's rows about â: g± themselves) and at least
        /// that elsewhere, and a piece charges nothing only where v is 0. (SCvx needs the model
        /// and the merit to agree at the reference, else the predicted decrease never vanishes.)
        #[test]
        fn the_model_charges_the_truth_at_the_reference(
            sa in 0.0..2.0f64, sb in 0.0..2.0f64, psi in -3.1..3.1f64, turn in -3.1..3.1f64,
            fixed in any::<bool>(),
        ) {
            let r = rule();
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            let piece = r.piece(a, b, fixed);
            let truth = r.violation(a, b, fixed);
            let charged = if piece == Piece::Turn && !fixed && truth > 0.0 {
                let g = r.turn_gradients(a, b);
                g[0].0.max(g[1].0)
            } else {
                charge(&r, piece, a, b, fixed)
            };
            if piece == Piece::Turn && truth > 0.0 {
                prop_assert!((charged - truth).abs() < 1e-12, "{charged} against {truth}");
            }
            // (the slack is nonnegative: a piece met with room to spare charges 0)
            prop_assert!(charged.max(0.0) >= truth - 1e-12, "{piece:?}: {charged} against {truth}");
            if charged <= 0.0 {
                prop_assert_eq!(truth, 0.0, "{:?} charges {}", piece, charged);
            }
        }

        /// The gradients of g± agree with central finite differences.
        #[test]
        fn turn_gradients_match_finite_differences(
            sa in 0.05..2.0f64, sb in 0.0..2.0f64, psi in -3.1..3.1f64, turn in -3.1..3.1f64,
        ) {
            let r = rule();
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            let h = 1e-6;
            let g = r.turn_gradients(a, b);
            for i in 0..2 {
                let mut da = [[0.0; 2]; 2];
                let mut db = [[0.0; 2]; 2];
                for j in 0..2 {
                    let (mut ap, mut am, mut bp, mut bm) = (a, a, b, b);
                    ap[j] += h;
                    am[j] -= h;
                    bp[j] += h;
                    bm[j] -= h;
                    da[i][j] = (r.turn_gradients(ap, b)[i].0 - r.turn_gradients(am, b)[i].0) / (2.0 * h);
                    db[i][j] = (r.turn_gradients(a, bp)[i].0 - r.turn_gradients(a, bm)[i].0) / (2.0 * h);
                }
                for j in 0..2 {
                    prop_assert!((g[i].1[j] - da[i][j]).abs() < 1e-5 * (1.0 + sb / sa), "∇a {:?} {:?}", g[i].1, da[i]);
                    prop_assert!((g[i].2[j] - db[i][j]).abs() < 1e-5, "∇b {:?} {:?}", g[i].2, db[i]);
                }
                let v = r.model.violation(a, b);
                prop_assert!((g[0].0.max(g[1].0) - v).abs() < 1e-12);
            }
        }

        /// About a reference that turns exactly θ (k ≥ 2, both velocities free), the Turn rows
        /// charge any small step at least what the measure v does, to first order: the model
        /// must not promise a decrease by turning both velocities apart (regression: N = 20,
        /// lanes, seed 4, window 1 of 2 charged 0.064 m where the merit measured 0.170 m).
        #[test]
        fn turn_rows_charge_a_step_at_least_the_measure(
            sa in 0.15..2.0f64, sb in 0.15..2.0f64, psi in -3.1..3.1f64, left in any::<bool>(),
            da in 0.0..1.0f64, dpa in -3.2..3.2f64, db in 0.0..1.0f64, dpb in -3.2..3.2f64,
        ) {
            let r = rule();
            let theta = r.model.tan.atan();
            let turn = if left { theta } else { -theta };
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            prop_assert_eq!(r.piece(a, b, false), Piece::Turn);
            let h = 1e-6;
            let a2 = [a[0] + h * da * dpa.cos(), a[1] + h * da * dpa.sin()];
            let b2 = [b[0] + h * db * dpb.cos(), b[1] + h * db * dpb.sin()];
            let (rows_a, rows_b) = r.turn_rows(a, b, false);
            let rows_a = rows_a.expect("rows on a free a");
            let value = |c: [f64; 2], v: [f64; 2]| c[0] * v[0] + c[1] * v[1];
            let charged = value(rows_a[0], a2)
                .max(value(rows_a[1], a2))
                .max(value(rows_b[0], b2))
                .max(value(rows_b[1], b2))
                .max(0.0);
            let truth = r.violation(a2, b2, false);
            prop_assert!(charged >= truth - 1e-3 * h, "charged {charged} against {truth}");
        }

        /// Any pair that meets a Turn piece's rows, about any reference, meets C1_14: the rows
        /// are a restriction, not a linearisation.
        #[test]
        fn turn_rows_are_a_restriction(
            ra in 0.05..2.0f64, rb in 0.0..2.0f64, rpsi in -3.1..3.1f64, rturn in -0.6..0.6f64,
            sa in 0.0..2.0f64, sb in 0.0..2.0f64, psi in -3.1..3.1f64, turn in -3.1..3.1f64,
            fixed in any::<bool>(),
        ) {
            let r = rule();
            let (ref_a, ref_b) = (polar(ra, rpsi), polar(rb, rpsi + rturn));
            let (a, b) = (polar(sa, psi), polar(sb, psi + turn));
            let (rows_a, rows_b) = r.turn_rows(ref_a, ref_b, fixed);
            let a = if fixed { ref_a } else { a }; // the fixed start does not move
            if rows_a.map_or(true, |rows| rows_hold(&rows, a)) && rows_hold(&rows_b, b) {
                prop_assert_eq!(r.violation(a, b, fixed), 0.0, "a {:?} b {:?}", a, b);
            }
        }
    }
}
