//! Text reports of a plan for the terminal.

use crate::plan::Plan;
use std::fmt::Write as _;

/// One row per window: Step 1's status, SCP iterations, objective terms and time, plus the team's
/// mean depth and the USV's progress.
pub fn summary_table(plan: &Plan) -> String {
    let mut t = String::new();
    let _ = writeln!(
        t,
        "{:>6} {:>10} {:>5} {:>12} {:>10} {:>10} {:>12} {:>9} {:>10}",
        "window", "status", "iter", "energy", "mean z", "USV moved", "objective", "time s", "viol"
    );
    let _ = writeln!(
        t,
        "{:>6} {:>10} {:>5} {:>12} {:>10} {:>10} {:>12} {:>9} {:>10}",
        "", "", "", "(m/s²)²", "m", "m", "", "", "m | rad"
    );
    for w in &plan.windows {
        let st = &w.step1;
        let n = st.auvs.len().max(1) as f64;
        let k = st.usv.input.len().max(1) as f64;
        let p0 = st.usv.position.first().copied().unwrap_or([0.0; 2]);
        let pk = st.usv.position.last().copied().unwrap_or([0.0; 2]);
        let _ = writeln!(
            t,
            "{:>6} {:>10} {:>5} {:>12.4} {:>10.1} {:>10.1} {:>12.2} {:>9.3} {:>10.1e}",
            w.index,
            st.status,
            st.iterations,
            st.objective.energy,
            st.objective.depth / (n * k),
            (pk[0] - p0[0]).hypot(pk[1] - p0[1]),
            st.objective.total,
            st.solve_time_s,
            st.max_violation
        );
    }
    t
}
