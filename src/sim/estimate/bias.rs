//! The dead-reckoning bias model shared by both estimators.
//!
//! A vehicle's measured increment is δ = (1 + s)·R_z(β)·Δ + n (horizontal part rotated by the
//! heading bias β, everything scaled by the DVL scale-factor error s, white noise n ~ N(0, C)), so
//! the true displacement is
//!
//! Δ = p\[e+1\] − p\[e\] = g(b, δ − n),  g(b, δ) = G(b)·δ,  G(b) = diag(R_z(−β), 1) / (1 + s).
//!
//! - The filter predicts with g(b̂, δ) and its Jacobian ∂g/∂b, with process noise G C Gᵀ (the
//!   white noise mapped into the world frame; [`prediction`]).
//! - The smoother's factor ([`BiasedOdometry`]) states the same constraint multiplied by
//!   G(b)⁻¹ = (1 + s)·diag(R_z(β), 1): r = (1 + s)·R_z(β)·(p\[e+1\] − p\[e\]) − δ. Because g is
//!   linear in δ, r = G⁻¹·(Δ − g(b, δ)) exactly, and its noise is exactly n, with covariance C
//!   whatever b is; the factor is whitened by C as an unbiased odometry factor is. (Whitening
//!   Δ − g by a fixed C instead would ignore the (1 + s)⁻² and the rotation of C by β.)

use factrs::{
    linalg::{vectorx, Const, ForwardProp, Numeric, VectorX},
    residuals::Residual3,
    variables::{VectorVar2, VectorVar3},
};
use nalgebra::{Matrix3, Matrix3x2};

/// g(b, δ) = [R_z(−β)·δ_xy / (1 + s); δ_z / (1 + s)]: the true displacement an increment δ
/// measured with biases b = [β, s] stands for.
pub(super) fn g(b: [f64; 2], delta: [f64; 3]) -> [f64; 3] {
    let (sn, cs) = b[0].sin_cos();
    let k = 1.0 / (1.0 + b[1]);
    [
        k * (cs * delta[0] + sn * delta[1]),
        k * (-sn * delta[0] + cs * delta[1]),
        k * delta[2],
    ]
}

/// The filter's linearisation of g at (b, δ): ∂g/∂b (3×2) and G = ∂g/∂δ (3×3).
pub(super) fn prediction(b: [f64; 2], delta: [f64; 3]) -> (Matrix3x2<f64>, Matrix3<f64>) {
    let (sn, cs) = b[0].sin_cos();
    let k = 1.0 / (1.0 + b[1]);
    let gv = g(b, delta);
    let jb = Matrix3x2::new(
        k * (-sn * delta[0] + cs * delta[1]),
        -k * gv[0],
        k * (-cs * delta[0] - sn * delta[1]),
        -k * gv[1],
        0.0,
        -k * gv[2],
    );
    let jd = Matrix3::new(k * cs, k * sn, 0.0, -k * sn, k * cs, 0.0, 0.0, 0.0, k);
    (jb, jd)
}

/// Odometry of a vehicle with biases: r = (1 + s)·R_z(β)·(p1 − p0) − δ over (p0, p1, b), with
/// the increment's white-noise covariance (see the module documentation).
#[derive(Clone, Debug)]
pub(super) struct BiasedOdometry {
    /// The measured increment δ, m.
    pub delta: [f64; 3],
}

#[factrs::mark]
impl Residual3 for BiasedOdometry {
    type Differ = ForwardProp<Const<8>>;
    type V1 = VectorVar3;
    type V2 = VectorVar3;
    type V3 = VectorVar2;
    type DimIn = Const<8>;
    type DimOut = Const<3>;

    fn residual3<T: Numeric>(
        &self,
        p0: VectorVar3<T>,
        p1: VectorVar3<T>,
        b: VectorVar2<T>,
    ) -> VectorX<T> {
        let d = p1.0 - p0.0;
        let beta = b.0[0];
        let (sn, cs) = (beta.sin(), beta.cos());
        let k = T::from(1.0) + b.0[1];
        vectorx![
            k * (cs * d[0] - sn * d[1]) - T::from(self.delta[0]),
            k * (sn * d[0] + cs * d[1]) - T::from(self.delta[1]),
            k * d[2] - T::from(self.delta[2])
        ]
    }
}
