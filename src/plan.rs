//! The plan file, format `shoal-plan/5` (documented field by field in docs/plan-format.md).
//!
//! Index conventions: a window has K steps; positions and velocities are given for k = 0..=K
//! (K + 1 entries, k = 0 is the window's initial state), inputs for k = 0..K−1 (K entries; input
//! k acts from step k to step k + 1). Times are t = window_start + k·δ seconds.

use crate::scenario::Scenario;
use serde::{Deserialize, Serialize};

/// Value of the `format` field of every plan this version writes.
pub const FORMAT: &str = "shoal-plan/5";

/// `Plan::method` of Algorithm 1's plans (Steps 1–3 by sequential convex programming).
pub const METHOD_MPC: &str = "mpc";
/// `Plan::method` of the paper's RRT-like sampling baseline (Section V, `src/sampling/`).
pub const METHOD_RRT_LIKE: &str = "rrt-like";

fn method_mpc() -> String {
    METHOD_MPC.into()
}

/// A plan as `shoal plan` writes it to `plan.json`: the resolved scenario, the floor, the
/// models, the initial state and every window's stages, graph, links and metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// Always [`FORMAT`]; readers refuse anything else.
    pub format: String,
    /// Version of shoal that wrote the plan.
    pub shoal_version: String,
    /// Which planner made the plan: [`METHOD_MPC`] (Algorithm 1, the default), [`METHOD_RRT_LIKE`]
    /// (the paper's sampling baseline, `src/sampling/`) or the `method` of a waypoints file
    /// (`shoal plan --waypoints`, e.g. "ompl-rrtstar"). Plans written before it read as "mpc".
    #[serde(default = "method_mpc")]
    pub method: String,
    /// Where the scenario came from: "embedded default" or the path of the file.
    pub scenario_source: String,
    /// Overrides given with `--set`, in order, as "key=value".
    pub overrides: Vec<String>,
    /// The fully resolved scenario: every parameter, including the seed.
    pub scenario: Scenario,
    /// Where the floor came from, its lattice and its fingerprint.
    pub seafloor: SeafloorRecord,
    /// Discrete models actually used (derived from the scenario; recorded for readers).
    pub model: ModelRecord,
    /// The current the plan was made in (`sim::current::planned`): the AUVs' velocities are
    /// through the water and their positions move with it, eq. (8)'s ϖ term. Still water for
    /// plans of methods that do not model it.
    pub current: crate::scenario::Current,
    /// State at the start of window 0.
    pub initial: InitialState,
    /// One per receding-horizon window, in order; window w + 1 starts where window w's final
    /// stage ends (Algorithm 1, line 7).
    pub windows: Vec<Window>,
    /// Metrics over the whole mission (every window).
    pub metrics: Metrics,
    /// What the planner warns of: a stage that did not converge (its plan is feasible, not
    /// the optimum of its window). Empty when there is nothing to say.
    #[serde(default)]
    pub warnings: Vec<String>,
}

/// Where the floor came from and a fingerprint of its grid, so a checker can tell it has the
/// same floor the plan was made on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SeafloorRecord {
    /// "synthetic" (regenerated from scenario.seafloor.synthetic and scenario.seed) or "file".
    pub source: String,
    /// Path of the grid file when source = "file".
    pub path: Option<String>,
    /// The grid's nodes, metres: `nx`, `ny`, the centre of the south-west node (`x0`, `y0`)
    /// and the spacing (`dx`, `dy`), written as those six fields of the record.
    #[serde(flatten)]
    pub lattice: crate::seafloor::Lattice,
    /// Deepest (lowest) data node elevation, metres.
    pub z_min: f64,
    /// Shallowest (highest) data node elevation, metres.
    pub z_max: f64,
    /// Hex digest of the node values (see `Seafloor::fingerprint`).
    pub fingerprint: String,
    /// "synthetic", "esri-ascii" or "geotiff" ("" in plans written before it was recorded).
    #[serde(default)]
    pub format: String,
    /// CRS of the grid file: `"EPSG:<code>"`, "projected (user-defined)", "geographic
    /// (user-defined)" or "none" (synthetic, ESRI ASCII, a GeoTIFF without GeoKeys).
    #[serde(default = "crs_none")]
    pub crs: String,
    /// Sign convention of the file's values ("elevation" or "depth").
    #[serde(default)]
    pub values: crate::seafloor::Values,
    /// [latitude, longitude] of the local frame's origin when the grid is geographic.
    #[serde(default)]
    pub origin: Option<[f64; 2]>,
}

