//! Studies run from Python (`shoal sweep`): a study file or a dictionary, run on every core.

use crate::dict::toml_of_json;
use crate::errors::{chain, guarded, Failure};
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// Run a study (`kind` "path" with the study file's path, or "json" with a dictionary's JSON
/// and `base`, the file name its relative paths and its name come from) into directory `out`
/// on every core; returns the table's path and the counts (passed, violated, failed).
#[pyfunction]
pub(crate) fn sweep(
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
