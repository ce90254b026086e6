//! Step 1 of Section IV-A: problem P2 — energy-efficient, floor-following, collision-free paths
//! for the USV and the AUVs, with the graph terms of P1 relaxed (Algorithm 1, line 9).
//!
//!   OF2:  min Σ_k ( w1·OF1_1 + w2·OF1_2 ) − w8·OF1_8     (or + w8_2·OF1_8_2)
//!   s.t.  C2_1 = C1_1…C1_7, C2_2 (floor clearance), C1_14 (heading rate)
//!
//! P2 is the window problem of `team` without acoustic links (every constraint family is
//! there, one file each), solved by the SCvx loop of `scp` from the formation guess of
//! `team::guess`.

use crate::conic::SolveReport;
use crate::error::PlanError;
use crate::scp::{Iteration, ScpOutcome};
use crate::team::TeamProblem;
use crate::trajectory::Trajectory;

/// Solve P2 for the window of `problem` (built without links). `heading` is the USV's course at
/// the end of the previous window, if any: the first guess continues it. `observer` hears of
/// every SCP iteration.
pub fn solve(
    problem: &mut TeamProblem,
    heading: Option<f64>,
    observer: &mut dyn FnMut(&Iteration<SolveReport>),
) -> Result<ScpOutcome<Trajectory>, PlanError> {
    let guess = problem.initial_guess(heading);
    problem.solve(guess, observer)
}
