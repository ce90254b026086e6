//! The checker's own vehicle models, written from the paper and the scenario's physical
//! parameters alone (no code shared with `crate::vehicle`).
//!
//! AUV, per axis i ∈ {x, y, z} (eqs. (5)–(7) with the horizontal velocities of eq. (7)):
//!
//!   ṗ = v,   v̇ = −e·v + u,   u constant over a step of length δ,
//!
//! with e_x = e_y = e_surge and e_z = e_heave, e = −γ_v / (m − γ_v̇) (Fossen's signs make γ_v and
//! γ_v̇ negative, so e > 0 for a stable vehicle).
//!
//! With `zoh` the continuous model is integrated numerically by classical RK4. The model is linear
//! and time-invariant and p does not enter the right-hand side, so one RK4 sweep over a step is
//! itself a linear map (p, v, u) ↦ (p + a·v + b·u, c·v + d·u); the four numbers are obtained by
//! running the RK4 sweep on the unit responses (v₀ = 1, u = 0) and (v₀ = 0, u = 1). That is the
//! same arithmetic as integrating every step separately, done once per axis. With `euler` the
//! paper's eq. (8) is applied literally: P⁺ = P + δV, V⁺ = (1 − δe)V + δU.

use crate::scenario::{Auv, Discretisation};

/// RK4 step size bound: e·h ≤ this. The local error of RK4 on v̇ = −e·v is ≈ (e·h)⁵/120 of the
/// transient, ≈ 3e-16 at 0.002, so truncation is below rounding; the propagator is then good to
/// ≈ n·1e-16 relative (n substeps, ≈ 2e4 for the default heave axis at δ = 100 s), about 1e-12 —
/// far below the dynamics tolerances. The propagator is computed once per plan, so the substeps
/// cost nothing that matters.
const MAX_RATE_STEP: f64 = 0.002;
/// Never fewer substeps than this (keeps h small relative to δ for slowly damped axes too).
const MIN_SUBSTEPS: usize = 1000;
/// Never more (a guard against absurd parameters; reached only when e·δ > 2000, where RK4 stays
/// stable up to e·δ ≈ 2.7e6 but loses the accuracy argued above).
const MAX_SUBSTEPS: usize = 1_000_000;

/// Damping rates (1/s) computed from the scenario: surge, heave and yaw.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rates {
    /// e_surge = −γ_vx / (m − γ_v̇x), 1/s; the rate of the x and y axes.
    pub surge: f64,
    /// e_heave = −γ_vz / (m − γ_v̇z), 1/s; the rate of the z axis.
    pub heave: f64,
    /// e_yaw = −γ_ωz / (J_z − N_ṙ), 1/s; the rate of the heading.
    pub yaw: f64,
}

impl Rates {
    /// e = −damping / (inertia − added inertia) per degree of freedom. Returns the rates and a
    /// list of reasons they are not physical (non-positive effective inertia, positive damping,
    /// non-finite), which the checker reports as a model failure.
    pub fn from_params(p: &Auv) -> (Rates, Vec<String>) {
        let mut problems = Vec::new();
        let mut rate = |what: &str, damping: f64, inertia: f64, added: f64| {
            let effective = inertia - added;
            let e = -damping / effective;
            if !(effective > 0.0 && effective.is_finite()) {
                problems.push(format!(
                    "{what}: effective inertia {inertia} − ({added}) = {effective} is not positive"
                ));
            } else if !(e >= 0.0 && e.is_finite()) {
                problems.push(format!("{what}: damping rate {e} 1/s is not ≥ 0"));
            }
            e
        };
        let surge = rate("surge", p.damping_surge, p.mass, p.added_mass_surge);
        let heave = rate("heave", p.damping_heave, p.mass, p.added_mass_heave);
        let yaw = rate("yaw", p.damping_yaw, p.inertia_yaw, p.added_inertia_yaw);
        (Rates { surge, heave, yaw }, problems)
    }

    /// Per-axis rates [x, y, z].
    pub fn axes(&self) -> [f64; 3] {
        [self.surge, self.surge, self.heave]
    }
}

/// One step of one axis: p⁺ = p + a·v + b·u, v⁺ = c·v + d·u.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisStep {
    /// Position gain of the velocity, seconds.
    pub a: f64,
    /// Position gain of the input, s².
    pub b: f64,
    /// Velocity gain of the velocity, dimensionless.
    pub c: f64,
    /// Velocity gain of the input, seconds.
    pub d: f64,
}

