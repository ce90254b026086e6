//! The checks themselves. Every array access goes through `get`, so a malformed plan cannot
//! make the checker panic; what is missing is reported by the "structure" family.

use super::*;
use crate::plan::{AuvPath, Stage, Window, FORMAT, METHOD_MPC, SAMPLED};
use crate::scenario::Scenario;
use std::f64::consts::PI;

/// The most the SCP shrinks its trust region after one entry of its log (`scp.rs`: a rejected
/// step shrinks it to below the step it took, at most 16-fold).
const MAX_SHRINK: f64 = 16.0;

/// Accumulates the worst margin of one family.
pub(super) struct Family {
    name: &'static str,
    unit: &'static str,
    tolerance: f64,
    worst: f64,
    pub(super) where_: String,
    pub(super) checked: usize,
}

impl Family {
    pub(super) fn new(name: &'static str, unit: &'static str, tolerance: f64) -> Family {
        Family {
            name,
            unit,
            tolerance,
            worst: f64::INFINITY,
            where_: String::new(),
            checked: 0,
        }
    }

    /// Record one check. A NaN margin (the check could not be evaluated) counts as −∞.
    pub(super) fn record(&mut self, margin: f64, at: impl FnOnce() -> String) {
        self.checked += 1;
        let m = if margin.is_nan() {
            f64::NEG_INFINITY
        } else {
            margin
        };
        if m < self.worst || (self.checked == 1 && m == self.worst) {
            self.worst = m;
            self.where_ = at();
        }
    }

    /// Whether the checks so far pass.
    pub(super) fn passing(&self) -> bool {
        self.worst >= -self.tolerance
    }

    pub(super) fn finish(self) -> FamilyResult {
        FamilyResult {
            name: self.name,
            worst_margin: self.worst,
            unit: self.unit,
            tolerance: self.tolerance,
            where_: self.where_,
            checked: self.checked,
        }
    }
}

pub(super) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

pub(super) fn diff<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    norm(&std::array::from_fn::<f64, D, _>(|i| a[i] - b[i]))
}

/// Angle wrapped into [−π, π).
pub(super) fn wrap(x: f64) -> f64 {
    (x + PI).rem_euclid(2.0 * PI) - PI
}

/// Relative difference of a and b against `scale` (0 when equal).
pub(super) fn rel(a: f64, b: f64, scale: f64) -> f64 {
    // both NaN: a term that cannot be evaluated (a point off the grid, reported by its own
    // family) on both sides
    if a == b || (a.is_nan() && b.is_nan()) {
        0.0
    } else {
        (a - b).abs() / scale.max(f64::MIN_POSITIVE)
    }
}

fn all_finite<const D: usize>(v: &[[f64; D]]) -> bool {
    v.iter().flatten().all(|c| c.is_finite())
}

pub(super) fn at(w: usize, k: usize, who: &str) -> String {
    format!("window {w}, k = {k}, {who}")
}

pub(super) fn seg(w: usize, k: usize, who: &str) -> String {
    format!("window {w}, k = {}→{k}, {who}", k - 1)
}

/// The stages a window records, the final stage (the plan the team executes) first, each with
/// the prefix that names it in messages: "" for the final stage, "step1 " for Step 1's.
fn stages(win: &Window) -> [(&'static str, &Stage); 2] {
    [("", &win.final_), ("step1 ", &win.step1)]
}

/// "final" or "step1" from a stage prefix.
fn stage_name(pre: &str) -> &'static str {
    if pre.is_empty() {
        "final"
    } else {
        "step1"
    }
}

pub(super) struct Checker<'a> {
    pub(super) plan: &'a Plan,
    /// The plan's own scenario: its geometry, model, objective and recorded metrics.
    pub(super) s: &'a Scenario,
    /// The scenario whose limits the plan is held to ([`super::LIMIT_KEYS`]): the plan's own
    /// unless the user states others.
    pub(super) limits: &'a Scenario,
    pub(super) floor: &'a Seafloor,
    /// K.
    pub(super) k: usize,
    /// δ.
    pub(super) dt: f64,
    problems: Vec<String>,
    structural_checks: usize,
}

