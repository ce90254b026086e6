//! `shoal sweep`: a study of many runs (seeds, team sizes, any scenario key, floors) described
//! by one file ([`Study`]), run on every core or in shards (one per task of a Slurm job array),
//! each run a pure function of its resolved scenario that appends one row to a table
//! ([`table`]); a run that fails records its error and the sweep goes on (docs/sweep.md). The
//! final table is written twice: `runs.csv` and its typed copy `runs.parquet`.

mod columns;
mod flown;
mod parquet_file;
pub mod study;
pub mod table;

pub use crate::compare::MAX_RUNS;
pub use study::{Axis, Run, Study, Values};

use crate::compare::{plan_and_check, Base, Planned};
use crate::scenario::{self, Scenario};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::time::Instant;
use thiserror::Error;

/// Errors of a sweep as a whole (a run's own failure is recorded in its row).
#[derive(Debug, Error)]
pub enum SweepError {
    /// The study file cannot be read or is malformed.
    #[error("{path}: {why}", path = .path.display())]
    Study {
        /// The study file.
        path: PathBuf,
        /// What is wrong, naming the key.
        why: String,
    },
    /// A table cannot be read or written.
    #[error("{path}: {why}", path = .path.display())]
    Table {
        /// The table file.
        path: PathBuf,
        /// Why.
        why: String,
    },
    /// The shard named is not one of the sweep's.
    #[error("shard {index}/{count}: {why}")]
    Shard {
        /// I.
        index: usize,
        /// N.
        count: usize,
        /// Why.
        why: String,
    },
    /// A shard table to collect does not match the others.
    #[error("nothing to collect in {0}: no shard-*-of-*.csv table")]
    NothingToCollect(PathBuf),
}

/// Which runs this process makes: the I-th (0-based) of N parts of the study's runs, dealt
/// in a fixed pseudo-random order ([`Shard::runs`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// I, 0 ≤ I < N.
    pub index: usize,
    /// N ≥ 1.
    pub count: usize,
}

impl Shard {
    /// "I/N" (0-based I).
    pub fn parse(text: &str) -> Result<Shard, String> {
        let (i, n) = text
            .split_once('/')
            .ok_or_else(|| format!("\"{text}\" is not I/N"))?;
        let num = |t: &str| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| format!("\"{t}\" is not a whole number"))
        };
        Shard::new(num(i)?, num(n)?)
    }

    /// Shard I of N, checked.
    pub fn new(index: usize, count: usize) -> Result<Shard, String> {
        if count == 0 || index >= count {
            return Err(format!("{index}/{count}: need 0 ≤ I < N"));
        }
        Ok(Shard { index, count })
    }

    /// The shard a cluster's job array gives this process: Slurm's SLURM_ARRAY_TASK_ID of
    /// SLURM_ARRAY_TASK_COUNT (the array 0..N−1), or Kubernetes' JOB_COMPLETION_INDEX of
    /// SHOAL_SHARDS (an indexed Job's completions); None outside one.
    pub fn from_env(var: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>, String> {
        let num = |name: &str| match var(name) {
            Some(v) => v
                .trim()
                .parse::<usize>()
                .map(Some)
                .map_err(|_| format!("{name} = \"{v}\" is not a whole number")),
            None => Ok(None),
        };
        match (num("SLURM_ARRAY_TASK_ID")?, num("SLURM_ARRAY_TASK_COUNT")?) {
            (Some(i), Some(n)) => return Shard::new(i, n).map(Some),
            (Some(_), None) => {
                return Err("SLURM_ARRAY_TASK_ID is set without SLURM_ARRAY_TASK_COUNT".into())
            }
            _ => {}
        }
        match (num("JOB_COMPLETION_INDEX")?, num("SHOAL_SHARDS")?) {
            (Some(i), Some(n)) => Shard::new(i, n).map(Some),
            (Some(_), None) => Err(
                "JOB_COMPLETION_INDEX is set without SHOAL_SHARDS (the Job's completions)".into(),
            ),
            _ => Ok(None),
        }
    }

    /// The runs (indices, ascending) of this shard of a study of `total` runs: the runs put in
    /// a fixed pseudo-random order (by a hash of their index, the same on every machine), then
    /// dealt out in turn, so the shards' sizes differ by at most one. Dealing the runs in
    /// their own order (every N-th) would give a shard the same value of a fast axis in every
    /// run when N divides its length: with `team.auvs = [1, 3, 5, 8]` and two shards, one
    /// would get every N = 3 and N = 8, nearly three times the other's work.
    pub fn runs(&self, total: usize) -> Vec<usize> {
        let mut order: Vec<usize> = (0..total).collect();
        order.sort_by_key(|&i| splitmix64(i as u64));
        let mut mine: Vec<usize> = order
            .into_iter()
            .skip(self.index)
            .step_by(self.count)
            .collect();
        mine.sort_unstable();
        mine
    }

    /// The table file of this shard in `dir`.
    pub fn table(&self, dir: &Path) -> PathBuf {
        dir.join(format!("shard-{}-of-{}.csv", self.index, self.count))
    }
}

