//! The lanes term of P5 (Step 3; ours, not in the paper): the team sweeps lanes a swath apart
//! at survey altitude. It prices, at w_lanes per metre, how far each AUV's cross-track gap to
//! its neighbour in the window's chain falls short of the swath, and how far each AUV flies
//! above the survey altitude:
//! w_lanes·[Σ_k Σ_i max(0, b − n̂ᵀ(P_{o(i+1)}\[k\] − P_{o(i)}\[k\])) + Σ_k Σ_n max(0, z_n\[k\] −
//! Z(x_n\[k\], y_n\[k\]) − h_s)], with o the chain's order (its lanes, `acoustic.graph =
//! "lanes"`), n̂ the window's cross-track direction, b `auv.swath_width` and h_s
//! `auv.survey_altitude`; the gaps' sum runs over k = 1..K − 1, the altitude's over k = 1..=K.
//! Zero when every lane neighbour is a swath or more across the track and every AUV at most
//! h_s above the floor.
//!
//! Why not the gaps at k = K: C1_6 gathers every AUV within d_s of the USV there (3-D), so a
//! team at the floor has a circle of radius √(d_s² − z²) to spread in (about 112 m at
//! z = −100 m) while the chain's links stay 120–150 m long: too little room for lanes a swath
//! apart from N = 5 on. Asked for them, the team either climbed (before
//! the altitude was priced) or kept a shortfall whose size depends on the floor under the
//! rendezvous, thousands in J at N = 5, which made the objective swing from seed to seed
//! (docs/design-decisions.md, "The lanes term").
//!
//! Why the gaps: OF1_5, a sum of squared distances, is largest with the team in two clusters at
//! the corridor's edges, where swaths overlap while strips between them go unswept
//! (docs/design-decisions.md, "The lanes term"). The gap to a lane
//! neighbour adds sea floor only up to one swath, so the term asks for lanes a swath apart and
//! no more.
//!
//! Why the altitude: C1_5 and C1_6 bound the 3-D range to the USV at the surface, so an AUV
//! gains width across the track by climbing (dr/dz = |z|/r). Priced for the gaps alone, the
//! outermost AUVs of a team of 15–20 climbed 40–70 m above the floor, where their swaths see
//! nothing (the explored area counts only swaths flown at survey altitude). With the height
//! above h_s priced at the gaps' own w_lanes, a metre of climb costs more than the at most
//! |z|/r < 1 metre of gap it can buy (docs/design-decisions.md, "The lanes term").
//!
//! Both sums are maxima of affine functions, convex, one variable and two rows per pair (per
//! AUV) and step: the gaps exact in the convex model, the height through the floor linearised
//! about the reference, as OF1_2's. n̂ and o are fixed for the window (from Step 1's plan), so
//! the true objective is one function of the positions for the whole SCP.

use super::links::LinkSet;
use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;

/// The window's lanes: the chain's order across the track and the cross-track direction.
#[derive(Debug, Clone, PartialEq)]
pub struct Lanes {
    /// The AUVs in chain order, so that the cross-track offset grows along it.
    pub order: Vec<usize>,
    /// n̂, the unit horizontal direction across the track (left of the USV's course, or right,
    /// whichever makes Step 1's offsets grow along `order`).
    pub cross: [f64; 2],
}

