//! Frames: Fossen's NED inside the model, shoal's world frame (x east, y north, z up, heading
//! from +x towards +y) outside. Positions and vectors swap x and y and flip z; headings are
//! ψ_NED = π/2 − ψ_shoal.

use nalgebra::Matrix3;
use std::f64::consts::{FRAC_PI_2, PI};

/// R(Θ) = R_z(ψ)R_y(θ)R_x(φ), body to NED, from η's Euler angles (Fossen eq. 2.18).
pub fn body_to_ned(eta: &[f64; 6]) -> Matrix3<f64> {
    let (sf, cf) = eta[3].sin_cos();
    let (st, ct) = eta[4].sin_cos();
    let (sp, cp) = eta[5].sin_cos();
    Matrix3::new(
        cp * ct,
        -sp * cf + cp * st * sf,
        sp * sf + cp * cf * st,
        sp * ct,
        cp * cf + sf * st * sp,
        -cp * sf + st * sp * cf,
        -st,
        ct * sf,
        ct * cf,
    )
}

/// A point or vector from shoal's frame (x east, y north, z up) to NED (x north, y east, z down).
pub fn ned_from_shoal(p: [f64; 3]) -> [f64; 3] {
    [p[1], p[0], -p[2]]
}

/// A point or vector from NED to shoal's frame (the inverse of [`ned_from_shoal`]).
pub fn shoal_from_ned(p: [f64; 3]) -> [f64; 3] {
    [p[1], p[0], -p[2]]
}

/// NED heading ψ (from north towards east) of a shoal heading (from +x = east towards
/// +y = north), in (−π, π].
pub fn heading_ned_from_shoal(psi: f64) -> f64 {
    wrap(FRAC_PI_2 - psi)
}

/// Shoal heading of a NED heading (the inverse of [`heading_ned_from_shoal`]), in (−π, π].
pub fn heading_shoal_from_ned(psi: f64) -> f64 {
    wrap(FRAC_PI_2 - psi)
}

/// An angle wrapped to (−π, π].
pub(super) fn wrap(a: f64) -> f64 {
    let w = a.rem_euclid(2.0 * PI);
    if w > PI {
        w - 2.0 * PI
    } else {
        w
    }
}
