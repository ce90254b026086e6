//! `shoal compare`: the paper's comparison (Section V, Fig. 6) measured. The MPC (Algorithm 1)
//! and the RRT-like baseline plan the same scenarios (team sizes × seeds × floors); every plan
//! is checked by `shoal check`; one row per run records wall time, the objective's terms, the
//! check's margins, the explored area and the chain ([`Row`]); [`summary`] groups them.

mod row;
mod summary;

pub use row::Row;
pub use summary::{markdown, summary, Group};

use crate::check::check_plan;
use crate::error::PlanError;
use crate::mission::scenario_floor;
use crate::plan::Plan;
use crate::planner::{Planner, Provenance};
use crate::sampling::waypoints::{self, WaypointsFile};
use crate::scenario::{with_overrides, Scenario, ScenarioError};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;
use thiserror::Error;

/// The most runs one study may make: a `shoal sweep` study (the product of its axes) or a
/// `shoal compare` comparison (scenarios × team sizes × seeds × planners). A study's size is
/// computed before anything is made, and a larger one is refused (docs/sweep.md): a study past
/// it would take weeks on a cluster, and its list of runs alone would fill the memory.
pub const MAX_RUNS: usize = 1_000_000;

/// `n` with its digits in groups of three, spaces between ("1 000 000").
pub(crate) fn grouped(n: u128) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(' ');
        }
        out.push(c);
    }
    out
}

/// The planners a study compares.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Method {
    /// Algorithm 1 (Steps 1–3 by sequential convex programming).
    Mpc,
    /// The paper's RRT-like baseline (`crate::sampling`).
    RrtLike,
}

impl Method {
    /// "mpc" or "rrt-like", as plans record it.
    pub fn name(self) -> &'static str {
        match self {
            Method::Mpc => crate::plan::METHOD_MPC,
            Method::RrtLike => crate::plan::METHOD_RRT_LIKE,
        }
    }
}

/// One floor of a study: a base scenario (its floor, start and every other key) and a name.
#[derive(Debug, Clone, PartialEq)]
pub struct Base {
    /// The name rows carry: "default" or the scenario file's stem.
    pub name: String,
    /// The scenario, before each run's team size and seed.
    pub scenario: Scenario,
    /// Where a scenario's relative `seafloor.file` is found.
    pub dir: PathBuf,
}

/// A comparison: every method on every base × team size × seed.
#[derive(Debug, Clone, PartialEq)]
pub struct Study {
    /// The scenarios (floors) compared on.
    pub bases: Vec<Base>,
    /// The planners.
    pub methods: Vec<Method>,
    /// Team sizes N.
    pub auvs: Vec<usize>,
    /// Seeds (the start and, on the synthetic floor, the floor).
    pub seeds: Vec<u64>,
    /// A directory of other planners' waypoints files, `BASE-nN-sSEED.json` (e.g. made by
    /// scripts/ompl_compare.sh): each run that has one gets a row of the file's method too.
    pub waypoints: Option<PathBuf>,
}

impl Default for Study {
    /// The study on the embedded default: MPC and RRT-like, N = 1, 3, 5, seeds 1–10.
    fn default() -> Self {
        Study {
            bases: vec![Base {
                name: "default".into(),
                scenario: Scenario::default(),
                dir: PathBuf::from("."),
            }],
            methods: vec![Method::Mpc, Method::RrtLike],
            auvs: vec![1, 3, 5],
            seeds: (1..=10).collect(),
            waypoints: None,
        }
    }
}

