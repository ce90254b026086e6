//! The metrics of a plan ([`Metrics`]) over one window ([`window_metrics`]) and over a whole
//! mission ([`mission_metrics`]).
//!
//! Conventions (those of [`crate::plan`]): a window has K steps, positions k = 0..=K, inputs
//! k = 0..K−1; K is taken from the USV path (`usv.position.len() − 1`). Nodes of the acoustic
//! graph are the USV, at (x, y, 0), and the AUVs; a link is *usable* when its 3-D length is at
//! most d_s + [`RANGE_TOL`] and it has line of sight: `floor.segment_clearance(a, b, r)` returns
//! a minimum clearance ≥ 0 and no sample of it is over an obstacle cell (NODATA or land,
//! `floor.segment_obstacle(a, b, r)`) (an error from the query, e.g. an endpoint off the grid,
//! counts as no line of sight). An AUV whose path is shorter than the USV's is absent at the missing steps:
//! it has no usable link there.

use crate::plan::{Link, Metrics, Stage};
use crate::seafloor::Seafloor;
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};

/// A link up to this much (metres) longer than d_s still counts as in range: the checker's
/// tolerance (Step 3 keeps every band's upper end 1 mm inside d_s, so planned links never need
/// more), so that a plan the planner accepts as connected passes `shoal check`.
pub const RANGE_TOL: f64 = 1e-6;

/// What the metrics need from the scenario (built by the caller).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MetricParams {
    /// δ, time between steps, seconds (positive).
    pub dt: f64,
    /// d_s, sonar range, metres.
    pub sonar_range: f64,
    /// r, sampling step of the line-of-sight query 𝓛_r, metres.
    pub resolution: f64,
    /// Full width w of an AUV's sensor swath on the floor, metres. Zero or less: no area.
    pub swath_width: f64,
    /// Highest altitude above the floor (metres) at which a swath counts: a segment whose ends
    /// are not both on the grid and at most this high adds no area.
    pub survey_altitude: f64,
}

/// Height c of the strips the explored area is measured on, metres: max(w / 10, 1 m).
pub fn strip_height(swath_width: f64) -> f64 {
    (swath_width / 10.0).max(1.0)
}

/// A plane set measured on horizontal strips of height c aligned to the origin: strip j is
/// j·c ≤ y < (j + 1)·c, and the set holds, in strip j, the x-intervals where the swept set meets
/// the strip's centre line y = (j + ½)c, exactly. Sets built with the same c share their strips,
/// so those of different windows can be unioned. Its area is c · Σ interval lengths: the
/// midpoint rule in y of the swept area, exact in x.
#[derive(Debug, Clone, PartialEq)]
pub struct ExploredStrips {
    c: f64,
    /// Strip j → sorted, disjoint x-intervals [lo, hi], metres; no empty strips. Ordered, so
    /// that the area is summed in one order and is reproducible to the bit.
    rows: BTreeMap<i64, Vec<[f64; 2]>>,
}

impl ExploredStrips {
    /// The empty set on strips of height `c` metres.
    pub fn new(c: f64) -> ExploredStrips {
        ExploredStrips {
            c,
            rows: BTreeMap::new(),
        }
    }

