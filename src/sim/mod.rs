//! Executing a plan and localizing the team (`shoal simulate`): the vehicles a plan is flown
//! with, the current they feel, the navigation sensors they carry, and the estimators that
//! turn those measurements into positions, with and without the acoustic chain.
//!
//! - [`remus`]: the 6-DoF REMUS 100 model (the paper's Section II-A, eqs. (1)–(2) and
//!   Appendix A), integrated by RK4.
//! - [`estimate`]: the navigation factor graph (batch, factrs) and an EKF over the same
//!   measurements.

pub mod budget;
pub mod control;
pub mod current;
pub mod envelope;
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
pub use run::{fly_plan, monte_carlo, simulate, Gate, Options, Progress, SimError};

/// Write `record` to `path` as JSON, atomically (a temporary file renamed into place). The text
/// is first read back as `shoal view --sim` reads it: a record that would not read back (a
/// non-finite number, which JSON writes as null) is refused, naming the first such field,
/// instead of written.
pub fn write(record: &SimRecord, path: &std::path::Path) -> Result<(), crate::output::OutputError> {
    let fail = |why: String| crate::output::OutputError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(why),
    };
    let text = serde_json::to_vec(record).map_err(|e| fail(e.to_string()))?;
    if let Err(e) = serde_json::from_slice::<SimRecord>(&text) {
        let field = serde_json::from_slice::<serde_json::Value>(&text)
            .ok()
            .and_then(|v| first_null(&v, String::new()));
        return Err(fail(match field {
            Some(f) => format!("the record's {f} is not a finite number, which JSON cannot hold"),
            None => format!("the record would not read back: {e}"),
        }));
    }
    crate::output::write_atomic(path, &text)
}

/// Read a record `shoal simulate` wrote. A record and figures that a killed `shoal simulate`
/// left half moved into their folder are completed first ([`crate::output_set::settle`]).
pub fn read(path: &std::path::Path) -> Result<SimRecord, crate::output::OutputError> {
    crate::output_set::settle(crate::atomic_file::folder_of(path));
    let text =
        std::fs::read_to_string(path).map_err(|source| crate::output::OutputError::Read {
            path: path.to_path_buf(),
            source,
        })?;
    serde_json::from_str(&text).map_err(|e| crate::output::OutputError::SimRecord {
        path: path.to_path_buf(),
        why: e.to_string(),
    })
}

/// The path (`flight.executed[0][3][2]`) of the first null in `v`.
fn first_null(v: &serde_json::Value, at: String) -> Option<String> {
    match v {
        serde_json::Value::Null => Some(at),
        serde_json::Value::Array(xs) => xs
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_null(x, format!("{at}[{i}]"))),
        serde_json::Value::Object(m) => m.iter().find_map(|(k, x)| {
            let key = if at.is_empty() {
                k.clone()
            } else {
                format!("{at}.{k}")
            };
            first_null(x, key)
        }),
        _ => None,
    }
}
