//! C2_2, seafloor clearance (the paper's C1_12 as Step 1 models it): every AUV at least ε above
//! the floor, Z(x, y) + ε − z ≤ 0, not only at the waypoints but at every sample of 𝓛_r along
//! each segment k−1 → k (100 s apart, a seamount can sit between two waypoints), over the
//! keep-out field (`Seafloor::keep_out`), in which every obstacle cell (NODATA, land) lies above
//! the surface.
//!
//! Departure: the paper freezes Z at the previous iterate's position ("𝕫_n[k] is found and
//! bounded"); here C2_2 is linearised about the reference (value and gradient of Z) and
//! softened by a slack ν_f[n][k] per segment, priced by the SCP's penalty, as SCvx needs.
//! The true violation is the segment's worst sample but its first (P[k−1], which the segment
//! before measures, or the window's fixed start): the samples the rows take.

use super::model::{Assembly, INACTIVE};
use super::{TeamProblem, OBSTACLE};
use crate::error::PlanError;
use crate::linearise::{floor_sample, segment_intervals};
use crate::trajectory::Trajectory;

/// Extra clearance (m) the convex model asks for beyond ε (constraint tightening). 0.5 m, not
/// 0.25 m: the floor's linearisation error over a step of tens of metres is often 0.3–0.7 m,
/// and every step it broke was rejected (docs/design-decisions.md, "Solver settings").
pub(super) const FLOOR_MARGIN: f64 = 0.5;

/// Floor rows per segment (see [`rows`]), besides the waypoint's. 6, not the 12 of the
/// sessions before the floor's bend was priced: with the bend term the model holds over a
/// whole step, the nearly parallel rows of neighbouring samples only cost the interior-point
/// method iterations, and the samples a rejected candidate breaks get rows ([`force`]), so
/// that a model which left them out is not built again (docs/design-decisions.md, "The floor rows").
pub(super) const FLOOR_ROWS: usize = 6;

/// Least distance (m) between two samples that get rows of one segment, whatever the
/// resolution r of 𝓛_r (5 m, the default r): a finer r makes the measure the SCP and the
/// checker apply more careful, not the model's rows denser. With rows at every metre (r = 1),
/// the 12 rows of a 150 m segment covered 12 m about its worst sample, the step broke the
/// floor elsewhere on the segment, and the SCP stalled or gave up on a feasible problem.
pub(super) const ROW_SPACING: f64 = 5.0;

/// How many sample indices apart two rows of a segment a → b sampled at `n` intervals must be
/// (at least 1): [`ROW_SPACING`] over the interval length.
pub(super) fn apart(a: [f64; 3], b: [f64; 3], n: usize) -> usize {
    let step = (b[0] - a[0]).hypot(b[1] - a[1]) / n as f64;
    if step > 0.0 {
        ((ROW_SPACING / step).round() as usize).max(1)
    } else {
        1
    }
}

/// Least distance (m) at which [`curvature`] measures the floor's departure from its tangent
/// plane: below about a grid cell the departure is the bilinear cells' kinks, which a step of a
/// few metres does not see.
const CURVATURE_MIN_DISTANCE: f64 = 5.0;

/// The floor slacks' price: the SCP's penalty λ per metre.
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    for n in 0..l.n {
        for k in 1..=l.k {
            m.penalise(l.floor_slack(n, k), 1.0, penalty);
        }
    }
}

/// How far the field bends up from its tangent plane about (x, y) within `radius`: the least
/// L ≥ 0 with Z(x + d) ≤ Z(x) + ∇Z·d + ½L‖d‖², measured on eight directions at `radius`,
/// `radius`/2 and `radius`/4 (not below `CURVATURE_MIN_DISTANCE`; points off the grid are
/// skipped). Zero where the field is concave (a ridge, a valley's walls seen from outside).
pub(super) fn curvature(
    field: &crate::seafloor::Seafloor,
    at: [f64; 3],
    z: f64,
    grad: [f64; 2],
    radius: f64,
) -> f64 {
    let mut l = 0.0f64;
    for d in [radius, 0.5 * radius, 0.25 * radius] {
        if d < CURVATURE_MIN_DISTANCE {
            break;
        }
        for i in 0..8 {
            let (sin, cos) = (i as f64 * std::f64::consts::FRAC_PI_4).sin_cos();
            let (dx, dy) = (d * cos, d * sin);
            if let Ok(zd) = field.elevation(at[0] + dx, at[1] + dy) {
                let e = zd - z - grad[0] * dx - grad[1] * dy;
                l = l.max(2.0 * e / (d * d));
            }
        }
    }
    l
}

