//! The study file of `shoal sweep` (TOML; docs/sweep.md): a base scenario, fixed overrides and
//! the axes whose Cartesian product makes the runs.
//!
//! ```toml
//! scenario = "mission.toml"   # relative to this file; absent: the embedded default
//! method = "mpc"              # or "rrt-like"
//! keep_plans = false          # also write every run's plan.json
//! simulate = false            # also fly every plan and record its localization
//!
//! [set]                       # overrides of every run
//! "horizon.steps" = 10
//!
//! [axes]                      # the runs: every combination, the first axis slowest
//! seed = "1..100"             # a range, both ends included
//! "team.auvs" = [3, 5, 10, 20]
//! ```

use super::SweepError;
use crate::compare::{grouped, Method, MAX_RUNS};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use toml_edit::{DocumentMut, Item, Value};

/// One axis: a scenario key and the values it takes, each as TOML text.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    /// The dotted scenario key, e.g. "team.auvs".
    pub key: String,
    /// Its values, in order.
    pub values: Values,
}

/// The values of an axis: a list as written, or a range of whole numbers kept as its two ends
/// (a range is never made into a list: `seed = "0..1000000000000"` is two numbers).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Values {
    /// Each value as TOML text (e.g. `5`, `"a.tif"`).
    List(Vec<String>),
    /// The whole numbers from `first` to `last`, both included (`first` ≤ `last`).
    Range {
        /// The first value.
        first: i64,
        /// The last value.
        last: i64,
    },
}

impl Values {
    /// How many values (a full 64-bit range has 2^64: more than a u64 holds).
    pub fn len(&self) -> u128 {
        match self {
            Values::List(v) => v.len() as u128,
            Values::Range { first, last } => (i128::from(*last) - i128::from(*first) + 1) as u128,
        }
    }

    /// Whether there is no value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The `i`-th value (0-based, `i` < [`Values::len`]) as TOML text.
    pub fn get(&self, i: usize) -> String {
        match self {
            Values::List(v) => v.get(i).cloned().unwrap_or_default(),
            Values::Range { first, .. } => (i128::from(*first) + i as i128).to_string(),
        }
    }

    /// The values as the study writes them: `"a..b"` or `[x, y]`.
    pub fn describe(&self) -> String {
        match self {
            Values::List(v) => format!("[{}]", v.join(", ")),
            Values::Range { first, last } => format!("\"{first}..{last}\""),
        }
    }
}

/// A parsed study.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The study file (names errors; relative paths resolve against its directory).
    pub path: PathBuf,
    /// The base scenario file, resolved; None: the embedded default.
    pub scenario: Option<PathBuf>,
    /// The planner.
    pub method: Method,
    /// Whether every run's plan is written.
    pub keep_plans: bool,
    /// Whether every run's plan is also flown (`shoal simulate`) and its localization recorded.
    pub simulate: bool,
    /// Overrides of every run, as `key=value`.
    pub set: Vec<String>,
    /// The axes, in the file's order.
    pub axes: Vec<Axis>,
}

/// One run: its index and each axis's value (in the axes' order).
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    /// From 0, in the order of the Cartesian product (the first axis slowest).
    pub index: usize,
    /// The value of each axis, as TOML text.
    pub values: Vec<String>,
}

impl Study {
    /// Read and check a study file.
    pub fn load(path: &Path) -> Result<Study, SweepError> {
        let text = std::fs::read_to_string(path).map_err(|e| SweepError::Study {
            path: path.to_path_buf(),
            why: format!("cannot read: {e}"),
        })?;
        Study::parse(&text, path)
    }

