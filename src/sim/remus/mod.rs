//! The 6-DoF REMUS 100 model (the paper's Section II-A, eqs. (1)–(2), and Appendix A), integrated
//! by RK4.
//!
//! The equations of motion are Fossen's (Handbook of Marine Craft Hydrodynamics and Motion
//! Control, 2nd ed., 2021, §§ 3, 6, 8 and 10.3):
//!
//!   M_RB ν̇ + C_RB(ν)ν + M_A ν̇_r + C_A(ν_r)ν_r + D(ν_r)ν_r + g(η) = τ,   η̇ = J(η)ν,
//!
//! where ν = [u, v, w, p, q, r] is the body velocity over the ground and ν_r = ν − ν_c is the
//! velocity through the water. The current ν_c = [R(Θ)ᵀv_c; 0] is irrotational and constant in
//! NED, so ν̇_c = [−ω × R(Θ)ᵀv_c; 0]. C_RB and C_A are the skew-symmetric forms of M_RB and M_A
//! (Fossen's m2c). Written out, M ν̇ = τ − C_RB(ν)ν − C_A(ν_r)ν_r − D(ν_r)ν_r − g(η) + M_A ν̇_c,
//! with M = M_RB + M_A factored once at construction.
//!
//! D(ν_r)ν_r and the controls are Prestero's (2001), see [`Coefficients`]:
//! - quadratic axial and crossflow drag;
//! - body lift;
//! - the fins' lift from the flow (angle of attack and rotation);
//! - the fin lift Y_uuδr·u_r²·δr (and the same form for the other fins);
//! - thrust along body x, with a roll torque K_prop/X_prop per newton.
//!
//! The Munk moment and the other added-mass cross terms come from C_A.
//!
//! **Validity.** Prestero fitted his coefficients at 1.5 m/s and small angles of attack. The model
//! is open-loop unstable at speed, because the Munk moments outweigh the fins. Straight, level
//! flight at 1.54 m/s (neutral ballast, no propeller torque) has its heave–pitch pair at
//! 0.44 ± 0.17i /s and a sway–yaw root at +1.0 /s, so a course or a depth needs feedback on
//! the fins. Roll is a lightly damped 1.27 s oscillation. The vehicle is 6.7 N buoyant, and the
//! propeller torque rolls it to about −5°. The Euler-angle kinematics are singular at θ = ±90°.
//! The open-loop vehicle can get there: with the stern planes held hard nose-down it corkscrews
//! to θ ≈ −86°.
//!
//! **Step.** RK4 at a fixed step of [`RECOMMENDED_STEP`] = 0.05 s. The fastest modes are roll
//! (a 1.3 s period) and the quadratic pitch and sway damping, which stiffen with rate. A test
//! shows that 0.1 s is still stable at full speed with full fins.
//!
//! **Frames.** Fossen's NED (x north, y east, z down, ψ from north towards east) inside. The
//! helpers ([`ned_from_shoal`], [`RigidState::velocity_shoal`], …) convert at the boundary to shoal's world frame (x east, y north, z up,
//! heading from +x towards +y).

mod coefficients;
mod frames;
#[cfg(test)]
mod tests;

pub use coefficients::{Coefficients, MAX_SPEED};
pub use frames::{
    body_to_ned, heading_ned_from_shoal, heading_shoal_from_ned, ned_from_shoal, shoal_from_ned,
};

use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use thiserror::Error;

/// The RK4 step we recommend, s.
pub const RECOMMENDED_STEP: f64 = 0.05;

/// Prestero's fin limit, ±13.6° (Table 2.2, as the public reproduction of his model reads it).
/// Fossen's model uses ±15°.
pub const MAX_FIN_DEG: f64 = 13.6;

