//! The type of each column of a sweep's table, for its typed copy (`runs.parquet`): decided
//! from what is known, not guessed from the text where it can be: `run` is a whole number, the
//! row's columns take their [`Row`] field's type, the simulation's columns theirs
//! ([`super::flown::KINDS`]), and an axis its TOML values' (all integers: a whole number; any
//! real: a real; all booleans: a boolean; anything else: text; a range: a whole number), from
//! the study or, for `shoal sweep collect`, from the shards' study record. Only a column of no
//! known kind is typed from its text, the same way.

use super::flown;
use super::study::Values;
use crate::compare::Row;
use csv::StringRecord;
use toml_edit::Value;

/// A column's type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// A whole number (Parquet INT64).
    Int,
    /// A real number; NaN (no value) is a null (Parquet DOUBLE).
    Real,
    /// Text; empty is a null (Parquet BYTE_ARRAY, logical type STRING).
    Text,
    /// `true` or `false` (Parquet BOOLEAN).
    Bool,
}

/// The type of each of [`Row`]'s columns, in order, from its fields' types: a [`Row::key`]
/// (every real NaN, every count 0, every text empty) seen through serde, where NaN becomes a
/// null, a whole number an integer and a real a float.
pub fn row_kinds() -> Vec<(String, Kind)> {
    let probe = serde_json::to_value(Row::key("", "", 0, 0)).unwrap_or_default();
    let (names, _) = super::table::row_fields(&Row::key("", "", 0, 0));
    names
        .iter()
        .map(|name| {
            let kind = match probe.get(name) {
                Some(serde_json::Value::Number(n)) if !n.is_f64() => Kind::Int,
                Some(serde_json::Value::String(_)) => Kind::Text,
                Some(serde_json::Value::Bool(_)) => Kind::Bool,
                _ => Kind::Real,
            };
            (name.to_string(), kind)
        })
        .collect()
}

/// The type of an axis from its values: a range's are whole numbers, a list's their TOML
/// type's.
pub fn values_kind(values: &Values) -> Kind {
    match values {
        Values::Range { .. } => Kind::Int,
        Values::List(v) => axis_kind(v),
    }
}

/// The type of an axis from its values as TOML text.
pub fn axis_kind(values: &[String]) -> Kind {
    let kinds: Vec<Kind> = values
        .iter()
        .map(|v| match v.trim().parse::<Value>() {
            Ok(Value::Integer(_)) => Kind::Int,
            Ok(Value::Float(_)) => Kind::Real,
            Ok(Value::Boolean(_)) => Kind::Bool,
            _ => Kind::Text,
        })
        .collect();
    unify(&kinds)
}

/// The type of an axis from its column's text (TOML values, strings unquoted).
pub fn text_kind<'a>(cells: impl Iterator<Item = &'a str>) -> Kind {
    let kinds: Vec<Kind> = cells
        .map(|c| match (int(c), real(c), c) {
            (Some(_), _, _) => Kind::Int,
            (None, Some(_), _) => Kind::Real,
            (_, _, "true" | "false") => Kind::Bool,
            _ => Kind::Text,
        })
        .collect();
    unify(&kinds)
}

/// One type for a column whose values have `kinds`: integers and reals make reals; any other
/// mixture, text.
fn unify(kinds: &[Kind]) -> Kind {
    let all = |k: Kind| kinds.iter().all(|&x| x == k);
    if kinds.is_empty() || all(Kind::Text) {
        Kind::Text
    } else if all(Kind::Int) {
        Kind::Int
    } else if all(Kind::Bool) {
        Kind::Bool
    } else if kinds.iter().all(|&k| k == Kind::Int || k == Kind::Real) {
        Kind::Real
    } else {
        Kind::Text
    }
}

/// A whole number written as Rust or TOML writes it (`1_000`, `+5`, `0x10`).
pub fn int(cell: &str) -> Option<i64> {
    cell.parse().ok().or_else(|| match cell.parse::<Value>() {
        Ok(Value::Integer(i)) => Some(*i.value()),
        _ => None,
    })
}

/// A real number written as Rust or TOML writes it (`NaN`, `inf`, `1_000.5`, `nan`).
pub fn real(cell: &str) -> Option<f64> {
    cell.parse().ok().or_else(|| match cell.parse::<Value>() {
        Ok(Value::Float(f)) => Some(*f.value()),
        Ok(Value::Integer(i)) => Some(*i.value() as f64),
        _ => None,
    })
}

/// The type of every column of a table with `header` and `records`: `run`, the row's and the
/// simulation's columns by name, an axis by `axis(key)` (its TOML values' type, when the study
/// is known) or else by its column's text.
pub fn kinds(
    header: &StringRecord,
    records: &[StringRecord],
    axis: impl Fn(&str) -> Option<Kind>,
) -> Vec<Kind> {
    let row = row_kinds();
    header
        .iter()
        .enumerate()
        .map(|(i, name)| {
            if name == "run" {
                return Kind::Int;
            }
            if let Some((_, k)) = row.iter().find(|(n, _)| n == name) {
                return *k;
            }
            if let Some(j) = flown::COLUMNS.iter().position(|c| *c == name) {
                return flown::KINDS[j];
            }
            axis(name).unwrap_or_else(|| text_kind(records.iter().filter_map(|r| r.get(i))))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rows_columns_take_their_fields_types() {
        let kinds = row_kinds();
        let of = |name: &str| kinds.iter().find(|(n, _)| n == name).map(|(_, k)| *k);
        assert_eq!(of("scenario"), Some(Kind::Text));
        assert_eq!(of("auvs"), Some(Kind::Int));
        assert_eq!(of("seed"), Some(Kind::Int));
        assert_eq!(of("error"), Some(Kind::Text));
        assert_eq!(of("wall_s"), Some(Kind::Real));
        assert_eq!(of("out_of_band"), Some(Kind::Int));
        assert_eq!(of("margin_c1_5_m"), Some(Kind::Real));
        assert_eq!(of("samples_kept"), Some(Kind::Int));
        // in the order of the CSV's columns
        let (names, _) = super::super::table::row_fields(&Row::key("", "", 0, 0));
        let order: Vec<&str> = kinds.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(order, names.iter().collect::<Vec<_>>());
    }

    #[test]
    fn an_axis_takes_its_toml_values_type() {
        let v = |s: &[&str]| s.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        assert_eq!(axis_kind(&v(&["1", "3", "1_000"])), Kind::Int);
        assert_eq!(axis_kind(&v(&["1", "2.5"])), Kind::Real);
        assert_eq!(axis_kind(&v(&["true", "false"])), Kind::Bool);
        assert_eq!(axis_kind(&v(&["\"a.tif\"", "\"b.tif\""])), Kind::Text);
        assert_eq!(axis_kind(&v(&["\"3\"", "4"])), Kind::Text);
        assert_eq!(axis_kind(&v(&["[1, 2]"])), Kind::Text);
        assert_eq!(text_kind(["1", "3"].into_iter()), Kind::Int);
        assert_eq!(text_kind(["1", "0.5"].into_iter()), Kind::Real);
        assert_eq!(text_kind(["a.tif", "3"].into_iter()), Kind::Text);
        assert_eq!(int("1_000"), Some(1000));
        assert!(real("nan").is_some_and(f64::is_nan) && real("NaN").is_some_and(f64::is_nan));
    }
}
