//! `shoal._shoal`: the compiled part of the Python package `shoal` (python/shoal/__init__.py is
//! the public API over it). A thin layer over the library: scenarios are loaded, floors built,
//! plans made, checked and swept by the library's own functions; this file only moves data
//! between Rust and Python (numpy arrays, JSON text for nested dictionaries) and turns errors
//! and panics into Python exceptions.
//!
//! Planning, checking and sweeping run with the Python thread detached (the GIL released), so
//! other Python threads go on meanwhile.

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyReadonlyArray2};
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use shoal::check::CheckReport;
use shoal::mission::FloorSource;
use shoal::plan::Plan;
use shoal::scenario::{self, Scenario, ScenarioError as RustScenarioError};
use shoal::seafloor::{Lattice, Seafloor, Values};
use shoal::{PlanError, Provenance};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::sync::Arc;

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
enum Failure {
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
fn chain(e: &dyn std::error::Error) -> String {
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

fn plan_failure(e: &PlanError) -> Failure {
    let text = chain(e);
    match e {
        PlanError::Seafloor(_) => Failure::Seafloor(text),
        PlanError::Vehicle(_) => Failure::Scenario(text),
        PlanError::InvalidStart { .. }
        | PlanError::NoInitialPosition(_)
        | PlanError::ConvexInfeasible { .. }
        | PlanError::Infeasible { .. }
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
fn guarded<T>(f: impl FnOnce() -> Result<T, Failure>) -> Result<T, Failure> {
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

/// `value` (JSON) without its nulls: a `None` in a Python dictionary means "not given".
fn without_nulls(value: serde_json::Value) -> serde_json::Value {
    use serde_json::Value;
    match value {
        Value::Object(map) => Value::Object(
            map.into_iter()
                .filter(|(_, v)| !v.is_null())
                .map(|(k, v)| (k, without_nulls(v)))
                .collect(),
        ),
        Value::Array(items) => Value::Array(items.into_iter().map(without_nulls).collect()),
        other => other,
    }
}

/// The TOML text of a JSON object (a Python dictionary given for a scenario or a study file).
fn toml_of_json(json: &str, what: &str) -> Result<String, String> {
    let value: serde_json::Value =
        serde_json::from_str(json).map_err(|e| format!("{what}: not a dictionary: {e}"))?;
    if !value.is_object() {
        return Err(format!("{what}: expected a dictionary of keys and values"));
    }
    toml::to_string(&without_nulls(value))
        .map_err(|e| format!("{what}: cannot be written as TOML: {e}"))
}

/// Line numbers of TOML made from a dictionary mean nothing to its author: the key alone
/// locates the problem.
fn without_line(mut e: RustScenarioError) -> RustScenarioError {
    match &mut e {
        RustScenarioError::UnknownKey { line, .. }
        | RustScenarioError::WrongType { line, .. }
        | RustScenarioError::MissingKey { line, .. }
        | RustScenarioError::OutOfRange { line, .. }
        | RustScenarioError::Invalid { line, .. } => *line = None,
        _ => {}
    }
    e
}

/// Source name of a scenario given as a dictionary.
const DICT_SOURCE: &str = "scenario dict";

/// A scenario, where its relative paths resolve, and its source name for the plan record.
fn resolve_scenario(
    kind: &str,
    text: &str,
    overrides: &[String],
) -> Result<(Scenario, PathBuf, String), Failure> {
    let scenario_err = |e: RustScenarioError| Failure::Scenario(chain(&e));
    match kind {
        "default" => Ok((
            scenario::default_with(overrides).map_err(scenario_err)?,
            PathBuf::new(),
            scenario::EMBEDDED_DEFAULT.to_string(),
        )),
        "path" => {
            let path = Path::new(text);
            let s = scenario::load(path, overrides).map_err(scenario_err)?;
            let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
            Ok((s, dir, path.display().to_string()))
        }
        "json" => {
            let toml = toml_of_json(text, DICT_SOURCE).map_err(Failure::Scenario)?;
            let s = scenario::from_toml_str(&toml, DICT_SOURCE, overrides)
                .map_err(|e| scenario_err(without_line(e)))?;
            Ok((s, PathBuf::new(), DICT_SOURCE.to_string()))
        }
        other => Err(Failure::Other(format!("unknown scenario kind {other:?}"))),
    }
}

/// A floor from a grid of heights `z[j][i]` at (x0 + i·dx, y0 + j·dy), row j = 0 the
/// southernmost; NaN marks a NODATA node.
fn floor_of_array(
    z: Vec<f64>,
    shape: (usize, usize),
    lattice: (f64, f64, f64, f64),
) -> Result<Seafloor, Failure> {
    let (ny, nx) = shape;
    let (x0, y0, dx, dy) = lattice;
    let nodata: Vec<bool> = z.iter().map(|v| v.is_nan()).collect();
    Seafloor::from_nodes(Lattice::new(nx, ny, x0, y0, dx, dy), z, nodata)
        .map_err(|e| Failure::Seafloor(format!("the seafloor array: {}", chain(&e))))
}

/// The floor record of a plan made over an array: a floor from no file, which `shoal check`
/// needs given explicitly (`--seafloor`), as the plan's JSON says.
fn array_source() -> FloorSource {
    FloorSource {
        source: "file".into(),
        path: None,
        format: "array".into(),
        crs: "none".into(),
        values: Values::Elevation,
        origin: None,
        warnings: Vec::new(),
    }
}

/// A seafloor given from Python: the array's nodes (row-major, NaN for NODATA), its shape
/// (rows, columns) and its lattice (x0, y0, dx, dy).
type ArrayFloor = (Vec<f64>, (usize, usize), (f64, f64, f64, f64));

fn array_floor(
    z: Option<PyReadonlyArray2<'_, f64>>,
    lattice: Option<(f64, f64, f64, f64)>,
) -> PyResult<Option<ArrayFloor>> {
    match (z, lattice) {
        (None, _) => Ok(None),
        (Some(_), None) => Err(SeafloorError::new_err(
            "a seafloor array needs its lattice: x0, y0 (the south-west node, metres), dx, dy \
             (the spacing, metres)",
        )),
        (Some(z), Some(l)) => {
            let a = z.as_array();
            let shape = (a.nrows(), a.ncols());
            Ok(Some((a.iter().copied().collect(), shape, l)))
        }
    }
}

/// A plan, its floor and the warnings of the floor's loader.
#[pyclass(frozen, module = "shoal._shoal")]
struct RawPlan {
    plan: Arc<Plan>,
    floor: Arc<Seafloor>,
    load_warnings: Vec<String>,
}

/// Make a plan: the scenario (`kind` "default", "path" or "json" with `text`), `overrides`
/// (`key=value`), the floor (None: the scenario's; or an array and its lattice) and the
/// planner ("mpc" or "rrt-like").
#[pyfunction]
#[pyo3(signature = (kind, text, overrides, method, z=None, lattice=None))]
fn plan(
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
            let (floor, floor_source) = match array {
                Some((z, shape, l)) => (floor_of_array(z, shape, l)?, array_source()),
                None => shoal::mission::scenario_floor(&s, &dir).map_err(|e| plan_failure(&e))?,
            };
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
fn plan_from_json(
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
            let floor = match array {
                Some((z, shape, l)) => {
                    let floor = floor_of_array(z, shape, l)?;
                    // the same test `load_floor` makes of a file
                    let found = floor.fingerprint();
                    if found != plan.seafloor.fingerprint {
                        let e = shoal::check::CheckError::FingerprintMismatch {
                            origin: "the seafloor array".into(),
                            expected: plan.seafloor.fingerprint.clone(),
                            found,
                        };
                        return Err(Failure::Seafloor(chain(&e)));
                    }
                    floor
                }
                None => shoal::check::load_floor(&plan, path.as_deref())
                    .map_err(|e| Failure::Seafloor(chain(&e)))?,
            };
            Ok(RawPlan {
                plan: Arc::new(plan),
                floor: Arc::new(floor),
                load_warnings: Vec::new(),
            })
        })
    })?;
    Ok(made)
}

/// The steps of the mission: (window, k) for every step of every window's final stage, window
/// w > 0 without its k = 0 (window w − 1's last step, the same instant and state).
fn mission_steps(p: &Plan) -> Vec<(usize, usize)> {
    let mut steps = Vec::new();
    for (w, win) in p.windows.iter().enumerate() {
        let last = win.final_.usv.position.len().saturating_sub(1);
        let first = usize::from(w > 0);
        steps.extend((first..=last).map(|k| (w, k)));
    }
    steps
}

/// The inputs of the mission: (window, k) for k = 0..K of every window.
fn mission_inputs(p: &Plan) -> Vec<(usize, usize)> {
    p.windows
        .iter()
        .enumerate()
        .flat_map(|(w, win)| (0..win.final_.usv.input.len()).map(move |k| (w, k)))
        .collect()
}

/// An AUV quantity over (step, vehicle, axis), NaN where the plan has no entry.
fn auv_array(
    p: &Plan,
    steps: &[(usize, usize)],
    get: impl Fn(&shoal::plan::AuvPath, usize) -> Option<[f64; 3]>,
) -> Array3<f64> {
    let n = p.scenario.team.auvs;
    let mut a = Array3::from_elem((steps.len(), n, 3), f64::NAN);
    for (t, &(w, k)) in steps.iter().enumerate() {
        for (v, path) in p.windows[w].final_.auvs.iter().take(n).enumerate() {
            if let Some(x) = get(path, k) {
                for d in 0..3 {
                    a[[t, v, d]] = x[d];
                }
            }
        }
    }
    a
}

fn usv_array(p: &Plan, steps: &[(usize, usize)], input: bool) -> Array2<f64> {
    let mut a = Array2::from_elem((steps.len(), 2), f64::NAN);
    for (t, &(w, k)) in steps.iter().enumerate() {
        let usv = &p.windows[w].final_.usv;
        let series = if input { &usv.input } else { &usv.position };
        if let Some(x) = series.get(k) {
            a[[t, 0]] = x[0];
            a[[t, 1]] = x[1];
        }
    }
    a
}

#[pymethods]
impl RawPlan {
    /// AUV positions, (steps, N, 3), metres.
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let p = &self.plan;
        auv_array(p, &mission_steps(p), |a, k| a.position.get(k).copied()).into_pyarray(py)
    }

    /// AUV velocities, (steps, N, 3), m/s.
    fn velocities<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let p = &self.plan;
        auv_array(p, &mission_steps(p), |a, k| a.velocity.get(k).copied()).into_pyarray(py)
    }