    /// Parse study `text` (from `path`).
    pub fn parse(text: &str, path: &Path) -> Result<Study, SweepError> {
        let bad = |why: String| SweepError::Study {
            path: path.to_path_buf(),
            why,
        };
        let doc: DocumentMut = text.parse().map_err(|e| bad(format!("not TOML: {e}")))?;
        let dir = path.parent().unwrap_or(Path::new("."));
        let mut study = Study {
            path: path.to_path_buf(),
            scenario: None,
            method: Method::Mpc,
            keep_plans: false,
            simulate: false,
            set: Vec::new(),
            axes: Vec::new(),
        };
        for (key, item) in doc.iter() {
            match (key, item) {
                ("scenario", Item::Value(Value::String(s))) => {
                    study.scenario = Some(dir.join(s.value()));
                }
                ("method", Item::Value(Value::String(s))) => {
                    study.method = match s.value().as_str() {
                        "mpc" => Method::Mpc,
                        "rrt-like" => Method::RrtLike,
                        other => {
                            return Err(bad(format!(
                                "method = \"{other}\": allowed are \"mpc\" and \"rrt-like\""
                            )))
                        }
                    };
                }
                ("keep_plans", Item::Value(Value::Boolean(b))) => study.keep_plans = *b.value(),
                ("simulate", Item::Value(Value::Boolean(b))) => study.simulate = *b.value(),
                ("set", Item::Table(t)) => {
                    for (k, v) in t.iter() {
                        let v = v
                            .as_value()
                            .ok_or_else(|| bad(format!("set.\"{k}\": must be a value")))?;
                        study.set.push(format!("{k}={}", v.to_string().trim()));
                    }
                }
                ("axes", Item::Table(t)) => {
                    for (k, v) in t.iter() {
                        let values =
                            axis_values(v).map_err(|why| bad(format!("axes.\"{k}\": {why}")))?;
                        study.axes.push(Axis {
                            key: k.to_string(),
                            values,
                        });
                    }
                }
                ("scenario" | "method" | "keep_plans" | "set" | "axes", _) => {
                    return Err(bad(format!(
                        "{key}: wrong type (scenario: a path, method: \"mpc\" or \"rrt-like\", \
                         keep_plans and simulate: true or false, set and axes: tables)"
                    )))
                }
                _ => {
                    return Err(bad(format!(
                        "unknown key \"{key}\"; allowed are scenario, method, keep_plans, \
                         simulate, [set] and [axes]"
                    )))
                }
            }
        }
        if let Some(a) = study.axes.iter().find(|a| a.values.is_empty()) {
            return Err(bad(format!("axes.\"{}\": has no value", a.key)));
        }
        study.total().map_err(bad)?;
        Ok(study)
    }

    /// How many runs the study makes: the product of its axes' sizes, computed from each
    /// axis's size (a range's from its ends) with checked arithmetic; more than [`MAX_RUNS`]
    /// is refused, saying what each axis contributes.
    pub fn total(&self) -> Result<usize, String> {
        let sizes: Vec<u128> = self.axes.iter().map(|a| a.values.len()).collect();
        let product = sizes.iter().try_fold(1u128, |p, &n| p.checked_mul(n));
        match product {
            Some(n) if n <= MAX_RUNS as u128 => Ok(n as usize),
            _ => {
                let factors = match sizes.as_slice() {
                    [first, rest @ ..] if !rest.is_empty() && rest.iter().all(|n| n == first) => {
                        format!("{} axes of {} values", sizes.len(), grouped(*first))
                    }
                    _ => self
                        .axes
                        .iter()
                        .map(|a| format!("{} ({} values)", a.key, grouped(a.values.len())))
                        .collect::<Vec<_>>()
                        .join(" × "),
                };
                let runs = match product {
                    Some(n) if n > u128::from(u64::MAX) => {
                        format!("{} runs (more than a 64-bit count holds)", grouped(n))
                    }
                    Some(n) => format!("{} runs", grouped(n)),
                    None => format!("more than {} runs", grouped(u128::MAX)),
                };
                Err(format!(
                    "axes: {factors} make {runs}; a study has at most {} runs (docs/sweep.md)",
                    grouped(MAX_RUNS as u128)
                ))
            }
        }
    }

    /// Run `index` (0-based, below [`Study::total`]): each axis's value, the first axis
    /// slowest.
    pub fn run(&self, index: usize) -> Run {
        Run {
            index,
            values: values_of(&self.axes, index),
        }
    }

    /// Every run, in order (the study checked: at most [`MAX_RUNS`]).
    pub fn runs(&self) -> impl Iterator<Item = Run> + '_ {
        (0..self.total().unwrap_or(0)).map(|i| self.run(i))
    }

    /// The overrides of `run`: the study's `set`, then its axes' values. A floor file given
    /// by a relative path in the study is relative to the study file (as its `scenario` is),
    /// not to the base scenario's directory.
    pub fn overrides(&self, run: &Run) -> Vec<String> {
        let axes = self
            .axes
            .iter()
            .zip(&run.values)
            .map(|(a, v)| format!("{}={v}", a.key));
        self.set
            .iter()
            .cloned()
            .chain(axes)
            .map(|o| self.anchored(o))
            .collect()
    }

    /// Override `key=value`, a relative `seafloor.file` made absolute from the study's
    /// directory.
    fn anchored(&self, over: String) -> String {
        let Some((key, value)) = over.split_once('=') else {
            return over;
        };
        if key.trim() != "seafloor.file" {
            return over;
        }
        let Ok(Value::String(file)) = value.trim().parse::<Value>() else {
            return over;
        };
        let file = Path::new(file.value());
        if file.is_absolute() {
            return over;
        }
        // absolute, so that a base scenario's loader does not take it as relative to its own
        // directory
        let dir = self.path.parent().unwrap_or(Path::new(""));
        match std::path::absolute(dir.join(file)) {
            Ok(p) => format!("{key}={}", Value::from(p.to_string_lossy().into_owned())),
            Err(_) => over,
        }
    }
}

