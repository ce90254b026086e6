//! The planner's error type: everything that can stop a plan, from a bad start state to a
//! convex subproblem with no feasible point, each naming the constraint or datum at fault.

use crate::conic::{ConicError, SolverStatus};
use crate::scp::ScpFailure;
use crate::seafloor::SeafloorError;
use crate::vehicle::VehicleError;
use thiserror::Error;

/// The step of Algorithm 1 whose team problem failed: Step 1 (P2) or Step 3 (P5).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Step {
    /// Step 1: problem P2 (Algorithm 1, line 9).
    One,
    /// Step 3: problem P5 (Algorithm 1, line 17).
    Three,
}

impl std::fmt::Display for Step {
    /// "step1" or "step3", as errors and the plan file name them.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Step::One => "step1",
            Step::Three => "step3",
        })
    }
}

/// Errors of planning.
#[derive(Debug, Error)]
pub enum PlanError {
    /// The seafloor could not be loaded or queried.
    #[error(transparent)]
    Seafloor(#[from] SeafloorError),
    /// The vehicle parameters give no valid model.
    #[error(transparent)]
    Vehicle(#[from] VehicleError),
    /// The conic solver rejected the problem data.
    #[error(transparent)]
    Conic(#[from] ConicError),
    /// The state a window starts from breaks a constraint no input can change.
    #[error("the start of window {window} is infeasible: {why}")]
    InvalidStart {
        /// The window (0-based).
        window: usize,
        /// The constraint and the vehicle that breaks it.
        why: String,
    },
    /// Algorithm 1, line 5 found no AUV start point.
    #[error("no initial AUV position can be drawn (Algorithm 1, line 5): {0}")]
    NoInitialPosition(String),
    /// A convex solve ended without a usable solution.
    #[error("{step}: the convex subproblem failed: Clarabel status {status} after {iterations} interior-point iterations")]
    Solver {
        /// The step whose subproblem it was.
        step: Step,
        /// How the solve ended.
        status: SolverStatus,
        /// Interior-point iterations.
        iterations: u32,
    },
    /// A convex solve's solution, rolled through the vehicle models, breaks a constraint that
    /// the model holds hard (C1_4, C1_5/C1_6, the grid, the speed limits) by more than the
    /// checker allows: the solver's accuracy, not the problem. The SCP retries it with a
    /// smaller trust region, as it does a solve in numerical trouble.
    #[error("{step}: the convex solver's solution (Clarabel status {status}) breaks {constraint} by {excess:.3e} once rolled through the vehicle models, beyond the model's margin and the checker's tolerance")]
    Inexact {
        /// The step whose subproblem it was.
        step: Step,
        /// How the solve ended.
        status: SolverStatus,
        /// Which hard constraint: "a length (C1_4, C1_5/C1_6 or the grid), m" or "a speed
        /// limit, m/s".
        constraint: &'static str,
        /// By how much, in the constraint's unit.
        excess: f64,
    },
    /// A convex subproblem has no feasible point.
    #[error("{step}: the convex subproblem is infeasible (Clarabel status {status}); {}", culprit_text(.culprit))]
    ConvexInfeasible {
        /// The step whose subproblem it was.
        step: Step,
        /// How the solve ended.
        status: SolverStatus,
        /// The first constraint group without which it becomes feasible, if one is.
        culprit: Option<String>,
    },
    /// A constraint stays violated when the SCP has converged with its largest penalty.
    #[error("{step}: a constraint cannot hold: {detail}")]
    Infeasible {
        /// The step whose problem it was.
        step: Step,
        /// The constraint, the vehicle, the step and the position.
        detail: String,
    },
    /// A constraint is still violated when the SCP stops at its iteration limit.
    #[error("{step}: stopped at its iteration limit ({limit} = {iterations}) with a constraint still violated: {detail}; raise {limit}")]
    Unfinished {
        /// The step whose problem it was.
        step: Step,
        /// The key that set the limit: scp.max_iterations or scp.step1_max_iterations.
        limit: String,
        /// The iterations made.
        iterations: usize,
        /// The constraint, the vehicle, the step and the position.
        detail: String,
    },
    /// A planned link keeps no line of sight however far its band is lowered (C1_13).
    #[error("step3: the {link} has no line of sight at step {k} after {rounds} rounds of lowering its range (C1_13): {why}")]
    LineOfSight {
        /// "A2U link AUV 2–USV" or "A2A edge AUV 1–AUV 4".
        link: String,
        /// The time step.
        k: usize,
        /// Rounds of the line-of-sight loop run.
        rounds: usize,
        /// What blocks it.
        why: String,
    },
    /// An AUV reaches the USV through no chain of links in range and in sight.
    #[error("the acoustic chain breaks at window {window}, step {k}: {why}")]
    Disconnected {
        /// The window (0-based).
        window: usize,
        /// The time step.
        k: usize,
        /// Which AUV is cut off, and where.
        why: String,
    },
    /// The SCP loop itself failed.
    #[error(transparent)]
    Scp(#[from] ScpFailure),
    /// The RRT-like baseline (`shoal plan --method rrt-like`) found no valid sample from any
    /// node of its tree at one step.
    #[error(
        "the RRT-like tree found no valid team sample at window {window}, step {k}: {nodes} \
         node(s) drew {drawn} vehicle samples, rejected by {why}; raise sampling.attempts or \
         sampling.samples, or ease the constraint named"
    )]
    NoValidTree {
        /// The window (0-based).
        window: usize,
        /// The step k (1..=K) at which every sample failed.
        k: usize,
        /// Nodes of the tree at step k − 1.
        nodes: usize,
        /// Vehicle draws made at step k.
        drawn: u64,
        /// The constraints that rejected the draws, most first, with their counts.
        why: String,
    },
    /// A waypoints file (`shoal plan --waypoints`) cannot be read or does not fit the scenario.
    #[error("{path}: {why}")]
    Waypoints {
        /// The file.
        path: String,
        /// What is wrong, naming the field.
        why: String,
    },
}

fn culprit_text(c: &Option<String>) -> String {
    match c {
        Some(c) => format!("it becomes feasible without {c}, so that constraint cannot hold"),
        None => "no single constraint group is to blame: several conflict".into(),
    }
}
