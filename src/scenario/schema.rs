//! The shape of a scenario file, derived from the types themselves: the default scenario with
//! every optional part filled in (an example `[initial]`, `seafloor.file`, `seafloor.origin` and
//! `seafloor.crs`)
//! serialised
//! to a TOML document. Used to list the keys allowed at each level, to name the type a key
//! expects, and to generate the template, so that no key or default value is written twice.

use super::{
    A2aGraph, AwayFrom, DepthObjective, Discretisation, Initial, Scenario, UsvObjective, W8Scaling,
    WeightScaling,
};
use crate::seafloor::Values;
use toml_edit::{DocumentMut, Item, TableLike, Value};

/// Example path shown (commented out) for `seafloor.file` in the template.
pub(crate) const EXAMPLE_FLOOR_FILE: &str = "bathymetry.tif";
/// Example mission origin (latitude, longitude) shown (commented out) for `seafloor.origin`.
pub(crate) const EXAMPLE_ORIGIN: [f64; 2] = [43.2, 5.3];
/// Example CRS shown (commented out) for `seafloor.crs`.
pub(crate) const EXAMPLE_CRS: &str = "EPSG:4326";
/// Example paths shown (commented out) for `current.file_east` and `current.file_north`.
pub(crate) const EXAMPLE_CURRENT_FILES: [&str; 2] = ["current_u.asc", "current_v.asc"];

/// An `[initial]` block valid for `s`: the AUVs evenly spread on a circle of radius d_s/2 around
/// the origin (where the USV starts), halfway between the surface and the shallowest synthetic
/// floor. Coordinates are rounded to 0.1 m so the example reads well.
pub(crate) fn example_initial(s: &Scenario) -> Initial {
    let n = s.team.auvs.max(1);
    let r = 0.5 * s.acoustic.sonar_range;
    let z = 0.5 * s.seafloor.synthetic.depth_range[1];
    let round = |v: f64| {
        let v = (v * 10.0).round() / 10.0;
        if v == 0.0 {
            0.0 // no "-0.0" in the example
        } else {
            v
        }
    };
    let auvs = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            [round(r * a.cos()), round(r * a.sin()), round(z)]
        })
        .collect();
    Initial {
        usv: [0.0, 0.0],
        auvs,
    }
}

/// The default scenario with every optional field present.
pub(crate) fn full_default() -> Scenario {
    let mut s = Scenario::default();
    s.initial = Some(example_initial(&s));
    s.seafloor.file = Some(EXAMPLE_FLOOR_FILE.to_string());
    s.seafloor.origin = Some(EXAMPLE_ORIGIN);
    s.seafloor.crs = Some(EXAMPLE_CRS.to_string());
    s.current.file_east = Some(EXAMPLE_CURRENT_FILES[0].to_string());
    s.current.file_north = Some(EXAMPLE_CURRENT_FILES[1].to_string());
    // the converged run's settings, for Step 1 alone
    s.scp.step1_tolerance = Some(1e-7);
    s.scp.step1_max_iterations = Some(300);
    s
}

/// Serialise a scenario to an (ordered) TOML document. The types serialise infallibly (plain
/// numbers, strings, arrays, tables); a failure here is a programming error caught by the tests.
pub(crate) fn to_document(s: &Scenario) -> DocumentMut {
    toml_edit::ser::to_document(s).unwrap_or_default()
}

/// The schema: the full default as a TOML document, in field order, plus which arrays have a
/// fixed length (Rust arrays `[f64; N]`, as opposed to `Vec`s).
pub(crate) struct Schema {
    pub doc: DocumentMut,
    /// (dotted key, length); `key[]` stands for every element of the array at `key`.
    fixed: Vec<(String, usize)>,
}

/// What looking a dotted key up in the schema gives.
pub(crate) enum Lookup<'a> {
    /// A section (table) with these keys, in order.
    Section(Vec<&'a str>),
    /// A value (leaf).
    Leaf(&'a Item),
    /// `prefix` names a value, so nothing can lie below it.
    BelowLeaf { prefix: String },
    /// The segment at `index` is not a key of the section `prefix` (empty: the top level).
    Unknown {
        index: usize,
        prefix: String,
        allowed: Vec<&'a str>,
    },
}

impl Schema {
    pub fn new() -> Self {
        let doc = to_document(&full_default());
        let mut fixed = Vec::new();
        find_fixed(&doc, doc.as_table(), &mut Vec::new(), &mut fixed);
        Schema { doc, fixed }
    }

    /// The length the array at `key` must have, if fixed (`key[]`: its elements).
    ///
    /// Needed because toml_edit's deserialiser ignores extra elements of a fixed-size array
    /// (`destination = [1, 2, 3]` would silently read as [1, 2]).
    pub fn fixed_len(&self, key: &str) -> Option<usize> {
        self.fixed.iter().find(|(k, _)| k == key).map(|(_, n)| *n)
    }

    pub fn root(&self) -> &dyn TableLike {
        self.doc.as_table()
    }

    /// Look a dotted key (already split) up.
    pub fn lookup(&self, segs: &[&str]) -> Lookup<'_> {
        let mut table: &dyn TableLike = self.root();
        for (i, seg) in segs.iter().enumerate() {
            let prefix = segs[..i].join(".");
            let Some(item) = table.get(seg) else {
                return Lookup::Unknown {
                    index: i,
                    prefix,
                    allowed: keys_of(table),
                };
            };
            match item.as_table_like() {
                Some(t) => table = t,
                None if i + 1 == segs.len() => return Lookup::Leaf(item),
                None => {
                    return Lookup::BelowLeaf {
                        prefix: segs[..=i].join("."),
                    }
                }
            }
        }
        Lookup::Section(keys_of(table))
    }

    /// "allowed keys in [acoustic]: sonar_range, band_tolerance, …" for the section `prefix`.
    pub fn allowed_text(&self, prefix: &str) -> String {
        let segs: Vec<&str> = if prefix.is_empty() {
            Vec::new()
        } else {
            prefix.split('.').collect()
        };
        match self.lookup(&segs) {
            Lookup::Section(keys) => allowed_list(prefix, &keys),
            Lookup::Unknown { .. } | Lookup::BelowLeaf { .. } | Lookup::Leaf(_) => {
                format!("{prefix} takes a single value, not keys below it")
            }
        }
    }

    /// What a value at `key` (dotted, no indices) must look like, in words; None for unknown keys.
    pub fn expected(&self, key: &str) -> Option<String> {
        let segs: Vec<&str> = key.split('.').collect();
        match self.lookup(&segs) {
            Lookup::Section(_) => Some("a table (section) of keys".to_string()),
            Lookup::Leaf(item) => Some(describe(key, item)),
            _ => None,
        }
    }
}