/// Body velocities ν = [u, v, w, p, q, r] (m/s, rad/s) and pose η = [x, y, z, φ, θ, ψ] in
/// Fossen's NED convention (x north, y east, z down; ψ from north towards east).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RigidState {
    /// ν: surge, sway, heave (m/s), roll, pitch and yaw rates (rad/s), in the body frame,
    /// relative to the ground (the current is not subtracted).
    pub nu: [f64; 6],
    /// η: north, east, down (m), roll, pitch, yaw (rad), ZYX Euler angles.
    pub eta: [f64; 6],
}

impl RigidState {
    /// A level vehicle at shoal-frame `position` (m), shoal `heading` (rad from +x towards +y),
    /// moving ahead at surge speed `speed` (m/s) with no rotation.
    pub fn from_shoal(position: [f64; 3], heading: f64, speed: f64) -> RigidState {
        let p = ned_from_shoal(position);
        RigidState {
            nu: [speed, 0.0, 0.0, 0.0, 0.0, 0.0],
            eta: [p[0], p[1], p[2], 0.0, 0.0, heading_ned_from_shoal(heading)],
        }
    }

    /// Position in shoal's world frame (x east, y north, z up), m.
    pub fn position_shoal(&self) -> [f64; 3] {
        shoal_from_ned([self.eta[0], self.eta[1], self.eta[2]])
    }

    /// Heading in shoal's world frame (rad from +x towards +y, in (−π, π]).
    pub fn heading_shoal(&self) -> f64 {
        heading_shoal_from_ned(self.eta[5])
    }

    /// Velocity over the ground in NED, R(Θ)·[u, v, w], m/s.
    pub fn velocity_ned(&self) -> [f64; 3] {
        let v = body_to_ned(&self.eta) * Vector3::new(self.nu[0], self.nu[1], self.nu[2]);
        [v[0], v[1], v[2]]
    }

    /// Velocity over the ground in shoal's world frame (x east, y north, z up), m/s.
    pub fn velocity_shoal(&self) -> [f64; 3] {
        shoal_from_ned(self.velocity_ned())
    }
}

/// Actuator commands.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Actuators {
    /// Propeller thrust along the body x axis, N.
    pub thrust: f64,
    /// Rudder angle δ_r, rad (positive: the tail is pushed to starboard, the nose turns to
    /// port, ψ decreases).
    pub rudder: f64,
    /// Stern-plane angle δ_s, rad (positive: trailing edge down, the nose pitches down).
    pub stern: f64,
}

/// Why a set of coefficients cannot make a model.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RemusError {
    /// A coefficient is NaN or infinite.
    #[error("REMUS coefficients must be finite")]
    NotFinite,
    /// M = M_RB + M_A is not symmetric positive definite.
    #[error("the mass matrix M = M_RB + M_A is not symmetric positive definite")]
    MassMatrix,
}

/// The REMUS 100: Prestero's coefficients ([`Coefficients`]), actuator limits, and the mass
/// matrix factored once.
#[derive(Debug, Clone, PartialEq)]
pub struct Remus100 {
    /// Largest thrust, N (commands are clamped to ±max_thrust). The default is the axial drag at
    /// the REMUS 100's top speed of 2.5 m/s (Fossen): 1.62 × 2.5² = 10.125 N.
    pub max_thrust: f64,
    /// Largest fin angle (rudder and stern planes), rad. Default ±13.6° (Prestero).
    pub max_fin: f64,
    coeffs: Coefficients,
    m_rb: Matrix6<f64>,
    m_a: Matrix6<f64>,
    m_inv: Matrix6<f64>,
}

impl Default for Remus100 {
    fn default() -> Self {
        let c = Coefficients::prestero();
        Remus100::assemble(c, c.surge_drag(MAX_SPEED), MAX_FIN_DEG.to_radians())
    }
}