/// Errors of a study as a whole (a run's own failure is recorded in its row).
#[derive(Debug, Error)]
pub enum CompareError {
    /// The study has nothing to run.
    #[error("the study is empty: {0}")]
    Empty(&'static str),
    /// A run's scenario (base, team size, seed) is invalid.
    #[error("{base}: {source}")]
    Scenario {
        /// The base's name.
        base: String,
        /// Why.
        #[source]
        source: Box<ScenarioError>,
    },
    /// The seeds as `--seeds` takes them cannot be read, or are too many.
    #[error("--seeds {text}: {why}")]
    Seeds {
        /// The text given.
        text: String,
        /// What is wrong, and what is allowed.
        why: String,
    },
    /// The study makes more than [`MAX_RUNS`] runs.
    #[error(
        "{factors} make {runs} runs; a comparison has at most {max} runs (docs/sweep.md)",
        runs = grouped(*.runs), max = grouped(MAX_RUNS as u128)
    )]
    TooManyRuns {
        /// Its factors, e.g. "1 scenario × 2 planners × 3 team sizes × 1 000 000 seeds".
        factors: String,
        /// Their product (saturated at u128::MAX).
        runs: u128,
    },
    /// An output cannot be written.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
}

/// The seeds of `--seeds`: a list ("1,4,7") or a range of whole numbers, both ends included
/// ("1-10"). A range is counted from its ends before it is made: one of more than [`MAX_RUNS`]
/// seeds is refused (each seed is at least one run).
pub fn parse_seeds(text: &str) -> Result<Vec<u64>, CompareError> {
    let bad = |why: String| CompareError::Seeds {
        text: text.to_string(),
        why,
    };
    let num = |t: &str| {
        t.trim().parse::<u64>().map_err(|_| {
            bad(format!(
                "\"{}\" is not a whole number from 0 to {}; give a list (1,4,7) or a range (1-10)",
                t.trim(),
                u64::MAX
            ))
        })
    };
    let too_many = |n: u128| {
        bad(format!(
            "{} seeds; a comparison has at most {} runs (docs/sweep.md)",
            grouped(n),
            grouped(MAX_RUNS as u128)
        ))
    };
    match text.split_once('-') {
        Some((a, b)) => {
            let (a, b) = (num(a)?, num(b)?);
            if a > b {
                return Err(bad(format!("the range runs backwards ({a} > {b})")));
            }
            let n = u128::from(b - a) + 1;
            if n > MAX_RUNS as u128 {
                return Err(too_many(n));
            }
            Ok((a..=b).collect())
        }
        None => {
            let seeds = text.split(',').map(num).collect::<Result<Vec<_>, _>>()?;
            if seeds.len() > MAX_RUNS {
                return Err(too_many(seeds.len() as u128));
            }
            Ok(seeds)
        }
    }
}

/// "3 team sizes" or "1 team size".
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{} {}", grouped(n as u128), if n == 1 { one } else { many })
}

impl Study {
    /// Refuse an empty study, and one of more than [`MAX_RUNS`] runs (its size computed from
    /// its factors with checked arithmetic; a directory of waypoints files counts as one more
    /// planner).
    pub fn validate(&self) -> Result<(), CompareError> {
        for (empty, what) in [
            (self.bases.is_empty(), "no scenario"),
            (self.methods.is_empty(), "no method"),
            (self.auvs.is_empty(), "no team size"),
            (self.seeds.is_empty(), "no seed"),
        ] {
            if empty {
                return Err(CompareError::Empty(what));
            }
        }
        let planners = self.methods.len() + usize::from(self.waypoints.is_some());
        let sizes = [
            self.bases.len(),
            planners,
            self.auvs.len(),
            self.seeds.len(),
        ];
        let runs = sizes
            .iter()
            .try_fold(1u128, |p, &n| p.checked_mul(n as u128))
            .unwrap_or(u128::MAX);
        if runs > MAX_RUNS as u128 {
            let factors = [
                count(sizes[0], "scenario", "scenarios"),
                count(sizes[1], "planner", "planners"),
                count(sizes[2], "team size", "team sizes"),
                count(sizes[3], "seed", "seeds"),
            ];
            return Err(CompareError::TooManyRuns {
                factors: factors.join(" × "),
                runs,
            });
        }
        Ok(())
    }

    /// Make every (base, team size) scenario once, before any run, so that a team size the
    /// scenario does not allow is refused at once rather than after the runs before it.
    fn preflight(&self) -> Result<(), CompareError> {
        let seed = self.seeds.first().copied().unwrap_or(0);
        for base in &self.bases {
            for &n in &self.auvs {
                let sets = [format!("team.auvs={n}"), format!("seed={seed}")];
                with_overrides(&base.scenario, &base.name, &sets).map_err(|source| {
                    CompareError::Scenario {
                        base: base.name.clone(),
                        source: Box::new(source),
                    }
                })?;
            }
        }
        Ok(())
    }

