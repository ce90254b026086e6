//! Errors: the Python exception classes of `shoal`, what went wrong on the Rust side
//! ([`Failure`]) and which class it becomes, and panics turned into errors ([`guarded`]).

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use shoal::PlanError;
use std::panic::{catch_unwind, AssertUnwindSafe};

create_exception!(
    shoal,
    ShoalError,
    PyException,
    "An error of shoal; the message is shoal's own (the file, the key, what is allowed)."
);
create_exception!(
    shoal,
    ScenarioError,
    ShoalError,
    "The scenario (or study) cannot be loaded: unknown key, wrong type, value out of range."
);
create_exception!(
    shoal,
    SeafloorError,
    ShoalError,
    "The seafloor cannot be read or built (grid file, array, lattice)."
);
create_exception!(
    shoal,
    PlanningError,
    ShoalError,
    "The planner stopped without a plan."
);
create_exception!(
    shoal,
    InfeasibleError,
    PlanningError,
    "No plan meets the constraints: a start state, a constraint, a link or the chain cannot hold."
);
create_exception!(
    shoal,
    SolverError,
    PlanningError,
    "The convex solver or the SCP loop failed numerically."
);
create_exception!(
    shoal,
    PlanFileError,
    ShoalError,
    "A plan's JSON text cannot be read (not JSON, another format, a missing field)."
);
create_exception!(
    shoal,
    SweepError,
    ShoalError,
    "A study cannot be read or its table written."
);

/// What went wrong, with the Python exception class it becomes.
pub(crate) enum Failure {
    Scenario(String),
    Seafloor(String),
    Infeasible(String),
    Solver(String),
    PlanFile(String),
    Sweep(String),
    Other(String),
}

impl From<Failure> for PyErr {
    fn from(f: Failure) -> PyErr {
        match f {
            Failure::Scenario(m) => ScenarioError::new_err(m),
            Failure::Seafloor(m) => SeafloorError::new_err(m),
            Failure::Infeasible(m) => InfeasibleError::new_err(m),
            Failure::Solver(m) => SolverError::new_err(m),
            Failure::PlanFile(m) => PlanFileError::new_err(m),
            Failure::Sweep(m) => SweepError::new_err(m),
            Failure::Other(m) => ShoalError::new_err(m),
        }
    }
}

/// The error and its causes joined by ": ", leaving out a cause whose text the message already
/// ends with (as the `shoal` command prints them).
pub(crate) fn chain(e: &dyn std::error::Error) -> String {
    let mut out = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !out.ends_with(&text) {
            out.push_str(": ");
            out.push_str(&text);
        }
        cause = c.source();
    }
    out
}

pub(crate) fn plan_failure(e: &PlanError) -> Failure {
    let text = chain(e);
    match e {
        PlanError::Seafloor(_) => Failure::Seafloor(text),
        PlanError::Vehicle(_) => Failure::Scenario(text),
        PlanError::InvalidStart { .. }
        | PlanError::NoInitialPosition(_)
        | PlanError::ConvexInfeasible { .. }
        | PlanError::Infeasible { .. }
        | PlanError::Unfinished { .. }
        | PlanError::LineOfSight { .. }
        | PlanError::Disconnected { .. }
        | PlanError::NoValidTree { .. }
        | PlanError::Waypoints { .. } => Failure::Infeasible(text),
        PlanError::Conic(_)
        | PlanError::Solver { .. }
        | PlanError::Inexact { .. }
        | PlanError::Scp(_) => Failure::Solver(text),
    }
}

/// Run `f`, turning a panic into a [`Failure`]: a bug in shoal reaches Python as a
/// `ShoalError` saying so, never as pyo3's PanicException.
pub(crate) fn guarded<T>(f: impl FnOnce() -> Result<T, Failure>) -> Result<T, Failure> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|payload| {
        let what = payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "no message".into());
        Err(Failure::Other(format!(
            "internal error in shoal (a bug; please report it with the input): {what}"
        )))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_panic_is_an_error_that_says_it_is_a_bug() {
        let r: Result<(), Failure> = guarded(|| panic!("boom"));
        let Err(Failure::Other(m)) = r else {
            panic!("expected the panic as an error")
        };
        assert!(
            m.contains("internal error in shoal") && m.ends_with("boom"),
            "{m}"
        );
    }
}
