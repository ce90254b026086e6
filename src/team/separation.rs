//! AUV–AUV separation (ours; the paper has none): every pair of AUVs i < j keeps at least
//! d = `auv.min_separation` apart at every step k ≥ 1 and along the segment k − 1 → k between
//! steps. Without it P2's C1_6 rendezvous at k = K and OF1_5's pull could stack two AUVs on one
//! point (the default scenario at N = 5, seed 15, ended its window with AUVs 0 and 4 2.4 mm
//! apart). The default, 10 m, is the worst case of MOOS-IvP's collision avoidance: its
//! BHV_AvoidCollision gives a manoeuvre the least utility when its closest point of approach
//! is within `min_util_cpa_dist`, 10 m by default.
//!
//! ‖P_i − P_j‖ ≥ d is not convex. Along a segment both ends move on straight lines (as the
//! floor rows take them, C1_12), so the pair's relative position r(t) = (1 − t)·r\[k−1\] + t·r\[k\]
//! is linear in t ∈ [0, 1]. The model keeps the half-space
//!
//!   n̂ᵀ(P_i − P_j) ≥ d − ν_i − ν_j   at both ends of the segment, with one n̂,
//!
//! n̂ the unit direction of the reference's closest approach on the segment. n̂ᵀr is linear in t,
//! so it holds along the whole segment, and n̂ᵀr ≤ ‖r‖: a convex restriction of the true
//! constraint, which the reference itself meets whenever it keeps the separation (n̂ᵀr̄ is then
//! the reference's least distance at both ends, or more; see [`direction`]). The slacks ν ≥ 0,
//! one per AUV and segment (`Layout::separation_slack`), are priced by the SCP's penalty like
//! the floor's.
//!
//! Only the (pair, segment)s near enough to matter get rows: those whose reference keeps a
//! horizontal least distance below d + min(2Δ, [`NEAR`]). Δ is the trust radius (`trust::auv`
//! keeps every AUV waypoint within Δ of the reference horizontally, hence every point of a
//! segment, so a pair 2Δ beyond d cannot come within d). Each row couples two AUVs' blocks of
//! the convex model, and rows for every pair tripled the time of a solve at N = 5 and made the
//! N = 10 window five times slower; so a pair farther than [`NEAR`] beyond d is left to the
//! SCP's measure ([`violations`], every pair and segment), as the floor rows leave samples: a
//! step that brings it within d is seen by the merit, and the pair has rows from the next
//! reference on. The set only grows within a window's problem, and the convex solver is
//! rebuilt when it does (the sparsity pattern is the set's).

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;

/// Extra distance (m) the model asks for beyond d, so that the solver's residuals on the
/// re-simulated plan cannot leave the separation short by more than the checker's tolerance.
pub(super) const SEPARATION_MARGIN: f64 = 1e-3;

/// How far beyond d (m) a pair's reference may keep and still get rows, at most (see the
/// module's text). Each row couples two AUVs' blocks, and the factorisation's cost grows with
/// the pairs coupled: N = 10, seed 2, one window took 3.2 s without the family, 17.3 s with a
/// reach of 60 m (5× the time per interior-point iteration) and 4.8 s with 15 m, every plan
/// of N = 5 and 10, seeds 1–5, keeping the separation. A pair that a step brings from beyond
/// the reach to within d is seen by the SCP's measure and gets rows from the next reference on.
pub(super) const NEAR: f64 = 15.0;

/// A pair of AUVs i < j over the segment k − 1 → k, k = 1..=K.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct PairSegment {
    pub i: usize,
    pub j: usize,
    pub k: usize,
}

