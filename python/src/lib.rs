//! `shoal._shoal`: the compiled part of the Python package `shoal` (python/shoal/ is the public
//! API over it). A thin layer over the library: scenarios are loaded, floors built, plans made,
//! checked and swept by the library's own functions; this crate only moves data between Rust
//! and Python (numpy arrays, JSON text for nested dictionaries) and turns errors and panics
//! into Python exceptions.
//!
//! Planning, checking and sweeping run with the Python thread detached (the GIL released), so
//! other Python threads go on meanwhile.
//!
//! This file registers the module's contents; the modules below hold them, one job each.

mod arrays;
mod dict;
mod errors;
mod floor;
mod plan;
mod report;
mod scenario;
mod sweep;
mod version;

use errors::{
    InfeasibleError, PlanFileError, PlanningError, ScenarioError, SeafloorError, ShoalError,
    SolverError, SweepError,
};
use pyo3::prelude::*;

#[pymodule]
fn _shoal(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ShoalError", py.get_type::<ShoalError>())?;
    m.add("ScenarioError", py.get_type::<ScenarioError>())?;
    m.add("SeafloorError", py.get_type::<SeafloorError>())?;
    m.add("PlanningError", py.get_type::<PlanningError>())?;
    m.add("InfeasibleError", py.get_type::<InfeasibleError>())?;
    m.add("SolverError", py.get_type::<SolverError>())?;
    m.add("PlanFileError", py.get_type::<PlanFileError>())?;
    m.add("SweepError", py.get_type::<SweepError>())?;
    m.add_class::<plan::RawPlan>()?;
    m.add_function(wrap_pyfunction!(plan::plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan::plan_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::default_scenario_toml, m)?)?;
    m.add_function(wrap_pyfunction!(version::version, m)?)?;
    Ok(())
}