pub(super) fn run(
    plan: &Plan,
    floor: &Seafloor,
    limits: &Scenario,
    used: super::LimitsUsed,
) -> CheckReport {
    let s = &plan.scenario;
    let mut c = Checker {
        plan,
        s,
        limits,
        floor,
        k: s.horizon.steps,
        dt: s.horizon.dt,
        problems: Vec::new(),
        structural_checks: 0,
    };
    c.structure();
    let mut families = Vec::new();
    let structure = {
        let mut f = Family::new("structure", "problems", 0.0);
        f.checked = c.structural_checks;
        f.worst = -(c.problems.len() as f64);
        f.where_ = c.problems.first().cloned().unwrap_or_default();
        f.finish()
    };
    families.push(structure);
    families.push(c.identity());
    let (model_family, step) = c.model();
    families.push(model_family);
    families.extend(c.dynamics(&step));
    families.extend(c.speeds());
    families.push(c.underwater());
    families.extend(c.ranges());
    families.extend(c.floor());
    families.push(c.heading_rate());
    families.extend(c.envelope());
    families.push(c.separation());
    families.extend(c.recorded());
    families.push(c.chain());
    families.push(c.metrics());
    families.push(c.explored_area());
    let (objective, objectives) = c.objective();
    families.push(objective);
    families.extend(c.graph_families());
    CheckReport {
        families,
        problems: c.problems,
        objectives,
        plan_fingerprint: plan.seafloor.fingerprint.clone(),
        floor_fingerprint: floor.fingerprint(),
        limits: used,
    }
}