/// C2_2 linearised at the segment samples of the reference, over the keep-out field (so that
/// no sample can lie over an obstacle cell). The samples are those of the paper's 𝓛_r
/// (fractions j/n, j = 1..=n, n = ⌈horizontal length / r⌉); of these, the `FLOOR_ROWS` with the
/// least clearance on the reference (spread out: a sample next to one already taken is taken
/// last) get a row, all sharing the group's slack ν_f[n][k]. The SCP measures the true
/// violation over every sample, so a sample left out this iteration that the step makes
/// critical is picked up at the next one, and convergence is only declared when all of them
/// hold. Every row touches P[k−1] and P[k], so the pattern is fixed.
///
/// Returns, per segment (`trust::segment`), whether one of its rows has a curvature term.
pub(super) fn rows(
    p: &TeamProblem,
    r: &Trajectory,
    m: &mut Assembly,
    radius: f64,
) -> Result<Vec<bool>, PlanError> {
    let l = p.layout;
    // constraint tightening: the model asks for FLOOR_MARGIN more than ε, so the error of the
    // linearisation cannot leave the true constraint (measured with ε) violated at the end
    let eps = p.scenario.auv.floor_clearance + FLOOR_MARGIN;
    let res = p.scenario.acoustic.resolution;
    let mut g = Vec::new();
    let mut bent = vec![false; l.n * l.k];
    for n in 0..l.n {
        for k in 1..=l.k {
            // a first guess may run past the grid's edge: linearise at the nearest point
            // inside (the grid-bound rows bring the candidate back in)
            let (pa, pb) = (p.inside(r.auv_p[n][k - 1]), p.inside(r.auv_p[n][k]));
            let used = segment_intervals(pa, pb, res);
            g.clear();
            for j in 1..=used {
                let sj = j as f64 / used as f64;
                g.push((floor_sample(p.keep_out, eps, pa, pb, sj)?.0, j));
            }
            let mut picks = pick_samples(&mut g, FLOOR_ROWS, apart(pa, pb, used));
            force(&mut picks, &p.forced[super::trust::segment(l, n, k)], used);
            // the waypoint P[k] always has a row: the trust region is horizontal, so in the
            // model a waypoint without one could dive below the floor at any radius
            if !picks.contains(&used) {
                picks.push(used);
            }
            for slot in 0..FLOOR_ROWS + 1 {
                let row_data = match picks.get(slot) {
                    Some(&j) => {
                        let sj = j as f64 / used as f64;
                        let (gv, grad) = floor_sample(p.keep_out, eps, pa, pb, sj)?;
                        let ps = crate::linearise::lerp(pa, pb, sj);
                        let bend = curvature(p.keep_out, ps, gv - eps + ps[2], grad, radius);
                        let gv = reference_margin(gv);
                        let c = [grad[0], grad[1], -1.0];
                        // ∇g·x − ν ≤ ∇g·x̄ − g(x̄)
                        let mut rhs = c[0] * ps[0] + c[1] * ps[1] + c[2] * ps[2] - gv;
                        if k == 1 {
                            let p0 = p.start.auvs[n].position;
                            rhs -= (1.0 - sj) * (c[0] * p0[0] + c[1] * p0[1] + c[2] * p0[2]);
                        }
                        Some((sj, c, rhs, bend))
                    }
                    None => None,
                };
                let (sj, c, rhs, bend) = row_data.unwrap_or((0.0, [0.0; 3], INACTIVE, 0.0));
                // the curvature term ½L‖d‖² of the sample's horizontal step d, bounded by the
                // ends' (‖d‖² ≤ (1 − s)‖d[k−1]‖² + s‖d[k]‖², convexity) through their τ
                let bend = 0.5 * bend * p.scenario.acoustic.sonar_range;
                bent[super::trust::segment(l, n, k)] |= bend > 0.0;
                let row = m.row(rhs);
                if k > 1 {
                    for i in 0..3 {
                        m.a.push(row, l.auv_p(n, k - 1) + i, (1.0 - sj) * c[i]);
                    }
                    m.a.push(row, l.start_square(n, k), (1.0 - sj) * bend);
                }
                for i in 0..3 {
                    m.a.push(row, l.auv_p(n, k) + i, sj * c[i]);
                }
                m.a.push(row, l.end_square(n, k), sj * bend);
                m.a.push(row, l.floor_slack(n, k), -1.0);
            }
        }
    }
    Ok(bent)
}