    /// How many runs the study makes: every method's, and one per waypoints file present.
    pub fn runs(&self) -> usize {
        let files = match &self.waypoints {
            Some(dir) => self
                .bases
                .iter()
                .flat_map(|b| self.auvs.iter().map(move |n| (b, n)))
                .flat_map(|(b, n)| self.seeds.iter().map(move |seed| (b, n, seed)))
                .filter(|(b, n, seed)| dir.join(waypoints_name(&b.name, **n, **seed)).exists())
                .count(),
            None => 0,
        };
        // within MAX_RUNS once validated; saturating, so that an unvalidated study cannot
        // overflow here
        [
            self.bases.len(),
            self.methods.len(),
            self.auvs.len(),
            self.seeds.len(),
        ]
        .iter()
        .fold(1usize, |p, &n| p.saturating_mul(n))
        .saturating_add(files)
    }
}

/// One run as planned: its key, its plan (or why there is none) and its wall time.
pub struct Planned {
    /// The row's key and measures.
    pub row: Row,
    /// The plan, when one was made.
    pub plan: Option<Plan>,
    /// The floor it was made over.
    pub floor: Option<crate::seafloor::Seafloor>,
}

/// Run every (base, N, seed, method) of `study`, in that order; `progress` hears of each run as
/// it ends (with the run's index from 0), and may keep its plan.
pub fn run(
    study: &Study,
    progress: &mut dyn FnMut(usize, &Planned),
) -> Result<Vec<Row>, CompareError> {
    run_until(study, &AtomicBool::new(false), progress)
}

/// [`run`], stopping before the next run once `cancel` is set: the rows of the runs that
/// finished, fewer than [`Study::runs`] when it was cancelled.
pub fn run_until(
    study: &Study,
    cancel: &AtomicBool,
    progress: &mut dyn FnMut(usize, &Planned),
) -> Result<Vec<Row>, CompareError> {
    study.validate()?;
    study.preflight()?;
    let mut rows = Vec::with_capacity(study.runs());
    let stop = || cancel.load(Ordering::SeqCst);
    for base in &study.bases {
        for &n in &study.auvs {
            for &seed in &study.seeds {
                if stop() {
                    return Ok(rows);
                }
                let sets = [format!("team.auvs={n}"), format!("seed={seed}")];
                let s = with_overrides(&base.scenario, &base.name, &sets).map_err(|source| {
                    CompareError::Scenario {
                        base: base.name.clone(),
                        source: Box::new(source),
                    }
                })?;
                for &method in &study.methods {
                    if stop() {
                        return Ok(rows);
                    }
                    let planned = plan_one(base, &s, Made::By(method));
                    progress(rows.len(), &planned);
                    rows.push(planned.row);
                }
                if let Some(dir) = &study.waypoints {
                    let file = dir.join(waypoints_name(&base.name, n, seed));
                    if file.exists() && !stop() {
                        let planned = plan_one(base, &s, Made::From(&file));
                        progress(rows.len(), &planned);
                        rows.push(planned.row);
                    }
                }
            }
        }
    }
    Ok(rows)
}