impl Checker<'_> {
    /// The resolution the checker samples at: the plan's r, or `CHECK_RESOLUTION` if finer.
    pub(super) fn resolution(&self) -> f64 {
        self.s.acoustic.resolution.min(CHECK_RESOLUTION)
    }

    pub(super) fn require(&mut self, ok: bool, problem: impl FnOnce() -> String) {
        self.structural_checks += 1;
        if !ok {
            self.problems.push(problem());
        }
    }

    /// Every stage of every window, the final stage (the plan) before Step 1's: (window, prefix
    /// naming the stage in messages, stage).
    pub(super) fn stages(&self) -> impl Iterator<Item = (usize, &'static str, &Stage)> {
        self.plan
            .windows
            .iter()
            .enumerate()
            .flat_map(|(w, win)| stages(win).map(move |(pre, st)| (w, pre, st)))
    }

    /// Every AUV path of every stage of every window: (window, stage prefix, stage, AUV index,
    /// path).
    pub(super) fn auv_paths(
        &self,
    ) -> impl Iterator<Item = (usize, &'static str, &Stage, usize, &AuvPath)> {
        self.stages().flat_map(|(w, pre, st)| {
            st.auvs
                .iter()
                .enumerate()
                .map(move |(n, p)| (w, pre, st, n, p))
        })
    }

    // ------------------------------------------------------------------------------------
    // 1. structure
    // ------------------------------------------------------------------------------------
    fn structure(&mut self) {
        let (plan, s) = (self.plan, self.s);
        let k = self.k;
        self.require(plan.format == FORMAT, || {
            format!("format is \"{}\", expected \"{FORMAT}\"", plan.format)
        });
        // scenario parameters the checks rely on
        self.require(k >= 1, || "horizon.steps (K) is 0".into());
        let dt = self.dt;
        self.require(dt.is_finite() && dt > 0.0, || {
            format!("horizon.dt = {dt} is not a positive number")
        });
        let r = s.acoustic.resolution;
        self.require(r.is_finite() && r > 0.0, || {
            format!("acoustic.resolution = {r} is not a positive number")
        });
        for (name, v) in [
            ("usv.max_speed", s.usv.max_speed),
            ("auv.max_speed", s.auv.max_speed),
            ("auv.max_heading_rate", s.auv.max_heading_rate),
            ("auv.min_heading_speed", s.auv.min_heading_speed),
            ("auv.max_depth", s.auv.max_depth),
            ("auv.max_flight_path_angle", s.auv.max_flight_path_angle),
            ("auv.min_speed", s.auv.min_speed),
            ("acoustic.sonar_range", s.acoustic.sonar_range),
            ("acoustic.max_range", s.acoustic.max_range),
        ] {
            self.require(v.is_finite() && v >= 0.0, || {
                format!("{name} = {v} is not a finite number ≥ 0")
            });
        }
        for (name, v) in [
            ("auv.floor_clearance", s.auv.floor_clearance),
            ("auv.surface_clearance", s.auv.surface_clearance),
            ("weights.w1", s.weights.w1),
            ("weights.w2", s.weights.w2),
            ("weights.w8", s.weights.w8),
            ("weights.w8_2", s.weights.w8_2),
        ] {
            self.require(v.is_finite(), || format!("{name} = {v} is not finite"));
        }
        let n = s.team.auvs;
        self.require(n >= 1, || "team.auvs (N) is 0".into());
        // initial state
        let init = &plan.initial;
        self.require(init.auvs.len() == n, || {
            format!(
                "initial state has {} AUVs, team.auvs = {n}",
                init.auvs.len()
            )
        });
        let init_finite = init.usv.iter().all(|c| c.is_finite())
            && init
                .auvs
                .iter()
                .all(|a| a.position.iter().chain(&a.velocity).all(|c| c.is_finite()));
        self.require(init_finite, || {
            "initial state holds a non-finite number".into()
        });
        // windows
        self.require(!plan.windows.is_empty(), || {
            "the plan has no windows".into()
        });
        self.require(plan.windows.len() == s.windows, || {
            format!(
                "{} windows, scenario.windows = {}",
                plan.windows.len(),
                s.windows
            )
        });
        for (w, win) in plan.windows.iter().enumerate() {
            self.require(win.index == w, || {
                format!("window {w} has index {}", win.index)
            });
            let t = w as f64 * k as f64 * dt;
            self.require(
                (win.start_time - t).abs() <= 1e-9 * t.abs().max(1.0),
                || {
                    format!(
                        "window {w} starts at t = {} s, expected w·K·δ = {t} s",
                        win.start_time
                    )
                },
            );
            self.graph_structure(w, win);
            for (pre, st) in stages(win) {
                self.stage_structure(w, pre, st);
            }
        }
    }

    /// The stage's SCP log against what the stage claims: as many entries as iterations, every
    /// number finite, every convex solve usable (Solved or AlmostSolved), and a status its log
    /// bears out: "converged" ends on the iteration that found no decrease left (not
    /// accepted, or accepted as a feasible candidate of lower merit); "max_iterations" ran
    /// `scp.max_iterations` iterations (in its last line-of-sight round, so at least that
    /// many); "stalled" ends with a trust region below
    /// `MAX_SHRINK` times `scp.min_trust_region` (a rejected step shrinks it at most that much
    /// after the entry) or on an iteration that found no decrease; "solver_trouble" (the
    /// convex solver failed at every radius tried after the last entry, solves the log does
    /// not hold) needs no more than a log.
    fn scp_log(&mut self, w: usize, stage: &str, st: &Stage) {
        let log = &st.scp;
        self.require(log.len() == st.iterations, || {
            format!(
                "window {w}: {stage} records {} SCP iterations and {} log entries",
                st.iterations,
                log.len()
            )
        });
        for (i, it) in log.iter().enumerate() {
            let numbers = [
                it.trust_region,
                it.merit_before,
                it.merit_after,
                it.predicted,
                it.ratio,
                it.violation,
                it.solver_time_s,
            ];
            self.require(numbers.iter().all(|v| v.is_finite()), || {
                format!("window {w}: {stage} SCP iteration {i} records a non-finite number")
            });
            self.require(
                matches!(it.solver_status.as_str(), "Solved" | "AlmostSolved"),
                || {
                    format!(
                        "window {w}: {stage} SCP iteration {i}: solver status \"{}\"",
                        it.solver_status
                    )
                },
            );
        }
        let Some(last) = log.last() else {
            self.require(false, || {
                format!("window {w}: {stage} has no SCP iteration")
            });
            return;
        };
        let scp = &self.s.scp;
        // Step 1 runs with its own limit where `scp.step1_max_iterations` is set
        let max_iterations = match stage {
            "step1" => scp.step1().max_iterations,
            _ => scp.max_iterations,
        };
        let (holds, claim) = match st.status.as_str() {
            // the loop may end on a last candidate that was feasible and better
            "converged" => (
                !last.accepted
                    || (last.merit_after < last.merit_before
                        && last.violation <= scp.feasibility_tol),
                "its last iteration was an accepted step that did not lower the merit or \
                 broke a constraint",
            ),
            "max_iterations" => (
                st.iterations >= max_iterations,
                "it ran fewer than its scp.max_iterations (or scp.step1_max_iterations) \
                 iterations",
            ),
            "stalled" => (
                !last.accepted || last.trust_region < MAX_SHRINK * scp.min_trust_region,
                "its trust region never collapsed",
            ),
            _ => (true, ""),
        };
        self.require(holds, || {
            format!(
                "window {w}: {stage} status \"{}\", but {claim} (log of {} entries)",
                st.status,
                log.len()
            )
        });
    }

    /// Lengths and finiteness of one stage of window `w`; `pre` names the stage in messages
    /// ("" for the final stage, "step1 " for Step 1's).
    fn stage_structure(&mut self, w: usize, pre: &str, st: &Stage) {
        let (k, n) = (self.k, self.s.team.auvs);
        let stage = stage_name(pre);
        // a sampling planner's stage (any method but the MPC's) has no SCP log
        if self.plan.method == METHOD_MPC {
            self.require(
                matches!(
                    st.status.as_str(),
                    "converged" | "max_iterations" | "stalled" | "solver_trouble"
                ),
                || format!("window {w}: {stage} status \"{}\"", st.status),
            );
            self.scp_log(w, stage, st);
        } else {
            self.require(
                st.sampled() && st.scp.is_empty() && st.iterations == 0,
                || {
                    format!(
                        "window {w}: {stage} of a \"{}\" plan has status \"{}\" and {} SCP \
                     iterations (a sampled stage has status \"{SAMPLED}\" and none)",
                        self.plan.method, st.status, st.iterations
                    )
                },
            );
        }
        let o = st.objective;
        self.require(
            [o.energy, o.depth, o.usv, o.total]
                .iter()
                .all(|v| v.is_finite()),
            || format!("window {w}: a stored {stage} objective term is not finite"),
        );
        let usv = &st.usv;
        self.require(usv.position.len() == k.saturating_add(1), || {
            format!(
                "window {w}, {pre}USV: {} positions, expected K + 1 = {}",
                usv.position.len(),
                k.saturating_add(1)
            )
        });
        self.require(usv.input.len() == k, || {
            format!(
                "window {w}, {pre}USV: {} inputs, expected K = {k}",
                usv.input.len()
            )
        });
        self.require(all_finite(&usv.position) && all_finite(&usv.input), || {
            format!("window {w}, {pre}USV: a non-finite number")
        });
        self.require(st.auvs.len() == n, || {
            format!(
                "window {w}: {} AUV paths in the {stage} stage, team.auvs = {n}",
                st.auvs.len()
            )
        });
        for (i, a) in st.auvs.iter().enumerate() {
            for (what, len, want) in [
                ("positions", a.position.len(), k.saturating_add(1)),
                ("velocities", a.velocity.len(), k.saturating_add(1)),
                ("inputs", a.input.len(), k),
                ("surge speeds", a.surge_speed.len(), k.saturating_add(1)),
                ("headings", a.heading.len(), k.saturating_add(1)),
            ] {
                self.require(len == want, || {
                    format!("window {w}, {pre}AUV {i}: {len} {what}, expected {want}")
                });
            }
            let finite = all_finite(&a.position)
                && all_finite(&a.velocity)
                && all_finite(&a.input)
                && a.surge_speed.iter().all(|v| v.is_finite())
                && a.heading.iter().flatten().all(|v| v.is_finite());
            self.require(finite, || {
                format!("window {w}, {pre}AUV {i}: a non-finite number")
            });
        }
    }
}