/// How a sweep runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Options {
    /// Where the table (and the plans) go.
    pub out: PathBuf,
    /// Only this shard's runs, into its own table; None: every run, into `runs.csv`.
    pub shard: Option<Shard>,
    /// Skip the runs already in the table.
    pub resume: bool,
}

/// What happened to one run, as the progress listener hears it.
#[derive(Debug, Clone, PartialEq)]
pub struct Done {
    /// The run's index.
    pub index: usize,
    /// "passed", "violated" or "failed".
    pub status: String,
    /// Its wall time (planning, checking and, with `simulate`, flying), s.
    pub wall_s: f64,
}

/// The sweep's totals.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outcome {
    /// The table written.
    pub table: PathBuf,
    /// Its typed copy (`runs.parquet`), written when the sweep has no shards.
    pub parquet: Option<PathBuf>,
    /// Runs of the study (all shards).
    pub total: usize,
    /// Runs this process was to make (its shard).
    pub mine: usize,
    /// Runs skipped because the table had them (`resume`).
    pub skipped: usize,
    /// Runs made now, by status.
    pub passed: usize,
    /// Runs whose plan failed its check.
    pub violated: usize,
    /// Runs that made no plan.
    pub failed: usize,
    /// Wall time of the sweep, s.
    pub wall_s: f64,
    /// Sum of the runs' own wall times, s (over the wall time: the parallel speed-up).
    pub runs_s: f64,
}

/// The table of a sweep without shards.
pub fn table_path(dir: &Path) -> PathBuf {
    dir.join("runs.csv")
}

/// Its typed copy, as Parquet (a shard's table has none).
pub fn parquet_path(dir: &Path) -> PathBuf {
    parquet_file::beside(&table_path(dir))
}

/// Write the typed copy of the table `csv` (its `header` and sorted `records`) beside it;
/// an axis's type is its TOML values' when `study` is given, else read from its column.
fn write_parquet(
    csv: &Path,
    header: &csv::StringRecord,
    records: &[csv::StringRecord],
    study: Option<&Study>,
) -> Result<PathBuf, SweepError> {
    let axis = |key: &str| {
        study
            .and_then(|s| s.axes.iter().find(|a| a.key == key))
            .map(|a| columns::values_kind(&a.values))
    };
    let kinds = columns::kinds(header, records, axis);
    let path = parquet_file::beside(csv);
    let name = study
        .and_then(|s| s.path.file_name())
        .map(|n| n.to_string_lossy());
    parquet_file::write(&path, header, &kinds, records, name.as_deref())?;
    Ok(path)
}