/// Record every array of the schema whose length the types fix. Found by probing: an array is of
/// fixed length if the document with one element less no longer deserialises.
fn find_fixed(
    doc: &DocumentMut,
    t: &dyn TableLike,
    path: &mut Vec<String>,
    out: &mut Vec<(String, usize)>,
) {
    for (k, item) in t.iter() {
        path.push(k.to_string());
        if let Some(sub) = item.as_table_like() {
            find_fixed(doc, sub, path, out);
        } else if let Some(a) = item.as_array() {
            let key = path.join(".");
            if shortened_fails(doc, path, false) {
                out.push((key.clone(), a.len()));
            }
            if let Some(Value::Array(inner)) = a.get(0) {
                if shortened_fails(doc, path, true) {
                    out.push((format!("{key}[]"), inner.len()));
                }
            }
        }
        path.pop();
    }
}

/// Does the document fail to deserialise once the array at `path` (or, with `inner`, its first
/// element) loses its last element?
fn shortened_fails(doc: &DocumentMut, path: &[String], inner: bool) -> bool {
    let mut d = doc.clone();
    let mut item: &mut Item = d.as_item_mut();
    for seg in path {
        item = match item.get_mut(seg.as_str()) {
            Some(i) => i,
            None => return false,
        };
    }
    let Some(mut arr) = item.as_array_mut() else {
        return false;
    };
    if inner {
        arr = match arr.get_mut(0).and_then(Value::as_array_mut) {
            Some(a) => a,
            None => return false,
        };
    }
    if arr.is_empty() {
        return false;
    }
    arr.remove(arr.len() - 1);
    toml_edit::de::from_document::<Scenario>(d).is_err()
}

pub(crate) fn allowed_list(prefix: &str, keys: &[&str]) -> String {
    if prefix.is_empty() {
        format!("allowed top-level keys: {}", keys.join(", "))
    } else {
        format!("allowed keys in [{prefix}]: {}", keys.join(", "))
    }
}

fn keys_of(t: &dyn TableLike) -> Vec<&str> {
    t.iter().map(|(k, _)| k).collect()
}

/// The string values an enum key accepts, as they are written in TOML.
pub(crate) fn enum_values(key: &str) -> Option<Vec<String>> {
    fn names<T: serde::Serialize>(vs: &[T]) -> Vec<String> {
        vs.iter()
            .filter_map(|v| match serde_json::to_value(v) {
                Ok(serde_json::Value::String(s)) => Some(s),
                _ => None,
            })
            .collect()
    }
    match key {
        "auv.discretisation" => Some(names(&[Discretisation::Zoh, Discretisation::Euler])),
        "acoustic.graph" => Some(names(&[
            A2aGraph::PerStep,
            A2aGraph::Lanes,
            A2aGraph::Window,
        ])),
        "usv.objective" => Some(names(&[UsvObjective::Away, UsvObjective::Destination])),
        "usv.away_from" => Some(names(&[AwayFrom::Track, AwayFrom::Window])),
        "weights.of1_2" => Some(names(&[DepthObjective::Height, DepthObjective::Depth])),
        "weights.scaling" => Some(names(&[WeightScaling::PerAuv, WeightScaling::Sum])),
        "weights.w8_scaling" => Some(names(&[W8Scaling::Energy, W8Scaling::None])),
        "seafloor.values" => Some(names(&[Values::Elevation, Values::Depth])),
        _ => None,
    }
}

fn describe(key: &str, item: &Item) -> String {
    if let Some(vals) = enum_values(key) {
        let quoted: Vec<String> = vals.iter().map(|v| format!("\"{v}\"")).collect();
        return format!("one of {}", quoted.join(", "));
    }
    if let Some(range) = super::validate::integer_text(key) {
        return range;
    }
    match item.as_value() {
        Some(v) => describe_value(v),
        None => "a table (section) of keys".to_string(),
    }
}

fn describe_value(v: &Value) -> String {
    match v {
        Value::String(_) => "a string".to_string(),
        Value::Integer(_) => "a non-negative integer".to_string(),
        Value::Float(_) => "a number".to_string(),
        Value::Boolean(_) => "true or false".to_string(),
        Value::Datetime(_) => "a date-time".to_string(),
        Value::InlineTable(_) => "a table (section) of keys".to_string(),
        Value::Array(a) => match a.get(0) {
            Some(Value::Array(inner)) => format!(
                "an array of arrays of {} numbers, e.g. [[x, y, z], …]",
                inner.len()
            ),
            Some(Value::Float(_)) | Some(Value::Integer(_)) => {
                format!("an array of {} numbers", a.len())
            }
            Some(other) => format!("an array of {}", describe_value(other)),
            None => "an array".to_string(),
        },
    }
}