    /// AUV inputs, (steps − 1, N, 3), m/s².
    fn inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<f64>> {
        let p = &self.plan;
        auv_array(p, &mission_inputs(p), |a, k| a.input.get(k).copied()).into_pyarray(py)
    }

    /// USV positions, (steps, 2), metres.
    fn usv_positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        usv_array(&self.plan, &mission_steps(&self.plan), false).into_pyarray(py)
    }

    /// USV inputs (its velocity), (steps − 1, 2), m/s.
    fn usv_inputs<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        usv_array(&self.plan, &mission_inputs(&self.plan), true).into_pyarray(py)
    }

    /// Time of every step, (steps,), seconds since the start of the mission.
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let p = &self.plan;
        let dt = p.scenario.horizon.dt;
        let t: Vec<f64> = mission_steps(p)
            .iter()
            .map(|&(w, k)| p.windows[w].start_time + k as f64 * dt)
            .collect();
        Array1::from(t).into_pyarray(py)
    }

    /// The window of every step, (steps,).
    fn window_of_step<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<i64>> {
        let w: Vec<i64> = mission_steps(&self.plan)
            .iter()
            .map(|&(w, _)| w as i64)
            .collect();
        Array1::from(w).into_pyarray(py)
    }

    /// The planned links, (steps, N, 2): per step the A2U link (AUV, −1) first, then the N − 1
    /// A2A edges (i, j) of the chain in path order; −1 pads a step with fewer links.
    fn links<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray3<i64>> {
        let p = &self.plan;
        let steps = mission_steps(p);
        let n = p.scenario.team.auvs;
        let mut a = Array3::from_elem((steps.len(), n, 2), -1i64);
        for (t, &(w, k)) in steps.iter().enumerate() {
            if let Some(links) = p.windows[w].links.links.get(k) {
                for (l, link) in links.iter().take(n).enumerate() {
                    a[[t, l, 0]] = link.a as i64;
                    a[[t, l, 1]] = link.b.map_or(-1, |b| b as i64);
                }
            }
        }
        a.into_pyarray(py)
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
        let (z, nodata) = f.nodes();
        let mut a = Array2::from_elem((f.ny(), f.nx()), f64::NAN);
        for (idx, (v, &missing)) in z.iter().zip(nodata).enumerate() {
            if !missing {
                a[[idx / f.nx(), idx % f.nx()]] = *v;
            }
        }
        (a.into_pyarray(py), (f.x0(), f.y0(), f.dx(), f.dy()))
    }

    /// Run the library's independent checker on the plan and its floor; the report as JSON
    /// (passed, families, problems) and its text table.
    fn check(&self, py: Python<'_>) -> PyResult<(String, String)> {
        let (plan, floor) = (Arc::clone(&self.plan), Arc::clone(&self.floor));
        let report = py.detach(move || guarded(|| Ok(shoal::check(&plan, &floor))))?;
        Ok((report_json(&report), report.table()))
    }
}