fn crs_none() -> String {
    "none".into()
}

/// The discrete vehicle models the plan was made with.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelRecord {
    /// Damping rates of E' (1/s): surge, heave, yaw.
    pub damping: crate::vehicle::Damping,
    /// Discrete AUV model coefficients per axis.
    pub auv: crate::vehicle::AuvModel,
    /// USV model, eq. (9): P\[k+1\] = P\[k\] + δ·U\[k\], ‖U\[k\]‖ ≤ max_speed (m/s).
    pub usv: crate::vehicle::UsvModel,
}

/// The state window 0 starts from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InitialState {
    /// "seeded" (drawn from the seed, Algorithm 1 line 5) or "explicit" (from the scenario).
    pub origin: String,
    /// USV position \[x, y\], metres (on the surface, z = 0).
    pub usv: [f64; 2],
    /// State of each AUV n = 0..N−1.
    pub auvs: Vec<AuvState>,
}

/// Position and velocity of one AUV at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AuvState {
    /// \[x, y, z\], metres (z < 0 below the surface).
    pub position: [f64; 3],
    /// \[V_x, V_y, V_z\], m/s.
    pub velocity: [f64; 3],
}

/// One receding-horizon window of Algorithm 1: Steps 1, 2 and 3 over K steps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Window {
    /// Window index w, from 0.
    pub index: usize,
    /// Time of step k = 0 of this window, seconds since the start of the mission.
    pub start_time: f64,
    /// The first courses tried before Step 1 (`usv.courses` > 1, first window only; absent
    /// otherwise): Step 1 starts from the one of least merit.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub courses: Vec<Course>,
    /// Step 1 (problem P2).
    pub step1: Stage,
    /// Step 2: the A2U link (P3) and A2A path (P4) per step, from Step 1's positions.
    pub graph: Graph,
    /// Step 3 (problem P5) with the line-of-sight rounds of Algorithm 1, lines 18–22: the plan
    /// the team executes. The next window starts from its last state.
    #[serde(rename = "final")]
    pub final_: Stage,
    /// The links P5 kept in their bands, the bands used, and where a link is outside its band.
    pub links: LinkReport,
    /// This window's metrics, over its final stage.
    pub metrics: Metrics,
    /// How a sampling planner found the window's paths (absent in the MPC's plans).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub sampling: Option<SamplingReport>,
}

/// What a sampling planner (the RRT-like baseline, or an external one through a waypoints
/// file) did for one window: its complexity, made visible (the issue of Remark III.1).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct SamplingReport {
    /// 𝔯, samples drawn from each node per step (0 for an external planner).
    pub samples: usize,
    /// Nodes kept per step (0 for an external planner).
    pub tree_budget: usize,
    /// Vehicle draws made (every USV and AUV draw, valid or not).
    pub drawn: u64,
    /// Valid team samples kept as tree nodes over the window (before pruning).
    pub kept: u64,
    /// Why draws were rejected: the constraint's name and how many draws it rejected.
    pub rejected: Vec<(String, u64)>,
    /// Per step k = 1..=K: draws, valid children, nodes kept after pruning and the wall time
    /// (empty for an external planner).
    pub steps: Vec<SamplingStep>,
    /// An external planner's seed and settings, as its waypoints file gives them.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub notes: String,
}

/// One step of a sampling planner's tree.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct SamplingStep {
    /// Vehicle draws at this step.
    pub drawn: u64,
    /// Valid team samples (children) found at this step.
    pub valid: u64,
    /// Nodes kept after pruning to `tree_budget`.
    pub kept: u64,
    /// Wall-clock time of the step, seconds.
    pub time_s: f64,
}

impl Window {
    /// Whether both of the window's SCP stages converged.
    pub fn converged(&self) -> bool {
        self.step1.converged() && self.final_.converged()
    }
}

/// A first course tried by the first window: the formation guess along `heading` and the
/// merit (objective + λ·violation) of the iterate one SCP iteration of P2 made from it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Course {
    /// Radians from east towards north.
    pub heading: f64,
    /// Absent when the convex solve failed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merit: Option<f64>,
}

