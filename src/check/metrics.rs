//! The metrics a plan records, recomputed from its final stages and the floor (issue 13: the
//! checker verifies what a plan claims, not only its positions): per window and over the
//! mission, the input energy Σ‖U‖², the mean and least height above the floor over the AUV
//! waypoints k = 1..=K (off-grid waypoints skipped), and the largest heading rate |Δψ|/δ between
//! recorded headings. Each is compared relative to its magnitude (at least 1).
//!
//! The connected and chain fractions (steps k = 0..=K of a window; over the mission, k = 0..=K
//! of the first window and k = 1..=K of the later ones) are recounted with the checker's own
//! links (in range within `LENGTH_TOL`, in sight within `LOS_TOL`, over no obstacle cell) and
//! must match exactly. The explored area, the union of the swaths (the points within w/2 of
//! the segment, w = `auv.swath_width`) of every AUV segment flown at survey altitude (both ends
//! on the grid and at most `auv.survey_altitude` above the floor, read here from the floor by
//! the checker), is measured on columns of width w/32 along x,
//! exactly along each column's centre line; the planner measures it on strips along y, so the
//! two are independent estimates of one area and must agree within [`AREA_TOL`].

use super::graph::node;
use super::run::{diff, Checker, Family};
use super::{FamilyResult, LENGTH_TOL, LOS_TOL};
use crate::plan::{Link, Metrics, Stage};

/// Relative tolerance of a recomputed metric.
const METRIC_TOL: f64 = 1e-6;

/// Relative tolerance of the recomputed explored area: two midpoint rules of one area, on
/// lines w/32 (here) and w/10 (the planner) apart, across each other. Along a straight swath
/// both are nearly exact (0.02 % apart on the default plan); the round ends of a swath are
/// where they differ, up to 2.2 % for one AUV over two steps (issue 13's property test), so
/// 5 %: a recorded area off by more is not the plan's.
const AREA_TOL: f64 = 0.05;

/// The explored area (km²) of some stages: the union of the stadiums of radius w/2 about
/// every AUV segment whose ends are both `low` (at survey altitude), measured on columns of
/// width c = w/32 along x. Each stadium is convex, so a column's centre line x = (i + ½)c meets
/// it in one y-interval; the intervals of a column are merged and their lengths summed.
fn explored_km2(stages: &[&Stage], w: f64, low: &dyn Fn(&[f64; 3]) -> bool) -> Option<f64> {
    if !(w > 0.0 && w.is_finite()) {
        return Some(0.0);
    }
    let (r, c) = (w / 2.0, w / 32.0);
    let mut columns: std::collections::BTreeMap<i64, Vec<[f64; 2]>> = Default::default();
    let mut budget = MAX_COLUMN_HITS;
    for st in stages {
        for auv in &st.auvs {
            for s in auv.position.windows(2) {
                let (a, b) = ([s[0][0], s[0][1]], [s[1][0], s[1][1]]);
                if !(a.iter().chain(&b).all(|v| v.is_finite()) && low(&s[0]) && low(&s[1])) {
                    continue;
                }
                let first = ((a[0].min(b[0]) - r) / c - 0.5).ceil();
                let last = ((a[0].max(b[0]) + r) / c - 0.5).floor();
                budget -= last - first;
                if budget < 0.0 {
                    return None; // a path of thousands of kilometres: not measured
                }
                for i in first as i64..=last as i64 {
                    let x = (i as f64 + 0.5) * c;
                    if let Some(iv) = stadium_column(a, b, r, x) {
                        columns.entry(i).or_default().push(iv);
                    }
                }
            }
        }
    }
    let mut area = 0.0;
    for ivs in columns.values_mut() {
        ivs.sort_by(|p, q| p[0].total_cmp(&q[0]));
        let (mut lo, mut hi) = (ivs[0][0], ivs[0][1]);
        for iv in ivs.iter().skip(1) {
            if iv[0] > hi {
                area += hi - lo;
                (lo, hi) = (iv[0], iv[1]);
            } else {
                hi = hi.max(iv[1]);
            }
        }
        area += hi - lo;
    }
    Some(area * c / 1e6)
}

/// Most (segment, column) pairs `explored_km2` measures: 25 AUVs × 4 windows × 40 steps of
/// 600 m at w/32 = 1.6 m are 4·10⁷.
const MAX_COLUMN_HITS: f64 = 1e8;

