//! The study record of a table: a small JSON file beside every table a sweep writes
//! (`runs.study.json` beside `runs.csv`, `shard-I-of-N.study.json` beside a shard's table),
//! written whole before the table's first row. It says which study the table belongs to (the
//! study's content and its fingerprint, a SHA-256 of that content), how many runs the study
//! has, which shard the table is and its columns, so that `--resume` refuses a table of
//! another study and `shoal sweep collect` can tell a shard table that is short of its runs or
//! holds runs that are not its own. The table itself stays plain CSV (no comment line that CSV
//! readers would trip on).

use super::study::{Axis, Study};
use super::{Shard, SweepError};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::path::{Path, PathBuf};

/// The record's format.
pub const FORMAT: &str = "shoal-study/1";

/// What makes a study's rows what they are: the fingerprint is a SHA-256 of this, as JSON.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Content {
    /// The study file's stem (the rows' `scenario` column).
    pub name: String,
    /// The base scenario's file name, or "embedded default".
    pub scenario: String,
    /// SHA-256 of the base scenario's text (hex).
    pub scenario_sha256: String,
    /// The planner, "mpc" or "rrt-like".
    pub method: String,
    /// The `[set]` overrides, `key=value`, in order.
    pub set: Vec<String>,
    /// The axes, in order.
    pub axes: Vec<Axis>,
    /// Whether every plan is flown.
    pub simulate: bool,
}

/// A shard, as the record writes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct ShardOf {
    /// I (0-based).
    pub index: usize,
    /// N.
    pub count: usize,
}

/// The record of one table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// [`FORMAT`].
    pub format: String,
    /// SHA-256 (hex) of [`Record::content`] as JSON.
    pub fingerprint: String,
    /// The study file as it was given (for people; not compared).
    pub study: String,
    /// Runs of the study (every shard).
    pub runs: usize,
    /// The shard this table holds; None: every run.
    pub shard: Option<ShardOf>,
    /// Runs this table must hold when complete.
    pub table_runs: usize,
    /// The table's columns.
    pub columns: Vec<String>,
    /// The study's content.
    pub content: Content,
}

/// The record beside table `table` (`runs.csv` → `runs.study.json`).
pub fn path_of(table: &Path) -> PathBuf {
    table.with_extension("study.json")
}

