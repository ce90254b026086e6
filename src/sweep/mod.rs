//! `shoal sweep`: a study of many runs (seeds, team sizes, any scenario key, floors) described
//! by one file ([`Study`]), run on every core or in shards (one per task of a Slurm job array),
//! each run a pure function of its resolved scenario that appends one row to a table
//! ([`table`]); a run that fails records its error and the sweep goes on (docs/sweep.md). The
//! final table is written twice: `runs.csv` and its typed copy `runs.parquet`. Beside every
//! table is the record of its study ([`record`]): `--resume` and `collect` refuse a table of
//! another study, and `collect` names every row and run it cannot take (`verify`).

mod columns;
mod flown;
mod parquet_file;
pub mod record;
pub mod study;
pub mod table;
mod verify;

pub use crate::compare::MAX_RUNS;
pub use record::Record;
pub use study::{Axis, Run, Study, Values};

use crate::compare::{plan_and_check, Base, Planned};
use crate::scenario::{self, Scenario, ScenarioError};
use rayon::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;
use std::time::Instant;
use thiserror::Error;
use verify::Problem;

/// At most this many problems are listed by a collect that is refused (then how many more).
const PROBLEMS_SHOWN: usize = 50;

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
    /// The study's scenario (its base with its `[set]`) cannot be made: no run could be.
    #[error("{study}: its scenario cannot be made, so no run could: {source}", study = .study.display())]
    Base {
        /// The study file.
        study: PathBuf,
        /// The scenario's error (naming its file, line and key).
        #[source]
        source: Box<ScenarioError>,
    },
    /// A table to resume that another study made, or that has no record of its study.
    #[error("{path} was made by another study ({why}); use another -o or delete it", path = .path.display())]
    AnotherStudy {
        /// The table.
        path: PathBuf,
        /// What differs.
        why: String,
    },
    /// Shard tables that cannot be collected whole: every problem with its file (listed by file
    /// and line, the first `PROBLEMS_SHOWN`, then how many more in each file).
    #[error(
        "{dir}: cannot collect the shard tables whole, nothing written; {n} problem{s}:\n  {list}",
        dir = .dir.display(),
        n = .problems.len(),
        s = if .problems.len() == 1 { "" } else { "s" },
        list = listed(.problems)
    )]
    Collect {
        /// The sweep's directory.
        dir: PathBuf,
        /// Each problem: its file, and what is wrong (naming the file and the line).
        problems: Vec<(PathBuf, String)>,
    },
}

