// Tests build expected scenarios by changing single fields of the default, which reads best as
// plain assignments.
#![allow(clippy::field_reassign_with_default)]

use super::schema::{example_initial, full_default, EXAMPLE_FLOOR_FILE};
use super::*;
use proptest::prelude::*;
use std::collections::BTreeSet;

mod errors;
mod init_template;
mod loading;
mod never_panic;

const FILE: &str = "mission.toml";

fn set(v: &[&str]) -> Vec<String> {
    v.iter().map(|s| s.to_string()).collect()
}

fn parse(text: &str) -> Result<Scenario, ScenarioError> {
    from_toml_str(text, FILE, &[])
}

fn parse_with(text: &str, overrides: &[&str]) -> Result<Scenario, ScenarioError> {
    from_toml_str(text, FILE, &set(overrides))
}

/// Every dotted leaf key of a serialised scenario (arrays are leaves).
fn leaf_keys(t: &toml::Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in t {
        let key = if prefix.is_empty() {
            k.clone()
        } else {
            format!("{prefix}.{k}")
        };
        match v {
            toml::Value::Table(sub) => leaf_keys(sub, &key, out),
            _ => out.push(key),
        }
    }
}

fn section_keys(t: &toml::Table, prefix: &str, out: &mut Vec<String>) {
    for (k, v) in t {
        if let toml::Value::Table(sub) = v {
            let key = if prefix.is_empty() {
                k.clone()
            } else {
                format!("{prefix}.{k}")
            };
            out.push(key.clone());
            section_keys(sub, &key, out);
        }
    }
}

fn full_default_table() -> toml::Table {
    match toml::Value::try_from(full_default()) {
        Ok(toml::Value::Table(t)) => t,
        other => panic!("full default does not serialise to a table: {other:?}"),
    }
}

/// The dotted keys assigned in a template (commented-out assignments included).
fn template_assignments(text: &str) -> BTreeSet<String> {
    let mut section = String::new();
    let mut keys = BTreeSet::new();
    for line in text.lines() {
        // A commented-out line counts only if it is TOML on its own (or opens an array).
        let l = match line.strip_prefix("# ") {
            Some(l) if l.ends_with('[') || toml::from_str::<toml::Table>(l).is_ok() => l.trim(),
            Some(_) => continue,
            None => line.trim(),
        };
        if let Some(h) = l.strip_prefix('[').and_then(|h| h.strip_suffix(']')) {
            if h.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
            {
                section = h.to_string();
                continue;
            }
        }
        if let Some((k, _)) = l.split_once(" = ") {
            if k.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') && !k.is_empty() {
                keys.insert(if section.is_empty() {
                    k.to_string()
                } else {
                    format!("{section}.{k}")
                });
            }
        }
    }
    keys
}

/// The template with its commented-out optional parts switched on.
fn template_uncommented() -> String {
    let t = default_toml();
    let mut out = String::new();
    let mut in_initial = false;
    for line in t.lines() {
        if line == "# [initial]" {
            in_initial = true;
        }
        let toml_line = [
            "# file = ",
            "# origin = ",
            "# crs = ",
            "# step1_tolerance = ",
            "# step1_max_iterations = ",
            "# file_east = ",
            "# file_north = ",
            "# [initial]",
            "# usv = ",
            "# auvs = ",
            "#   [",
            "# ]",
        ]
        .iter()
        .any(|p| line.starts_with(p));
        let optional_key = [
            "# file = ",
            "# origin = ",
            "# crs = ",
            "# step1_tolerance = ",
            "# step1_max_iterations = ",
            "# file_east = ",
            "# file_north = ",
        ]
        .iter()
        .any(|p| line.starts_with(p));
        let l = if toml_line && (in_initial || optional_key) {
            line.strip_prefix("# ").unwrap_or(line)
        } else {
            line
        };
        out.push_str(l);
        out.push('\n');
    }
    out
}