fn report_json(r: &CheckReport) -> String {
    // margins may be ±∞ (nothing checked, or not evaluable): JSON has no infinity, so they
    // travel as strings and Python turns them back into floats
    let num = |v: f64| {
        if v.is_finite() {
            serde_json::json!(v)
        } else {
            serde_json::json!(v.to_string())
        }
    };
    let families: Vec<serde_json::Value> = r
        .families
        .iter()
        .map(|f| {
            serde_json::json!({
                "name": f.name,
                "checked": f.checked,
                "worst_margin": num(f.worst_margin),
                "unit": f.unit,
                "tolerance": num(f.tolerance),
                "where": f.where_,
                "passed": f.passed(),
            })
        })
        .collect();
    serde_json::json!({
        "passed": r.passed(),
        "families": families,
        "problems": r.problems,
        "plan_fingerprint": r.plan_fingerprint,
        "floor_fingerprint": r.floor_fingerprint,
    })
    .to_string()
}

/// Run a study (`kind` "path" with the study file's path, or "json" with a dictionary's JSON
/// and `base`, the file name its relative paths and its name come from) into directory `out`
/// on every core; returns the table's path and the counts (passed, violated, failed).
#[pyfunction]
fn sweep(
    py: Python<'_>,
    kind: &str,
    text: &str,
    base: PathBuf,
    out: PathBuf,
) -> PyResult<(PathBuf, usize, usize, usize)> {
    let (kind, text) = (kind.to_string(), text.to_string());
    let done = py.detach(move || {
        guarded(|| {
            let sweep_err = |e: shoal::sweep::SweepError| Failure::Scenario(chain(&e));
            let study = match kind.as_str() {
                "path" => shoal::sweep::Study::load(Path::new(&text)).map_err(sweep_err)?,
                "json" => {
                    let toml = toml_of_json(&text, "study dict").map_err(Failure::Scenario)?;
                    shoal::sweep::Study::parse(&toml, &base).map_err(sweep_err)?
                }
                other => return Err(Failure::Other(format!("unknown study kind {other:?}"))),
            };
            let opts = shoal::sweep::Options {
                out,
                shard: None,
                resume: false,
            };
            let o =
                shoal::sweep::run(&study, &opts, &|_| {}).map_err(|e| Failure::Sweep(chain(&e)))?;
            Ok((o.table, o.passed, o.violated, o.failed))
        })
    })?;
    Ok(done)
}