    /// Whether x lies in an interval of the strip holding y.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let j = (y / self.c).floor() as i64;
        let row = self.rows.get(&j);
        row.is_some_and(|r| r.iter().any(|i| i[0] <= x && x <= i[1]))
    }

    /// Area, km²: c · Σ (hi − lo) / 10⁶.
    pub fn area_km2(&self) -> f64 {
        let len: f64 = self.rows.values().flatten().map(|i| i[1] - i[0]).sum();
        // a float sum of nothing is −0.0: + 0.0 makes an empty set's area +0
        len * self.c * 1e-6 + 0.0
    }

    /// Adds `other`. Panics if the strips differ (different heights).
    pub fn union_with(&mut self, other: &ExploredStrips) {
        assert_eq!(self.c, other.c, "union of sets on different strips");
        for (j, intervals) in &other.rows {
            let row = self.rows.entry(*j).or_default();
            row.extend_from_slice(intervals);
            merge(row);
        }
    }

    /// Adds the swath of every segment k−1 → k of every AUV of `stage` whose two ends are
    /// `surveyed` (rows left unmerged).
    fn add_stage(&mut self, stage: &Stage, swath_width: f64, surveyed: &dyn Fn([f64; 3]) -> bool) {
        if !(swath_width > 0.0 && swath_width.is_finite()) {
            return;
        }
        for auv in &stage.auvs {
            for s in auv.position.windows(2) {
                let (a, b) = ([s[0][0], s[0][1]], [s[1][0], s[1][1]]);
                if a.iter().chain(&b).all(|v| v.is_finite()) && surveyed(s[0]) && surveyed(s[1]) {
                    self.add_stadium(a, b, swath_width / 2.0);
                }
            }
        }
    }

    /// Adds the points within `r` of the segment a–b. The stadium is convex, so a centre line
    /// meets it in one interval: the hull of its intersections with the two end discs and the
    /// rectangle {0 ≤ along ≤ L, |across| ≤ r}.
    fn add_stadium(&mut self, a: [f64; 2], b: [f64; 2], r: f64) {
        let c = self.c;
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let len = dx.hypot(dy);
        // strips whose centre line lies in [min y − r, max y + r]
        let first = ((a[1].min(b[1]) - r) / c - 0.5).ceil() as i64;
        let last = ((a[1].max(b[1]) + r) / c - 0.5).floor() as i64;
        for j in first..=last {
            let y = (j as f64 + 0.5) * c;
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in [a, b] {
                let h = r * r - (y - p[1]) * (y - p[1]);
                if h >= 0.0 {
                    (lo, hi) = (lo.min(p[0] - h.sqrt()), hi.max(p[0] + h.sqrt()));
                }
            }
            if len > 0.0 {
                // t = x − a_x; along = t·u_x + (y − a_y)·u_y, across = −t·u_y + (y − a_y)·u_x
                let (ux, uy, ey) = (dx / len, dy / len, y - a[1]);
                let mut t = (f64::NEG_INFINITY, f64::INFINITY);
                clip(&mut t, ux, ey * uy, 0.0, len);
                clip(&mut t, -uy, ey * ux, -r, r);
                if t.0 <= t.1 {
                    (lo, hi) = (lo.min(a[0] + t.0), hi.max(a[0] + t.1));
                }
            }
            if lo < hi {
                self.rows.entry(j).or_default().push([lo, hi]);
            }
        }
    }

    fn normalise(&mut self) {
        self.rows.values_mut().for_each(merge);
    }
}

/// Narrows the interval `t` to {t : lo ≤ coef·t + offset ≤ hi}.
fn clip(t: &mut (f64, f64), coef: f64, offset: f64, lo: f64, hi: f64) {
    if coef.abs() < 1e-12 {
        if !(lo..=hi).contains(&offset) {
            *t = (f64::INFINITY, f64::NEG_INFINITY);
        }
        return;
    }
    let (t0, t1) = ((lo - offset) / coef, (hi - offset) / coef);
    *t = (t.0.max(t0.min(t1)), t.1.min(t0.max(t1)));
}

/// Sorts intervals and merges the overlapping ones.
fn merge(intervals: &mut Vec<[f64; 2]>) {
    intervals.sort_unstable_by(|p, q| p[0].total_cmp(&q[0]));
    let mut out: Vec<[f64; 2]> = Vec::with_capacity(intervals.len());
    for i in intervals.drain(..) {
        match out.last_mut() {
            Some(l) if i[0] <= l[1] => l[1] = l[1].max(i[1]),
            _ => out.push(i),
        }
    }
    *intervals = out;
}

/// The set swept by the AUVs of one window: for every AUV and segment k−1 → k whose two ends
/// are `surveyed` (at survey altitude: [`surveyed`]), the points within w/2 of the horizontal
/// segment (a stadium of area L·w + πw²/4), on strips of height [`strip_height`]`(w)`.
/// Segments with a non-finite endpoint are skipped.
///
/// Discretisation error: that of the midpoint rule in y on the chord length ℓ(y) of the swept
/// set; for one stadium at most c·(total variation of ℓ) = 2c·(its longest horizontal chord), a
/// crude worst case. It is nil where ℓ is linear in y, O(c²) at each kink of ℓ and
/// O(c^{3/2}·w^{1/2}) at each end of a swath, where ℓ of the circular cap goes as a square root
/// (no lattice resonance: x is exact). Measured with w = 50 m, c = 5 m over random offsets and
/// directions: ≤ 0.2 % for L = 500 m, ≤ 1 % for L = 100 m, ≤ 2.5 % for L = 10 m (the tests
/// check 0.5 % at 500 m). Cost: one interval per strip crossed, ≈ (|Δy| + w)/c per segment.
pub fn explored_strips(
    stage: &Stage,
    swath_width: f64,
    surveyed: &dyn Fn([f64; 3]) -> bool,
) -> ExploredStrips {
    let mut strips = ExploredStrips::new(strip_height(swath_width));
    strips.add_stage(stage, swath_width, surveyed);
    strips.normalise();
    strips
}