/// Give rows to the samples nearest the fractions `forced` (where rejected candidates broke
/// the floor, `TeamProblem::judged`), in place of the last picks (never of the worst sample
/// and its neighbours, the first three). Without them a model that leaves out the samples its
/// own candidate breaks is built again, the same, about the same reference, and the SCP
/// stalls (6 rows per segment: `tests/check_planner.rs`'s regression seed 490443).
fn force(picks: &mut Vec<usize>, forced: &[f64], used: usize) {
    let mut slot = picks.len();
    for &f in forced.iter().rev() {
        let j = ((f * used as f64).round() as usize).clamp(1, used);
        if picks.contains(&j) {
            continue;
        }
        if picks.len() < FLOOR_ROWS {
            picks.push(j);
        } else if slot > 3 {
            slot -= 1;
            picks[slot] = j;
        }
    }
}

/// A row's g with the margin the reference has of it: g is taken with the full
/// `FLOOR_MARGIN`; a sample the reference holds with less than that to spare, or violates,
/// gets a row that the reference meets exactly or violates by the true amount. The model and
/// the SCP's measure (C2_2 with ε) then agree at the reference, as SCvx needs: with the full
/// margin a violated reference looked `FLOOR_MARGIN` × λ worse to the model than to the
/// measure, and once λ had grown the model predicted no decrease at all (issue 13's sweep,
/// draw 2: "a constraint cannot hold" on a feasible mission).
fn reference_margin(g: f64) -> f64 {
    let room = (FLOOR_MARGIN - g).max(0.0); // how far the reference is above ε
    g - FLOOR_MARGIN + FLOOR_MARGIN.min(room)
}

/// Up to `count` sample indices from (g, j) pairs: the largest g and the samples on either
/// side of it first, then the rest by largest g, skipping a neighbour (within `apart` indices)
/// of one already taken until no other sample is left.
///
/// The worst sample's neighbours come first because the field has a kink between them where
/// the worst sample sits on a crest (bilinear cells meet there): the tangent plane at the
/// worst sample says nothing of the far side, and a step that tilted the segment broke the
/// sample beside it, which the spreading rule had left out, while the model promised the
/// opposite (a link over a ridge, `step3::tests::links_regain_sight_over_a_ridge_in_one_round`:
/// the worst sample moved 5 m, to the neighbour, and Step 3 stalled).
pub(super) fn pick_samples(g: &mut [(f64, usize)], count: usize, apart: usize) -> Vec<usize> {
    g.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut picks: Vec<usize> = Vec::with_capacity(count);
    if let Some(&(_, worst)) = g.first() {
        for j in [Some(worst), worst.checked_sub(1), Some(worst + 1)]
            .into_iter()
            .flatten()
        {
            if picks.len() < count && g.iter().any(|&(_, i)| i == j) {
                picks.push(j);
            }
        }
    }
    for &(_, j) in g.iter() {
        if picks.len() == count {
            break;
        }
        if !picks.iter().any(|&p| p.abs_diff(j) <= apart) {
            picks.push(j);
        }
    }
    for &(_, j) in g.iter() {
        if picks.len() == count {
            break;
        }
        if !picks.contains(&j) {
            picks.push(j);
        }
    }
    picks
}