impl Remus100 {
    /// A model from `coeffs`, with the default limits: thrust up to the drag at 2.5 m/s and fins
    /// up to ±13.6°.
    pub fn new(coeffs: Coefficients) -> Result<Remus100, RemusError> {
        if coeffs.all().iter().any(|x| !x.is_finite()) {
            return Err(RemusError::NotFinite);
        }
        let m = mass_matrices(&coeffs);
        let total = m.0 + m.1;
        if (total - total.transpose()).abs().max() > 1e-12 * total.abs().max()
            || total.cholesky().is_none()
        {
            return Err(RemusError::MassMatrix);
        }
        let thrust = coeffs.surge_drag(MAX_SPEED).abs();
        Ok(Remus100::assemble(coeffs, thrust, MAX_FIN_DEG.to_radians()))
    }

    /// The REMUS 100 in an ideal fluid ([`Coefficients::ideal_fluid`]), with no thrust and no
    /// fins (both limits 0). Kinetic energy and Kirchhoff's impulses are conserved.
    pub fn ideal_fluid() -> Remus100 {
        Remus100::assemble(Coefficients::prestero().ideal_fluid(), 0.0, 0.0)
    }

    fn assemble(coeffs: Coefficients, max_thrust: f64, max_fin: f64) -> Remus100 {
        let (m_rb, m_a) = mass_matrices(&coeffs);
        let m_inv = (m_rb + m_a)
            .cholesky()
            .map(|c| c.inverse())
            .unwrap_or_else(Matrix6::zeros);
        Remus100 {
            max_thrust,
            max_fin,
            coeffs,
            m_rb,
            m_a,
            m_inv,
        }
    }

    /// The coefficients the model was built from.
    pub fn coefficients(&self) -> &Coefficients {
        &self.coeffs
    }

    /// M = M_RB + M_A (constant, symmetric positive definite).
    pub fn mass_matrix(&self) -> Matrix6<f64> {
        self.m_rb + self.m_a
    }

    /// Kinetic energy of the body and its added mass, ½ νᵀMν, J (ν through the water).
    pub fn kinetic_energy(&self, nu: &[f64; 6]) -> f64 {
        let n = Vector6::from_column_slice(nu);
        0.5 * n.dot(&(self.mass_matrix() * n))
    }

    /// `a` clamped to the limits: thrust to ±max_thrust, fins to ±max_fin.
    pub fn clamp(&self, a: &Actuators) -> Actuators {
        let lim = |x: f64, l: f64| x.max(-l.abs()).min(l.abs());
        Actuators {
            thrust: lim(a.thrust, self.max_thrust),
            rudder: lim(a.rudder, self.max_fin),
            stern: lim(a.stern, self.max_fin),
        }
    }

    /// The generalized force M ν̇ on the vehicle (N, N·m), body frame: the right-hand side
    /// τ − C_RB(ν)ν − C_A(ν_r)ν_r − D(ν_r)ν_r − g(η) + M_A ν̇_c, actuators clamped.
    pub fn forces(&self, s: &RigidState, a: &Actuators, current_ned: [f64; 3]) -> [f64; 6] {
        let f = self.force_vector(s, a, current_ned);
        [f[0], f[1], f[2], f[3], f[4], f[5]]
    }

    fn force_vector(&self, s: &RigidState, a: &Actuators, current_ned: [f64; 3]) -> Vector6<f64> {
        let a = self.clamp(a);
        let c = &self.coeffs;
        let rot = body_to_ned(&s.eta);
        let nu = Vector6::from_column_slice(&s.nu);
        let omega = Vector3::new(nu[3], nu[4], nu[5]);
        let vc = rot.transpose() * Vector3::from(current_ned);
        let vc_dot = -omega.cross(&vc);
        let nu_r = nu - stack(vc, Vector3::zeros());
        let tau = self.hydrodynamic(&nu_r) + self.controls(&nu_r, &a);
        // g(η) (Fossen eq. 4.6): −[f_g + f_b; r_g × f_g + r_b × f_b], with f_g = W R(Θ)ᵀe₃ and
        // f_b = −B R(Θ)ᵀe₃ in the body frame (z down).
        let k = rot.transpose() * Vector3::z();
        let (w, b) = (c.weight(), c.buoyancy);
        let arm = w * Vector3::from(c.r_g) - b * Vector3::from(c.r_b);
        let g = stack(-(w - b) * k, -arm.cross(&k));
        let nu_c_dot = stack(vc_dot, Vector3::zeros());
        tau - coriolis(&self.m_rb, &nu) - coriolis(&self.m_a, &nu_r) - g + self.m_a * nu_c_dot
    }

