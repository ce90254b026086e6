//! The objective terms of every stage, recomputed from the stage's own paths.
//!
//! Step 1 (P2) records energy, depth, height, usv and the weighted total; every one is checked.
//! The final stage (Step 3, P5) records the same four physical terms, checked the same way, and
//! a total that also weighs P5's own terms (the link bands and the spread of the team): that
//! total is not recomputed here (the recomputed value is NaN and the table shows "-").

use super::run::{rel, Checker, Family};
use super::{FamilyResult, ObjectiveCheck, OBJECTIVE_REL_TOL};
use crate::plan::{ObjectiveTerms, Stage};
use crate::scenario::{AwayFrom, DepthObjective, UsvObjective};

impl Checker<'_> {
    pub(super) fn objective(&self) -> (FamilyResult, Vec<ObjectiveCheck>) {
        let mut f = Family::new("objective", "relative", OBJECTIVE_REL_TOL);
        let mut out = Vec::new();
        for (w, pre, st) in self.stages() {
            let stage = if pre.is_empty() { "final" } else { "step1" };
            let check_total = !pre.is_empty();
            let mine = self.terms(w, st, check_total);
            let stored = st.objective;
            let mut terms = vec![
                ("energy", stored.energy, mine.energy, 0.0),
                ("depth", stored.depth, mine.depth, 0.0),
                ("height", stored.height, mine.height, 0.0),
                ("usv", stored.usv, mine.usv, 0.0),
            ];
            if check_total {
                terms.push(("total", stored.total, mine.total, self.total_scale(&mine)));
            }
            for (name, a, b, scale) in terms {
                let scale = f64::max(scale, a.abs().max(b.abs()));
                f.record(-rel(a, b, scale), || {
                    format!("window {w}, {stage} {name}: stored {a}, recomputed {b}")
                });
            }
            out.push(ObjectiveCheck {
                window: w,
                stage,
                stored,
                recomputed: mine,
            });
        }
        (f.finish(), out)
    }

    /// The terms of one stage of window `w`; `total` is NaN unless `with_total`.
    fn terms(&self, w: usize, st: &Stage, with_total: bool) -> ObjectiveTerms {
        let energy: f64 = st
            .auvs
            .iter()
            .flat_map(|a| a.input.iter().take(self.k))
            .map(|u| u.iter().map(|c| c * c).sum::<f64>())
            .sum();
        let waypoints = || {
            st.auvs
                .iter()
                .flat_map(|a| a.position.iter().take(self.k.saturating_add(1)).skip(1))
        };
        let depth: f64 = waypoints().map(|p| p[2]).sum();
        // Σ (z − Z(x, y)); a point off the grid is reported by the floor family already
        let height: f64 = waypoints()
            .map(|p| p[2] - self.floor.elevation(p[0], p[1]).unwrap_or(f64::NAN))
            .sum();
        let (first, last) = (st.usv.position.first(), st.usv.position.get(self.k));
        let usv = match (first, last) {
            (Some(p0), Some(pk)) => match self.s.usv.objective {
                UsvObjective::Away => self.away(w, *p0, *pk),
                UsvObjective::Destination => {
                    let d = self.s.usv.destination;
                    (pk[0] - d[0]).powi(2) + (pk[1] - d[1]).powi(2)
                }
            },
            _ => f64::NAN,
        };
        let mut terms = ObjectiveTerms {
            energy,
            depth,
            height,
            usv,
            total: f64::NAN,
            ..ObjectiveTerms::default()
        };
        if with_total {
            let [e, d, u] = self.weighted(&terms);
            terms.total = e + d + u;
        }
        terms
    }

    /// OF1_8's squared distance of `pk` (P_USV\[K\] of window `w`) from what it is measured
    /// from: the window's start `p0` with `usv.away_from = "window"`; with `"track"`, the
    /// nearest point of the polyline through the final USV paths of windows 0..w, then `p0`.
    fn away(&self, w: usize, p0: [f64; 2], pk: [f64; 2]) -> f64 {
        let earlier = match self.s.usv.away_from {
            AwayFrom::Track => &self.plan.windows[..w],
            AwayFrom::Window => &[][..],
        };
        let track: Vec<[f64; 2]> = earlier
            .iter()
            .flat_map(|win| win.final_.usv.position.iter().copied())
            .chain([p0])
            .collect();
        let mut least = f64::INFINITY;
        for (i, a) in track.iter().enumerate() {
            let b = track.get(i + 1).unwrap_or(a);
            // the nearest point of segment a–b: a + t(b − a), t ∈ [0, 1]
            let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
            let len2 = ex * ex + ey * ey;
            let t = match len2 > 0.0 {
                true => (((pk[0] - a[0]) * ex + (pk[1] - a[1]) * ey) / len2).clamp(0.0, 1.0),
                false => 0.0,
            };
            least = least.min((pk[0] - a[0] - t * ex).powi(2) + (pk[1] - a[1] - t * ey).powi(2));
        }
        least
    }

    /// The weighted terms of P2's total: w1·energy, w2·(height or depth), ∓w8·usv.
    fn weighted(&self, t: &ObjectiveTerms) -> [f64; 3] {
        let wt = &self.s.weights;
        let of1_2 = match wt.of1_2 {
            DepthObjective::Height => t.height,
            DepthObjective::Depth => t.depth,
        };
        let usv = match self.s.usv.objective {
            UsvObjective::Away => -self.s.w8() * t.usv, // weights.w8_scaling
            UsvObjective::Destination => wt.w8_2 * t.usv,
        };
        let per_auv = wt.per_auv(self.s.team.auvs); // weights.scaling
        [wt.w1 * per_auv * t.energy, wt.w2 * per_auv * of1_2, usv]
    }

    /// The scale the total is compared against: the sum of the weighted terms' magnitudes.
    fn total_scale(&self, t: &ObjectiveTerms) -> f64 {
        self.weighted(t).iter().map(|v| v.abs()).sum()
    }
}
