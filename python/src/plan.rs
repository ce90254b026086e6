//! Plans: made from a scenario ([`plan`]) or read from their JSON ([`plan_from_json`]), held
//! with their floor as a [`RawPlan`], whose methods hand Python the arrays, the summary, the
//! plan file's text and the check.

use crate::arrays;
use crate::errors::{chain, guarded, plan_failure, Failure, ShoalError};
use crate::floor::{array_floor, plan_floor, scenario_floor};
use crate::report::report_json;
use crate::scenario::resolve_scenario;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray2};
use pyo3::prelude::*;
use shoal::plan::Plan;
use shoal::seafloor::Seafloor;
use shoal::Provenance;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A plan, its floor and the warnings of the floor's loader.
#[pyclass(frozen, module = "shoal._shoal")]
pub(crate) struct RawPlan {
    plan: Arc<Plan>,
    floor: Arc<Seafloor>,
    load_warnings: Vec<String>,
}

/// Make a plan: the scenario (`kind` "default", "path" or "json" with `text`), `overrides`
/// (`key=value`), the floor (None: the scenario's; or an array and its lattice) and the
/// planner ("mpc" or "rrt-like").
#[pyfunction]
#[pyo3(signature = (kind, text, overrides, method, z=None, lattice=None))]
pub(crate) fn plan(
    py: Python<'_>,
    kind: &str,
    text: &str,
    overrides: Vec<String>,
    method: &str,
    z: Option<PyReadonlyArray2<'_, f64>>,
    lattice: Option<(f64, f64, f64, f64)>,
) -> PyResult<RawPlan> {
    let array = array_floor(z, lattice)?;
    let (kind, text, method) = (kind.to_string(), text.to_string(), method.to_string());
    let made = py.detach(move || {
        guarded(|| {
            let (s, dir, source) = resolve_scenario(&kind, &text, &overrides)?;
            let (floor, floor_source) = scenario_floor(&s, &dir, array)?;
            let provenance = Provenance {
                scenario_source: source,
                overrides,
                seafloor: floor_source.clone(),
            };
            let plan = match method.as_str() {
                "mpc" => shoal::Planner::new(&s, &floor).provenance(provenance).run(),
                "rrt-like" => shoal::sampling::plan(&s, &floor, &provenance, &mut |_| {}),
                other => {
                    return Err(Failure::Other(format!(
                        "method {other:?}: allowed are \"mpc\" and \"rrt-like\""
                    )))
                }
            }
            .map_err(|e| plan_failure(&e))?;
            Ok(RawPlan {
                plan: Arc::new(plan),
                floor: Arc::new(floor),
                load_warnings: floor_source.warnings,
            })
        })
    })?;
    Ok(made)
}

/// A plan from its JSON text (a plan.json), over the floor it names (None), a grid file
/// (`path`), or an array and its lattice.
#[pyfunction]
#[pyo3(signature = (text, path=None, z=None, lattice=None))]
pub(crate) fn plan_from_json(
    py: Python<'_>,
    text: &str,
    path: Option<PathBuf>,
    z: Option<PyReadonlyArray2<'_, f64>>,
    lattice: Option<(f64, f64, f64, f64)>,
) -> PyResult<RawPlan> {
    let array = array_floor(z, lattice)?;
    let text = text.to_string();
    let made = py.detach(move || {
        guarded(|| {
            let plan = shoal::output::parse_plan(&text, Path::new("the plan's JSON"))
                .map_err(|e| Failure::PlanFile(chain(&e)))?;
            let floor = plan_floor(&plan, path.as_deref(), array)?;
            Ok(RawPlan {
                plan: Arc::new(plan),
                floor: Arc::new(floor),
                load_warnings: Vec::new(),
            })
        })
    })?;
    Ok(made)
}

#[pymethods]
impl RawPlan {
    /// AUV positions, (steps, N, 3), metres.
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        arrays::positions(&self.plan).into_pyarray(py)
    }

    /// AUV velocities, (steps, N, 3), m/s.
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        arrays::velocities(&self.plan).into_pyarray(py)
    }

    /// AUV inputs, (steps − 1, N, 3), m/s².
    fn inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        arrays::inputs(&self.plan).into_pyarray(py)
    }

    /// USV positions, (steps, 2), metres.
    fn usv_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::usv_positions(&self.plan).into_pyarray(py)
    }

    /// USV inputs (its velocity), (steps − 1, 2), m/s.
    fn usv_inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        arrays::usv_inputs(&self.plan).into_pyarray(py)
    }

    /// Time of every step, (steps,), seconds since the start of the mission.
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        arrays::times(&self.plan).into_pyarray(py)
    }

    /// The window of every step, (steps,).
    fn window_of_step<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        arrays::window_of_step(&self.plan).into_pyarray(py)
    }

    /// The planned links, (steps, N, 2): per step the A2U link (AUV, −1) first, then the N − 1
    /// A2A edges (i, j) of the chain in path order; −1 pads a step with fewer links.
    fn links<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<i64>> {
        arrays::links(&self.plan).into_pyarray(py)
    }

    /// The plan's summary as JSON: seed, method, sizes, warnings, metrics (mission and per
    /// window), the resolved scenario and the floor record.
    fn summary_json(&self) -> PyResult<String> {
        let p = &self.plan;
        let windows: Vec<&shoal::plan::Metrics> = p.windows.iter().map(|w| &w.metrics).collect();
        let summary = serde_json::json!({
            "seed": p.scenario.seed,
            "method": p.method,
            "auvs": p.scenario.team.auvs,
            "windows": p.windows.len(),
            "dt": p.scenario.horizon.dt,
            "steps_per_window": p.scenario.horizon.steps,
            "warnings": p.warnings,
            "load_warnings": self.load_warnings,
            "unconverged_stages": p.unconverged_stages(),
            "metrics": p.metrics,
            "window_metrics": windows,
            "scenario": p.scenario,
            "seafloor": p.seafloor,
            "scenario_source": p.scenario_source,
            "overrides": p.overrides,
            "shoal_version": p.shoal_version,
        });
        serde_json::to_string(&summary).map_err(|e| ShoalError::new_err(e.to_string()))
    }

    /// The plan file's text, as `shoal plan` writes plan.json.
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&*self.plan).map_err(|e| ShoalError::new_err(e.to_string()))
    }

    /// The floor: its heights (ny, nx), NaN at NODATA nodes, and its lattice (x0, y0, dx, dy).
    #[allow(clippy::type_complexity)]
    fn seafloor<'py>(&self, py: Python<'py>) -> (Bound<'py, PyArray2<f64>>, (f64, f64, f64, f64)) {
        let f = &self.floor;
        let lattice = (f.x0(), f.y0(), f.dx(), f.dy());
        (arrays::floor_heights(f).into_pyarray(py), lattice)
    }

    /// Run the library's independent checker on the plan and its floor; the report as JSON
    /// (passed, families, problems) and its text table.
    fn check(&self, py: Python<'_>) -> PyResult<(String, String)> {
        let (plan, floor) = (Arc::clone(&self.plan), Arc::clone(&self.floor));
        let report = py.detach(move || guarded(|| Ok(shoal::check(&plan, &floor))))?;
        Ok((report_json(&report), report.table()))
    }
}