    /// Prestero's hydrodynamic forces on the flow-relative velocity `n` (drag, body lift and
    /// the fins' lift from the flow); the added-mass terms are in C_A.
    fn hydrodynamic(&self, n: &Vector6<f64>) -> Vector6<f64> {
        let c = &self.coeffs;
        let (u, v, w, p, q, r) = (n[0], n[1], n[2], n[3], n[4], n[5]);
        Vector6::new(
            c.x_uu * u * u.abs(),
            c.y_vv * v * v.abs()
                + c.y_rr * r * r.abs()
                + (c.y_uv_body + c.y_uv_fin) * u * v
                + c.y_ur_fin * u * r,
            c.z_ww * w * w.abs()
                + c.z_qq * q * q.abs()
                + (c.z_uw_body + c.z_uw_fin) * u * w
                + c.z_uq_fin * u * q,
            c.k_pp * p * p.abs(),
            c.m_ww * w * w.abs()
                + c.m_qq * q * q.abs()
                + (c.m_uw_body + c.m_uw_fin) * u * w
                + c.m_uq_fin * u * q,
            c.n_vv * v * v.abs()
                + c.n_rr * r * r.abs()
                + (c.n_uv_body + c.n_uv_fin) * u * v
                + c.n_ur_fin * u * r,
        )
    }

    /// Fin lift (Prestero: ∝ u_r² times the fin angle) and the propeller's thrust and torque.
    fn controls(&self, n: &Vector6<f64>, a: &Actuators) -> Vector6<f64> {
        let c = &self.coeffs;
        let uu = n[0] * n[0];
        Vector6::new(
            a.thrust,
            c.y_uu_dr * uu * a.rudder,
            c.z_uu_ds * uu * a.stern,
            c.prop_torque_per_thrust() * a.thrust,
            c.m_uu_ds * uu * a.stern,
            c.n_uu_dr * uu * a.rudder,
        )
    }

    /// d[ν; η]/dt for state `s`, actuators `a` (clamped to the limits) and a current
    /// `current_ned` (m/s, NED, irrotational and constant).
    pub fn derivative(&self, s: &RigidState, a: &Actuators, current_ned: [f64; 3]) -> [f64; 12] {
        let nu_dot = self.m_inv * self.force_vector(s, a, current_ned);
        let (phi, theta) = (s.eta[3], s.eta[4]);
        let (sf, cf) = phi.sin_cos();
        let (st, ct) = theta.sin_cos();
        let [p, q, r] = [s.nu[3], s.nu[4], s.nu[5]];
        let pos = s.velocity_ned();
        let mut d = [0.0; 12];
        d[..6].copy_from_slice(nu_dot.as_slice());
        d[6..9].copy_from_slice(&pos);
        // T(Θ) of Fossen eq. (2.29): singular at θ = ±90°.
        d[9] = p + (sf * q + cf * r) * st / ct;
        d[10] = cf * q - sf * r;
        d[11] = (sf * q + cf * r) / ct;
        d
    }

