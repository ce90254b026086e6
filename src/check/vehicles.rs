//! The vehicle families: the model record, the dynamics (C1_1, eq. (9)), speeds (C1_7),
//! depth (C1_4), ranges (C1_5, C1_6), heading rate (C1_14), the recorded surge speed and
//! heading, and the chain of windows.

use super::model::{AuvStep, Rates};
use super::run::{at, diff, norm, rel, seg, wrap, Checker, Family};
use super::{
    FamilyResult, CHAIN_TOL, DERIVED_TOL, DYNAMICS_POSITION_TOL, DYNAMICS_VELOCITY_TOL,
    HEADING_TURN_TOL, LENGTH_TOL, MODEL_REL_TOL, SPEED_TOL,
};

impl Checker<'_> {
    // ------------------------------------------------------------------------------------
    // model record (damping rates and discrete coefficients)
    // ------------------------------------------------------------------------------------
    pub(super) fn model(&self) -> (FamilyResult, AuvStep) {
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
    pub(super) fn dynamics(&self, step: &AuvStep) -> Vec<FamilyResult> {
        let mut fp = Family::new("C1_1 AUV dynamics (position)", "m", DYNAMICS_POSITION_TOL);
        let mut fv = Family::new("C1_1 AUV dynamics (velocity)", "m/s", DYNAMICS_VELOCITY_TOL);
        let mut fu = Family::new("eq. (9) USV dynamics", "m", DYNAMICS_POSITION_TOL);
        let current = crate::sim::current::CurrentField::new(&self.plan.current);
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
                // the recorded current moves the position over the step (eq. (8)'s ϖ term)
                let c = current.at(*p0);
                let p = std::array::from_fn(|i| p[i] + self.dt * c[i]);
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
    pub(super) fn speeds(&self) -> Vec<FamilyResult> {
        let mut fu = Family::new("USV speed", "m/s", SPEED_TOL);
        let mut fa = Family::new("C1_7 AUV speed", "m/s", SPEED_TOL);
        for (w, pre, st) in self.stages() {
            for (k, u) in st.usv.input.iter().enumerate().take(self.k) {
                fu.record(self.limits.usv.max_speed - norm(u), || {
                    format!("window {w}, input k = {k}, {pre}USV: ‖U‖ = {}", norm(u))
                });
            }
        }
        for (w, pre, _, n, a) in self.auv_paths() {
            for (k, v) in a.velocity.iter().enumerate().take(self.k.saturating_add(1)) {
                fa.record(self.limits.auv.max_speed - norm(v), || {
                    at(w, k, &format!("{pre}AUV {n}: ‖V‖ = {}", norm(v)))
                });
            }
        }
        vec![fu.finish(), fa.finish()]
    }

    // ------------------------------------------------------------------------------------
    // 4. underwater (C1_4)
    // ------------------------------------------------------------------------------------
    pub(super) fn underwater(&self) -> FamilyResult {
        let mut f = Family::new("C1_4 underwater", "m", LENGTH_TOL);
        let limit = -self.limits.auv.surface_clearance;
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
    pub(super) fn ranges(&self) -> Vec<FamilyResult> {
        let mut f5 = Family::new("C1_5 range ≤ d_max", "m", LENGTH_TOL);
        let mut f6 = Family::new("C1_6 sonar range at k = 0, K", "m", LENGTH_TOL);
        let a = &self.limits.acoustic;
        let (d_max, d_s) = (a.max_range, a.sonar_range);
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
    // 7. heading rate (C1_14) from the velocities
    // ------------------------------------------------------------------------------------
    pub(super) fn heading_rate(&self) -> FamilyResult {
        let dt = self.dt;
        let tol = if dt > 0.0 && dt.is_finite() {
            HEADING_TURN_TOL / dt
        } else {
            HEADING_TURN_TOL
        };
        let mut f = Family::new("C1_14 heading rate", "rad/s", tol);
        let vmin = self.limits.auv.min_heading_speed;
        let max = self.limits.auv.max_heading_rate;
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
    pub(super) fn recorded(&self) -> Vec<FamilyResult> {
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
    pub(super) fn chain(&self) -> FamilyResult {
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