/// Run `study` (its shard, if any) on every core of the current rayon pool; `progress` hears of
/// each run as it ends. Rows are appended as runs finish, then sorted by run.
pub fn run(
    study: &Study,
    opts: &Options,
    progress: &(dyn Fn(&Done) + Sync),
) -> Result<Outcome, SweepError> {
    let clock = Instant::now();
    let runs: Vec<Run> = study.runs().collect();
    let keys: Vec<String> = study.axes.iter().map(|a| a.key.clone()).collect();
    let mut header = table::header(&keys);
    if study.simulate {
        flown::COLUMNS.iter().for_each(|c| header.push_field(c));
    }
    let path = match opts.shard {
        Some(s) => s.table(&opts.out),
        None => table_path(&opts.out),
    };
    if !opts.resume && path.exists() {
        std::fs::remove_file(&path).map_err(|e| SweepError::Table {
            path: path.clone(),
            why: format!("cannot start it afresh: {e}"),
        })?;
    }
    let done: std::collections::HashSet<usize> = match table::read(&path)? {
        Some((h, records)) if h == header => records
            .iter()
            .filter_map(|r| r.get(0).and_then(|v| v.parse().ok()))
            .collect(),
        _ => Default::default(),
    };
    let mine: Vec<&Run> = match opts.shard {
        Some(s) => s.runs(runs.len()).into_iter().map(|i| &runs[i]).collect(),
        None => runs.iter().collect(),
    };
    let todo: Vec<&&Run> = mine.iter().filter(|r| !done.contains(&r.index)).collect();
    let appender = Mutex::new(table::Appender::open(&path, &header)?);
    let base = base_of(study);
    let outcome = Mutex::new(Outcome {
        table: path.clone(),
        total: runs.len(),
        mine: mine.len(),
        skipped: mine.len() - todo.len(),
        ..Outcome::default()
    });
    let write_error = Mutex::new(None);
    todo.par_iter().for_each(|run| {
        let clock = Instant::now();
        let planned = run_one(study, &base, run);
        let r = &planned.row;
        if study.keep_plans {
            if let Some(plan) = &planned.plan {
                let file = opts
                    .out
                    .join("plans")
                    .join(format!("run-{:06}.json", run.index));
                let _ = crate::output::write_plan(plan, &file);
            }
        }
        let mut rec = table::record(run.index, &keys, &run.values, r);
        if study.simulate {
            let sim = flown::fields(planned.plan.as_ref(), planned.floor.as_ref());
            sim.iter().for_each(|f| rec.push_field(f));
        }
        if let Err(e) = appender
            .lock()
            .map(|mut a| a.append(&rec))
            .unwrap_or(Ok(()))
        {
            *write_error.lock().unwrap_or_else(|p| p.into_inner()) = Some(e.to_string());
        }
        let wall_s = clock.elapsed().as_secs_f64();
        {
            let mut o = outcome.lock().unwrap_or_else(|p| p.into_inner());
            match r.status.as_str() {
                "passed" => o.passed += 1,
                "violated" => o.violated += 1,
                _ => o.failed += 1,
            }
            o.runs_s += wall_s;
        }
        progress(&Done {
            index: run.index,
            status: r.status.clone(),
            wall_s,
        });
    });
    if let Some(why) = write_error.into_inner().unwrap_or_else(|p| p.into_inner()) {
        return Err(SweepError::Table { path, why });
    }
    drop(appender);
    let (_, records) = table::read(&path)?.unwrap_or_default();
    let records = table::write_sorted(&path, &header, records)?;
    let mut o = outcome.into_inner().unwrap_or_else(|p| p.into_inner());
    if opts.shard.is_none() {
        o.parquet = Some(write_parquet(&path, &header, &records, Some(study))?);
    }
    o.wall_s = clock.elapsed().as_secs_f64();
    Ok(o)
}

/// The study's base: its name (the study file's stem) and where its scenario's relative
/// paths resolve.
fn base_of(study: &Study) -> Base {
    let name = study
        .path
        .file_stem()
        .map_or("study".into(), |s| s.to_string_lossy().into_owned());
    let dir = match &study.scenario {
        Some(p) => p.parent().unwrap_or(Path::new(".")).to_path_buf(),
        None => study.path.parent().unwrap_or(Path::new(".")).to_path_buf(),
    };
    Base {
        name,
        scenario: Scenario::default(),
        dir,
    }
}

