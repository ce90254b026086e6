//! Another planner's paths as a shoal plan (`shoal plan --waypoints FILE`): a waypoints file,
//! format `shoal-waypoints/1` (docs/baseline.md), gives every vehicle's waypoint at each step;
//! the inputs and velocities follow from the vehicle model (ZOH: U\[k\] = (P\[k+1\] − P\[k\] −
//! A_p V\[k\]) / B_p per axis, from the start's velocity), the graph and metrics as for the
//! RRT-like baseline. The plan is written whatever it breaks (`shoal check` then says what),
//! except waypoints that cannot be flown at all: a coordinate that is not finite, a point off
//! the seafloor grid or beyond any depth is refused, naming the file, the vehicle and the index.
//! This is how the OMPL reference (scripts/ompl_rrt_star.py) is checked and compared.

use super::assemble::{window, Sampled};
use super::validity::{self, Limits};
use crate::error::PlanError;
use crate::mission::{check_start, next_window};
use crate::plan::{Plan, SamplingReport, METHOD_MPC};
use crate::planner::{Provenance, Setup};
use crate::scenario::Scenario;
use crate::seafloor::Seafloor;
use crate::step2::p4_hamiltonian::longest_path_avoiding;
use crate::team::TeamProblem;
use crate::trajectory::{Start, Trajectory};
use crate::vehicle::{AuvModel, UsvModel};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Value of the `format` field of a waypoints file.
pub const WAYPOINTS_FORMAT: &str = "shoal-waypoints/1";

/// A waypoints file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaypointsFile {
    /// Always [`WAYPOINTS_FORMAT`].
    pub format: String,
    /// The planner that made the paths, e.g. "ompl-rrtstar" (recorded as the plan's method).
    pub method: String,
    /// The planner's own seed, if it draws.
    #[serde(default)]
    pub seed: Option<u64>,
    /// Wall-clock time of the planner, seconds.
    #[serde(default)]
    pub solve_time_s: f64,
    /// Free text: the planner's settings.
    #[serde(default)]
    pub notes: String,
    /// One per window of the scenario, in order.
    pub windows: Vec<WaypointsWindow>,
}

/// One window's waypoints.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WaypointsWindow {
    /// P_USV\[k\], k = 0..=K.
    pub usv: Vec<[f64; 2]>,
    /// P_n\[k\], n = 0..N−1, k = 0..=K.
    pub auvs: Vec<Vec<[f64; 3]>>,
    /// States the planner sampled, if it says.
    #[serde(default)]
    pub samples_drawn: u64,
    /// States it kept (e.g. tree vertices), if it says.
    #[serde(default)]
    pub samples_kept: u64,
    /// Its time for this window, seconds.
    #[serde(default)]
    pub solve_time_s: f64,
}

/// Read a waypoints file; errors name the file and the field.
pub fn read(path: &Path) -> Result<WaypointsFile, PlanError> {
    let bad = |why: String| PlanError::Waypoints {
        path: path.display().to_string(),
        why,
    };
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read: {e}")))?;
    let file: WaypointsFile =
        serde_json::from_str(&text).map_err(|e| bad(format!("not a waypoints file: {e}")))?;
    if file.format != WAYPOINTS_FORMAT {
        return Err(bad(format!(
            "format is \"{}\"; this shoal reads \"{WAYPOINTS_FORMAT}\"",
            file.format
        )));
    }
    if file.method.is_empty() || file.method == METHOD_MPC {
        return Err(bad(format!(
            "method is \"{}\"; name the planner that made the paths (not \"\" or \"{METHOD_MPC}\")",
            file.method
        )));
    }
    Ok(file)
}

/// The plan of `file`'s paths on scenario `s` over `floor` (`path` names the file in errors).
pub fn plan(
    s: &Scenario,
    floor: &Seafloor,
    provenance: &Provenance,
    file: &WaypointsFile,
    path: &str,
) -> Result<Plan, PlanError> {
    let bad = |why: String| PlanError::Waypoints {
        path: path.to_string(),
        why,
    };
    let setup = Setup::of(s, floor)?;
    let (auv, usv, keep_out) = (setup.model.auv, setup.model.usv, &setup.keep_out);
    if auv.pu.iter().any(|&b| b <= 0.0) {
        return Err(bad(
            "auv.discretisation = \"euler\" fixes each waypoint by the velocity before it; \
             waypoints need \"zoh\""
                .into(),
        ));
    }
    if file.windows.len() != s.windows {
        return Err(bad(format!(
            "windows: {} given for the scenario's windows = {}",
            file.windows.len(),
            s.windows
        )));
    }
    let mut start = setup.start();
    let l = Limits::of(s);
    let mut windows = Vec::with_capacity(s.windows);
    let mut track: Vec<[f64; 2]> = Vec::new();
    for (w, ww) in file.windows.iter().enumerate() {
        check_start(s, floor, keep_out, &start, w)?;
        let t = trajectory(s, floor, &auv, &usv, &start, ww)
            .map_err(|why| bad(format!("windows[{w}].{why}")))?;
        let chains: Vec<Vec<usize>> = (1..t.usv_p.len())
            .map(|k| {
                let points: Vec<[f64; 3]> = t.auv_p.iter().map(|p| p[k]).collect();
                validity::find_chain(&l, floor, t.usv_p[k], &points).unwrap_or_else(|_| {
                    let cut = |i: usize, j: usize| validity::link(&l, floor, points[i], points[j]);
                    longest_path_avoiding(&points, |i, j| cut(i, j).is_err()).order
                })
            })
            .collect();
        let more = s.horizon.terminal_margin && w + 1 < s.windows;
        let problem = TeamProblem::new(s, floor, keep_out, auv, usv, start.clone())
            .with_track(&track)
            .with_terminal(more);
        let report = SamplingReport {
            drawn: ww.samples_drawn,
            kept: ww.samples_kept,
            notes: notes(file),
            ..SamplingReport::default()
        };
        windows.push(window(
            s,
            floor,
            Sampled {
                index: w,
                trajectory: &t,
                chains: &chains,
                problem: &problem,
                time_s: ww.solve_time_s,
                report,
                require_connected: false,
            },
        )?);
        track.extend_from_slice(&t.usv_p);
        start = next_window(&t, None).0;
    }
    Ok(setup.plan(s, floor, provenance, &file.method, windows))
}