/// The embedded default scenario as commented TOML (what `shoal init` writes).
#[pyfunction]
fn default_scenario_toml() -> String {
    scenario::default_toml()
}

/// The version of shoal (the library) this module was built from.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

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
    m.add_class::<RawPlan>()?;
    m.add_function(wrap_pyfunction!(plan, m)?)?;
    m.add_function(wrap_pyfunction!(plan_from_json, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(default_scenario_toml, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_dictionary_becomes_toml_without_its_nones() {
        let toml = toml_of_json(
            r#"{"seed": 3, "team": {"auvs": 4}, "initial": null, "horizon": {"dt": 50.0}}"#,
            "d",
        )
        .unwrap();
        let s = scenario::from_toml_str(&toml, DICT_SOURCE, &[]).unwrap();
        assert_eq!((s.seed, s.team.auvs, s.horizon.dt), (3, 4, 50.0));
        assert!(toml_of_json("[1, 2]", "d")
            .unwrap_err()
            .contains("dictionary"));
    }

    #[test]
    fn a_bad_dictionary_names_the_key_and_no_line() {
        let Err(Failure::Scenario(m)) = resolve_scenario("json", r#"{"team": {"auv": 3}}"#, &[])
        else {
            panic!("expected a scenario error")
        };
        assert!(m.starts_with("scenario dict: unknown key team.auv"), "{m}");
    }

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
