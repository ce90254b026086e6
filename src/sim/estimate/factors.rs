//! The smoother's custom residuals (depth, range; the biased odometry is in `bias.rs`) and the
//! whitening of its covariances.

use factrs::{
    linalg::{vectorx, Const, ForwardProp, Numeric, VectorX},
    noise::GaussianNoise,
    residuals::{Residual1, Residual2},
    variables::VectorVar3,
};

use super::validate::{cov2_factor, cov_factor};
use super::{Cov2, Cov3, EstimateError};

/// A depth gauge: r = z − z_measured.
#[derive(Clone, Debug)]
pub(super) struct DepthResidual {
    pub z: f64,
}

#[factrs::mark]
impl Residual1 for DepthResidual {
    type Differ = ForwardProp<Const<3>>;
    type V1 = VectorVar3;
    type DimIn = Const<3>;
    type DimOut = Const<1>;

    fn residual1<T: Numeric>(&self, p: VectorVar3<T>) -> VectorX<T> {
        vectorx![p.0[2] - T::from(self.z)]
    }
}

/// The square of the length below which a range's Jacobian fades to zero, m².
const RANGE_EPS2: f64 = 1e-12;

/// An acoustic range: r = √(‖a − b‖² + ε²) − range, ε = 1 µm. The ε keeps the autodiff
/// derivative finite (zero) when the two positions coincide, where ‖·‖ has none; it biases a
/// range of d metres by ε²/2d, 5·10⁻¹³ m at 1 m.
#[derive(Clone, Debug)]
pub(super) struct RangeResidual {
    pub range: f64,
}

#[factrs::mark]
impl Residual2 for RangeResidual {
    type Differ = ForwardProp<Const<6>>;
    type V1 = VectorVar3;
    type V2 = VectorVar3;
    type DimIn = Const<6>;
    type DimOut = Const<1>;

    fn residual2<T: Numeric>(&self, a: VectorVar3<T>, b: VectorVar3<T>) -> VectorX<T> {
        let d = a.0 - b.0;
        vectorx![(d.norm_squared() + T::from(RANGE_EPS2)).sqrt() - T::from(self.range)]
    }
}

/// The whitening of a validated covariance: R = L⁻¹ with L Lᵀ = cov, so RᵀR = cov⁻¹.
pub(super) fn noise3(cov: &Cov3) -> Result<GaussianNoise<3>, EstimateError> {
    let l = cov_factor(cov).map_err(|why| EstimateError::Solver(format!("covariance: {why}")))?;
    let r = l
        .try_inverse()
        .ok_or_else(|| EstimateError::Solver("covariance inverse".into()))?;
    Ok(GaussianNoise::<3>::from_matrix_sqrt_inf(r))
}

/// The whitening of a validated bias covariance (see [`noise3`]).
pub(super) fn noise2(cov: &Cov2) -> Result<GaussianNoise<2>, EstimateError> {
    let l = cov2_factor(cov).map_err(|why| EstimateError::Solver(format!("covariance: {why}")))?;
    let r = l
        .try_inverse()
        .ok_or_else(|| EstimateError::Solver("covariance inverse".into()))?;
    Ok(GaussianNoise::<2>::from_matrix_sqrt_inf(r))
}