/// The closest approach of r(t) = (1 − t)·r0 + t·r1 over t ∈ [0, 1]: (t*, r(t*)).
pub fn closest(r0: [f64; 3], r1: [f64; 3]) -> (f64, [f64; 3]) {
    let d: [f64; 3] = std::array::from_fn(|c| r1[c] - r0[c]);
    let dd = dot(d, d);
    let t = if dd > 0.0 {
        (-dot(r0, d) / dd).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (t, std::array::from_fn(|c| r0[c] + t * d[c]))
}

/// The least distance of the segment r0 → r1 from the origin.
pub fn least_distance(r0: [f64; 3], r1: [f64; 3]) -> f64 {
    norm(closest(r0, r1).1)
}

/// The least horizontal distance of the segment r0 → r1 from the origin.
fn least_horizontal(r0: [f64; 3], r1: [f64; 3]) -> f64 {
    least_distance([r0[0], r0[1], 0.0], [r1[0], r1[1], 0.0])
}

/// n̂ of the rows of the segment r0 → r1 (relative positions of a pair at its ends): the unit
/// direction of its closest approach to the origin. Of all unit vectors it makes
/// min(n̂ᵀr0, n̂ᵀr1) largest, equal to the least distance: at an interior closest point r(t*) is
/// normal to r1 − r0, so n̂ᵀr is that distance all along; at an end, say r0, the distance grows
/// towards r1, so n̂ᵀr1 ≥ n̂ᵀr0 = ‖r0‖. A segment through the origin has no such direction: then
/// the horizontal normal of its direction (the pair passes side by side), or east for a pair
/// that stays on one point.
pub fn direction(r0: [f64; 3], r1: [f64; 3]) -> [f64; 3] {
    let (_, c) = closest(r0, r1);
    let n = norm(c);
    if n > 1e-9 {
        return c.map(|x| x / n);
    }
    let (dx, dy) = (r1[0] - r0[0], r1[1] - r0[1]);
    let h = dx.hypot(dy);
    if h > 1e-9 {
        [-dy / h, dx / h, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    }
}

/// n̂ of segment k's rows: [`direction`], but on the first segment, whose start is the
/// window's fixed start, the start's own direction when the pair starts apart. The start's row
/// then holds as the start does, and the model can move the pair apart along it; with the
/// reference's closest approach, a start a hair beyond d could fail its constant row whatever
/// the plan (N = 10, seed 3: Step 1 gave up with two AUVs 8.96 m apart on its first segment).
fn segment_direction(r0: [f64; 3], r1: [f64; 3], k: usize) -> [f64; 3] {
    let n0 = norm(r0);
    if k == 1 && n0 > 1e-9 {
        r0.map(|x| x / n0)
    } else {
        direction(r0, r1)
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn relative(t: &Trajectory, i: usize, j: usize, k: usize) -> [f64; 3] {
    let (a, b) = (t.auv_p[i][k], t.auv_p[j][k]);
    std::array::from_fn(|c| a[c] - b[c])
}

/// Whether the family applies: d > 0 and two AUVs or more.
pub(super) fn active(p: &TeamProblem) -> bool {
    p.scenario.auv.min_separation > 0.0 && p.layout.n >= 2
}

/// The true violation of the separation by AUVs i and j on segment k − 1 → k: d less their
/// least distance along it, metres (negative when kept).
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, i: usize, j: usize, k: usize) -> f64 {
    let d = p.scenario.auv.min_separation;
    d - least_distance(relative(t, i, j, k - 1), relative(t, i, j, k))
}

/// Every pair and segment that breaks the separation, with its violation (m).
pub(super) fn violations(p: &TeamProblem, t: &Trajectory) -> Vec<(f64, PairSegment)> {
    let mut out = Vec::new();
    if !active(p) {
        return out;
    }
    let l = p.layout;
    for k in 1..=l.k {
        for i in 0..l.n {
            for j in i + 1..l.n {
                let v = violation(p, t, i, j, k);
                if v > 0.0 {
                    out.push((v, PairSegment { i, j, k }));
                }
            }
        }
    }
    out
}

/// The (pair, segment)s of the reference `r` near enough to get rows at trust radius `radius`
/// (see the module's text), in order.
pub(super) fn near(p: &TeamProblem, r: &Trajectory, radius: f64) -> Vec<PairSegment> {
    let mut out = Vec::new();
    if !active(p) {
        return out;
    }
    let l = p.layout;
    let reach = p.scenario.auv.min_separation + (2.0 * radius).min(NEAR);
    for k in 1..=l.k {
        for i in 0..l.n {
            for j in i + 1..l.n {
                let h = least_horizontal(relative(r, i, j, k - 1), relative(r, i, j, k));
                // a non-finite reference (a stray first guess) is given its rows
                if h.is_nan() || h < reach {
                    out.push(PairSegment { i, j, k });
                }
            }
        }
    }
    out
}

/// `set` with `more` added, in order; whether it grew.
pub(super) fn extend(set: &mut Vec<PairSegment>, more: &[PairSegment]) -> bool {
    let before = set.len();
    set.extend_from_slice(more);
    set.sort_unstable();
    set.dedup();
    set.len() > before
}

/// The slacks' price: the SCP's penalty λ per metre.
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    if !p.layout.separation {
        return;
    }
    let l = p.layout;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.penalise(l.separation_slack(n, k), 1.0, penalty);
        }
    }
}