impl Lanes {
    /// The lanes of a window from its chain (the A2A path at k = 1: with `acoustic.graph =
    /// "lanes"` the same at every step) and Step 1's plan `step1`: n̂ is normal to the USV's
    /// course from P_USV\[0\] to P_USV\[K\], oriented so that the last AUV of the chain is, on
    /// average over k = 1..=K, farther along n̂ than the first. None without a chain of at least
    /// two AUVs, or when the USV moves less than 1 m (no course to be across).
    pub fn of(links: &LinkSet, step1: &Trajectory) -> Option<Lanes> {
        let n = step1.auv_p.len();
        if n < 2 || links.links.len() < 2 {
            return None;
        }
        let mut adjacent = vec![Vec::new(); n];
        for l in &links.links[1] {
            if let Some(b) = l.b {
                adjacent[l.a].push(b);
                adjacent[b].push(l.a);
            }
        }
        let first = (0..n).find(|&i| adjacent[i].len() == 1)?;
        let mut order = vec![first];
        let (mut previous, mut current) = (usize::MAX, first);
        while order.len() < n {
            let next = *adjacent[current].iter().find(|&&x| x != previous)?;
            order.push(next);
            (previous, current) = (current, next);
        }
        let (a, b) = (step1.usv_p[0], *step1.usv_p.last()?);
        let d = [b[0] - a[0], b[1] - a[1]];
        let length = d[0].hypot(d[1]);
        if length < 1.0 {
            return None;
        }
        let mut cross = [-d[1] / length, d[0] / length];
        let (o0, o1) = (order[0], order[n - 1]);
        let along: f64 = (1..step1.auv_p[0].len())
            .map(|k| gap(cross, step1.auv_p[o0][k], step1.auv_p[o1][k]))
            .sum();
        if along < 0.0 {
            cross = [-cross[0], -cross[1]];
        }
        Some(Lanes { order, cross })
    }

    /// The gaps' part of the term, metres: Σ_k Σ_i max(0, swath − n̂ᵀ(P_{o(i+1)}\[k\] −
    /// P_{o(i)}\[k\])), k = 1..K (not at k = K, where C1_6 gathers the team).
    pub fn shortfall(&self, t: &Trajectory, swath: f64) -> f64 {
        let steps = t.auv_p.first().map_or(0, Vec::len);
        (1..steps.saturating_sub(1))
            .flat_map(|k| {
                self.order.windows(2).map(move |w| {
                    (swath - gap(self.cross, t.auv_p[w[0]][k], t.auv_p[w[1]][k])).max(0.0)
                })
            })
            .sum()
    }
}

/// n̂ᵀ(to − from), horizontally.
fn gap(cross: [f64; 2], from: [f64; 3], to: [f64; 3]) -> f64 {
    cross[0] * (to[0] - from[0]) + cross[1] * (to[1] - from[1])
}

/// The unweighted term of `t`, metres (0 without lanes): the gaps' shortfall
/// ([`Lanes::shortfall`]) and Σ_k Σ_n max(0, z_n\[k\] − Z(x_n\[k\], y_n\[k\]) − h_s), k = 1..=K.
pub(super) fn value(p: &TeamProblem, t: &Trajectory) -> f64 {
    let Some(lanes) = &p.lanes else { return 0.0 };
    let survey = p.scenario.auv.survey_altitude;
    let above: f64 = t
        .auv_p
        .iter()
        .flat_map(|path| path[1..].iter())
        .map(|&q| (q[2] - p.floor_linearisation(q).0 - survey).max(0.0))
        .sum();
    lanes.shortfall(t, p.scenario.auv.swath_width) + above
}