/// Whether the waypoint `q` is at survey altitude: on the grid, and at most
/// `survey_altitude` above the floor there.
pub fn surveyed(floor: &Seafloor, survey_altitude: f64, q: [f64; 3]) -> bool {
    floor
        .elevation(q[0], q[1])
        .is_ok_and(|z| q[2] - z <= survey_altitude)
}

/// Metrics of one window; `links[k]`, k = 0..=K, are its planned links (A2U first, then A2A)
/// and `times` the Step 1, 2, 3 solve times in seconds. The same as [`mission_metrics`] of a
/// one-window mission; see there for the definitions.
pub fn window_metrics(
    stage: &Stage,
    links: &[Vec<Link>],
    floor: &Seafloor,
    p: &MetricParams,
    times: [f64; 3],
) -> Metrics {
    mission_metrics(&[(stage, links)], floor, p, &[times])
}

/// Metrics of a mission of consecutive windows (step k = 0 of window w + 1 is step K of window
/// w), each with its planned links per step; `times` are each window's Step 1, 2, 3 solve times.
///
/// - `input_energy`: Σ_windows Σ_n Σ_k ‖U_n\[k\]‖², (m/s²)².
/// - `explored_area_km2`: area of the union over windows of [`explored_strips`], km² (an area
///   swept twice counts once), of the segments flown at survey altitude (both ends at most
///   `survey_altitude` above the floor, [`surveyed`]).
/// - `revisited_area_km2`: Σ_windows (area of the window's [`explored_strips`]) − the union's,
///   km²: ground swept again in a later window (0 for one window).
/// - `mean_height`, `min_height`: z − Z(x, y) over every AUV waypoint k = 1..=K of every window,
///   metres; waypoints off the grid (or not finite) are skipped, and with none left both are 0.
/// - `connected_fraction`: fraction of steps at which every AUV reaches the USV through usable
///   links (see the module docs) between any nodes, not only the planned ones.
/// - `chain_fraction`: fraction of steps at which every planned link of `links[k]` is usable
///   and the planned links alone connect every AUV to the USV. A step with no `links[k]` (in
///   particular every step of a window with empty `links`, i.e. no Step 2 data) fails, as does
///   a link naming an AUV that does not exist.
/// - Steps counted: k = 0..=K of the first window and k = 1..=K of the later ones, so no step
///   is counted twice; with no step, both fractions are 0.
/// - `max_heading_rate`: max over AUVs, windows and k = 1..=K with both headings defined of
///   |wrap(ψ\[k\] − ψ\[k−1\])| / δ, wrap to (−π, π], rad/s (0 if no such pair).
/// - `step{1,2,3}_time_s`: sums of `times`, seconds.
pub fn mission_metrics(
    windows: &[(&Stage, &[Vec<Link>])],
    floor: &Seafloor,
    p: &MetricParams,
    times: &[[f64; 3]],
) -> Metrics {
    let mut swept = ExploredStrips::new(strip_height(p.swath_width));
    let mut window_areas = 0.0;
    let (mut energy, mut max_rate) = (0.0, 0.0_f64);
    let (mut height_sum, mut heights, mut min_height) = (0.0, 0usize, f64::INFINITY);
    let (mut steps, mut connected, mut chain) = (0usize, 0usize, 0usize);
    for (w, &(stage, links)) in windows.iter().enumerate() {
        let own = explored_strips(stage, p.swath_width, &|q| {
            surveyed(floor, p.survey_altitude, q)
        });
        window_areas += own.area_km2();
        swept.union_with(&own);
        for auv in &stage.auvs {
            energy += auv.input.iter().flatten().map(|u| u * u).sum::<f64>();
            for q in auv.position.iter().skip(1) {
                let h = floor.elevation(q[0], q[1]).map(|z| q[2] - z);
                if let Some(h) = h.ok().filter(|h| h.is_finite()) {
                    (height_sum, heights, min_height) =
                        (height_sum + h, heights + 1, min_height.min(h));
                }
            }
            for s in auv.heading.windows(2) {
                if let [Some(h0), Some(h1)] = s {
                    max_rate = max_rate.max(wrap(h1 - h0).abs() / p.dt);
                }
            }
        }
        let k_max = stage.usv.position.len();
        for k in usize::from(w > 0)..k_max {
            let mut g = StepGraph::new(stage, k, floor, p);
            steps += 1;
            connected += usize::from(g.connects(None));
            chain += usize::from(links.get(k).is_some_and(|l| g.connects(Some(l))));
        }
    }
    let ratio = |n: f64, d: usize| if d == 0 { 0.0 } else { n / d as f64 };
    let time = |i: usize| times.iter().map(|t| t[i]).sum();
    Metrics {
        input_energy: energy,
        explored_area_km2: swept.area_km2(),
        // one window: exactly 0 (the union of one set is itself)
        revisited_area_km2: if windows.len() > 1 {
            (window_areas - swept.area_km2()).max(0.0)
        } else {
            0.0
        },
        mean_height: ratio(height_sum, heights),
        min_height: if heights == 0 { 0.0 } else { min_height },
        connected_fraction: ratio(connected as f64, steps),
        chain_fraction: ratio(chain as f64, steps),
        max_heading_rate: max_rate,
        step1_time_s: time(0),
        step2_time_s: time(1),
        step3_time_s: time(2),
    }
}