/// RK4 over [0, δ] of ṗ = v, v̇ = −e·v + u from (0, v0) with `n` equal substeps.
fn rk4(e: f64, v0: f64, u: f64, dt: f64, n: usize) -> (f64, f64) {
    let h = dt / n as f64;
    let f = |v: f64| -e * v + u;
    let (mut p, mut v) = (0.0, v0);
    for _ in 0..n {
        // ṗ = v has no p-dependence: the p-increments are the v-stages.
        let k1 = f(v);
        let v2 = v + 0.5 * h * k1;
        let k2 = f(v2);
        let v3 = v + 0.5 * h * k2;
        let k3 = f(v3);
        let v4 = v + h * k3;
        let k4 = f(v4);
        p += h / 6.0 * (v + 2.0 * v2 + 2.0 * v3 + v4);
        v += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    (p, v)
}

/// Number of RK4 substeps for rate `e` over `dt`.
pub fn substeps(e: f64, dt: f64) -> usize {
    let need = (e.abs() * dt.abs() / MAX_RATE_STEP).ceil();
    if need.is_finite() {
        (need as usize).clamp(MIN_SUBSTEPS, MAX_SUBSTEPS)
    } else {
        // e or δ not finite: the result is NaN whatever the count, which fails the checks
        MIN_SUBSTEPS
    }
}

impl AxisStep {
    /// The step of the continuous model, integrated by RK4.
    pub fn continuous(e: f64, dt: f64) -> AxisStep {
        let n = substeps(e, dt);
        let (a, c) = rk4(e, 1.0, 0.0, dt, n);
        let (b, d) = rk4(e, 0.0, 1.0, dt, n);
        AxisStep { a, b, c, d }
    }

    /// Eq. (8) literally.
    pub fn euler(e: f64, dt: f64) -> AxisStep {
        AxisStep {
            a: dt,
            b: 0.0,
            c: 1.0 - dt * e,
            d: dt,
        }
    }
}

/// The checker's AUV model for one step of length δ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuvStep {
    /// The steps of the x, y and z axes.
    pub axes: [AxisStep; 3],
}

impl AuvStep {
    /// The step of length `dt` (seconds) for the per-axis damping rates `rates` \[x, y, z\]
    /// (1/s, see [`Rates::axes`]): RK4 on the continuous model for `Zoh`, eq. (8) for `Euler`.
    pub fn new(rates: [f64; 3], dt: f64, kind: Discretisation) -> AuvStep {
        AuvStep {
            axes: rates.map(|e| match kind {
                Discretisation::Zoh => AxisStep::continuous(e, dt),
                Discretisation::Euler => AxisStep::euler(e, dt),
            }),
        }
    }

    /// `(P[k+1], V[k+1])` from `(P[k], V[k])` under `U[k]`.
    pub fn step(&self, p: [f64; 3], v: [f64; 3], u: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let mut pn = [0.0; 3];
        let mut vn = [0.0; 3];
        for i in 0..3 {
            let s = self.axes[i];
            pn[i] = p[i] + (s.a * v[i] + s.b * u[i]);
            vn[i] = s.c * v[i] + s.d * u[i];
        }
        (pn, vn)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form of the continuous step, derived by hand: with x = e·δ,
    /// v(δ) = e^{−x} v0 + (1 − e^{−x})/e · u and
    /// p(δ) = p0 + (1 − e^{−x})/e · v0 + (δ − (1 − e^{−x})/e)/e · u.
    fn closed(e: f64, dt: f64) -> AxisStep {
        let x = e * dt;
        let g = -(-x).exp_m1() / e; // (1 − e^{−x})/e
        AxisStep {
            a: g,
            b: (dt - g) / e,
            c: (-x).exp(),
            d: g,
        }
    }

    #[test]
    fn rk4_matches_the_closed_form() {
        for (e, dt) in [
            (0.1546, 100.0),
            (0.397, 100.0),
            (0.5, 1.0),
            (2.0, 3.0),
            (1e-3, 50.0),
        ] {
            let r = AxisStep::continuous(e, dt);
            let c = closed(e, dt);
            for (got, want, scale) in [
                (r.a, c.a, dt),
                (r.b, c.b, dt * dt),
                (r.c, c.c, 1.0),
                (r.d, c.d, dt),
            ] {
                assert!(
                    (got - want).abs() <= 1e-10 * scale,
                    "e = {e}, δ = {dt}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn undamped_axis_is_a_double_integrator() {
        let r = AxisStep::continuous(0.0, 10.0);
        assert!((r.a - 10.0).abs() < 1e-12);
        assert!((r.b - 50.0).abs() < 1e-10);
        assert!((r.c - 1.0).abs() < 1e-15);
        assert!((r.d - 10.0).abs() < 1e-12);
    }

    #[test]
    fn rates_from_default_parameters() {
        let (r, problems) = Rates::from_params(&Auv::default());
        assert!(problems.is_empty());
        assert!((r.surge - 4.86 / (30.51 + 0.93)).abs() < 1e-15);
        assert!((r.heave - 26.2 / (30.51 + 35.5)).abs() < 1e-15);
        assert!((r.yaw - 18.8 / (3.45 + 4.88)).abs() < 1e-15);
        let bad = Auv {
            mass: -1.0,
            ..Auv::default()
        };
        assert!(!Rates::from_params(&bad).1.is_empty());
    }
}