/// The y-interval in which the line x = `x` meets the points within `r` of the segment a–b:
/// the y of the line's points at distance r, found on the segment's two end discs and on
/// the two long sides of its rectangle.
fn stadium_column(a: [f64; 2], b: [f64; 2], r: f64, x: f64) -> Option<[f64; 2]> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for p in [a, b] {
        let h = r * r - (x - p[0]).powi(2);
        if h >= 0.0 {
            (lo, hi) = (lo.min(p[1] - h.sqrt()), hi.max(p[1] + h.sqrt()));
        }
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len > 0.0 && dx.abs() > 1e-12 * len {
        // the rectangle's long sides, a ± r·n with n = (−dy, dx)/len, run from t = 0 to 1
        for side in [-1.0, 1.0] {
            let (ox, oy) = (a[0] - side * r * dy / len, a[1] + side * r * dx / len);
            let t = (x - ox) / dx;
            if (0.0..=1.0).contains(&t) {
                let y = oy + t * dy;
                (lo, hi) = (lo.min(y), hi.max(y));
            }
        }
    } else if len > 0.0 && (x - a[0]).abs() <= r {
        // a segment along y: the rectangle spans the segment's y range on every line it meets
        (lo, hi) = (lo.min(a[1].min(b[1])), hi.max(a[1].max(b[1])));
    }
    (lo <= hi).then_some([lo, hi])
}

/// The recomputable metrics of some final stages: (energy, height sum, heights, least height,
/// largest heading rate).
fn recompute(stages: &[&Stage], checker: &Checker) -> [f64; 4] {
    let (mut energy, mut sum, mut count, mut least, mut rate) =
        (0.0, 0.0, 0usize, f64::INFINITY, 0.0f64);
    for st in stages {
        for auv in &st.auvs {
            energy += auv.input.iter().flatten().map(|u| u * u).sum::<f64>();
            for q in auv.position.iter().skip(1) {
                if let Ok(z) = checker.floor.elevation(q[0], q[1]) {
                    let h = q[2] - z;
                    if h.is_finite() {
                        (sum, count, least) = (sum + h, count + 1, least.min(h));
                    }
                }
            }
            for pair in auv.heading.windows(2) {
                if let [Some(a), Some(b)] = pair {
                    let d = (b - a).rem_euclid(std::f64::consts::TAU);
                    let d = if d > std::f64::consts::PI {
                        std::f64::consts::TAU - d
                    } else {
                        d
                    };
                    rate = rate.max(d / checker.dt);
                }
            }
        }
    }
    let mean = if count == 0 { 0.0 } else { sum / count as f64 };
    let least = if count == 0 { 0.0 } else { least };
    [energy, mean, least, rate]
}