/// Angle wrapped to (−π, π].
fn wrap(a: f64) -> f64 {
    let r = a.rem_euclid(TAU);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

/// The first step k of `stage` at which an AUV reaches the USV through no chain of links in
/// range (d_s + `RANGE_TOL`) and in line of sight, and that AUV: the hard requirement of the
/// acoustic chain, which the planner checks before it accepts a window.
pub fn first_cut_off(stage: &Stage, floor: &Seafloor, p: &MetricParams) -> Option<(usize, usize)> {
    (0..stage.usv.position.len())
        .find_map(|k| StepGraph::new(stage, k, floor, p).cut_off().map(|n| (k, n)))
}

/// The acoustic graph at one step: node 0 the USV at z = 0, node n + 1 AUV n (None if its path
/// has no step k); whether each link is usable, computed once.
struct StepGraph<'a> {
    nodes: Vec<Option<[f64; 3]>>,
    usable: Vec<Option<bool>>,
    floor: &'a Seafloor,
    p: &'a MetricParams,
}

impl<'a> StepGraph<'a> {
    fn new(stage: &Stage, k: usize, floor: &'a Seafloor, p: &'a MetricParams) -> StepGraph<'a> {
        let usv = stage.usv.position.get(k).map(|u| [u[0], u[1], 0.0]);
        let auvs = stage.auvs.iter().map(|a| a.position.get(k).copied());
        let nodes: Vec<_> = std::iter::once(usv).chain(auvs).collect();
        let usable = vec![None; nodes.len() * nodes.len()];
        StepGraph {
            nodes,
            usable,
            floor,
            p,
        }
    }

    fn usable(&mut self, i: usize, j: usize) -> bool {
        let key = i.min(j) * self.nodes.len() + i.max(j);
        if let Some(u) = self.usable[key] {
            return u;
        }
        let u = match (self.nodes[i], self.nodes[j]) {
            (Some(a), Some(b)) => {
                let d2: f64 = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum();
                d2.sqrt() <= self.p.sonar_range + RANGE_TOL
                    && self
                        .floor
                        .segment_clearance(a, b, self.p.resolution)
                        .is_ok_and(|c| c.min_clearance >= 0.0)
                    && self
                        .floor
                        .segment_obstacle(a, b, self.p.resolution)
                        .is_ok_and(|o| o.is_none())
            }
            _ => false,
        };
        self.usable[key] = Some(u);
        u
    }

    /// The first AUV that reaches the USV over no chain of usable links, if any.
    fn cut_off(&mut self) -> Option<usize> {
        let (mut seen, mut stack) = (vec![false; self.nodes.len()], vec![0]);
        seen[0] = true;
        while let Some(i) = stack.pop() {
            for j in 0..self.nodes.len() {
                if !seen[j] && self.usable(i, j) {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        seen.iter().position(|&s| !s).map(|node| node - 1)
    }

    /// Whether every node reaches the USV: over every usable link (`planned` None), or over the
    /// planned links, each of which must be usable.
    fn connects(&mut self, planned: Option<&[Link]>) -> bool {
        let m = self.nodes.len();
        let mut adjacent = vec![Vec::new(); m];
        if let Some(links) = planned {
            for l in links {
                let (i, j) = (
                    l.a.saturating_add(1),
                    l.b.map_or(0, |b| b.saturating_add(1)),
                );
                if i >= m || j >= m || !self.usable(i, j) {
                    return false;
                }
                adjacent[i].push(j);
                adjacent[j].push(i);
            }
        }
        let (mut seen, mut stack) = (vec![false; m], vec![0]);
        seen[0] = true;
        while let Some(i) = stack.pop() {
            for j in 0..m {
                if seen[j] {
                    continue;
                }
                let linked = match planned {
                    Some(_) => adjacent[i].contains(&j),
                    None => self.usable(i, j),
                };
                if linked {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        seen.iter().all(|&s| s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{AuvPath, ObjectiveTerms, UsvPath};
    use crate::seafloor::Lattice;

    const P: MetricParams = MetricParams {
        dt: 10.0,
        sonar_range: 150.0,
        resolution: 1.0,
        swath_width: 50.0,
        survey_altitude: 15.0,
    };

    /// Regression: a plan whose AUVs never come down to survey altitude printed "explored
    /// -0.000 km²" (a float sum of nothing is −0.0).
    #[test]
    fn regression_nothing_explored_is_zero_not_negative_zero() {
        let area = ExploredStrips::new(strip_height(50.0)).area_km2();
        assert!(area == 0.0 && area.is_sign_positive(), "{area}");
        assert_eq!(format!("{area:.3}"), "0.000");
    }

    /// Every waypoint at survey altitude (for the geometry tests, which have no floor).
    fn everywhere(_: [f64; 3]) -> bool {
        true
    }

    /// 400 m × 400 m around the origin, 10 m nodes, floor at −100 m except the node column
    /// x = 0, at `ridge` metres (a wall along y between x = −10 and 10).
    fn floor(ridge: f64) -> Seafloor {
        let (n, d, o) = (41, 10.0, -200.0);
        let z = (0..n * n).map(|k| if k % n == 20 { ridge } else { -100.0 });
        Seafloor::from_nodes(
            Lattice::new(n, n, o, o, d, d),
            z.collect(),
            vec![false; n * n],
        )
        .unwrap()
    }

    /// At rest (zero velocity and inputs, no heading) at each position.
    fn auv(position: Vec<[f64; 3]>) -> AuvPath {
        let k = position.len();
        AuvPath {
            velocity: vec![[0.0; 3]; k],
            input: vec![[0.0; 3]; k - 1],
            surge_speed: vec![0.0; k],
            heading: vec![None; k],
            position,
        }
    }

    fn stage(usv: Vec<[f64; 2]>, auvs: Vec<Vec<[f64; 3]>>) -> Stage {
        Stage {
            status: "converged".into(),
            iterations: 1,
            solve_time_s: 0.0,
            objective: ObjectiveTerms::default(),
            max_violation: 0.0,
            usv: UsvPath {
                input: vec![[0.0; 2]; usv.len() - 1],
                position: usv,
            },
            auvs: auvs.into_iter().map(auv).collect(),
            scp: Vec::new(),
        }
    }

    fn a2u(a: usize) -> Link {
        Link { a, b: None }
    }

    fn a2a(a: usize, b: usize) -> Link {
        Link { a, b: Some(b) }
    }

    /// A straight swath from `a` to `b` as a one-AUV, one-step stage at z = −90.
    fn swath(a: [f64; 2], b: [f64; 2]) -> Stage {
        let auv = vec![[a[0], a[1], -90.0], [b[0], b[1], -90.0]];
        stage(vec![[0.0; 2]; 2], vec![auv])
    }

    fn area_m2(swept: &ExploredStrips) -> f64 {
        swept.area_km2() * 1e6
    }

    #[test]
    fn energy_sums_squared_inputs() {
        let mut s = stage(vec![[0.0; 2]; 3], vec![vec![[0.0, 0.0, -50.0]; 3]; 2]);
        s.auvs[0].input = vec![[1.0, 2.0, 2.0], [0.0, 0.0, 3.0]];
        s.auvs[1].input = vec![[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]];
        let f = floor(-100.0);
        assert_eq!(window_metrics(&s, &[], &f, &P, [0.0; 3]).input_energy, 19.0);
        let w: &[Vec<Link>] = &[];
        let m = mission_metrics(&[(&s, w), (&s, w)], &f, &P, &[[1.0, 2.0, 3.0]; 2]);
        assert_eq!(m.input_energy, 38.0);
        let times = (m.step1_time_s, m.step2_time_s, m.step3_time_s);
        assert_eq!(times, (2.0, 4.0, 6.0));
    }

    #[test]
    fn one_swath_matches_the_stadium_area() {
        let (l, w) = (500.0, P.swath_width);
        let exact = l * w + PI * w * w / 4.0;
        for (angle, origin) in [
            (0.0, [0.0, 0.0]),
            (0.3, [1.3, -7.9]),
            (PI / 4.0, [3.0, 2.5]),
            (PI / 2.0, [-0.4, 0.1]),
            (2.0, [1.0, 1.0]),
        ] {
            let b = [origin[0] + l * angle.cos(), origin[1] + l * angle.sin()];
            let area = area_m2(&explored_strips(&swath(origin, b), w, &everywhere));
            assert!(
                (area - exact).abs() < 0.005 * exact,
                "{angle}: {area} vs {exact}"
            );
            // the crude bound of `explored_strips`: longest chord ≤ L + w
            assert!((area - exact).abs() <= 2.0 * strip_height(w) * (l + w));
        }
        assert_eq!(
            explored_strips(&swath([0.0; 2], [10.0, 0.0]), 0.0, &everywhere).area_km2(),
            0.0
        );
    }

    #[test]
    fn overlapping_parallel_swaths_count_their_union() {
        let (l, d, r) = (500.0, 30.0, P.swath_width / 2.0);
        let s = stage(
            vec![[0.0; 2]; 2],
            vec![
                vec![[0.0, 0.0, -90.0], [l, 0.0, -90.0]],
                vec![[0.0, d, -90.0], [l, d, -90.0]],
            ],
        );
        // rectangle [0, L] × [−r, d + r] plus the union of two discs of radius r, d apart
        let lens = 2.0 * r * r * (d / (2.0 * r)).acos() - d / 2.0 * (4.0 * r * r - d * d).sqrt();
        let exact = l * (2.0 * r + d) + 2.0 * PI * r * r - lens;
        let area = area_m2(&explored_strips(&s, P.swath_width, &everywhere));
        assert!((area - exact).abs() < 0.01 * exact, "{area} vs {exact}");
    }

    #[test]
    fn windows_union_their_swaths() {
        let f = floor(-100.0);
        // on the grid (x, y in [−200, 200]), 10 m above its floor at z = −100
        let (first, second) = (
            swath([-180.0, 0.0], [0.0, 0.0]),
            swath([0.0, 0.0], [180.0, 0.0]),
        );
        let none: &[Vec<Link>] = &[];
        let one = window_metrics(&first, none, &f, &P, [0.0; 3]).explored_area_km2;
        let twice = mission_metrics(&[(&first, none), (&first, none)], &f, &P, &[]);
        assert_eq!(twice.explored_area_km2, one);
        let both = mission_metrics(&[(&first, none), (&second, none)], &f, &P, &[]);
        let mut swept = explored_strips(&first, P.swath_width, &everywhere);
        swept.union_with(&explored_strips(&second, P.swath_width, &everywhere));
        assert_eq!(both.explored_area_km2, swept.area_km2());
        let exact = (360.0 * 50.0 + PI * 50.0 * 50.0 / 4.0) * 1e-6;
        assert!((both.explored_area_km2 - exact).abs() < 0.01 * exact);
        assert!(swept.contains(90.0, 24.0) && !swept.contains(90.0, 26.0));
    }

    /// A swath counts only where the AUV flies at survey altitude: of three AUVs abreast over
    /// a flat floor at −100 m, the one 10 m up explores its stadium, the one 40 m up nothing,
    /// and the one that climbs from 10 to 40 m over its second segment only its first.
    #[test]
    fn only_swaths_flown_at_survey_altitude_count() {
        let f = floor(-100.0);
        let low = vec![[-150.0, -100.0, -90.0], [0.0, -100.0, -90.0]];
        let high = vec![[-150.0, 0.0, -60.0], [0.0, 0.0, -60.0]];
        let climbs = vec![
            [-150.0, 100.0, -90.0],
            [0.0, 100.0, -90.0],
            [150.0, 100.0, -60.0],
        ];
        let none: &[Vec<Link>] = &[];
        let one = |path: Vec<[f64; 3]>| {
            let s = stage(vec![[0.0; 2]; path.len()], vec![path]);
            window_metrics(&s, none, &f, &P, [0.0; 3]).explored_area_km2
        };
        let stadium = (150.0 * 50.0 + PI * 50.0 * 50.0 / 4.0) * 1e-6;
        assert!((one(low) - stadium).abs() < 0.01 * stadium);
        assert_eq!(one(high), 0.0);
        assert!((one(climbs) - stadium).abs() < 0.01 * stadium);
    }

    #[test]
    fn heights_skip_k0_and_off_grid_waypoints() {
        let s = stage(
            vec![[0.0; 2]; 3],
            vec![
                vec![[0.0, 0.0, -50.0], [10.0, 0.0, -90.0], [20.0, 0.0, -80.0]],
                vec![[0.0, 5.0, -60.0], [10.0, 5.0, -95.0], [1000.0, 5.0, -95.0]],
            ],
        );
        let m = window_metrics(&s, &[], &floor(-100.0), &P, [0.0; 3]);
        assert!((m.mean_height - 35.0 / 3.0).abs() < 1e-12);
        assert_eq!(m.min_height, 5.0);
    }

    /// AUVs 0 and 1 on either side of x = 0 at z = −80; the USV at (−50, 50) at k = 0 (AUV 1's
    /// only routes cross the ridge) and at (0, 100) at k = 1 (both AUVs see it over the ridge).
    fn across_the_ridge() -> Stage {
        stage(
            vec![[-50.0, 50.0], [0.0, 100.0]],
            vec![vec![[-50.0, 0.0, -80.0]; 2], vec![[50.0, 0.0, -80.0]; 2]],
        )
    }

    #[test]
    fn a_ridge_cuts_the_graph_unless_the_usv_sees_over_it() {
        let s = across_the_ridge();
        let chain = vec![vec![a2u(0), a2a(0, 1)]; 2];
        let m = window_metrics(&s, &chain, &floor(-10.0), &P, [0.0; 3]);
        assert_eq!((m.connected_fraction, m.chain_fraction), (0.5, 0.0));
        let m = window_metrics(&s, &chain, &floor(-100.0), &P, [0.0; 3]);
        assert_eq!((m.connected_fraction, m.chain_fraction), (1.0, 1.0));
    }

    /// The planner refuses a window by this: step 0 is cut (AUV 1 behind the ridge), step 1
    /// is not (the USV has moved over it); without the ridge nothing is cut.
    #[test]
    fn first_cut_off_names_the_step_and_the_auv() {
        let s = across_the_ridge();
        assert_eq!(first_cut_off(&s, &floor(-10.0), &P), Some((0, 1)));
        assert_eq!(first_cut_off(&s, &floor(-100.0), &P), None);
    }

    /// A NODATA node at (0, 10) makes the cells of y in [0, 10] beside it obstacles, though
    /// the floor along y = 0 stays at −100 m: a link along y = 0 crosses them, one along
    /// y = −20 does not.
    #[test]
    fn a_link_over_an_obstacle_cell_has_no_line_of_sight() {
        let n = 41;
        let mut nodata = vec![false; n * n];
        nodata[21 * n + 20] = true;
        let f = Seafloor::from_nodes(
            Lattice::new(n, n, -200.0, -200.0, 10.0, 10.0),
            vec![-100.0; n * n],
            nodata,
        )
        .unwrap();
        let s = stage(vec![[-60.0, 0.0]], vec![vec![[60.0, 0.0, -80.0]]]);
        assert!(
            f.segment_clearance([-60.0, 0.0, 0.0], [60.0, 0.0, -80.0], 1.0)
                .unwrap()
                .min_clearance
                > 0.0
        );
        assert_eq!(first_cut_off(&s, &f, &P), Some((0, 0)));
        let s = stage(vec![[-60.0, -20.0]], vec![vec![[60.0, -20.0, -80.0]]]);
        assert_eq!(first_cut_off(&s, &f, &P), None);
    }

    #[test]
    fn chain_fraction_needs_every_planned_link_and_a_spanning_chain() {
        // AUV 1 ends 160 m from AUV 0 (over d_s) but 121 m from the USV
        let s = stage(
            vec![[0.0, 0.0]; 2],
            vec![
                vec![[0.0, -50.0, -50.0]; 2],
                vec![[100.0, -50.0, -50.0], [0.0, 110.0, -50.0]],
            ],
        );
        let f = floor(-100.0);
        let m = |links: &[Vec<Link>]| window_metrics(&s, links, &f, &P, [0.0; 3]);
        let c = m(&[vec![a2u(0), a2a(0, 1)], vec![a2u(0), a2a(0, 1)]]);
        assert_eq!((c.connected_fraction, c.chain_fraction), (1.0, 0.5));
        assert_eq!(m(&[]).chain_fraction, 0.0);
        assert_eq!(m(&[vec![a2u(0)], vec![a2u(0)]]).chain_fraction, 0.0);
        assert_eq!(m(&[vec![a2u(0), a2a(0, 1)]]).chain_fraction, 0.5);
        assert_eq!(m(&vec![vec![a2u(0), a2a(0, 5)]; 2]).chain_fraction, 0.0);
    }

    #[test]
    fn heading_rate_wraps_across_pi() {
        assert_eq!(wrap(PI), PI);
        assert_eq!(wrap(-PI), PI);
        assert!((wrap(1.5 * PI) + 0.5 * PI).abs() < 1e-12);
        let mut s = stage(vec![[0.0; 2]; 5], vec![vec![[0.0, 0.0, -50.0]; 5]]);
        s.auvs[0].heading = vec![Some(PI - 0.1), Some(-PI + 0.2), None, Some(0.0), Some(0.1)];
        let m = window_metrics(&s, &[], &floor(-100.0), &P, [0.0; 3]);
        assert!((m.max_heading_rate - 0.03).abs() < 1e-12);
    }

    #[test]
    fn one_auv_one_step() {
        let s = stage(
            vec![[0.0, 0.0]; 2],
            vec![vec![[0.0, -50.0, -90.0], [10.0, -50.0, -95.0]]],
        );
        let (f, links) = (floor(-100.0), vec![vec![a2u(0)]; 2]);
        let m = window_metrics(&s, &links, &f, &P, [1.0, 0.0, 0.5]);
        assert_eq!((m.connected_fraction, m.chain_fraction), (1.0, 1.0));
        assert_eq!((m.mean_height, m.min_height), (5.0, 5.0));
        assert!((m.max_heading_rate, m.step1_time_s, m.step3_time_s) == (0.0, 1.0, 0.5));
        let exact = (10.0 * 50.0 + PI * 50.0 * 50.0 / 4.0) * 1e-6;
        assert!((m.explored_area_km2 - exact).abs() < 0.03 * exact);
    }

    #[test]
    fn the_shared_step_between_windows_counts_once() {
        let f = floor(-10.0);
        let good = stage(
            vec![[0.0, 100.0]; 2],
            vec![vec![[-50.0, 0.0, -80.0]; 2], vec![[50.0, 0.0, -80.0]; 2]],
        );
        // k = 0 cut (as at k = 0 of across_the_ridge), k = 1 connected
        let later = across_the_ridge();
        let none: &[Vec<Link>] = &[];
        let m = window_metrics(&later, none, &f, &P, [0.0; 3]);
        assert_eq!(m.connected_fraction, 0.5);
        let m = mission_metrics(&[(&good, none), (&later, none)], &f, &P, &[]);
        assert_eq!((m.connected_fraction, m.chain_fraction), (1.0, 0.0));
        let m = mission_metrics(&[(&later, none), (&good, none)], &f, &P, &[]);
        assert!((m.connected_fraction - 2.0 / 3.0).abs() < 1e-12);
    }
}
