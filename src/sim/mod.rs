//! Executing a plan and localizing the team (`shoal simulate`).
//!
//! - [`remus`]: the 6-DoF REMUS 100 model (the paper's Section II-A, eqs. (1)–(2) and
//!   Appendix A), integrated by RK4.
//! - [`estimate`]: the navigation factor graph (batch, factrs) and an EKF over the same
//!   measurements.

pub mod estimate;
pub mod remus;