impl Checker<'_> {
    /// Whether p and q are joined by a usable link: in range and in line of sight.
    fn usable(&self, p: [f64; 3], q: [f64; 3]) -> bool {
        diff(p, q) <= self.s.acoustic.sonar_range + LENGTH_TOL
            && matches!(self.los(p, q), Ok(c) if c.min_clearance >= -LOS_TOL)
            && self.crossing(p, q).is_none()
    }

    /// Whether at step k of `st` every AUV reaches the USV through usable links: between any
    /// two nodes (`planned` None), or only the planned links (every one of which must be
    /// usable). None when a position is missing.
    fn reaches(&self, st: &Stage, k: usize, planned: Option<&[Link]>) -> Option<bool> {
        let n = st.auvs.len();
        // node 0 is the USV, node i + 1 is AUV i
        let who = |i: usize| i.checked_sub(1);
        let pos: Vec<[f64; 3]> = (0..=n)
            .map(|i| node(st, who(i), k))
            .collect::<Option<_>>()?;
        let mut edge = vec![vec![false; n + 1]; n + 1];
        match planned {
            None => {
                for i in 0..=n {
                    for j in i + 1..=n {
                        let ok = self.usable(pos[i], pos[j]);
                        (edge[i][j], edge[j][i]) = (ok, ok);
                    }
                }
            }
            Some(links) => {
                for l in links {
                    let (i, j) = (l.a + 1, l.b.map_or(0, |b| b + 1));
                    if i > n || j > n || !self.usable(pos[i], pos[j]) {
                        return Some(false);
                    }
                    (edge[i][j], edge[j][i]) = (true, true);
                }
            }
        }
        let mut reached = vec![false; n + 1];
        reached[0] = true;
        let mut queue = vec![0];
        while let Some(i) = queue.pop() {
            for j in 0..=n {
                if edge[i][j] && !reached[j] {
                    reached[j] = true;
                    queue.push(j);
                }
            }
        }
        Some(reached.iter().all(|&r| r))
    }

    /// (connected fraction, chain fraction) over windows `w0..w1`, counting k = 0 of the first
    /// only.
    fn fractions(&self, w0: usize, w1: usize) -> [f64; 2] {
        let (mut steps, mut connected, mut chain) = (0usize, 0usize, 0usize);
        for (w, win) in self.plan.windows.iter().enumerate().take(w1).skip(w0) {
            let st = &win.final_;
            for k in usize::from(w > w0)..st.usv.position.len() {
                steps += 1;
                connected += usize::from(self.reaches(st, k, None) == Some(true));
                let planned = win.links.links.get(k).map(Vec::as_slice);
                chain += usize::from(
                    planned.is_some_and(|l| self.reaches(st, k, Some(l)) == Some(true)),
                );
            }
        }
        if steps == 0 {
            return [0.0; 2];
        }
        [connected, chain].map(|c| c as f64 / steps as f64)
    }

    /// What metrics a plan records, and over which windows: each window's own, then the
    /// mission's (every window).
    fn scopes(&self) -> Vec<(String, &Metrics, std::ops::Range<usize>)> {
        let nw = self.plan.windows.len();
        let windows = self.plan.windows.iter().enumerate();
        windows
            .map(|(w, win)| (format!("window {w}"), &win.metrics, w..w + 1))
            .chain(std::iter::once((
                "mission".into(),
                &self.plan.metrics,
                0..nw,
            )))
            .collect()
    }

    // ------------------------------------------------------------------------------------
    // recorded metrics
    // ------------------------------------------------------------------------------------
    pub(super) fn metrics(&self) -> FamilyResult {
        let mut f = Family::new("recorded metrics", "relative", METRIC_TOL);
        let finals: Vec<&Stage> = self.plan.windows.iter().map(|w| &w.final_).collect();
        for (what, m, range) in self.scopes() {
            let [energy, mean, least, rate] = recompute(&finals[range.clone()], self);
            for (name, stored, found) in [
                ("input_energy", m.input_energy, energy),
                ("mean_height", m.mean_height, mean),
                ("min_height", m.min_height, least),
                ("max_heading_rate", m.max_heading_rate, rate),
            ] {
                let scale = stored.abs().max(found.abs()).max(1.0);
                f.record(-(stored - found).abs() / scale, || {
                    format!("{what} {name}: stored {stored}, recomputed {found}")
                });
            }
            let [connected, chain] = self.fractions(range.start, range.end);
            for (name, stored, found) in [
                ("connected_fraction", m.connected_fraction, connected),
                ("chain_fraction", m.chain_fraction, chain),
            ] {
                f.record(-(stored - found).abs(), || {
                    format!("{what} {name}: stored {stored}, recounted {found}")
                });
            }
        }
        f.finish()
    }

    // ------------------------------------------------------------------------------------
    // recorded explored area
    // ------------------------------------------------------------------------------------
    pub(super) fn explored_area(&self) -> FamilyResult {
        let mut f = Family::new("recorded explored area", "relative", AREA_TOL);
        let finals: Vec<&Stage> = self.plan.windows.iter().map(|w| &w.final_).collect();
        let swath = self.s.auv.swath_width;
        let ceiling = self.s.auv.survey_altitude;
        let low = |q: &[f64; 3]| match self.floor.elevation(q[0], q[1]) {
            Ok(z) => q[2] - z <= ceiling,
            Err(_) => false,
        };
        let mut measured = Vec::new(); // each scope's area, windows first, then the mission
        for (what, m, range) in self.scopes() {
            let stored = m.explored_area_km2;
            let Some(found) = explored_km2(&finals[range], swath, &low) else {
                f.record(f64::NEG_INFINITY, || {
                    format!("{what}: paths too long to measure the explored area on")
                });
                return f.finish();
            };
            let off = (stored - found).abs() / stored.abs().max(found.abs()).max(1e-4);
            f.record(-off, || {
                format!("{what}: stored {stored} km², measured across {found} km²")
            });
            measured.push(found);
        }
        // the revisited area: Σ window areas − the union, both measured above
        let (union, each) = measured.split_last().expect("the mission is a scope");
        let found = if each.len() > 1 {
            (each.iter().sum::<f64>() - union).max(0.0)
        } else {
            0.0
        };
        let stored = self.plan.metrics.revisited_area_km2;
        // relative to the mission's area: the two estimates' errors are of its size
        let off = (stored - found).abs() / union.max(stored.abs()).max(1e-4);
        f.record(-off, || {
            format!("mission revisited area: stored {stored} km², measured across {found} km²")
        });
        f.finish()
    }
}
