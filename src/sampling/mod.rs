//! The paper's sampling baseline (Section V, Fig. 6, Remark III.1): an RRT-like planner that,
//! "for every time step k = 1:K", draws 𝔯 valid random samples of the team's next waypoints
//! from every node of a tree and keeps the tree of best score in energy (OF1_1), floor-hugging
//! (OF1_2) and convergence (OF1_8_2, or OF1_8 as the scenario says). `shoal plan --method
//! rrt-like` runs it; its plans have the same format as the MPC's and pass the same `shoal
//! check`.
//!
//! What the paper leaves open and what we chose (docs/baseline.md says why):
//! - a sample is a vehicle's next velocity; the model then fixes its input and waypoint
//!   exactly ([`draw`]);
//! - the USV is sampled too, its velocity uniform on its speed disc (eq. (9));
//! - the team's samples keep the acoustic chain at every step by construction (`tree.rs`);
//! - the tree keeps at most `sampling.tree_budget` nodes per step, the best by running cost
//!   plus the USV's term (the full tree has Σ_k 𝔯^k nodes);
//! - windows follow one another as Algorithm 1's do (line 7).
//!
//! Every draw is from one ChaCha8 stream seeded by the scenario's `seed`: the same scenario
//! gives the same plan.

mod assemble;
pub mod draw;
mod tree;
pub mod validity;
pub mod waypoints;

pub use assemble::{window, Sampled};
pub use tree::Grown;

use crate::error::PlanError;
use crate::mission::{check_start, next_window};
use crate::plan::{Plan, SamplingStep, METHOD_RRT_LIKE};
use crate::planner::{Provenance, Setup};
use crate::scenario::Scenario;
use crate::seafloor::Seafloor;
use crate::team::TeamProblem;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::time::Instant;

/// The ChaCha stream of the baseline's draws (the initial state draws from stream 0).
const STREAM: u64 = 0x0052_5254;

/// What the baseline reports as it goes: a step of a window's tree has ended.
#[derive(Debug, Clone, Copy)]
pub struct StepDone<'a> {
    /// The window (0-based).
    pub window: usize,
    /// The step k (1..=K).
    pub k: usize,
    /// Draws, valid children, nodes kept and time of the step.
    pub step: &'a SamplingStep,
}

/// Plan every window of `s` over `floor` with the RRT-like baseline.
pub fn plan(
    s: &Scenario,
    floor: &Seafloor,
    provenance: &Provenance,
    progress: &mut dyn FnMut(StepDone),
) -> Result<Plan, PlanError> {
    let setup = Setup::of(s, floor)?; // Algorithm 1, line 5
    let (auv, usv, keep_out) = (setup.model.auv, setup.model.usv, &setup.keep_out);
    let mut start = setup.start();
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
    rng.set_stream(STREAM);
    let mut windows = Vec::with_capacity(s.windows);
    let mut track: Vec<[f64; 2]> = Vec::new();
    for w in 0..s.windows {
        check_start(s, floor, keep_out, &start, w)?;
        let more = s.horizon.terminal_margin && w + 1 < s.windows;
        let problem = TeamProblem::new(s, floor, keep_out, auv, usv, start.clone())
            .with_track(&track)
            .with_terminal(more);
        let clock = Instant::now();
        let grown = tree::Tree {
            scenario: s,
            floor,
            auv,
            usv,
            rng: &mut rng,
            problem: &problem,
        }
        .grow(w, &start, &mut |k, step| {
            progress(StepDone { window: w, k, step })
        })?;
        let time_s = clock.elapsed().as_secs_f64();
        let t = &grown.trajectory;
        windows.push(window(
            s,
            floor,
            Sampled {
                index: w,
                trajectory: t,
                chains: &grown.chains,
                problem: &problem,
                time_s,
                report: grown.report.clone(),
                require_connected: true,
            },
        )?);
        track.extend_from_slice(&t.usv_p);
        start = next_window(t, None).0; // line 7
    }
    Ok(setup.plan(s, floor, provenance, METHOD_RRT_LIKE, windows))
}

#[cfg(test)]
mod tests;