/// Nonnegative-cone rows: per (pair, segment) of `p`'s set, the half-space at both ends of the
/// segment about the reference `r`, and ν ≥ 0 for every slack:
///
///   −n̂ᵀP_i\[s\] + n̂ᵀP_j\[s\] − ν_i\[k\] − ν_j\[k\] ≤ −(d + margin),  s = k − 1, k
///
/// (at s = 0 the window's fixed start: a constant on the right).
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let l = p.layout;
    if !l.separation {
        return;
    }
    let d = p.scenario.auv.min_separation + SEPARATION_MARGIN;
    for &PairSegment { i, j, k } in &p.separation {
        let n = segment_direction(relative(r, i, j, k - 1), relative(r, i, j, k), k);
        for s in [k - 1, k] {
            if s == 0 {
                let r0 = relative(r, i, j, 0);
                let row = m.row(dot(n, r0) - d);
                m.a.push(row, l.separation_slack(i, k), -1.0);
                m.a.push(row, l.separation_slack(j, k), -1.0);
                continue;
            }
            let row = m.row(-d);
            for c in 0..3 {
                m.a.push(row, l.auv_p(i, s) + c, -n[c]);
                m.a.push(row, l.auv_p(j, s) + c, n[c]);
            }
            m.a.push(row, l.separation_slack(i, k), -1.0);
            m.a.push(row, l.separation_slack(j, k), -1.0);
        }
    }
    for n in 0..l.n {
        for k in 1..=l.k {
            m.nonnegative(l.separation_slack(n, k));
        }
    }
}