/// The checker samples every segment and link at least every `CHECK_RESOLUTION` metres (the
/// default r), whatever resolution the plan claims: a plan made at a coarse r (the plan file
/// says 1e308, say) is still held to the floor between its own samples.
pub(super) const CHECK_RESOLUTION: f64 = 5.0;

/// The samples of 𝓛_r on a → b: n + 1 evenly spaced points, n = max(1, ⌈horizontal length / r⌉),
/// each kept inside the segment's bounding box. None when r is not positive or n is absurd.
pub(super) fn own_samples(
    a: [f64; 3],
    b: [f64; 3],
    r: f64,
) -> Option<impl Iterator<Item = [f64; 3]>> {
    /// More than this many samples on one segment means a corrupt plan or resolution.
    const MAX_SAMPLES: f64 = 1e7;
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = (len / r).ceil().max(1.0);
    if !(r > 0.0 && len.is_finite() && n <= MAX_SAMPLES) {
        return None;
    }
    let n = n as usize;
    Some((0..=n).map(move |i| {
        let t = i as f64 / n as f64;
        std::array::from_fn(|d| (a[d] + t * (b[d] - a[d])).clamp(a[d].min(b[d]), a[d].max(b[d])))
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_is_into_minus_pi_pi() {
        assert!((wrap(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
        assert!((wrap(-3.0 * PI / 2.0) - PI / 2.0).abs() < 1e-15);
        assert!(wrap(0.1).abs() - 0.1 < 1e-15);
        assert!((wrap(2.0 * PI + 0.2) - 0.2).abs() < 1e-14);
    }

    #[test]
    fn own_samples_follow_the_rule() {
        let s: Vec<_> = own_samples([0.0, 0.0, -1.0], [10.0, 0.0, -3.0], 3.0)
            .unwrap()
            .collect();
        assert_eq!(s.len(), 5); // ⌈10/3⌉ = 4 intervals
        assert_eq!(s[0], [0.0, 0.0, -1.0]);
        assert_eq!(s[4], [10.0, 0.0, -3.0]);
        assert!(own_samples([0.0; 3], [1.0, 0.0, 0.0], 0.0).is_none());
        assert!(own_samples([0.0; 3], [f64::NAN, 0.0, 0.0], 1.0).is_none());
        assert_eq!(
            own_samples([0.0; 3], [0.0, 0.0, -5.0], 1.0)
                .unwrap()
                .count(),
            2
        );
    }
}
