//! Python dictionaries given for a scenario or a study file: they cross into Rust as JSON text
//! and become the TOML text the library reads.

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
pub(crate) fn toml_of_json(json: &str, what: &str) -> Result<String, String> {
    let value: serde_json::Value =
        serde_json::from_str(json).map_err(|e| format!("{what}: not a dictionary: {e}"))?;
    if !value.is_object() {
        return Err(format!("{what}: expected a dictionary of keys and values"));
    }
    toml::to_string(&without_nulls(value))
        .map_err(|e| format!("{what}: cannot be written as TOML: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::DICT_SOURCE;
    use shoal::scenario;

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
}