/// How a separation that cannot be kept is named.
pub(super) fn detail(p: &TeamProblem, t: &Trajectory, at: PairSegment) -> String {
    let PairSegment { i, j, k } = at;
    let d = p.scenario.auv.min_separation;
    let least = least_distance(relative(t, i, j, k - 1), relative(t, i, j, k));
    format!(
        "AUV separation: AUVs {i} and {j} come within {least:.2} m of each other between steps \
         {} and {k}, closer than auv.min_separation = {d} m",
        k - 1
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mission::scenario_floor;
    use crate::scenario::Scenario;
    use proptest::prelude::*;
    use rand::{Rng, SeedableRng};

    fn sample(r0: [f64; 3], r1: [f64; 3], steps: usize) -> f64 {
        (0..=steps)
            .map(|s| {
                let t = s as f64 / steps as f64;
                norm(std::array::from_fn(|c| r0[c] + t * (r1[c] - r0[c])))
            })
            .fold(f64::INFINITY, f64::min)
    }

    fn point() -> impl Strategy<Value = [f64; 3]> {
        proptest::array::uniform3(-60.0..60.0f64)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]
        /// The least distance is the segment's (fine sampling finds none smaller, and finds it).
        #[test]
        fn the_least_distance_is_the_segments(r0 in point(), r1 in point()) {
            let d = least_distance(r0, r1);
            let s = sample(r0, r1, 20_000);
            prop_assert!(d <= s + 1e-9, "closed form {d}, sampled {s}");
            prop_assert!(s - d < 1e-2, "closed form {d}, sampled {s}");
        }

        /// The rows' linearisation against finite differences: the gradient of the least
        /// distance D(r0, r1) is ((1 − t*)·n̂, t*·n̂) (the envelope theorem), the rows' n̂ split
        /// between the segment's ends; and at the reference the rows' smaller end value
        /// min(n̂ᵀr0, n̂ᵀr1) is D itself, so the model and the SCP's measure agree there.
        #[test]
        fn the_rows_direction_is_the_least_distances_gradient(r0 in point(), r1 in point()) {
            let d = least_distance(r0, r1);
            prop_assume!(d > 1.0);
            let n = direction(r0, r1);
            let (t, _) = closest(r0, r1);
            prop_assert!((dot(n, r0).min(dot(n, r1)) - d).abs() < 1e-9);
            let h = 1e-6;
            for c in 0..3 {
                let bump = |v: [f64; 3], s: f64| {
                    let mut w = v;
                    w[c] += s;
                    w
                };
                let g0 = (least_distance(bump(r0, h), r1) - least_distance(bump(r0, -h), r1))
                    / (2.0 * h);
                let g1 = (least_distance(r0, bump(r1, h)) - least_distance(r0, bump(r1, -h)))
                    / (2.0 * h);
                prop_assert!((g0 - (1.0 - t) * n[c]).abs() < 1e-5, "∂/∂r0[{c}]: {g0}");
                prop_assert!((g1 - t * n[c]).abs() < 1e-5, "∂/∂r1[{c}]: {g1}");
            }
        }

        /// A convex restriction: any segment whose ends both keep n̂ᵀr ≥ d (whatever n̂ the
        /// reference gave) keeps ‖r(t)‖ ≥ d all along.
        #[test]
        fn the_half_spaces_keep_the_whole_segment_apart(
            a0 in point(), a1 in point(), c0 in point(), c1 in point(), d in 1.0..30.0f64,
            s0 in 0.0..20.0f64, s1 in 0.0..20.0f64,
        ) {
            let n = direction(a0, a1);
            // any ends that keep n̂ᵀb ≥ d: c moved along n̂ until n̂ᵀb = d + s
            let onto = |c: [f64; 3], s: f64| {
                let shift = d + s - dot(n, c);
                [c[0] + shift * n[0], c[1] + shift * n[1], c[2] + shift * n[2]]
            };
            let (b0, b1) = (onto(c0, s0), onto(c1, s1));
            prop_assert!(dot(n, b0) >= d - 1e-9 && dot(n, b1) >= d - 1e-9);
            prop_assert!(least_distance(b0, b1) >= d - 1e-9);
            prop_assert!(sample(b0, b1, 2_000) >= d - 1e-9);
        }
    }

    /// A segment through the origin gets a sideways direction, a pair on one point east.
    #[test]
    fn a_segment_through_the_origin_gets_a_sideways_direction() {
        let n = direction([-10.0, 0.0, 0.0], [10.0, 0.0, 0.0]);
        assert!((n[0]).abs() < 1e-12 && (n[1].abs() - 1.0).abs() < 1e-12 && n[2] == 0.0);
        assert_eq!(direction([0.0; 3], [0.0; 3]), [1.0, 0.0, 0.0]);
    }

    /// Three AUVs, four steps of the default scenario, its first guess as the reference.
    fn problem(check: impl FnOnce(&mut TeamProblem, Trajectory)) {
        let mut s = Scenario::default();
        s.team.auvs = 3;
        s.horizon.steps = 4;
        let (floor, _) = scenario_floor(&s, std::path::Path::new("")).unwrap();
        let keep_out = floor.keep_out();
        let mut p = TeamProblem::first_window(&s, &floor, &keep_out).unwrap();
        let t = p.initial_guess(None);
        check(&mut p, t);
    }

    /// The solver's vector of a trajectory's positions (the rest zero).
    fn positions(p: &TeamProblem, t: &Trajectory) -> Vec<f64> {
        let l = p.layout;
        let mut x = vec![0.0; l.variables()];
        for n in 0..l.n {
            for k in 1..=l.k {
                x[l.auv_p(n, k)..l.auv_p(n, k) + 3].copy_from_slice(&t.auv_p[n][k]);
            }
        }
        x
    }

    /// The rows against the true violation at random points: with every slack zero, a point
    /// that meets a pair's rows keeps that pair d apart on its segment; at the reference, the
    /// slack a pair's rows need is its true violation (or none when it keeps the separation).
    #[test]
    fn the_rows_hold_only_where_the_separation_does() {
        problem(|p, mut r| {
            let l = p.layout;
            assert!(l.separation);
            // crowd the reference: AUV 1 passes AUV 0 within a few metres at step 2
            let a = r.auv_p[0][2];
            r.auv_p[1][2] = [a[0] + 3.0, a[1] - 2.0, a[2] + 1.0];
            r.auv_p[2][3] = r.auv_p[0][3];
            let radius = 200.0;
            p.separation = near(p, &r, radius);
            let mut m = Assembly::new(l.variables());
            rows(p, &r, &mut m);
            // the rows of each (pair, segment): two rows each, in order
            let row_value = |m: &Assembly, x: &[f64], row: usize| {
                let ax: f64 = (0..m.a.rows.len())
                    .filter(|&e| m.a.rows[e] == row)
                    .map(|e| m.a.vals[e] * x[m.a.cols[e]])
                    .sum();
                m.b[row] - ax // s = b − Ax ≥ 0 when the row holds
            };
            // at the reference: the shortfall of a pair's rows is its violation (on the first
            // segment, whose n̂ is the start's, at least its violation: a restriction)
            let x = positions(p, &r);
            for (e, ps) in p.separation.iter().enumerate() {
                let short = (0..2)
                    .map(|h| -row_value(&m, &x, 2 * e + h))
                    .fold(f64::NEG_INFINITY, f64::max);
                let v = violation(p, &r, ps.i, ps.j, ps.k) + SEPARATION_MARGIN;
                if ps.k == 1 {
                    assert!(short >= v - 1e-9, "{ps:?}: rows {short}, true {v}");
                } else if v > 0.0 {
                    assert!((short - v).abs() < 1e-6, "{ps:?}: rows {short}, true {v}");
                } else {
                    assert!(short <= 1e-9, "{ps:?}: rows {short}, true {v}");
                }
            }
            // at random points about the reference: rows met ⇒ separation kept
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
            let mut met = 0;
            for _ in 0..2_000 {
                let mut t = r.clone();
                for n in 0..l.n {
                    for k in 1..=l.k {
                        for c in 0..3 {
                            t.auv_p[n][k][c] += rng.gen_range(-15.0..15.0);
                        }
                    }
                }
                let x = positions(p, &t);
                for (e, ps) in p.separation.iter().enumerate() {
                    if (0..2).all(|h| row_value(&m, &x, 2 * e + h) >= 0.0) {
                        met += 1;
                        let v = violation(p, &t, ps.i, ps.j, ps.k);
                        assert!(v <= 1e-9, "{ps:?} meets its rows, violated by {v}");
                    }
                }
            }
            assert!(met > 100, "only {met} (pair, segment)s met their rows");
            // a pair left out of the set keeps NEAR beyond d on the reference (2Δ beyond it,
            // where it could not come within d inside the trust region, at a small Δ)
            let all = near(p, &r, 1e6);
            for ps in all.iter().filter(|ps| !p.separation.contains(ps)) {
                let v = violation(p, &r, ps.i, ps.j, ps.k);
                assert!(
                    v <= -(2.0 * radius).min(NEAR) + 1e-9,
                    "{ps:?} is left out at {v}"
                );
            }
            let small = near(p, &r, 5.0);
            for ps in all.iter().filter(|ps| !small.contains(ps)) {
                let v = violation(p, &r, ps.i, ps.j, ps.k);
                assert!(v <= -10.0 + 1e-9, "{ps:?} is left out at {v}");
            }
        });
    }
}