/// One run: its scenario resolved (a bad override fails the run, not the sweep), planned,
/// checked and measured.
fn run_one(study: &Study, base: &Base, run: &Run) -> Planned {
    let overrides = study.overrides(run);
    let resolved = match &study.scenario {
        Some(path) => scenario::load(path, &overrides),
        None => scenario::default_with(&overrides),
    };
    match resolved {
        Ok(s) => plan_and_check(base, &s, study.method),
        Err(e) => {
            let mut row = crate::compare::Row::key(&base.name, study.method.name(), 0, 0);
            row.status = "failed".into();
            row.error = e.to_string();
            row.wall_s = 0.0;
            Planned {
                row,
                plan: None,
                floor: None,
            }
        }
    }
}

/// SplitMix64's finaliser: a bijective hash of 64-bit words (Steele, Lea and Flood 2014),
/// fixed here so that every task of an array orders the runs alike.
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The shard tables of one sweep are `shard-I-of-N.csv` for one N and every I < N: tables of
/// another split (an earlier sweep's) or a missing shard (a task that never ran) would make a
/// table that is not the study's.
fn check_shards(dir: &Path, shards: &[PathBuf]) -> Result<(), SweepError> {
    let split = |p: &PathBuf| -> Option<(usize, usize)> {
        let name = p.file_stem()?.to_str()?.strip_prefix("shard-")?;
        let (i, n) = name.split_once("-of-")?;
        Some((i.parse().ok()?, n.parse().ok()?))
    };
    let mut counts = std::collections::BTreeMap::<usize, Vec<usize>>::new();
    for p in shards {
        let (i, n) = split(p).ok_or_else(|| SweepError::Table {
            path: p.clone(),
            why: "not a shard table's name (shard-I-of-N.csv)".into(),
        })?;
        counts.entry(n).or_default().push(i);
    }
    if counts.len() > 1 {
        let splits: Vec<String> = counts.keys().map(|n| format!("of-{n}")).collect();
        return Err(SweepError::Table {
            path: dir.to_path_buf(),
            why: format!(
                "shard tables of {} splits ({}): remove those of earlier sweeps",
                counts.len(),
                splits.join(", ")
            ),
        });
    }
    if let Some((n, found)) = counts.into_iter().next() {
        let missing: Vec<String> = (0..n)
            .filter(|i| !found.contains(i))
            .map(|i| format!("shard-{i}-of-{n}.csv"))
            .collect();
        if !missing.is_empty() {
            return Err(SweepError::Table {
                path: dir.to_path_buf(),
                why: format!(
                    "{} of {n} shard tables missing ({}): did every task of the array run?",
                    missing.len(),
                    missing.join(", ")
                ),
            });
        }
    }
    Ok(())
}

/// Merge the shard tables of `dir` (`shard-I-of-N.csv`) into `dir/runs.csv`, sorted by run,
/// and its typed copy `dir/runs.parquet` (each axis's type read from its column, the study
/// not being at hand). Returns the CSV table and its number of rows.
pub fn collect(dir: &Path) -> Result<(PathBuf, usize), SweepError> {
    let mut shards: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| SweepError::Table {
            path: dir.to_path_buf(),
            why: e.to_string(),
        })?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with("shard-") && n.ends_with(".csv"))
        })
        .collect();
    shards.sort();
    check_shards(dir, &shards)?;
    let mut header = None;
    let mut records = Vec::new();
    for p in &shards {
        if let Some((h, recs)) = table::read(p)? {
            match &header {
                Some(first) if first != &h => {
                    return Err(SweepError::Table {
                        path: p.clone(),
                        why: "its columns differ from the other shards' (another study?)".into(),
                    })
                }
                _ => header = Some(h),
            }
            records.extend(recs);
        }
    }
    let header = header.ok_or_else(|| SweepError::NothingToCollect(dir.to_path_buf()))?;
    let path = table_path(dir);
    let records = table::write_sorted(&path, &header, records)?;
    write_parquet(&path, &header, &records, None)?;
    Ok((path, records.len()))
}
