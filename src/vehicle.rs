//! Vehicle models: the AUV's linear model, eqs. (5)–(8), and the USV's, eq. (9).
//!
//! The AUV state is X = [P; V] (position and the velocity of eq. (7), [V_x, V_y, V_z]), the
//! input U is a per-mass force (m/s²). Continuous model, per axis i (eqs. (5)–(7)):
//!
//!   Ṗ_i = V_i,   V̇_i = −e_i V_i + U_i,
//!
//! with e_x = e_y = the surge damping rate and e_z = the heave rate of E'.
//!
//! **Sign of E'.** The paper defines D = −diag{γ} (Appendix A) and E' = diag{γ_vx/(m − γ_v̇x), …}.
//! With Fossen's convention (hydrodynamic derivatives X_u, X_u̇ negative) that E' is negative and
//! eq. (5) would be unstable in open loop; the damping rate is e = −γ_v/(m − γ_v̇) > 0, which is
//! what we use.
//!
//! **Discretisation.** Eq. (8) is forward Euler: V\[k+1\] = (1 − δe)V\[k\] + δU\[k\]. With a REMUS 100's
//! surge damping (e ≈ 0.15 s⁻¹) and δ = 100 s, 1 − δe ≈ −14.5: the discrete velocity oscillates
//! and grows without bound although the vehicle is stable. We default to the exact zero-order-hold
//! (ZOH) discretisation of the same continuous model, and keep Euler as an option that is refused
//! when |1 − δe| > 1.
//!
//! A useful property of ZOH: within a step, V(t) moves monotonically along the straight line from
//! V\[k\] towards U/e and V\[k+1\] lies on it, so ‖V(t)‖ ≤ max(‖V\[k\]‖, ‖V\[k+1\]‖): the speed limit C1_7
//! imposed at the waypoints holds for the whole continuous trajectory.

use crate::scenario::{Auv, Discretisation};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Errors building a vehicle model from physical parameters.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum VehicleError {
    #[error(
        "auv.discretisation = \"euler\" is unstable: on the {axis} axis 1 − δ·e = {factor:.3} \
         (δ = {dt} s, e = {rate:.4} 1/s) has magnitude above 1, so eq. (8) diverges; use \
         \"zoh\" or a time step δ ≤ {max_dt:.2} s"
    )]
    UnstableEuler {
        axis: &'static str,
        factor: f64,
        dt: f64,
        rate: f64,
        max_dt: f64,
    },
    #[error("auv.{field}: {why}")]
    BadParameter { field: &'static str, why: String },
}

/// Damping rates of E' (1/s), eq. (5): surge, heave and yaw.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Damping {
    pub surge: f64,
    pub heave: f64,
    pub yaw: f64,
}

impl Damping {
    /// E' from physical parameters (eq. (5) with Appendix A's M and D), positive rates.
    pub fn from_params(p: &Auv) -> Result<Damping, VehicleError> {
        let rate = |field: &'static str, damping: f64, inertia: f64, added: f64| {
            let effective = inertia - added; // m − γ_v̇ (added mass is negative, so this grows)
            if effective.is_nan() || effective <= 0.0 || !effective.is_finite() {
                return Err(VehicleError::BadParameter {
                    field,
                    why: format!("rigid plus added inertia must be positive, got {effective}"),
                });
            }
            if damping.is_nan() || damping > 0.0 {
                return Err(VehicleError::BadParameter {
                    field,
                    why: format!(
                        "linear damping must be ≤ 0 (Fossen's sign convention), got {damping}"
                    ),
                });
            }
            Ok(-damping / effective)
        };
        Ok(Damping {
            surge: rate("damping_surge", p.damping_surge, p.mass, p.added_mass_surge)?,
            heave: rate("damping_heave", p.damping_heave, p.mass, p.added_mass_heave)?,
            yaw: rate(
                "damping_yaw",
                p.damping_yaw,
                p.inertia_yaw,
                p.added_inertia_yaw,
            )?,
        })
    }
}

/// The discrete AUV model, per axis i ∈ {x, y, z} (diagonal, so three scalars per coefficient):
///
///   P_i\[k+1\] = P_i\[k\] + pv_i·V_i\[k\] + pu_i·U_i\[k\]
///   V_i\[k+1\] = vv_i·V_i\[k\] + vu_i·U_i\[k\]
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AuvModel {
    pub dt: f64,
    /// Continuous damping rates e_i per axis (1/s).
    pub rate: [f64; 3],
    pub pv: [f64; 3],
    pub pu: [f64; 3],
    pub vv: [f64; 3],
    pub vu: [f64; 3],
}

/// (1 − e^{−x})/x, accurate for small x.
fn phi1(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x / 2.0 + x * x / 6.0
    } else {
        -(-x).exp_m1() / x
    }
}

/// (x − 1 + e^{−x})/x², accurate for small x.
fn phi2(x: f64) -> f64 {
    if x.abs() < 1e-3 {
        0.5 - x / 6.0 + x * x / 24.0
    } else {
        (x + (-x).exp_m1()) / (x * x)
    }
}

impl AuvModel {
    /// Discretise with sampling time `dt` (δ) from the scenario's AUV parameters.
    pub fn new(p: &Auv, dt: f64) -> Result<AuvModel, VehicleError> {
        let d = Damping::from_params(p)?;
        Self::from_rates([d.surge, d.surge, d.heave], dt, p.discretisation)
    }