impl Course {
    /// The course of least merit (the first on a tie); `None` when every solve failed.
    pub fn best(courses: &[Course]) -> Option<&Course> {
        courses
            .iter()
            .filter(|c| c.merit.is_some())
            .fold(None, |best: Option<&Course>, c| match best {
                Some(b) if b.merit <= c.merit => Some(b),
                _ => Some(c),
            })
    }
}

/// Step 2's output for one window.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Graph {
    /// P3: per step k = 0..=K, the AUV (index) nearest the USV: the A2U link.
    pub a2u: Vec<usize>,
    /// P4: per step k = 0..=K, the A2A edges [i, j] (i < j) of the longest Hamiltonian path,
    /// N − 1 of them, in path order.
    pub a2a: Vec<Vec<[usize; 2]>>,
    /// True when every P4 was solved exactly (Held–Karp, N ≤ 12); false for the heuristic.
    pub exact: bool,
    /// Wall-clock time of Step 2 for the window, seconds.
    pub solve_time_s: f64,
}

/// One acoustic link: AUV `a` to AUV `b`, or to the USV when `b` is None.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Link {
    /// Index of the AUV at one end.
    pub a: usize,
    /// Index of the AUV at the other end (an A2A edge), or None for the USV (the A2U link).
    pub b: Option<usize>,
}

/// The band [lo, hi] (metres) a link's length is kept in: C5_2/C5_3's [d_s − d_t, d_s] with its
/// top at ρ·d_s (`acoustic.link_margin`; ρ = 1 is the paper's band), hi lowered for a link that
/// lost line of sight (Algorithm 1, line 20).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Band {
    /// Lower end, metres: ρ·d_s − d_t (lowered to `hi` if `hi` falls below it).
    pub lo: f64,
    /// Upper end, metres: ρ·d_s, less `acoustic.los_shrink` per line-of-sight round in which the
    /// link was blocked (not below 0).
    pub hi: f64,
}

/// A planned link whose length in the final plan is outside its band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutOfBand {
    /// Step k of the window (1..=K).
    pub k: usize,
    /// The link.
    pub link: Link,
    /// Its length at step k in the final plan, metres (an A2U link to the USV at z = 0).
    pub length: f64,
    /// The band it is outside.
    pub band: Band,
}

/// Step 3's links for one window: the links P5 kept in their bands, the bands, the links that
/// ended outside their band, and the line-of-sight rounds.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct LinkReport {
    /// Per step k = 0..=K: the planned links (the A2U link first, then the A2A edges in path
    /// order) and their bands. At k = 0 the positions are the window's fixed start, so its links
    /// are reported but not planned.
    pub links: Vec<Vec<Link>>,
    /// Per step k = 0..=K: the band of each link of `links\[k\]`, in the same order.
    pub bands: Vec<Vec<Band>>,
    /// Every (step, link) of k = 1..=K whose final length is outside its band by more than 1 mm.
    pub out_of_band: Vec<OutOfBand>,
    /// Line-of-sight rounds of Algorithm 1, lines 18–22 (1 = the first P5 solve had LoS on
    /// every link).
    pub los_rounds: usize,
    /// P5's bridges, `[k, i]`: at step k AUV i kept the USV in range and in line of sight
    /// because the planned path could not be in range yet from the window's start (absent in
    /// plans written before bridges).
    #[serde(default)]
    pub bridges: Vec<[usize; 2]>,
}

