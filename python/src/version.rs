//! The version of the library the module was built from.

use pyo3::prelude::*;

/// The version of shoal (the library) this module was built from.
#[pyfunction]
pub(crate) fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}
