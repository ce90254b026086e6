//! Executing a plan and localizing the team (`shoal simulate`): the vehicles a plan is flown
//! with, the current they feel, the navigation sensors they carry, and the estimators that
//! turn those measurements into positions, with and without the acoustic chain.
//!
//! - [`remus`]: the 6-DoF REMUS 100 model (the paper's Section II-A, eqs. (1)–(2) and
//!   Appendix A), integrated by RK4.
//! - [`estimate`]: the navigation factor graph (batch, factrs) and an EKF over the same
//!   measurements.

pub mod control;
pub mod current;
pub mod estimate;
pub mod flight;
pub mod measure;
pub mod montecarlo;
pub mod policy;
pub mod record;
pub mod reference;
pub mod remus;
pub mod run;
pub mod summary;

pub use record::SimRecord;
pub use run::{monte_carlo, simulate, SimError};

/// Write `record` to `path` as JSON, atomically (a temporary file renamed into place).
pub fn write(record: &SimRecord, path: &std::path::Path) -> Result<(), crate::output::OutputError> {
    let text = serde_json::to_vec(record).map_err(|e| crate::output::OutputError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    crate::output::write_atomic(path, &text)
}
