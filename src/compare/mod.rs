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
use std::time::Instant;
use thiserror::Error;

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
}

impl Study {
    /// Refuse an empty study.
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
        self.bases.len() * self.methods.len() * self.auvs.len() * self.seeds.len() + files
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
    study.validate()?;
    let mut rows = Vec::with_capacity(study.runs());
    for base in &study.bases {
        for &n in &study.auvs {
            for &seed in &study.seeds {
                let sets = [format!("team.auvs={n}"), format!("seed={seed}")];
                let s = with_overrides(&base.scenario, &base.name, &sets).map_err(|source| {
                    CompareError::Scenario {
                        base: base.name.clone(),
                        source: Box::new(source),
                    }
                })?;
                for &method in &study.methods {
                    let planned = plan_one(base, &s, Made::By(method));
                    progress(rows.len(), &planned);
                    rows.push(planned.row);
                }
                if let Some(dir) = &study.waypoints {
                    let file = dir.join(waypoints_name(&base.name, n, seed));
                    if file.exists() {
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