/// The true violation: worst floor-clearance shortfall (metres) of the segment k−1 → k of AUV
/// n over the keep-out field, sampled by the seafloor's own 𝓛_r rule, and where it occurs.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> (f64, [f64; 3]) {
    let (clearance, at) = p.keep_out_clearance(t.auv_p[n][k - 1], t.auv_p[n][k]);
    (p.scenario.auv.floor_clearance - clearance, at)
}

/// The message of a violation at `at` on the segment k−1 → k of AUV n: C2_2 with the floor's
/// height, or the obstacle the point is in or next to.
pub(super) fn detail(p: &TeamProblem, n: usize, k: usize, at: [f64; 3]) -> String {
    let eps = p.scenario.auv.floor_clearance;
    let passes = format!(
        "AUV {n} between steps {} and {k} passes ({:.1}, {:.1}, {:.1})",
        k - 1,
        at[0],
        at[1],
        at[2]
    );
    match p.obstacle_text(at) {
        Some(why) => format!("{OBSTACLE}: {passes}, which is {why}"),
        None => {
            let floor = p.floor.elevation(at[0], at[1]).unwrap_or(f64::NAN);
            format!(
                "seafloor clearance C2_2: {passes} where the floor is at z = {floor:.1} m; it \
                 needs {eps:.1} m of clearance and has {:.2} m",
                at[2] - floor
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mission::scenario_floor;
    use crate::scenario::Scenario;
    use proptest::prelude::*;

    /// The samples rejected candidates broke replace the last picks (never the worst sample
    /// and its neighbours), fill free slots first, and are not taken twice.
    #[test]
    fn forced_samples_take_the_last_slots() {
        let mut picks = vec![10, 9, 11, 2, 30, 40];
        force(&mut picks, &[0.5, 0.2], 100);
        // 0.2 → 20 replaces the last pick, 0.5 → 50 the one before
        assert_eq!(picks, vec![10, 9, 11, 2, 50, 20]);
        let mut picks = vec![10, 9, 11];
        force(&mut picks, &[0.1, 0.0, 1.0, 0.1], 100);
        // a fraction of 0 is the first sample; 10 is taken once
        assert_eq!(picks, vec![10, 9, 11, 100, 1]);
        let mut picks = vec![10, 9, 11, 2, 30, 40];
        force(&mut picks, &[0.01, 0.02, 0.03, 0.04], 100);
        assert_eq!(&picks[..3], &[10, 9, 11]);
    }

    /// The worst sample and both its neighbours get rows before the rest spread out; at the
    /// ends of the segment only the neighbour that exists; fewer samples than rows: all.
    #[test]
    fn the_worst_sample_and_its_neighbours_come_first() {
        let mut g: Vec<(f64, usize)> = (1..=20).map(|j| (-((j as f64) - 9.0).abs(), j)).collect();
        let picks = pick_samples(&mut g, 6, 1);
        assert_eq!(&picks[..3], &[9, 8, 10]);
        assert!(picks[3..]
            .iter()
            .all(|&j| j.abs_diff(8) > 1 && j.abs_diff(10) > 1));
        let mut g: Vec<(f64, usize)> = (1..=20).map(|j| (-(j as f64), j)).collect();
        assert_eq!(&pick_samples(&mut g, 6, 1)[..2], &[1, 2]);
        let mut g: Vec<(f64, usize)> = vec![(0.0, 1), (1.0, 2)];
        assert_eq!(pick_samples(&mut g, 6, 1), vec![2, 1]);
        let mut g: Vec<(f64, usize)> = (1..=20).map(|j| (j as f64, j)).collect();
        assert_eq!(pick_samples(&mut g, 1, 1), vec![20]);
    }

    /// One AUV, five steps of the default scenario: the problem and its first guess.
    fn with_guess(check: impl FnOnce(&TeamProblem, Trajectory)) {
        let mut s = Scenario::default();
        s.team.auvs = 1;
        s.horizon.steps = 5;
        let (floor, _) = scenario_floor(&s, std::path::Path::new("")).unwrap();
        let keep_out = floor.keep_out();
        let p = TeamProblem::first_window(&s, &floor, &keep_out).unwrap();
        let t = p.initial_guess(None);
        check(&p, t);
    }

    /// The shortfall of the rows' sample j of segment a → b at clearance ε (no margin).
    fn row_shortfall(p: &TeamProblem, a: [f64; 3], b: [f64; 3]) -> f64 {
        let eps = p.scenario.auv.floor_clearance;
        let n = segment_intervals(a, b, p.scenario.acoustic.resolution);
        (1..=n)
            .map(|j| {
                floor_sample(p.keep_out, eps, a, b, j as f64 / n as f64)
                    .unwrap()
                    .0
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Regression (issue 22, lanes chain, N = 20, seed 1, window 2 of 3): an AUV that hovered
    /// (P[1] and P[2] 0.3 m apart, one sample of 𝓛_r) with P[1] 2.675 m below ε had that
    /// shortfall measured in segment 0 → 1 and again in 1 → 2, while the model's rows of
    /// 1 → 2 take only P[2]. The model then predicted a decrease of λ · 2.675 = 2 675 at every
    /// trust radius, Step 3 stalled, and the chain broke in the next window. Each segment now
    /// measures the samples its rows take.
    #[test]
    fn regression_a_waypoint_below_the_floor_is_measured_once() {
        with_guess(|p, mut t| {
            let eps = p.scenario.auv.floor_clearance;
            let [x, y, _] = t.auv_p[0][1];
            let z = p.keep_out.elevation(x, y).unwrap();
            t.auv_p[0][1] = [x, y, z + eps - 2.0];
            t.auv_p[0][2] = [x + 0.3, y, z + eps + 5.0];
            let (v1, _) = violation(p, &t, 0, 1);
            let (v2, _) = violation(p, &t, 0, 2);
            assert!((v1 - 2.0).abs() < 1e-9, "segment 0 → 1 falls short by {v1}");
            assert!(v2 < 0.0, "segment 1 → 2 falls short by {v2}");
        });
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The SCP's measure of C2_2 on a segment is the largest shortfall among the samples
        /// the model's rows choose from (`floor_sample` at j = 1..=n): the model and the merit
        /// agree at the reference, as SCvx needs, for any segment.
        #[test]
        fn the_measure_takes_the_rows_samples(
            dx in -200.0..200.0f64, dy in -200.0..200.0f64,
            dz0 in -20.0..20.0f64, dz1 in -20.0..20.0f64, k in 1usize..=5,
        ) {
            with_guess(|p, mut t| {
                let [x, y, _] = t.auv_p[0][k - 1];
                let at = |x: f64, y: f64, dz: f64| [x, y, p.keep_out.elevation(x, y).unwrap() + dz];
                t.auv_p[0][k - 1] = at(x, y, dz0);
                t.auv_p[0][k] = at(x + dx, y + dy, dz1);
                let (v, _) = violation(p, &t, 0, k);
                let rows = row_shortfall(p, t.auv_p[0][k - 1], t.auv_p[0][k]);
                assert!((v - rows).abs() < 1e-9, "measure {v}, rows {rows}");
            });
        }
    }

    /// A floor z = f(x, y) on a 2 m grid over [−200, 200]².
    fn floor_of(f: impl Fn(f64, f64) -> f64) -> crate::seafloor::Seafloor {
        let (n, d, o) = (201, 2.0, -200.0);
        let z = (0..n * n)
            .map(|i| f(o + d * (i % n) as f64, o + d * (i / n) as f64))
            .collect();
        let lattice = crate::seafloor::Lattice::new(n, n, o, o, d, d);
        crate::seafloor::Seafloor::from_nodes(lattice, z, vec![false; n * n]).unwrap()
    }

    /// `curvature` recovers the bend of a bowl (Z = −100 + a·(x² + y²)/2: L = a), and finds none
    /// on a plane or a ridge (Z concave: the tangent plane lies above the floor).
    #[test]
    fn curvature_is_the_bowls_and_zero_on_a_plane_or_a_ridge() {
        let a = 0.01;
        let at = |f: &crate::seafloor::Seafloor, x: f64, y: f64, radius: f64| {
            let (z, grad) = f.elevation_and_gradient(x, y).unwrap();
            curvature(f, [x, y, z], z, grad, radius)
        };
        let bowl = floor_of(|x, y| -100.0 + 0.5 * a * (x * x + y * y));
        // at cell centres, where the bilinear grid's slope is the bowl's (at a node it is one
        // cell's, and L comes out larger: conservative)
        for (x, y, radius) in [(1.0, 1.0, 40.0), (31.0, -17.0, 80.0), (-55.0, 13.0, 20.0)] {
            let l = at(&bowl, x, y, radius);
            assert!(
                (l - a).abs() < 0.05 * a,
                "bowl at ({x}, {y}), Δ = {radius}: L = {l}"
            );
        }
        let plane = floor_of(|x, y| -100.0 + 0.1 * x - 0.05 * y);
        assert!(at(&plane, 11.0, 11.0, 50.0).abs() < 1e-9);
        let ridge = floor_of(|x, _| -100.0 - 0.5 * a * x * x);
        assert!(at(&ridge, 11.0, 11.0, 50.0).abs() < 1e-9);
        // below the least distance nothing is measured
        assert_eq!(at(&bowl, 1.0, 1.0, 4.0), 0.0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The curvature term bounds what it is for: on the bowl, from a cell centre, for any
        /// step d of a sample within the trust radius, the tangent plane plus ½L‖d‖² is at or above the floor (the
        /// linearised row so holds only where the true clearance does), and it agrees with the
        /// floor's value and slope at the reference (d = 0: the term and its derivative vanish).
        #[test]
        fn the_curvature_term_majorises_the_bowl_within_the_trust_radius(
            i in -30i32..30, j in -30i32..30,
            angle in 0.0..std::f64::consts::TAU, frac in 0.0..1.0f64, radius in 10.0..80.0f64,
        ) {
            // at a cell centre (where the grid's slope is the bowl's), in any direction
            let (x, y) = (2.0 * i as f64 + 1.0, 2.0 * j as f64 + 1.0);
            let bowl = floor_of(|x, y| -100.0 + 0.005 * (x * x + y * y));
            let (z, grad) = bowl.elevation_and_gradient(x, y).unwrap();
            let l = curvature(&bowl, [x, y, z], z, grad, radius);
            let (dx, dy) = (frac * radius * angle.cos(), frac * radius * angle.sin());
            let model = z + grad[0] * dx + grad[1] * dy + 0.5 * l * (dx * dx + dy * dy);
            let truth = bowl.elevation(x + dx, y + dy).unwrap();
            // the bilinear grid departs from the bowl by at most a·h²/8 = 5·10⁻³ m per cell
            prop_assert!(model >= truth - 0.02, "model {model}, floor {truth}");
        }
    }

    /// A row's g at the reference is the true shortfall when the reference violates C2_2 or
    /// holds it with less than `FLOOR_MARGIN` to spare (so the model and the SCP's measure
    /// agree there), and carries the whole margin otherwise.
    #[test]
    fn a_row_meets_the_reference_as_the_measure_does() {
        // g is taken with the full margin: g = Z + ε + FLOOR_MARGIN − z
        let violated_by = |d: f64| reference_margin(d + FLOOR_MARGIN);
        assert!((violated_by(1.0) - 1.0).abs() < 1e-12); // 1 m below ε: 1 m, not 1.5
        assert!(violated_by(0.0).abs() < 1e-12); // exactly at ε: met exactly
        assert!(violated_by(-0.2).abs() < 1e-12); // 0.2 m to spare: met exactly
        assert!((violated_by(-3.0) + 2.5).abs() < 1e-12); // 3 m to spare: 0.5 m kept
    }
}