/// The files of a comparison's rows in `out`: `runs.csv` (one row per run) and `summary.md` (the
/// groups of [`summary`]), each written whole. When `rows` are fewer than the study's `total`
/// runs (it was interrupted), summary.md says so first. Returns the files and the summary.
pub fn write_tables(
    out: &Path,
    rows: &[Row],
    total: usize,
) -> Result<(PathBuf, PathBuf, String), CompareError> {
    let csv_path = out.join("runs.csv");
    let to_output = |e: std::io::Error| crate::output::OutputError::Write {
        path: csv_path.clone(),
        source: e,
    };
    let mut csv = csv::Writer::from_writer(Vec::new());
    for r in rows {
        csv.serialize(r)
            .map_err(|e| to_output(std::io::Error::other(e)))?;
    }
    if rows.is_empty() {
        // the header alone, so that the file is a table even with no finished run
        let (names, _) = crate::sweep::table::row_fields(&Row::key("", "", 0, 0));
        csv.write_record(&names)
            .map_err(|e| to_output(std::io::Error::other(e)))?;
    }
    let bytes = csv
        .into_inner()
        .map_err(|e| to_output(std::io::Error::other(e.to_string())))?;
    crate::output::write_atomic(&csv_path, &bytes)?;
    let mut table = markdown(&summary(rows));
    if rows.len() < total {
        table = format!(
            "**Incomplete**: the comparison was interrupted after {} of its {} runs; the \
             groups below hold only the finished runs.\n\n{table}",
            rows.len(),
            total
        );
    }
    let md_path = out.join("summary.md");
    crate::output::write_atomic(&md_path, table.as_bytes())?;
    Ok((csv_path, md_path, table))
}

/// The waypoints file of a run in `Study::waypoints`: `BASE-nN-sSEED.json`.
pub fn waypoints_name(base: &str, auvs: usize, seed: u64) -> String {
    format!("{base}-n{auvs}-s{seed}.json")
}

/// How a run's plan is made: by one of shoal's planners, or from a waypoints file.
enum Made<'a> {
    By(Method),
    From(&'a Path),
}

/// A run's planner, its waypoints read.
enum Source<'a> {
    By(Method),
    From(&'a Path, WaypointsFile),
}

/// Plan scenario `s` with `method` (a relative `seafloor.file` found in `base.dir`), check
/// the plan and measure it; the row is named after `base`.
pub fn plan_and_check(base: &Base, s: &Scenario, method: Method) -> Planned {
    plan_one(base, s, Made::By(method))
}

/// Plan one run and measure it. A waypoints file's run is timed by the file's own
/// `solve_time_s` (the other planner's time), not by its import.
fn plan_one(base: &Base, s: &Scenario, made: Made) -> Planned {
    let source = match made {
        Made::By(m) => Source::By(m),
        Made::From(path) => match waypoints::read(path) {
            Ok(f) => Source::From(path, f),
            Err(e) => {
                let mut row = Row::key(&base.name, "waypoints", s.team.auvs, s.seed);
                row.fail(&e, 0.0);
                return Planned {
                    row,
                    plan: None,
                    floor: None,
                };
            }
        },
    };
    let name = match &source {
        Source::By(m) => m.name().to_string(),
        Source::From(_, f) => f.method.clone(),
    };
    let mut row = Row::key(&base.name, &name, s.team.auvs, s.seed);
    let clock = Instant::now();
    let made = scenario_floor(s, &base.dir).and_then(|(floor, source_of_floor)| {
        let provenance = Provenance {
            scenario_source: base.name.clone(),
            overrides: vec![
                format!("team.auvs={}", s.team.auvs),
                format!("seed={}", s.seed),
            ],
            seafloor: source_of_floor,
        };
        let plan = match &source {
            Source::By(Method::Mpc) => Planner::new(s, &floor).provenance(provenance).run(),
            Source::By(Method::RrtLike) => {
                crate::sampling::plan(s, &floor, &provenance, &mut |_| {})
            }
            Source::From(path, f) => {
                let name = path.display().to_string();
                waypoints::plan(s, &floor, &provenance, f, &name)
            }
        }?;
        Ok::<_, PlanError>((plan, floor))
    });
    let wall_s = match &source {
        Source::From(_, f) => f.solve_time_s,
        Source::By(_) => clock.elapsed().as_secs_f64(),
    };
    match made {
        Ok((plan, floor)) => {
            let report = check_plan(&plan, &floor);
            row.measure(&plan, &report, wall_s);
            Planned {
                row,
                plan: Some(plan),
                floor: Some(floor),
            }
        }
        Err(e) => {
            row.fail(&e, wall_s);
            Planned {
                row,
                plan: None,
                floor: None,
            }
        }
    }
}
