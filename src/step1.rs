//! Step 1 of Section IV-A: problem P2 — energy-efficient, floor-following, collision-free paths
//! for the USV and the AUVs, with the graph terms of P1 relaxed.
//!
//!   OF2:  min Σ_k ( w1·OF1_1 + w2·OF1_2 ) − w8·OF1_8     (or + w8_2·OF1_8_2)
//!   s.t.  C2_1 = C1_1…C1_7, C2_2 (floor clearance), C1_14 (heading rate)
//!
//! The variables, constraints and objective live in `team` (P5 shares them); P2 is the team
//! problem without acoustic links, started from the formation guess of
//! `TeamProblem::initial_guess` (Algorithm 1, line 9).

use crate::planner::PlanError;
use crate::scp::ScpOutcome;
use crate::team::TeamProblem;
use crate::trajectory::Trajectory;

/// Solve P2 for the window of `problem` (built without links). `heading` is the USV's course at
/// the end of the previous window, if any: the first guess continues it.
pub fn solve(
    problem: &mut TeamProblem,
    heading: Option<f64>,
) -> Result<ScpOutcome<Trajectory>, PlanError> {
    let guess = problem.initial_guess(heading);
    problem.solve(guess)
}
