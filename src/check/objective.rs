//! The objective terms of every stage, recomputed from the stage's own paths.
//!
//! Step 1 (P2) records energy, depth, height, usv and the weighted total; every one is checked.
//! The final stage (Step 3, P5) records the same four physical terms, checked the same way, and
//! a total that also weighs P5's own terms (the link bands and the spread of the team): that
//! total is not recomputed here (the recomputed value is NaN and the table shows "-").

use super::run::{rel, Checker, Family};
use super::{FamilyResult, ObjectiveCheck, OBJECTIVE_REL_TOL};
use crate::plan::{ObjectiveTerms, Stage};
use crate::scenario::{DepthObjective, UsvObjective};

impl Checker<'_> {
    pub(super) fn objective(&self) -> (FamilyResult, Vec<ObjectiveCheck>) {
        let mut f = Family::new("objective", "relative", OBJECTIVE_REL_TOL);
        let mut out = Vec::new();
        for (w, pre, st) in self.stages() {
            let stage = if pre.is_empty() { "final" } else { "step1" };
            let check_total = !pre.is_empty();
            let mine = self.terms(st, check_total);
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

    /// The terms of one stage; `total` is NaN unless `with_total`.
    fn terms(&self, st: &Stage, with_total: bool) -> ObjectiveTerms {
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
                UsvObjective::Away => (pk[0] - p0[0]).powi(2) + (pk[1] - p0[1]).powi(2),
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

    /// The weighted terms of P2's total: w1·energy, w2·(height or depth), ∓w8·usv.
    fn weighted(&self, t: &ObjectiveTerms) -> [f64; 3] {
        let wt = &self.s.weights;
        let of1_2 = match wt.of1_2 {
            DepthObjective::Height => t.height,
            DepthObjective::Depth => t.depth,
        };
        let usv = match self.s.usv.objective {
            UsvObjective::Away => -wt.w8 * t.usv,
            UsvObjective::Destination => wt.w8_2 * t.usv,
        };
        [wt.w1 * t.energy, wt.w2 * of1_2, usv]
    }

    /// The scale the total is compared against: the sum of the weighted terms' magnitudes.
    fn total_scale(&self, t: &ObjectiveTerms) -> f64 {
        self.weighted(t).iter().map(|v| v.abs()).sum()
    }
}
