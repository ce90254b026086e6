//! The checks themselves. Every array access goes through `get`, so a malformed plan cannot
//! make the checker panic; what is missing is reported by the "structure" family.

use super::model::{AuvStep, Rates};
use super::*;
use crate::plan::{AuvPath, Stage, Window, FORMAT};
use crate::scenario::Scenario;
use std::f64::consts::PI;

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

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

pub(super) fn diff<const D: usize>(a: [f64; D], b: [f64; D]) -> f64 {
    norm(&std::array::from_fn::<f64, D, _>(|i| a[i] - b[i]))
}

/// Angle wrapped into [−π, π).
fn wrap(x: f64) -> f64 {
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
    pub(super) s: &'a Scenario,
    pub(super) floor: &'a Seafloor,
    /// K.
    pub(super) k: usize,
    /// δ.
    dt: f64,
    problems: Vec<String>,
    structural_checks: usize,
}

pub(super) fn run(plan: &Plan, floor: &Seafloor) -> CheckReport {
    let s = &plan.scenario;
    let mut c = Checker {
        plan,
        s,
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
    families.extend(c.recorded());
    families.push(c.chain());
    let (objective, objectives) = c.objective();
    families.push(objective);
    families.extend(c.graph_families());
    CheckReport {
        families,
        problems: c.problems,
        objectives,
        plan_fingerprint: plan.seafloor.fingerprint.clone(),
        floor_fingerprint: floor.fingerprint(),
    }
}

impl Checker<'_> {
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
    fn auv_paths(&self) -> impl Iterator<Item = (usize, &'static str, &Stage, usize, &AuvPath)> {
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

    /// Lengths and finiteness of one stage of window `w`; `pre` names the stage in messages
    /// ("" for the final stage, "step1 " for Step 1's).
    fn stage_structure(&mut self, w: usize, pre: &str, st: &Stage) {
        let (k, n) = (self.k, self.s.team.auvs);
        let stage = stage_name(pre);
        self.require(
            st.status == "converged" || st.status == "max_iterations",
            || format!("window {w}: {stage} status \"{}\"", st.status),
        );
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

    // ------------------------------------------------------------------------------------
    // 9. seafloor identity
    // ------------------------------------------------------------------------------------
    fn identity(&self) -> FamilyResult {
        let mut f = Family::new("seafloor identity", "mismatches", 0.0);
        let r = &self.plan.seafloor;
        let found = self.floor.fingerprint();
        let same = found == r.fingerprint;
        f.record(if same { 0.0 } else { -1.0 }, || {
            if same {
                format!("fingerprint {found} matches")
            } else {
                format!(
                    "this is not the floor the plan was made on: fingerprint {} (plan) vs {found} \
                     (floor)",
                    r.fingerprint
                )
            }
        });
        let (z_min, z_max) = self.floor.z_range();
        for (name, plan, floor) in [
            ("nx", r.nx as f64, self.floor.nx() as f64),
            ("ny", r.ny as f64, self.floor.ny() as f64),
            ("x0", r.x0, self.floor.x0()),
            ("y0", r.y0, self.floor.y0()),
            ("dx", r.dx, self.floor.dx()),
            ("dy", r.dy, self.floor.dy()),
            ("z_min", r.z_min, z_min),
            ("z_max", r.z_max, z_max),
        ] {
            f.record(if plan == floor { 0.0 } else { -1.0 }, || {
                format!("seafloor record {name} = {plan}, the floor has {floor}")
            });
        }
        f.finish()
    }

    // ------------------------------------------------------------------------------------
    // model record (damping rates and discrete coefficients)
    // ------------------------------------------------------------------------------------
    fn model(&self) -> (FamilyResult, AuvStep) {
        let mut f = Family::new("model record", "relative", MODEL_REL_TOL);
        let s = self.s;
        let (rates, problems) = Rates::from_params(&s.auv);
        for p in problems {
            f.record(f64::NEG_INFINITY, || format!("scenario.auv {p}"));
        }
        let step = AuvStep::new(rates.axes(), self.dt, s.auv.discretisation);
        let m = &self.plan.model;
        for (name, stored, mine) in [
            ("damping.surge", m.damping.surge, rates.surge),
            ("damping.heave", m.damping.heave, rates.heave),
            ("damping.yaw", m.damping.yaw, rates.yaw),
            ("auv.rate[x]", m.auv.rate[0], rates.surge),
            ("auv.rate[y]", m.auv.rate[1], rates.surge),
            ("auv.rate[z]", m.auv.rate[2], rates.heave),
            ("auv.dt", m.auv.dt, self.dt),
            ("usv.dt", m.usv.dt, self.dt),
            ("usv.max_speed", m.usv.max_speed, s.usv.max_speed),
        ] {
            f.record(-rel(stored, mine, mine.abs()), || {
                format!("model.{name} = {stored}, the scenario gives {mine}")
            });
        }
        // Discrete coefficients, each against its natural scale (1, δ or δ²) so that tiny
        // coefficients such as e^{−eδ} ≈ 1e-17 are compared absolutely.
        let dt = self.dt.abs().max(f64::MIN_POSITIVE);
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            let mine = step.axes[i];
            for (name, stored, value, scale) in [
                ("pv", m.auv.pv[i], mine.a, dt),
                ("pu", m.auv.pu[i], mine.b, dt * dt),
                ("vv", m.auv.vv[i], mine.c, 1.0),
                ("vu", m.auv.vu[i], mine.d, dt),
            ] {
                f.record(-rel(stored, value, scale), || {
                    format!(
                        "model.auv.{name}[{axis}] = {stored}, the checker's {:?} model gives {value}",
                        s.auv.discretisation
                    )
                });
            }
        }
        (f.finish(), step)
    }

    // ------------------------------------------------------------------------------------
    // 2. dynamics (C1_1, eq. (9))
    // ------------------------------------------------------------------------------------
    fn dynamics(&self, step: &AuvStep) -> Vec<FamilyResult> {
        let mut fp = Family::new("C1_1 AUV dynamics (position)", "m", DYNAMICS_POSITION_TOL);
        let mut fv = Family::new("C1_1 AUV dynamics (velocity)", "m/s", DYNAMICS_VELOCITY_TOL);
        let mut fu = Family::new("eq. (9) USV dynamics", "m", DYNAMICS_POSITION_TOL);
        for (w, pre, _, n, a) in self.auv_paths() {
            for k in 0..self.k.min(a.input.len()) {
                let (Some(p0), Some(v0), Some(u), Some(p1), Some(v1)) = (
                    a.position.get(k),
                    a.velocity.get(k),
                    a.input.get(k),
                    a.position.get(k + 1),
                    a.velocity.get(k + 1),
                ) else {
                    continue;
                };
                let (p, v) = step.step(*p0, *v0, *u);
                let who = || seg(w, k + 1, &format!("{pre}AUV {n}"));
                fp.record(-diff(p, *p1), who);
                fv.record(-diff(v, *v1), who);
            }
        }
        for (w, pre, st) in self.stages() {
            let usv = &st.usv;
            for k in 0..self.k.min(usv.input.len()) {
                let (Some(p0), Some(u), Some(p1)) = (
                    usv.position.get(k),
                    usv.input.get(k),
                    usv.position.get(k + 1),
                ) else {
                    continue;
                };
                let p = [p0[0] + self.dt * u[0], p0[1] + self.dt * u[1]];
                fu.record(-diff(p, *p1), || seg(w, k + 1, &format!("{pre}USV")));
            }
        }
        vec![fp.finish(), fv.finish(), fu.finish()]
    }

    // ------------------------------------------------------------------------------------
    // 3. speeds
    // ------------------------------------------------------------------------------------
    fn speeds(&self) -> Vec<FamilyResult> {
        let mut fu = Family::new("USV speed", "m/s", SPEED_TOL);
        let mut fa = Family::new("C1_7 AUV speed", "m/s", SPEED_TOL);
        for (w, pre, st) in self.stages() {
            for (k, u) in st.usv.input.iter().enumerate().take(self.k) {
                fu.record(self.s.usv.max_speed - norm(u), || {
                    format!("window {w}, input k = {k}, {pre}USV: ‖U‖ = {}", norm(u))
                });
            }
        }
        for (w, pre, _, n, a) in self.auv_paths() {
            for (k, v) in a.velocity.iter().enumerate().take(self.k.saturating_add(1)) {
                fa.record(self.s.auv.max_speed - norm(v), || {
                    at(w, k, &format!("{pre}AUV {n}: ‖V‖ = {}", norm(v)))
                });
            }
        }
        vec![fu.finish(), fa.finish()]
    }

    // ------------------------------------------------------------------------------------
    // 4. underwater (C1_4)
    // ------------------------------------------------------------------------------------
    fn underwater(&self) -> FamilyResult {
        let mut f = Family::new("C1_4 underwater", "m", LENGTH_TOL);
        let limit = -self.s.auv.surface_clearance;
        for (w, pre, _, n, a) in self.auv_paths() {
            for (k, p) in a.position.iter().enumerate().take(self.k.saturating_add(1)) {
                f.record(limit - p[2], || {
                    at(w, k, &format!("{pre}AUV {n}: z = {}", p[2]))
                });
            }
        }
        f.finish()
    }

    // ------------------------------------------------------------------------------------
    // 5. ranges (C1_5, C1_6)
    // ------------------------------------------------------------------------------------
    fn ranges(&self) -> Vec<FamilyResult> {
        let mut f5 = Family::new("C1_5 range ≤ d_max", "m", LENGTH_TOL);
        let mut f6 = Family::new("C1_6 sonar range at k = 0, K", "m", LENGTH_TOL);
        let (d_max, d_s) = (self.s.acoustic.max_range, self.s.acoustic.sonar_range);
        for (w, pre, st, n, a) in self.auv_paths() {
            for k in 0..=self.k.min(a.position.len()) {
                let (Some(p), Some(q)) = (a.position.get(k), st.usv.position.get(k)) else {
                    continue;
                };
                let d = diff(*p, [q[0], q[1], 0.0]);
                let who = || at(w, k, &format!("{pre}AUV {n}: {d:.3} m from the USV"));
                f5.record(d_max - d, who);
                if k == 0 || k == self.k {
                    f6.record(d_s - d, who);
                }
            }
        }
        vec![f5.finish(), f6.finish()]
    }

    // ------------------------------------------------------------------------------------
    // 6. floor (C2_2 at waypoints and along segments, grid, obstacles)
    // ------------------------------------------------------------------------------------
    fn floor(&self) -> Vec<FamilyResult> {
        let mut fg = Family::new("inside the seafloor grid", "m", 0.0);
        let mut fw = Family::new("C2_2 floor clearance (waypoints)", "m", FLOOR_TOL);
        let mut fs = Family::new("C2_2 floor clearance (segments)", "m", FLOOR_TOL);
        let mut fo = Family::new("no obstacle (NODATA/land)", "samples", 0.0);
        let eps = self.s.auv.floor_clearance;
        let r = self.s.acoustic.resolution;
        let e = self.floor.extent();
        for (w, pre, _, n, a) in self.auv_paths() {
            let who = format!("{pre}AUV {n}");
            for (k, p) in a.position.iter().enumerate().take(self.k.saturating_add(1)) {
                fg.record(inside(&e, p[0], p[1]), || {
                    at(w, k, &format!("{who} at ({}, {})", p[0], p[1]))
                });
                match self.floor.elevation(p[0], p[1]) {
                    Ok(z) => fw.record(p[2] - z - eps, || {
                        at(w, k, &format!("{who}: z = {}, floor {z}", p[2]))
                    }),
                    Err(err) => fw.record(f64::NEG_INFINITY, || at(w, k, &format!("{who}: {err}"))),
                }
            }
            for k in 1..=self.k.min(a.position.len()) {
                let (Some(pa), Some(pb)) = (a.position.get(k - 1), a.position.get(k)) else {
                    continue;
                };
                let (pa, pb) = (*pa, *pb);
                // the seafloor's own 𝓛_r query
                match self.floor.segment_clearance(pa, pb, r) {
                    Ok(c) => fs.record(c.min_clearance - eps, || {
                        seg(
                            w,
                            k,
                            &format!(
                                "{who}: clearance {:.4} m at ({:.2}, {:.2}, {:.2})",
                                c.min_clearance, c.at[0], c.at[1], c.at[2]
                            ),
                        )
                    }),
                    Err(err) => {
                        fs.record(f64::NEG_INFINITY, || seg(w, k, &format!("{who}: {err}")))
                    }
                }
                // and our own sampling of the same rule, which also tests every sample for
                // obstacles: n = max(1, ⌈horizontal length / r⌉) intervals, endpoints included
                let Some(samples) = own_samples(pa, pb, r) else {
                    fo.record(f64::NEG_INFINITY, || {
                        seg(
                            w,
                            k,
                            &format!("{who}: cannot sample this segment at r = {r} m"),
                        )
                    });
                    continue;
                };
                for (i, q) in samples.enumerate() {
                    if !self.floor.contains(q[0], q[1]) {
                        continue; // reported by the grid family at the endpoints
                    }
                    match self.floor.elevation(q[0], q[1]) {
                        Ok(z) => fs.record(q[2] - z - eps, || {
                            seg(
                                w,
                                k,
                                &format!(
                                    "{who}: sample {i} at ({:.2}, {:.2}, {:.2}), floor {z:.3}",
                                    q[0], q[1], q[2]
                                ),
                            )
                        }),
                        Err(err) => {
                            fs.record(f64::NEG_INFINITY, || seg(w, k, &format!("{who}: {err}")))
                        }
                    }
                    let obstacle = self.floor.is_obstacle(q[0], q[1]).unwrap_or(true);
                    fo.record(if obstacle { -1.0 } else { 0.0 }, || {
                        let what = if obstacle {
                            "over NODATA or land"
                        } else {
                            "clear"
                        };
                        seg(
                            w,
                            k,
                            &format!("{who}: sample {i} at ({:.2}, {:.2}) is {what}", q[0], q[1]),
                        )
                    });
                }
            }
        }
        // the USV's waypoints are over the grid too, and its path and the planned links clear
        // of obstacles
        for (w, pre, st) in self.stages() {
            for (k, p) in st
                .usv
                .position
                .iter()
                .enumerate()
                .take(self.k.saturating_add(1))
            {
                fg.record(inside(&e, p[0], p[1]), || {
                    at(w, k, &format!("{pre}USV at ({}, {})", p[0], p[1]))
                });
            }
        }
        self.usv_and_link_obstacles(&mut fo);
        vec![fg.finish(), fw.finish(), fs.finish(), fo.finish()]
    }

    // ------------------------------------------------------------------------------------
    // 7. heading rate (C1_14) from the velocities
    // ------------------------------------------------------------------------------------
    fn heading_rate(&self) -> FamilyResult {
        let dt = self.dt;
        let tol = if dt > 0.0 && dt.is_finite() {
            HEADING_TURN_TOL / dt
        } else {
            HEADING_TURN_TOL
        };
        let mut f = Family::new("C1_14 heading rate", "rad/s", tol);
        let vmin = self.s.auv.min_heading_speed;
        let max = self.s.auv.max_heading_rate;
        for (w, pre, _, n, a) in self.auv_paths() {
            for k in 1..=self.k.min(a.velocity.len()) {
                let (Some(va), Some(vb)) = (a.velocity.get(k - 1), a.velocity.get(k)) else {
                    continue;
                };
                let (sa, sb) = (va[0].hypot(va[1]), vb[0].hypot(vb[1]));
                if !(sa >= vmin && sb >= vmin) {
                    if sa.is_nan() || sb.is_nan() {
                        f.record(f64::NAN, || {
                            seg(w, k, &format!("{pre}AUV {n}: non-finite velocity"))
                        });
                    }
                    continue;
                }
                let turn = wrap(vb[1].atan2(vb[0]) - va[1].atan2(va[0])).abs();
                let rate = turn / dt;
                f.record(max - rate, || {
                    seg(
                        w,
                        k,
                        &format!("{pre}AUV {n}: turns {turn:.5} rad, {rate:.3e} rad/s"),
                    )
                });
            }
        }
        f.finish()
    }

    // ------------------------------------------------------------------------------------
    // 7b. the recorded surge speed and heading agree with the velocities
    // ------------------------------------------------------------------------------------
    fn recorded(&self) -> Vec<FamilyResult> {
        let mut fs = Family::new("recorded surge speed", "m/s", DERIVED_TOL);
        let mut fh = Family::new("recorded heading", "rad", DERIVED_TOL);
        let vmin = self.s.auv.min_heading_speed;
        for (w, pre, _, n, a) in self.auv_paths() {
            for (k, v) in a.velocity.iter().enumerate().take(self.k.saturating_add(1)) {
                let speed = v[0].hypot(v[1]);
                if let Some(stored) = a.surge_speed.get(k) {
                    fs.record(-(stored - speed).abs(), || {
                        at(
                            w,
                            k,
                            &format!("{pre}AUV {n}: stored {stored}, ‖(V_x, V_y)‖ = {speed}"),
                        )
                    });
                }
                let Some(stored) = a.heading.get(k) else {
                    continue;
                };
                let psi = v[1].atan2(v[0]);
                let defined = speed >= vmin;
                let borderline = (speed - vmin).abs() <= DERIVED_TOL;
                let margin = match stored {
                    Some(h) if defined || borderline => -wrap(h - psi).abs(),
                    None if !defined || borderline => 0.0,
                    _ => f64::NEG_INFINITY,
                };
                fh.record(margin, || {
                    at(
                        w,
                        k,
                        &format!(
                            "{pre}AUV {n}: stored {}, atan2(V_y, V_x) = {psi} at horizontal speed {speed} \
                             (heading defined from {vmin} m/s)",
                            stored.map_or("null".to_string(), |h| h.to_string())
                        ),
                    )
                });
            }
        }
        vec![fs.finish(), fh.finish()]
    }

    // ------------------------------------------------------------------------------------
    // 8. windows chain
    // ------------------------------------------------------------------------------------
    fn chain(&self) -> FamilyResult {
        let mut f = Family::new("window chain", "m, m/s", CHAIN_TOL);
        let init = &self.plan.initial;
        let k = self.k;
        // an explicit [initial] of the scenario is where the plan must start, at rest
        if let Some(given) = &self.s.initial {
            f.record(-diff(init.usv, given.usv), || {
                format!(
                    "plan.initial USV {:?}, scenario.initial {:?}",
                    init.usv, given.usv
                )
            });
            for (n, p) in given.auvs.iter().enumerate() {
                let Some(a) = init.auvs.get(n) else { continue };
                f.record(-diff(a.position, *p).max(norm(&a.velocity)), || {
                    format!(
                        "plan.initial AUV {n} at {:?} / {:?}, scenario.initial {p:?} at rest",
                        a.position, a.velocity
                    )
                });
            }
        }
        for (w, pre, st) in self.stages() {
            // both stages start where the previous window's final stage (the plan) ended
            let prev = w
                .checked_sub(1)
                .and_then(|p| self.plan.windows.get(p))
                .map(|p| &p.final_);
            // USV
            let want = match prev {
                None => Some(init.usv),
                Some(p) => p.usv.position.get(k).copied(),
            };
            if let (Some(want), Some(got)) = (want, st.usv.position.first()) {
                f.record(-diff(*got, want), || {
                    format!("window {w}, k = 0, {pre}USV: {got:?}, the previous end is {want:?}")
                });
            }
            // AUVs
            for (n, a) in st.auvs.iter().enumerate() {
                let want = match prev {
                    None => init.auvs.get(n).map(|s| (s.position, s.velocity)),
                    Some(p) => p
                        .auvs
                        .get(n)
                        .and_then(|q| Some((*q.position.get(k)?, *q.velocity.get(k)?))),
                };
                let (Some((pw, vw)), Some(pg), Some(vg)) =
                    (want, a.position.first(), a.velocity.first())
                else {
                    continue;
                };
                let err = diff(*pg, pw).max(diff(*vg, vw));
                f.record(-err, || {
                    format!(
                        "window {w}, k = 0, {pre}AUV {n}: starts at {pg:?} / {vg:?}, {} is {pw:?} / {vw:?}",
                        if w == 0 { "plan.initial" } else { "the previous end" }
                    )
                });
            }
        }
        f.finish()
    }
}

/// Signed distance of (x, y) inside the extent `e` (negative outside; NaN for a non-finite
/// point: f64::min would hide a NaN).
fn inside(e: &crate::seafloor::Extent, x: f64, y: f64) -> f64 {
    if x.is_finite() && y.is_finite() {
        (x - e.x_min)
            .min(e.x_max - x)
            .min(y - e.y_min)
            .min(e.y_max - y)
    } else {
        f64::NAN
    }
}

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