/// "seed 3; …": the file's seed and notes, as the plan records them.
fn notes(file: &WaypointsFile) -> String {
    match file.seed {
        Some(seed) => format!("seed {seed}; {}", file.notes),
        None => file.notes.clone(),
    }
}

/// Why waypoint `p` of `who` ("the USV", "AUV 2") at step `k` cannot be flown, if it
/// cannot: a coordinate that is not finite, a point outside the seafloor grid (no plan leaves
/// it, and the paths between waypoints are measured on it), or a depth beyond any floor's.
fn waypoint_problem(floor: &Seafloor, who: &str, k: usize, p: &[f64]) -> Option<String> {
    let at = || {
        let parts: Vec<String> = p.iter().map(|c| format!("{c:?}")).collect();
        format!("{who}'s waypoint k = {k}, [{}]", parts.join(", "))
    };
    if !p.iter().all(|c| c.is_finite()) {
        return Some(format!("{}: a coordinate is not finite", at()));
    }
    if !floor.contains(p[0], p[1]) {
        return Some(format!(
            "{}: outside the seafloor grid, which covers {}; waypoints must lie over it",
            at(),
            floor.extent()
        ));
    }
    let max = crate::seafloor::MAX_ABS_ELEVATION;
    match p.get(2) {
        Some(z) if z.abs() > max => Some(format!(
            "{}: z = {z:?} m is beyond any floor; allowed is |z| ≤ {max} m",
            at()
        )),
        _ => None,
    }
}

/// The window's trajectory through the waypoints of `ww` from `start`, or what does not fit
/// (the field, relative to the window).
fn trajectory(
    s: &Scenario,
    floor: &Seafloor,
    auv: &AuvModel,
    usv: &UsvModel,
    start: &Start,
    ww: &WaypointsWindow,
) -> Result<Trajectory, String> {
    let (k, n) = (s.horizon.steps, s.team.auvs);
    if ww.usv.len() != k + 1 {
        return Err(format!(
            "usv: {} waypoints for K + 1 = {}",
            ww.usv.len(),
            k + 1
        ));
    }
    if ww.auvs.len() != n {
        return Err(format!("auvs: {} paths for team.auvs = {n}", ww.auvs.len()));
    }
    for (i, p) in ww.usv.iter().enumerate() {
        if let Some(why) = waypoint_problem(floor, "the USV", i, p) {
            return Err(format!("usv[{i}]: {why}"));
        }
    }
    let near = |a: &[f64], b: &[f64]| a.iter().zip(b).all(|(x, y)| (x - y).abs() <= 1e-6);
    if !near(&ww.usv[0], &start.usv) {
        return Err(format!(
            "usv[0] = {:?} is not the window's start {:?}",
            ww.usv[0], start.usv
        ));
    }
    let usv_u = ww
        .usv
        .windows(2)
        .map(|p| [(p[1][0] - p[0][0]) / usv.dt, (p[1][1] - p[0][1]) / usv.dt])
        .collect();
    let mut auv_u = Vec::with_capacity(n);
    for (a, (path, st)) in ww.auvs.iter().zip(&start.auvs).enumerate() {
        if path.len() != k + 1 {
            return Err(format!(
                "auvs[{a}]: {} waypoints for K + 1 = {}",
                path.len(),
                k + 1
            ));
        }
        for (i, p) in path.iter().enumerate() {
            if let Some(why) = waypoint_problem(floor, &format!("AUV {a}"), i, p) {
                return Err(format!("auvs[{a}][{i}]: {why}"));
            }
        }
        if !near(&path[0], &st.position) {
            return Err(format!(
                "auvs[{a}][0] = {:?} is not the window's start {:?}",
                path[0], st.position
            ));
        }
        let mut v = st.velocity;
        let mut inputs = Vec::with_capacity(k);
        for pair in path.windows(2) {
            let u: [f64; 3] =
                std::array::from_fn(|i| (pair[1][i] - pair[0][i] - auv.pv[i] * v[i]) / auv.pu[i]);
            v = auv.step(pair[0], v, u).1;
            inputs.push(u);
        }
        auv_u.push(inputs);
    }
    Ok(Trajectory::simulate(start, usv_u, auv_u, auv, usv))
}