/// The values of `axes` in run `index` (the first axis slowest), as TOML text.
pub fn values_of(axes: &[Axis], index: usize) -> Vec<String> {
    let mut rest = index as u128;
    let mut values = vec![String::new(); axes.len()];
    for (i, a) in axes.iter().enumerate().rev() {
        let n = a.values.len().max(1);
        values[i] = a.values.get((rest % n) as usize);
        rest /= n;
    }
    values
}

/// An axis's values: an array, or a range "a..b" of whole numbers (both ends included), kept
/// as its ends.
fn axis_values(item: &Item) -> Result<Values, String> {
    match item.as_value() {
        Some(Value::Array(a)) => Ok(Values::List(
            a.iter().map(|v| v.to_string().trim().to_string()).collect(),
        )),
        Some(Value::String(s)) => {
            let text = s.value();
            let (a, b) = text
                .split_once("..")
                .ok_or_else(|| format!("\"{text}\" is neither an array nor a range \"a..b\""))?;
            let b = b.trim_start_matches('=');
            let num = |t: &str| {
                t.trim()
                    .parse::<i64>()
                    .map_err(|_| format!("\"{text}\": \"{t}\" is not a whole number"))
            };
            let (a, b) = (num(a)?, num(b)?);
            if a > b {
                return Err(format!("\"{text}\": the range runs backwards"));
            }
            Ok(Values::Range { first: a, last: b })
        }
        Some(v) => Ok(Values::List(vec![v.to_string().trim().to_string()])),
        None => Err("must be an array of values or a range \"a..b\"".into()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Study, SweepError> {
        Study::parse(text, Path::new("dir/study.toml"))
    }

    #[test]
    fn a_study_is_its_base_its_overrides_and_the_product_of_its_axes() {
        let s = parse(
            "scenario = \"m.toml\"\nmethod = \"rrt-like\"\n[set]\n\"horizon.steps\" = 10\n\
             [axes]\nseed = \"1..3\"\n\"team.auvs\" = [3, 5]\n",
        )
        .unwrap();
        assert_eq!(s.scenario, Some(PathBuf::from("dir/m.toml")));
        assert_eq!(s.method, Method::RrtLike);
        let runs: Vec<Run> = s.runs().collect();
        assert_eq!((runs.len(), s.total()), (6, Ok(6)));
        assert_eq!(runs[0].values, ["1", "3"]);
        assert_eq!(runs[1].values, ["1", "5"]);
        assert_eq!(runs[5].values, ["3", "5"]);
        assert_eq!(
            s.overrides(&runs[3]),
            ["horizon.steps=10", "seed=2", "team.auvs=5"]
        );
    }

    #[test]
    fn no_axis_is_one_run_and_an_axis_of_strings_keeps_its_quotes() {
        let s = parse("").unwrap();
        assert_eq!(s.total(), Ok(1));
        let s = parse("[axes]\n\"seafloor.file\" = [\"a.tif\", \"/b.asc\"]\n").unwrap();
        // relative to the study file's directory, as its scenario is; absolute as given
        let cwd = std::env::current_dir().unwrap();
        let a = format!(
            "seafloor.file={}",
            Value::from(cwd.join("dir/a.tif").to_str().unwrap())
        );
        assert_eq!(s.overrides(&s.run(0)), [a]);
        assert_eq!(s.overrides(&s.run(1)), ["seafloor.file=\"/b.asc\""]);
    }

    #[test]
    fn bad_studies_name_the_file_and_the_key() {
        for (text, want) in [
            ("method = \"simplex\"", "method = \"simplex\": allowed are"),
            ("runs = 3", "unknown key \"runs\""),
            (
                "[axes]\nseed = \"5..1\"",
                "axes.\"seed\": \"5..1\": the range runs backwards",
            ),
            ("[axes]\nseed = \"x\"", "neither an array nor a range"),
            ("[axes]\nseed = []", "axes.\"seed\": has no value"),
            ("keep_plans = 3", "keep_plans: wrong type"),
        ] {
            let e = parse(text).unwrap_err().to_string();
            assert!(
                e.contains("dir/study.toml") && e.contains(want),
                "{text}: {e}"
            );
        }
    }
}