/// Mission metrics (per window, and over the mission in `Plan::metrics`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Σ ‖U_n\[k\]‖² over AUVs and steps, (m/s²)².
    pub input_energy: f64,
    /// Area of seafloor swept by the union of the AUVs' sensor swaths, km².
    pub explored_area_km2: f64,
    /// Area swept again in a later window, km²: the sum of the windows' explored areas less
    /// the mission's (an area swept in three windows counts twice). 0 for one window. Plans
    /// written before this metric read it as 0.
    #[serde(default)]
    pub revisited_area_km2: f64,
    /// Mean height above the floor, z − Z(x, y), over the AUV waypoints k = 1..=K, metres.
    pub mean_height: f64,
    /// Minimum height above the floor over the AUV waypoints k = 1..=K, metres.
    pub min_height: f64,
    /// Fraction of steps at which every AUV reaches the USV through links in range (≤ d_s) and
    /// in line of sight: must be 1.
    pub connected_fraction: f64,
    /// Fraction of steps at which the planned chain (A2U link + A2A path) has every link in
    /// range and in line of sight.
    pub chain_fraction: f64,
    /// Largest heading rate of any AUV, rad/s.
    pub max_heading_rate: f64,
    /// Solve time of Step 1 (P2), seconds (per window; summed over the mission).
    pub step1_time_s: f64,
    /// Solve time of Step 2 (P3, P4), seconds (per window; summed over the mission).
    pub step2_time_s: f64,
    /// Solve time of Step 3 (P5 and its line-of-sight rounds), seconds (per window; summed over
    /// the mission).
    pub step3_time_s: f64,
}

impl Plan {
    /// How many stages (Step 1 and Step 3 of every window) did not converge: feasible, not the
    /// optimum of their window.
    pub fn unconverged_stages(&self) -> usize {
        let stages = self.windows.iter().flat_map(|w| [&w.step1, &w.final_]);
        stages.filter(|st| !st.converged() && !st.sampled()).count()
    }
}

/// One SCP stage of a window, Step 1 (P2) or Step 3 (P5 with its line-of-sight rounds): how
/// the solve went and the team's paths.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stage {
    /// "converged"; "max_iterations" when the SCP stopped at its iteration limit with a
    /// feasible iterate; "stalled" when its trust region collapsed (or its penalty ran out)
    /// first; "solver_trouble" when the convex solver failed at every trust radius tried (the
    /// best feasible iterate before). Only "converged" is the optimum of the window's problem
    /// to `scp.tolerance`.
    pub status: String,
    /// SCP iterations (convex subproblems solved, over every line-of-sight round): the length
    /// of `scp`.
    pub iterations: usize,
    /// Wall-clock time of the stage, seconds.
    pub solve_time_s: f64,
    /// The objective's terms at the returned iterate.
    pub objective: ObjectiveTerms,
    /// Largest violation of a nonconvex constraint at the returned iterate (metres or radians).
    pub max_violation: f64,
    /// The USV's path.
    pub usv: UsvPath,
    /// The path of each AUV n = 0..N−1.
    pub auvs: Vec<AuvPath>,
    /// One record per SCP iteration.
    pub scp: Vec<ScpIteration>,
}

/// `Stage::status` of a stage found by a sampling planner (no SCP).
pub const SAMPLED: &str = "sampled";

impl Stage {
    /// Whether the stage's SCP converged (status "converged").
    pub fn converged(&self) -> bool {
        self.status == "converged"
    }

    /// Whether a sampling planner found the stage (status [`SAMPLED`]): it has no SCP log and
    /// no convergence to speak of.
    pub fn sampled(&self) -> bool {
        self.status == SAMPLED
    }
}

/// The objective terms of P2, unweighted, and the weighted total.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, Default)]
pub struct ObjectiveTerms {
    /// OF1_1: Σ_k Σ_n ‖U_n\[k\]‖², (m/s²)².
    pub energy: f64,
    /// Σ_k Σ_n z_n\[k\], metres (k = 1..K): OF1_2 when weights.of1_2 = "depth".
    pub depth: f64,
    /// Σ_k Σ_n (z_n\[k\] − Z(x_n\[k\], y_n\[k\])), metres: OF1_2 when weights.of1_2 = "height".
    pub height: f64,
    /// OF1_8: ‖P_USV\[K\] − c‖², c the nearest point of the USV's track (`usv.away_from`;
    /// P_USV\[0\] in the first window), m² (objective "away"), or OF1_8_2:
    /// ‖P_USV\[K\] − dest‖², m².
    pub usv: f64,
    /// OF1_5 (Step 3): Σ_k Σ ‖P_i − P_j‖² over AUV pairs not joined by an A2A edge, m².
    #[serde(default)]
    pub spread: f64,
    /// OF1_3 + OF1_4 as C5_2/C5_3 slacks (Step 3): Σ metres by which planned links are outside
    /// their bands.
    #[serde(default)]
    pub band: f64,
    /// The lanes term (Step 3; ours): Σ_{k<K} Σ metres by which lane neighbours' cross-track
    /// gaps fall short of the swath, plus Σ_k Σ metres by which the AUVs fly above the survey
    /// altitude (0 without it).
    #[serde(default)]
    pub lanes: f64,
    /// (w1·energy + w2·(height or depth))/N − w8·usv (away) or + w8_2·usv (destination), with
    /// /N only for `weights.scaling = "per_auv"` (the default), w8 as `Scenario::w8` scales it
    /// (`weights.w8_scaling`); in Step 3
    /// also − w5·spread(/N) + w3·(A2U band) + w4·(A2A band) + w_lanes·lanes(/N).
    pub total: f64,
}