/// The first [`PROBLEMS_SHOWN`] problems, one a line, then how many more in each file.
fn listed(problems: &[(PathBuf, String)]) -> String {
    let mut lines: Vec<String> = problems
        .iter()
        .take(PROBLEMS_SHOWN)
        .map(|(_, why)| why.clone())
        .collect();
    let mut more: Vec<(&PathBuf, usize)> = Vec::new();
    for (file, _) in problems.iter().skip(PROBLEMS_SHOWN) {
        match more.iter_mut().find(|(f, _)| *f == file) {
            Some((_, n)) => *n += 1,
            None => more.push((file, 1)),
        }
    }
    if !more.is_empty() {
        let each: Vec<String> = more
            .iter()
            .map(|(f, n)| format!("{n} in {}", f.display()))
            .collect();
        lines.push(format!(
            "… and {} more: {}",
            problems.len() - PROBLEMS_SHOWN,
            each.join(", ")
        ));
    }
    lines.join("\n  ")
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

    /// The runs of every shard of `count` (each ascending), dealt as [`Shard::runs`] deals
    /// them, in one pass (`count` vectors: for as many shards as there are tables).
    pub fn deal(count: usize, total: usize) -> Vec<Vec<usize>> {
        let count = count.max(1);
        let mut order: Vec<usize> = (0..total).collect();
        order.sort_by_key(|&i| splitmix64(i as u64));
        let mut shards = vec![Vec::new(); count];
        for (k, run) in order.into_iter().enumerate() {
            shards[k % count].push(run);
        }
        shards.iter_mut().for_each(|s| s.sort_unstable());
        shards
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
    /// Rows in the table now (this process's table: its shard's).
    pub rows: usize,
    /// Of those, runs that made no plan.
    pub rows_failed: usize,
    /// The error of the failed row of the lowest run, when one failed: "run I: why".
    pub first_failure: Option<String>,
    /// Whether the table holds every run it should (its shard's, or the study's).
    pub complete: bool,
    /// Whether the sweep was cancelled before every run was made.
    pub interrupted: bool,
    /// Rows of a resumed table that could not be taken (damaged), each by its line; their runs
    /// were made again.
    pub notes: Vec<String>,
}

/// The table of a sweep without shards.
pub fn table_path(dir: &Path) -> PathBuf {
    dir.join("runs.csv")
}

/// Its typed copy, as Parquet (a shard's table has none).
pub fn parquet_path(dir: &Path) -> PathBuf {
    parquet_file::beside(&table_path(dir))
}

/// Write the typed copy of the table `csv` (its `header` and sorted `records`) beside it, an
/// axis's type its values' (`axes`); `study` (the study file's name) goes into its metadata.
fn write_parquet(
    csv: &Path,
    header: &csv::StringRecord,
    records: &[csv::StringRecord],
    axes: &[Axis],
    study: Option<&str>,
) -> Result<PathBuf, SweepError> {
    let axis = |key: &str| {
        axes.iter()
            .find(|a| a.key == key)
            .map(|a| columns::values_kind(&a.values))
    };
    let kinds = columns::kinds(header, records, axis);
    let path = parquet_file::beside(csv);
    parquet_file::write(&path, header, &kinds, records, study)?;
    Ok(path)
}

/// The table's columns for `study`: `run`, its axes (but `seed`), the row's, and with
/// `simulate` the flight's.
fn header_of(study: &Study) -> csv::StringRecord {
    let keys: Vec<String> = study.axes.iter().map(|a| a.key.clone()).collect();
    let mut header = table::header(&keys);
    if study.simulate {
        flown::COLUMNS.iter().for_each(|c| header.push_field(c));
    }
    header
}

/// Make the study's scenario once, before any run: its base with its `[set]` and run 0's axis
/// values. An error that only an axis's value causes (a value out of range, of the wrong type)
/// is that run's, recorded in its row; any other (the base scenario unreadable or malformed, a
/// bad `[set]`, an axis key no scenario has) would fail every run, and refuses the study.
fn preflight(study: &Study) -> Result<(), SweepError> {
    let overrides = study.overrides(&study.run(0));
    let axis_sets: Vec<String> = overrides[study.set.len()..]
        .iter()
        .map(|o| format!("--set {o}"))
        .collect();
    let made = match &study.scenario {
        Some(path) => scenario::load(path, &overrides),
        None => scenario::default_with(&overrides),
    };
    match made {
        Ok(_) => Ok(()),
        Err(e)
            if axis_sets.contains(&e.source_name())
                && matches!(
                    e,
                    ScenarioError::OutOfRange { .. }
                        | ScenarioError::WrongType { .. }
                        | ScenarioError::MissingKey { .. }
                        | ScenarioError::Invalid { .. }
                ) =>
        {
            Ok(())
        }
        Err(e) => Err(SweepError::Base {
            study: study.path.clone(),
            source: Box::new(e),
        }),
    }
}

/// Run `study` (its shard, if any) on every core of the current rayon pool; `progress` hears of
/// each run as it ends. Rows are appended as runs finish, then sorted by run.
pub fn run(
    study: &Study,
    opts: &Options,
    progress: &(dyn Fn(&Done) + Sync),
) -> Result<Outcome, SweepError> {
    run_until(study, opts, progress, &AtomicBool::new(false))
}

/// [`run`], starting no new run once `cancel` is set (the runs under way finish and keep their
/// rows): the table then holds the runs made so far, sorted, `Outcome::interrupted` is set,
/// and `--resume` makes the rest.
///
/// Before any run: the study's size is checked ([`MAX_RUNS`]), its scenario made once
/// (an error that would fail every run refuses the study, [`SweepError::Base`]), and the
/// table's study record written beside it ([`record`]). With `resume`, a table whose record
/// is another study's (or that has none) is refused, and its rows that cannot be taken
/// (damaged) are dropped and their runs made again (`Outcome::notes`).
pub fn run_until(
    study: &Study,
    opts: &Options,
    progress: &(dyn Fn(&Done) + Sync),
    cancel: &AtomicBool,
) -> Result<Outcome, SweepError> {
    let clock = Instant::now();
    let total = study.total().map_err(|why| SweepError::Study {
        path: study.path.clone(),
        why,
    })?;
    preflight(study)?;
    let header = header_of(study);
    let keys: Vec<String> = study.axes.iter().map(|a| a.key.clone()).collect();
    let path = match opts.shard {
        Some(s) => s.table(&opts.out),
        None => table_path(&opts.out),
    };
    let record_path = record::path_of(&path);
    let columns: Vec<String> = header.iter().map(String::from).collect();
    let record = Record::of(study, opts.shard, &columns)?;
    if opts.resume && path.exists() {
        let why = match Record::read(&record_path)? {
            None => vec![format!(
                "it has no study record: {} is missing",
                record_path.display()
            )],
            Some(then) => then.differences(&record),
        };
        if !why.is_empty() {
            return Err(SweepError::AnotherStudy {
                path,
                why: why.join("; "),
            });
        }
    } else if path.exists() {
        std::fs::remove_file(&path).map_err(|e| SweepError::Table {
            path: path.clone(),
            why: format!("cannot start it afresh: {e}"),
        })?;
    }
    // runs.parquet is the typed copy of a whole table: gone until the table is whole again
    let parquet = parquet_file::beside(&path);
    if opts.shard.is_none() && parquet.exists() {
        std::fs::remove_file(&parquet).map_err(|e| SweepError::Table {
            path: parquet.clone(),
            why: format!("cannot remove the typed copy of the table being remade: {e}"),
        })?;
    }
    record.write(&record_path)?;
    let mine: Vec<usize> = match opts.shard {
        Some(s) => s.runs(total),
        None => (0..total).collect(),
    };
    let checked = verify::table(&path, &record, &mine)?;
    if let Some(p) = checked
        .problems
        .iter()
        .find(|p| matches!(p, Problem::Columns(_)))
    {
        return Err(SweepError::AnotherStudy {
            path: path.clone(),
            why: p.describe(&path),
        });
    }
    let done: std::collections::HashSet<usize> = checked.rows.iter().filter_map(run_of).collect();
    let todo: Vec<usize> = mine.iter().copied().filter(|r| !done.contains(r)).collect();
    let appender = Mutex::new(table::Appender::open(&path, &header)?);
    let base = base_of(study);
    let outcome = Mutex::new(Outcome {
        table: path.clone(),
        total,
        mine: mine.len(),
        skipped: mine.len() - todo.len(),
        ..Outcome::default()
    });
    let write_error = Mutex::new(None);
    todo.par_iter().for_each(|&index| {
        if cancel.load(Ordering::SeqCst) {
            return;
        }
        let run = &study.run(index);
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
    // the rows taken (a damaged row of a resumed table is dropped here, and said so; its run
    // was made again)
    let checked = verify::table(&path, &record, &mine)?;
    let mut o = outcome.into_inner().unwrap_or_else(|p| p.into_inner());
    o.notes = checked
        .problems
        .iter()
        .filter(|p| matches!(p, Problem::Row { .. } | Problem::Cut { .. }))
        .map(|p| format!("{}: row dropped", p.describe(&path)))
        .collect();
    let records = table::write_sorted(&path, &header, checked.rows)?;
    tally(&mut o, &header, &records);
    o.complete = records.len() == record.table_runs;
    o.interrupted = cancel.load(Ordering::SeqCst) && !o.complete;
    if opts.shard.is_none() && o.complete {
        let name = study.path.file_name().map(|n| n.to_string_lossy());
        o.parquet = Some(write_parquet(
            &path,
            &header,
            &records,
            &study.axes,
            name.as_deref(),
        )?);
    }
    o.wall_s = clock.elapsed().as_secs_f64();
    Ok(o)
}

/// A row's run index.
fn run_of(r: &csv::StringRecord) -> Option<usize> {
    r.get(0).and_then(|v| v.parse().ok())
}

/// Count the table's rows and those that failed, and name the first failure.
fn tally(o: &mut Outcome, header: &csv::StringRecord, records: &[csv::StringRecord]) {
    let col = |name: &str| header.iter().position(|h| h == name);
    let (status, error) = (col("status"), col("error"));
    o.rows = records.len();
    let failed: Vec<&csv::StringRecord> = records
        .iter()
        .filter(|r| status.and_then(|i| r.get(i)) == Some("failed"))
        .collect();
    o.rows_failed = failed.len();
    o.first_failure = failed.first().map(|r| {
        format!(
            "run {}: {}",
            r.get(0).unwrap_or("?"),
            error.and_then(|i| r.get(i)).unwrap_or("")
        )
    });
}

/// The study's name: its file's stem (the rows' `scenario` column).
pub(crate) fn study_name(study: &Study) -> String {
    study
        .path
        .file_stem()
        .map_or("study".into(), |s| s.to_string_lossy().into_owned())
}

/// The study's base: its name (the study file's stem) and where its scenario's relative
/// paths resolve.
fn base_of(study: &Study) -> Base {
    let name = study_name(study);
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
    let mut counts = std::collections::BTreeMap::<usize, Vec<usize>>::new();
    for p in shards {
        let (i, n) = shard_of_name(p).ok_or_else(|| SweepError::Table {
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
/// with its study record and its typed copy `dir/runs.parquet`. Each shard table is read
/// against its study record (`shard-I-of-N.study.json`): the shards must be of one study and
/// one split, and each must hold every run of its shard and nothing else, each row whole. Any
/// problem refuses the collect and nothing is written ([`SweepError::Collect`] names every
/// file and line). Returns the CSV table and its number of rows.
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
    // each problem with the file it is in
    let mut problems: Vec<(PathBuf, String)> = Vec::new();
    let mut first: Option<(PathBuf, Record, Vec<Vec<usize>>)> = None;
    let mut records = Vec::new();
    for p in &shards {
        let rp = record::path_of(p);
        let r = match Record::read(&rp) {
            Ok(Some(r)) => r,
            Ok(None) => {
                let why = format!(
                    "{}: no study record beside it ({} is missing); make the shard again",
                    p.display(),
                    rp.display()
                );
                problems.push((p.clone(), why));
                continue;
            }
            Err(e) => {
                problems.push((p.clone(), e.to_string()));
                continue;
            }
        };
        let named = shard_of_name(p);
        let recorded = r.shard.map(|s| (s.index, s.count));
        let Some((index, count)) = named.filter(|n| recorded == Some(*n)) else {
            let why = format!(
                "{}: the record is of {}, not of this shard's table",
                rp.display(),
                recorded.map_or("the whole study".into(), |(i, n)| format!("shard {i}/{n}"))
            );
            problems.push((p.clone(), why));
            continue;
        };
        match &first {
            Some((fp, f, _)) => {
                let d = f.whole().differences(&r.whole());
                if !d.is_empty() {
                    let why = format!(
                        "{} was made by another study than {} ({})",
                        p.display(),
                        fp.display(),
                        d.join("; ")
                    );
                    problems.push((p.clone(), why));
                    continue;
                }
            }
            None => first = Some((p.clone(), r.clone(), Shard::deal(count, r.runs))),
        }
        let dealt = first.as_ref().map(|f| &f.2[index]);
        let checked = verify::table(p, &r, dealt.map_or(&[][..], Vec::as_slice))?;
        problems.extend(checked.problems.iter().map(|x| (p.clone(), x.describe(p))));
        records.extend(checked.rows);
    }
    if !problems.is_empty() {
        return Err(SweepError::Collect {
            dir: dir.to_path_buf(),
            problems,
        });
    }
    let whole = first
        .ok_or_else(|| SweepError::NothingToCollect(dir.to_path_buf()))?
        .1
        .whole();
    let header = csv::StringRecord::from(whole.columns.clone());
    let path = table_path(dir);
    let records = table::write_sorted(&path, &header, records)?;
    whole.write(&record::path_of(&path))?;
    let name = Path::new(&whole.study)
        .file_name()
        .map(|n| n.to_string_lossy());
    write_parquet(
        &path,
        &header,
        &records,
        &whole.content.axes,
        name.as_deref(),
    )?;
    Ok((path, records.len()))
}

/// (I, N) of a shard table's name `shard-I-of-N.csv`.
fn shard_of_name(p: &Path) -> Option<(usize, usize)> {
    let name = p.file_stem()?.to_str()?.strip_prefix("shard-")?;
    let (i, n) = name.split_once("-of-")?;
    Some((i.parse().ok()?, n.parse().ok()?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_refused_collect_lists_the_first_problems_then_how_many_more_in_each_file() {
        let (a, b) = (
            PathBuf::from("d/shard-0-of-2.csv"),
            PathBuf::from("d/shard-1-of-2.csv"),
        );
        let mut problems: Vec<(PathBuf, String)> = (0..PROBLEMS_SHOWN + 3)
            .map(|i| (a.clone(), format!("d/shard-0-of-2.csv line {}: bad", i + 2)))
            .collect();
        problems.push((b.clone(), "d/shard-1-of-2.csv: empty file".into()));
        let e = SweepError::Collect {
            dir: "d".into(),
            problems,
        }
        .to_string();
        assert!(e.starts_with("d: cannot collect the shard tables whole, nothing written; 54 problems:\n  d/shard-0-of-2.csv line 2: bad\n"), "{e}");
        assert!(e.contains("line 51: bad\n"), "{e}");
        assert!(!e.contains("line 52: bad"), "{e}");
        assert!(
            e.ends_with("… and 4 more: 3 in d/shard-0-of-2.csv, 1 in d/shard-1-of-2.csv"),
            "{e}"
        );
    }
}