    /// One RK4 step of `h` seconds, actuators and current held over the step. Angles are left
    /// unwrapped (ψ accumulates turns).
    pub fn step(&self, s: &RigidState, a: &Actuators, current_ned: [f64; 3], h: f64) -> RigidState {
        let add = |x: &RigidState, k: &[f64; 12], f: f64| {
            let mut y = *x;
            for i in 0..6 {
                y.nu[i] += f * k[i];
                y.eta[i] += f * k[6 + i];
            }
            y
        };
        let k1 = self.derivative(s, a, current_ned);
        let k2 = self.derivative(&add(s, &k1, h / 2.0), a, current_ned);
        let k3 = self.derivative(&add(s, &k2, h / 2.0), a, current_ned);
        let k4 = self.derivative(&add(s, &k3, h), a, current_ned);
        let mut k = [0.0; 12];
        for i in 0..12 {
            k[i] = (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) / 6.0;
        }
        add(s, &k, h)
    }

    /// Thrust that holds surge speed `u` (m/s) in straight, level flight in still water, N:
    /// −X_u|u|·u|u|, not clamped to `max_thrust`.
    pub fn steady_thrust(&self, u: f64) -> f64 {
        self.coeffs.surge_drag(u)
    }

    /// The steady surge speed under `thrust` in straight, level flight in still water (the
    /// inverse of [`Remus100::steady_thrust`]), m/s.
    pub fn steady_speed(&self, thrust: f64) -> f64 {
        let k = -self.coeffs.x_uu;
        if k > 0.0 {
            thrust.signum() * (thrust.abs() / k).sqrt()
        } else {
            f64::INFINITY * thrust.signum()
        }
    }
}

/// (M_RB, M_A) at the body origin (Fossen eqs. 3.44 and 6.49; Prestero eq. 6.8).
fn mass_matrices(c: &Coefficients) -> (Matrix6<f64>, Matrix6<f64>) {
    let m = c.mass;
    let s = skew(&Vector3::from(c.r_g));
    let mut m_rb = Matrix6::zeros();
    m_rb.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(Matrix3::identity() * m));
    m_rb.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-m * s));
    m_rb.fixed_view_mut::<3, 3>(3, 0).copy_from(&(m * s));
    m_rb.fixed_view_mut::<3, 3>(3, 3)
        .copy_from(&Matrix3::from_diagonal(&Vector3::from(c.inertia)));
    let mut m_a = Matrix6::zeros();
    for (i, j, x) in [
        (0, 0, c.x_udot),
        (1, 1, c.y_vdot),
        (1, 5, c.y_rdot),
        (2, 2, c.z_wdot),
        (2, 4, c.z_qdot),
        (3, 3, c.k_pdot),
        (4, 2, c.m_wdot),
        (4, 4, c.m_qdot),
        (5, 1, c.n_vdot),
        (5, 5, c.n_rdot),
    ] {
        m_a[(i, j)] = -x;
    }
    (m_rb, m_a)
}

/// C(ν)ν for the skew-symmetric C of a mass matrix (Fossen's m2c, eq. 3.46 / 6.43): with the
/// momenta a = M₁₁v + M₁₂ω and b = M₂₁v + M₂₂ω of the symmetric part of M,
/// C(ν)ν = [ω × a; v × a + ω × b].
fn coriolis(m: &Matrix6<f64>, nu: &Vector6<f64>) -> Vector6<f64> {
    let sym = 0.5 * (m + m.transpose());
    let h = sym * nu;
    let (a, b) = (
        Vector3::new(h[0], h[1], h[2]),
        Vector3::new(h[3], h[4], h[5]),
    );
    let (v, w) = (
        Vector3::new(nu[0], nu[1], nu[2]),
        Vector3::new(nu[3], nu[4], nu[5]),
    );
    stack(w.cross(&a), v.cross(&a) + w.cross(&b))
}

/// [a; b].
fn stack(a: Vector3<f64>, b: Vector3<f64>) -> Vector6<f64> {
    Vector6::new(a[0], a[1], a[2], b[0], b[1], b[2])
}

/// S(x), the matrix with S(x)y = x × y.
fn skew(x: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -x[2], x[1], x[2], 0.0, -x[0], -x[1], x[0], 0.0)
}