/// Hex of SHA-256 of `bytes`.
fn sha256(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

impl Record {
    /// The record of `study`'s table for `shard` (None: every run) with `columns`.
    pub fn of(
        study: &Study,
        shard: Option<Shard>,
        columns: &[String],
    ) -> Result<Record, SweepError> {
        let (scenario, text) = match &study.scenario {
            Some(p) => {
                let text = std::fs::read(p).map_err(|e| SweepError::Study {
                    path: study.path.clone(),
                    why: format!("its base scenario {}: cannot read: {e}", p.display()),
                })?;
                let name = p
                    .file_name()
                    .map_or(p.display().to_string(), |n| n.to_string_lossy().into());
                (name, text)
            }
            None => (
                "embedded default".to_string(),
                crate::scenario::default_toml().into_bytes(),
            ),
        };
        let content = Content {
            name: super::study_name(study),
            scenario,
            scenario_sha256: sha256(&text),
            method: study.method.name().to_string(),
            set: study.set.clone(),
            axes: study.axes.clone(),
            simulate: study.simulate,
        };
        let runs = study.total().map_err(|why| SweepError::Study {
            path: study.path.clone(),
            why,
        })?;
        let table_runs = match shard {
            Some(s) => s.runs(runs).len(),
            None => runs,
        };
        Ok(Record {
            format: FORMAT.to_string(),
            fingerprint: fingerprint(&content),
            study: study.path.display().to_string(),
            runs,
            shard: shard.map(|s| ShardOf {
                index: s.index,
                count: s.count,
            }),
            table_runs,
            columns: columns.to_vec(),
            content,
        })
    }

    /// The same study's record for the table of every run (what `collect` writes).
    pub fn whole(&self) -> Record {
        Record {
            shard: None,
            table_runs: self.runs,
            ..self.clone()
        }
    }

    /// The record at `path`; None when there is none.
    pub fn read(path: &Path) -> Result<Option<Record>, SweepError> {
        let bad = |why: String| SweepError::Table {
            path: path.to_path_buf(),
            why,
        };
        let text = match std::fs::read_to_string(path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(bad(format!("cannot read: {e}"))),
        };
        let format = serde_json::from_str::<serde_json::Value>(&text)
            .ok()
            .and_then(|v| v.get("format")?.as_str().map(String::from));
        if format.as_deref() != Some(FORMAT) {
            return Err(bad(format!(
                "not a study record of this shoal (format {}, expected \"{FORMAT}\")",
                format.map_or("missing".into(), |f| format!("\"{f}\""))
            )));
        }
        let record: Record =
            serde_json::from_str(&text).map_err(|e| bad(format!("not a study record: {e}")))?;
        if record.fingerprint != fingerprint(&record.content) {
            return Err(bad(
                "its fingerprint is not that of its content (edited by hand?)".into(),
            ));
        }
        Ok(Some(record))
    }

    /// Write the record to `path`, whole.
    pub fn write(&self, path: &Path) -> Result<(), SweepError> {
        // a record has only strings, numbers and lists: serialising it cannot fail
        let mut json = serde_json::to_vec_pretty(self).unwrap_or_default();
        json.push(b'\n');
        crate::output::write_atomic(path, &json).map_err(|e| SweepError::Table {
            path: path.to_path_buf(),
            why: e.to_string(),
        })
    }

    /// How `now` differs from this record (`then`), each difference a phrase; empty when they
    /// are of the same study and table.
    pub fn differences(&self, now: &Record) -> Vec<String> {
        let (a, b) = (&self.content, &now.content);
        let mut out = Vec::new();
        fn differ(out: &mut Vec<String>, what: &str, then: String, now: String) {
            if then != now {
                out.push(format!("{what} differs: {then} then, {now} now"));
            }
        }
        differ(
            &mut out,
            "the study's name",
            quoted(&a.name),
            quoted(&b.name),
        );
        differ(
            &mut out,
            "scenario",
            quoted(&a.scenario),
            quoted(&b.scenario),
        );
        if a.scenario == b.scenario {
            differ(
                &mut out,
                "the base scenario's text (SHA-256)",
                short(&a.scenario_sha256),
                short(&b.scenario_sha256),
            );
        }
        differ(&mut out, "method", quoted(&a.method), quoted(&b.method));
        differ(&mut out, "set", list(&a.set), list(&b.set));
        for x in &a.axes {
            match b.axes.iter().find(|y| y.key == x.key) {
                Some(y) => differ(
                    &mut out,
                    &format!("axes.{}", x.key),
                    x.values.describe(),
                    y.values.describe(),
                ),
                None => out.push(format!("axes.{} was swept, is not now", x.key)),
            }
        }
        for y in &b.axes {
            if !a.axes.iter().any(|x| x.key == y.key) {
                out.push(format!("axes.{} is swept now, was not", y.key));
            }
        }
        let keys = |c: &Content| c.axes.iter().map(|x| x.key.clone()).collect::<Vec<_>>();
        if out.is_empty() && keys(a) != keys(b) {
            differ(&mut out, "the axes' order", list(&keys(a)), list(&keys(b)));
        }
        differ(
            &mut out,
            "simulate",
            a.simulate.to_string(),
            b.simulate.to_string(),
        );
        if out.is_empty() {
            differ(
                &mut out,
                "runs",
                self.runs.to_string(),
                now.runs.to_string(),
            );
            differ(&mut out, "shard", shard(self.shard), shard(now.shard));
            differ(&mut out, "columns", list(&self.columns), list(&now.columns));
        }
        out
    }
}

/// The fingerprint of `content`: SHA-256 (hex) of its JSON.
fn fingerprint(content: &Content) -> String {
    sha256(&serde_json::to_vec(content).unwrap_or_default())
}

fn quoted(s: &str) -> String {
    format!("\"{s}\"")
}

fn short(hash: &str) -> String {
    hash.chars().take(12).collect()
}

fn list(v: &[String]) -> String {
    format!("[{}]", v.join(", "))
}

fn shard(s: Option<ShardOf>) -> String {
    s.map_or("none".into(), |s| format!("{}/{}", s.index, s.count))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(text: &str) -> Record {
        let study = Study::parse(text, Path::new("dir/study.toml")).unwrap();
        Record::of(&study, None, &["run".to_string()]).unwrap()
    }

    #[test]
    fn a_record_names_what_differs_between_two_studies() {
        let a = record("[axes]\nseed = \"1..2\"\n\"team.auvs\" = [1, 2]\n");
        assert!(a.differences(&a.clone()).is_empty());
        assert_eq!(a.fingerprint.len(), 64);
        let b = record("[axes]\nseed = \"1..3\"\n\"team.auvs\" = [1, 2]\n");
        assert_ne!(a.fingerprint, b.fingerprint);
        assert_eq!(
            a.differences(&b),
            ["axes.seed differs: \"1..2\" then, \"1..3\" now"]
        );
        let c = record(
            "method = \"rrt-like\"\n[set]\n\"horizon.steps\" = 6\n[axes]\nseed = \"1..2\"\n",
        );
        let d = a.differences(&c);
        assert!(d.iter().any(|x| x.starts_with("method differs")), "{d:?}");
        assert!(d.iter().any(|x| x.starts_with("set differs")), "{d:?}");
        assert!(d.iter().any(|x| x.contains("team.auvs was swept")), "{d:?}");
    }

    #[test]
    fn a_record_round_trips_and_an_edited_one_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("runs.study.json");
        let a = record("[axes]\nseed = \"1..2\"\n\"x.y\" = [\"a\", 3]\n");
        a.write(&path).unwrap();
        assert_eq!(Record::read(&path).unwrap(), Some(a));
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.contains("\"last\": 2"), "{text}");
        std::fs::write(&path, text.replace("\"last\": 2", "\"last\": 9")).unwrap();
        let e = Record::read(&path).unwrap_err().to_string();
        assert!(e.contains("fingerprint"), "{e}");
        std::fs::write(&path, "{}").unwrap();
        let e = Record::read(&path).unwrap_err().to_string();
        assert!(e.contains("format missing"), "{e}");
        assert_eq!(Record::read(&dir.path().join("none.json")).unwrap(), None);
        assert_eq!(
            path_of(Path::new("o/shard-1-of-3.csv")),
            Path::new("o/shard-1-of-3.study.json")
        );
    }
}
