//! Scenarios given from Python: the embedded default, a file, or a dictionary (as JSON), with
//! `key=value` overrides, resolved by the library's own loaders.

use crate::dict::toml_of_json;
use crate::errors::{chain, Failure};
use pyo3::prelude::*;
use shoal::scenario::{self, Scenario, ScenarioError as RustScenarioError};
use std::path::{Path, PathBuf};

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
pub(crate) const DICT_SOURCE: &str = "scenario dict";

/// A scenario, where its relative paths resolve, and its source name for the plan record.
pub(crate) fn resolve_scenario(
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

/// The embedded default scenario as commented TOML (what `shoal init` writes).
#[pyfunction]
pub(crate) fn default_scenario_toml() -> String {
    scenario::default_toml()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bad_dictionary_names_the_key_and_no_line() {
        let Err(Failure::Scenario(m)) = resolve_scenario("json", r#"{"team": {"auv": 3}}"#, &[])
        else {
            panic!("expected a scenario error")
        };
        assert!(m.starts_with("scenario dict: unknown key team.auv"), "{m}");
    }
}