/// The term's rows (nonnegative cone) and prices, w_lanes each (per AUV with `weights.scaling =
/// "per_auv"`): per lane pair i and step k, its shortfall variable h ≥ 0 and
/// b − n̂ᵀ(P_{o(i+1)}\[k\] − P_{o(i)}\[k\]) − h ≤ 0; per AUV n and step k, its height above the
/// survey altitude a ≥ 0 and z − Z̄ − ∇Z̄ᵀ(x − x̄, y − ȳ) − h_s − a ≤ 0, the floor linearised
/// about the reference `r`. Nothing without lanes.
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let Some(lanes) = &p.lanes else { return };
    let l = p.layout;
    let w = &p.scenario.weights;
    let price = w.w_lanes * w.per_auv(l.n);
    let swath = p.scenario.auv.swath_width;
    for (i, pair) in lanes.order.windows(2).enumerate() {
        // not at k = K, where C1_6 gathers the team within d_s of the USV
        for k in 1..l.k {
            let h = l.lane_shortfall(i, k);
            m.q[h] = price;
            m.nonnegative(h);
            // −n̂ᵀP_{o(i+1)} + n̂ᵀP_{o(i)} − h ≤ −b
            let row = m.row(-swath);
            m.a.push(row, h, -1.0);
            for c in 0..2 {
                m.a.push(row, l.auv_p(pair[1], k) + c, -lanes.cross[c]);
                m.a.push(row, l.auv_p(pair[0], k) + c, lanes.cross[c]);
            }
        }
    }
    let survey = p.scenario.auv.survey_altitude;
    for n in 0..l.n {
        for k in 1..=l.k {
            let a = l.lane_altitude(n, k);
            m.q[a] = price;
            m.nonnegative(a);
            // z − ∇Zᵀ(x, y) − a ≤ h_s + Z̄ − ∇Zᵀ(x̄, ȳ)
            let x = r.auv_p[n][k];
            let (z, grad) = p.floor_linearisation(x);
            let row = m.row(survey + z - grad[0] * x[0] - grad[1] * x[1]);
            let col = l.auv_p(n, k);
            m.a.push(row, col, -grad[0]);
            m.a.push(row, col + 1, -grad[1]);
            m.a.push(row, col + 2, 1.0);
            m.a.push(row, a, -1.0);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mission::scenario_floor;
    use crate::plan::{Band, Link};
    use crate::scenario::Scenario;
    use proptest::prelude::*;

    /// A window of `n` AUVs at the given cross-track offsets (y, the USV heading east), the
    /// same at every step, K = 3.
    fn abreast(ys: &[f64]) -> Trajectory {
        let k = 3;
        Trajectory {
            usv_p: (0..=k).map(|j| [100.0 * j as f64, 0.0]).collect(),
            usv_u: vec![[1.0, 0.0]; k],
            auv_p: ys
                .iter()
                .map(|&y| (0..=k).map(|j| [100.0 * j as f64, y, -50.0]).collect())
                .collect(),
            auv_v: vec![vec![[0.0; 3]; k + 1]; ys.len()],
            auv_u: vec![vec![[0.0; 3]; k]; ys.len()],
        }
    }

    /// The chain `path` (A2A edges between consecutive entries, an A2U link to the first) at
    /// every step k = 0..=K.
    fn chain(path: &[usize], k: usize) -> LinkSet {
        let band = Band {
            lo: 120.0,
            hi: 150.0,
        };
        let mut step = vec![Link {
            a: path[0],
            b: None,
        }];
        step.extend(path.windows(2).map(|w| Link {
            a: w[0],
            b: Some(w[1]),
        }));
        LinkSet {
            links: vec![step.clone(); k + 1],
            bands: vec![vec![band; step.len()]; k + 1],
        }
    }

    /// The order follows the chain, n̂ points the way its offsets grow, and each gap falls short
    /// of the 50 m swath by its own measure: here −20 m (a pair out of lane order) by 70 m,
    /// 200 m by nothing and 30 m by 20 m, at steps 1 and 2 and not at k = K = 3, where C1_6
    /// gathers the team.
    #[test]
    fn lanes_follow_the_chain_across_the_track_and_count_each_gap_up_to_a_swath() {
        // y of AUVs 0..3: −70, 110, −100, 130 m; the chain is 1–3–0–2, from y = 110 to −100
        let t = abreast(&[-70.0, 110.0, -100.0, 130.0]);
        let lanes = Lanes::of(&chain(&[1, 3, 0, 2], 3), &t).expect("a chain");
        assert_eq!(lanes.order, vec![1, 3, 0, 2]);
        // the USV heads east, so across is ±y; along the chain y falls: n̂ = (0, −1)
        assert!(lanes.cross[0].abs() < 1e-12 && (lanes.cross[1] + 1.0).abs() < 1e-12);
        let v = lanes.shortfall(&t, 50.0);
        assert!((v - 2.0 * (70.0 + 0.0 + 20.0)).abs() < 1e-9, "{v}");
    }

    /// No lanes for one AUV, or when the USV stays put.
    #[test]
    fn no_lanes_without_a_pair_or_a_course() {
        let t = abreast(&[0.0]);
        assert_eq!(Lanes::of(&chain(&[0], 3), &t), None);
        let mut t = abreast(&[0.0, 60.0]);
        for p in &mut t.usv_p {
            *p = [0.0, 0.0];
        }
        assert_eq!(Lanes::of(&chain(&[0, 1], 3), &t), None);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The altitude rows of `rows` at a waypoint moved by d from the reference (a = 0): the
        /// excess they read, −s = z − Z̄ − ∇Z̄ᵀd − h_s, is the true z − Z(x̄ + d) − h_s up to the
        /// bilinear floor's second order (central differences: |d| ≤ 1 cm), and at the
        /// reference (d = 0) `value` is the shortfall plus Σ max(0, −s): model and merit agree
        /// there, as SCvx needs.
        #[test]
        fn the_altitude_rows_read_the_height_above_the_survey_altitude(
            k in 1usize..=3, dx in -0.01..0.01f64, dy in -0.01..0.01f64, dz in -30.0..30.0f64,
        ) {
            let mut s = Scenario::default();
            s.team.auvs = 2;
            s.horizon.steps = 3;
            let (floor, _) = scenario_floor(&s, std::path::Path::new("")).unwrap();
            let keep_out = floor.keep_out();
            let p = TeamProblem::first_window(&s, &floor, &keep_out).unwrap();
            let mut r = p.initial_guess(None);
            let p = p.with_links(chain(&[0, 1], 3)).with_lanes(&r);
            prop_assert!(p.lanes.is_some());
            let l = p.layout;
            // the reference's waypoints at heights from 5 to 35 m over the floor
            for (n, path) in r.auv_p.iter_mut().enumerate() {
                for (j, q) in path.iter_mut().enumerate().skip(1) {
                    q[2] = floor.elevation(q[0], q[1]).unwrap() + 5.0 + 10.0 * (n + j) as f64;
                }
            }
            let mut m = Assembly::new(l.variables());
            rows(&p, &r, &mut m);
            let slack = |x: &[f64]| {
                let mut s = m.b.clone();
                for i in 0..m.a.len() {
                    s[m.a.rows[i]] -= m.a.vals[i] * x[m.a.cols[i]];
                }
                s
            };
            // the altitude row of AUV n at step j: the one that holds its column a[n][j]
            let row_of = |n: usize, j: usize| {
                let a = l.lane_altitude(n, j);
                (0..m.a.len())
                    .find(|&i| m.a.cols[i] == a && m.a.vals[i] == -1.0 && m.b[m.a.rows[i]] != 0.0)
                    .map(|i| m.a.rows[i])
                    .unwrap()
            };
            let mut x = vec![0.0; l.variables()];
            for (n, path) in r.auv_p.iter().enumerate() {
                for (j, q) in path.iter().enumerate().skip(1) {
                    x[l.auv_p(n, j)..l.auv_p(n, j) + 3].copy_from_slice(q);
                }
            }
            let h_s = s.auv.survey_altitude;
            let at_reference = slack(&x);
            let mut read = 0.0;
            for n in 0..2 {
                for j in 1..=3 {
                    read += (-at_reference[row_of(n, j)]).max(0.0);
                }
            }
            let shortfall = p.lanes.as_ref().unwrap().shortfall(&r, s.auv.swath_width);
            prop_assert!((value(&p, &r) - (shortfall + read)).abs() < 1e-9);
            // moved by d
            let c = l.auv_p(0, k);
            x[c] += dx;
            x[c + 1] += dy;
            x[c + 2] += dz;
            let q = r.auv_p[0][k];
            let truth = q[2] + dz - floor.elevation(q[0] + dx, q[1] + dy).unwrap() - h_s;
            let model = -slack(&x)[row_of(0, k)];
            prop_assert!((model - truth).abs() < 1e-6, "model {model}, floor {truth}");
        }
    }
}