    /// Discretise the per-axis model with damping rates `rate` (1/s).
    pub fn from_rates(
        rate: [f64; 3],
        dt: f64,
        kind: Discretisation,
    ) -> Result<AuvModel, VehicleError> {
        let mut m = AuvModel {
            dt,
            rate,
            pv: [0.0; 3],
            pu: [0.0; 3],
            vv: [0.0; 3],
            vu: [0.0; 3],
        };
        for i in 0..3 {
            let e = rate[i];
            match kind {
                Discretisation::Zoh => {
                    let x = e * dt;
                    m.vv[i] = (-x).exp();
                    m.vu[i] = dt * phi1(x);
                    m.pv[i] = dt * phi1(x);
                    m.pu[i] = dt * dt * phi2(x);
                }
                Discretisation::Euler => {
                    // eq. (8): A_n = [I, δI; 0, I − δE'], B = [0; I]
                    let factor = 1.0 - dt * e;
                    if factor.abs() > 1.0 {
                        return Err(VehicleError::UnstableEuler {
                            axis: ["x (surge)", "y (surge)", "z (heave)"][i],
                            factor,
                            dt,
                            rate: e,
                            max_dt: 2.0 / e,
                        });
                    }
                    m.vv[i] = factor;
                    m.vu[i] = dt;
                    m.pv[i] = dt;
                    m.pu[i] = 0.0;
                }
            }
        }
        Ok(m)
    }

    /// One step of the discrete model from state (p, v) under input u.
    pub fn step(&self, p: [f64; 3], v: [f64; 3], u: [f64; 3]) -> ([f64; 3], [f64; 3]) {
        let mut pn = [0.0; 3];
        let mut vn = [0.0; 3];
        for i in 0..3 {
            pn[i] = p[i] + self.pv[i] * v[i] + self.pu[i] * u[i];
            vn[i] = self.vv[i] * v[i] + self.vu[i] * u[i];
        }
        (pn, vn)
    }
}

/// The USV model of eq. (9): P\[k+1\] = P\[k\] + δ·U\[k\], U the 2D velocity, ‖U‖ ≤ max_speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct UsvModel {
    pub dt: f64,
    pub max_speed: f64,
}

impl UsvModel {
    pub fn step(&self, p: [f64; 2], u: [f64; 2]) -> [f64; 2] {
        [p[0] + self.dt * u[0], p[1] + self.dt * u[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Auv;

    /// Integrate the continuous model with many small RK4 steps.
    fn rk4(e: f64, p0: f64, v0: f64, u: f64, dt: f64) -> (f64, f64) {
        let n = 20_000;
        let h = dt / n as f64;
        let f = |_p: f64, v: f64| (v, -e * v + u);
        let (mut p, mut v) = (p0, v0);
        for _ in 0..n {
            let k1 = f(p, v);
            let k2 = f(p + h / 2.0 * k1.0, v + h / 2.0 * k1.1);
            let k3 = f(p + h / 2.0 * k2.0, v + h / 2.0 * k2.1);
            let k4 = f(p + h * k3.0, v + h * k3.1);
            p += h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0);
            v += h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1);
        }
        (p, v)
    }

    #[test]
    fn remus_damping_rates_are_in_the_expected_range() {
        let d = Damping::from_params(&Auv::default()).unwrap();
        // 4.86 / (30.51 + 0.93) and 26.2 / (30.51 + 35.5)
        assert!((d.surge - 4.86 / 31.44).abs() < 1e-12);
        assert!((d.heave - 26.2 / 66.01).abs() < 1e-12);
        assert!(d.surge > 0.05 && d.surge < 0.6 && d.heave > 0.05 && d.heave < 0.6);
    }

    #[test]
    fn zoh_matches_the_continuous_model() {
        for &e in &[0.0, 1e-7, 0.01, 0.1546, 0.397, 2.0] {
            let m = AuvModel::from_rates([e; 3], 100.0, Discretisation::Zoh).unwrap();
            let (p, v) = m.step([10.0; 3], [0.7; 3], [0.05; 3]);
            let (pr, vr) = rk4(e, 10.0, 0.7, 0.05, 100.0);
            assert!(
                (p[0] - pr).abs() < 1e-6 * (1.0 + pr.abs()),
                "e={e}: {} vs {pr}",
                p[0]
            );
            assert!(
                (v[0] - vr).abs() < 1e-9 * (1.0 + vr.abs()),
                "e={e}: {} vs {vr}",
                v[0]
            );
        }
    }

    #[test]
    fn euler_is_refused_when_unstable_and_matches_eq8_when_stable() {
        let err = AuvModel::new(
            &Auv {
                discretisation: Discretisation::Euler,
                ..Auv::default()
            },
            100.0,
        )
        .unwrap_err();
        assert!(matches!(err, VehicleError::UnstableEuler { .. }));
        assert!(err.to_string().contains("zoh"));
        let m = AuvModel::from_rates([0.1; 3], 1.0, Discretisation::Euler).unwrap();
        let (p, v) = m.step([1.0; 3], [2.0; 3], [3.0; 3]);
        assert_eq!(p, [3.0; 3]); // P + δV
        assert!((v[0] - (0.9 * 2.0 + 3.0)).abs() < 1e-12); // (1 − δe)V + δU
    }

    #[test]
    fn positive_damping_is_rejected() {
        let p = Auv {
            damping_surge: 4.0,
            ..Auv::default()
        };
        let err = Damping::from_params(&p).unwrap_err();
        assert!(err.to_string().contains("damping_surge"));
    }
}
