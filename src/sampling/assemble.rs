//! A sampled window as the plan records it: the same stages, graph, links and metrics as the
//! MPC's windows, so `shoal check`, `plot`, `view`, `export` and `simulate` read it unchanged.
//!
//! Step 1 and the final stage hold the same paths (status "sampled", no SCP log); their
//! objective is P2's at those paths. Step 2's graph is P3's A2U link (the AUV nearest the USV)
//! and the sampled chain as the A2A path at k = 1..=K; at k = 0, the fixed start, the chain
//! [`validity::find_chain`] finds, or P4's path where there is none in range. The links' bands
//! are P5's [ρ·d_s − d_t, ρ·d_s] (the paper's with ρ = `acoustic.link_margin` = 1); a sampled
//! link shorter than ρ·d_s − d_t is listed out of its band, as the MPC's are.

use super::validity::{self, Limits};
use crate::error::PlanError;
use crate::metrics::{first_cut_off, window_metrics};
use crate::plan::{Graph, LinkReport, ObjectiveTerms, SamplingReport, Stage, Window, SAMPLED};
use crate::planner::metric_params;
use crate::scenario::Scenario;
use crate::seafloor::Seafloor;
use crate::step2::p3_a2u::a2u_link;
use crate::step2::p4_hamiltonian::longest_path_avoiding;
use crate::team::{LinkSet, TeamProblem};
use crate::trajectory::Trajectory;

/// A window found by a sampling planner.
pub struct Sampled<'a> {
    /// The window's index.
    pub index: usize,
    /// The team's paths, k = 0..=K.
    pub trajectory: &'a Trajectory,
    /// The AUVs' chain order at k = 1..=K (index k − 1).
    pub chains: &'a [Vec<usize>],
    /// The window's P2 (its objective is recorded).
    pub problem: &'a TeamProblem<'a>,
    /// Wall-clock time of the search, seconds (recorded as Step 1's).
    pub time_s: f64,
    /// What the search did.
    pub report: SamplingReport,
    /// Refuse a window with an AUV cut off from the USV ([`PlanError::Disconnected`]); false
    /// for another planner's paths, which are recorded as they are for `shoal check` to judge.
    pub require_connected: bool,
}

/// The window record of a sampled window; [`PlanError::Disconnected`] if an AUV is cut off
/// from the USV at some step.
pub fn window(s: &Scenario, floor: &Seafloor, w: Sampled) -> Result<Window, PlanError> {
    let t = w.trajectory;
    let terms = w.problem.terms(t);
    let stage = Stage {
        status: SAMPLED.into(),
        iterations: 0,
        solve_time_s: w.time_s,
        objective: ObjectiveTerms {
            energy: terms.energy,
            depth: terms.depth,
            height: terms.height,
            usv: terms.usv,
            total: w.problem.objective(&terms),
            ..ObjectiveTerms::default()
        },
        max_violation: 0.0,
        usv: t.usv_path(),
        auvs: t.auv_paths(s.auv.min_heading_speed),
        scp: Vec::new(),
    };
    let graph = graph(s, floor, t, w.chains);
    // the bands top at ρ·d_s, as P5's (`acoustic.link_margin`)
    let top = s.acoustic.link_margin * s.acoustic.sonar_range;
    let set = LinkSet::from_graph(&graph, top, s.acoustic.band_tolerance);
    let out_of_band = crate::step3::out_of_band(&set, t);
    let links = LinkReport {
        links: set.links,
        bands: set.bands,
        out_of_band,
        los_rounds: 0,
        bridges: Vec::new(),
    };
    let params = metric_params(s);
    let cut_off = first_cut_off(&stage, floor, &params).filter(|_| w.require_connected);
    if let Some((k, n)) = cut_off {
        let p = stage.auvs[n].position[k];
        return Err(PlanError::Disconnected {
            window: w.index,
            k,
            why: format!(
                "AUV {n} at ({:.1}, {:.1}, {:.1}) reaches the USV through no chain of links \
                 within d_s = {} m with line of sight",
                p[0], p[1], p[2], s.acoustic.sonar_range
            ),
        });
    }
    let metrics = window_metrics(&stage, &links.links, floor, &params, [w.time_s, 0.0, 0.0]);
    Ok(Window {
        index: w.index,
        start_time: w.index as f64 * s.horizon.steps as f64 * s.horizon.dt,
        courses: Vec::new(),
        // the search's time is Step 1's; the final stage is the same paths, found once
        final_: Stage {
            solve_time_s: 0.0,
            ..stage.clone()
        },
        step1: stage,
        graph,
        links,
        metrics,
        sampling: Some(w.report),
    })
}

/// P3's A2U link and the chain as the A2A path, every step.
fn graph(s: &Scenario, floor: &Seafloor, t: &Trajectory, chains: &[Vec<usize>]) -> Graph {
    let l = Limits::of(s);
    let steps = t.usv_p.len();
    let mut g = Graph {
        a2u: Vec::with_capacity(steps),
        a2a: Vec::with_capacity(steps),
        exact: false,
        solve_time_s: 0.0,
    };
    for k in 0..steps {
        let points: Vec<[f64; 3]> = t.auv_p.iter().map(|p| p[k]).collect();
        g.a2u.push(a2u_link(t.usv_p[k], &points).unwrap_or(0));
        let order = match k.checked_sub(1).and_then(|i| chains.get(i)) {
            Some(order) => order.clone(),
            None => validity::find_chain(&l, floor, t.usv_p[k], &points).unwrap_or_else(|_| {
                let far = |i: usize, j: usize| validity::link(&l, floor, points[i], points[j]);
                longest_path_avoiding(&points, |i, j| far(i, j).is_err()).order
            }),
        };
        g.a2a.push(validity::chain_edges(&order));
    }
    g
}
