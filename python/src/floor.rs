//! Seafloors given from Python: a numpy array of heights and its lattice become a [`Seafloor`];
//! otherwise the floor the scenario or the plan names.

use crate::errors::{chain, plan_failure, Failure, SeafloorError};
use numpy::PyReadonlyArray2;
use pyo3::prelude::*;
use shoal::mission::FloorSource;
use shoal::plan::Plan;
use shoal::scenario::Scenario;
use shoal::seafloor::{Lattice, Seafloor, Values};
use std::path::Path;

/// A seafloor given from Python: the array's nodes (row-major, NaN for NODATA), its shape
/// (rows, columns) and its lattice (x0, y0, dx, dy).
pub(crate) type ArrayFloor = (Vec<f64>, (usize, usize), (f64, f64, f64, f64));

/// The nodes of a seafloor array, copied out of numpy (so that planning can go on without the
/// GIL); `None` when no array is given.
pub(crate) fn array_floor(
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

/// The floor to plan scenario `s` over, and its record: the array given, or else the floor the
/// scenario names (its relative paths resolving against `dir`).
pub(crate) fn scenario_floor(
    s: &Scenario,
    dir: &Path,
    array: Option<ArrayFloor>,
) -> Result<(Seafloor, FloorSource), Failure> {
    match array {
        Some((z, shape, l)) => Ok((floor_of_array(z, shape, l)?, array_source())),
        None => shoal::mission::scenario_floor(s, dir).map_err(|e| plan_failure(&e)),
    }
}

/// The floor of a plan read from its JSON: the array given, or else the grid file at `path`, or
/// else the floor the plan names. It must be the floor the plan was made on (its fingerprint).
pub(crate) fn plan_floor(
    plan: &Plan,
    path: Option<&Path>,
    array: Option<ArrayFloor>,
) -> Result<Seafloor, Failure> {
    match array {
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
            Ok(floor)
        }
        None => shoal::check::load_floor(plan, path).map_err(|e| Failure::Seafloor(chain(&e))),
    }
}