/// The USV's path over a window's steps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UsvPath {
    /// P_USV\[k\], k = 0..=K.
    pub position: Vec<[f64; 2]>,
    /// U_USV\[k\] (velocity, m/s), k = 0..K−1.
    pub input: Vec<[f64; 2]>,
}

/// One AUV's path over a window's steps, with the surge speed and heading recovered from its
/// velocities.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AuvPath {
    /// P_n\[k\], k = 0..=K.
    pub position: Vec<[f64; 3]>,
    /// V_n\[k\], k = 0..=K.
    pub velocity: Vec<[f64; 3]>,
    /// U_n\[k\] (m/s²), k = 0..K−1.
    pub input: Vec<[f64; 3]>,
    /// Surge speed v_x\[k\] = ‖(V_x, V_y)‖, k = 0..=K.
    pub surge_speed: Vec<f64>,
    /// Heading ψ\[k\] = atan2(V_y, V_x) in radians, or null where the horizontal speed is below
    /// auv.min_heading_speed (heading undefined), k = 0..=K.
    pub heading: Vec<Option<f64>>,
}

/// The record of one SCP iteration: one convex subproblem and whether its candidate was
/// accepted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScpIteration {
    /// Trust-region radius used by this iteration's convex subproblem, metres.
    pub trust_region: f64,
    /// Merit (objective + penalty·violation) at the reference.
    pub merit_before: f64,
    /// Merit at the candidate.
    pub merit_after: f64,
    /// Decrease predicted by the convex model.
    pub predicted: f64,
    /// ρ = actual / predicted decrease.
    pub ratio: f64,
    /// Whether the candidate became the reference.
    pub accepted: bool,
    /// Largest true constraint violation of the candidate.
    pub violation: f64,
    /// λ, the penalty of the merit function at this iteration (`merit_before`, `merit_after`
    /// and `predicted` are measured with it). Absent in older plans.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub penalty: Option<f64>,
    /// Whether the subproblem was a momentum step, its model built about the reference
    /// extrapolated along its last step (`scp.momentum`): `predicted` and `ratio` are then
    /// measured from the extrapolated point, and the step is accepted only if it lowers the
    /// merit below `merit_before`. Absent in older plans: false.
    #[serde(default)]
    pub extrapolated: bool,
    /// Clarabel's status for the subproblem.
    pub solver_status: String,
    /// Clarabel's interior-point iterations for the subproblem.
    #[serde(default)]
    pub solver_iterations: u32,
    /// Clarabel's solve time for the subproblem, seconds.
    pub solver_time_s: f64,
}

/// The bounding box [x_min, x_max, y_min, y_max] of the finite points among `points`; None
/// when there is none.
pub fn bbox(points: impl IntoIterator<Item = [f64; 2]>) -> Option<[f64; 4]> {
    let b = points
        .into_iter()
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .fold(
            [
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ],
            |b, p| {
                [
                    b[0].min(p[0]),
                    b[1].max(p[0]),
                    b[2].min(p[1]),
                    b[3].max(p[1]),
                ]
            },
        );
    (b[0] <= b[1]).then_some(b)
}

impl Plan {
    /// The horizontal positions of every vehicle in every window's Step 1 and final stages
    /// (the initial state is their first), metres.
    pub fn positions(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        self.windows.iter().flat_map(|w| {
            [&w.step1, &w.final_].into_iter().flat_map(|st| {
                let usv = st.usv.position.iter().copied();
                let auvs = st
                    .auvs
                    .iter()
                    .flat_map(|a| a.position.iter().map(|p| [p[0], p[1]]));
                usv.chain(auvs)
            })
        })
    }
}
