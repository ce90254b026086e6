//! The metrics a plan records, recomputed from its final stages and the floor (issue 13: the
//! checker verifies what a plan claims, not only its positions): per window and over the
//! mission, the input energy Σ‖U‖², the mean and least height above the floor over the AUV
//! waypoints k = 1..=K (off-grid waypoints skipped), and the largest heading rate |Δψ|/δ between
//! recorded headings. Each is compared relative to its magnitude (at least 1). The connected
//! and chain fractions and the explored area are not recomputed here (the connectivity family
//! requires 100 % of steps connected whatever the plan records).

use super::run::{Checker, Family};
use super::FamilyResult;
use crate::plan::{Metrics, Stage};

/// Relative tolerance of a recomputed metric.
const METRIC_TOL: f64 = 1e-6;

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
    // ------------------------------------------------------------------------------------
    // recorded metrics
    // ------------------------------------------------------------------------------------
    pub(super) fn metrics(&self) -> FamilyResult {
        let mut f = Family::new("recorded metrics", "relative", METRIC_TOL);
        let mut compare = |what: &str, m: &Metrics, stages: &[&Stage]| {
            let [energy, mean, least, rate] = recompute(stages, self);
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
        };
        let finals: Vec<&Stage> = self.plan.windows.iter().map(|w| &w.final_).collect();
        for (w, win) in self.plan.windows.iter().enumerate() {
            compare(&format!("window {w}"), &win.metrics, &finals[w..=w]);
        }
        compare("mission", &self.plan.metrics, &finals);
        f.finish()
    }
}
