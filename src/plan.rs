//! The plan file, format `shoal-plan/2` (documented field by field in docs/plan-format.md).
//!
//! Index conventions: a window has K steps; positions and velocities are given for k = 0..=K
//! (K + 1 entries, k = 0 is the window's initial state), inputs for k = 0..K−1 (K entries; input
//! k acts from step k to step k + 1). Times are t = window_start + k·δ seconds.

use crate::scenario::Scenario;
use serde::{Deserialize, Serialize};

/// Value of the `format` field of every plan this version writes.
pub const FORMAT: &str = "shoal-plan/2";

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    pub format: String,
    /// Version of shoal that wrote the plan.
    pub shoal_version: String,
    /// Where the scenario came from: "embedded default" or the path of the file.
    pub scenario_source: String,
    /// Overrides given with `--set`, in order, as "key=value".
    pub overrides: Vec<String>,
    /// The fully resolved scenario: every parameter, including the seed.
    pub scenario: Scenario,
    pub seafloor: SeafloorRecord,
    /// Discrete models actually used (derived from the scenario; recorded for readers).
    pub model: ModelRecord,
    /// State at the start of window 0.
    pub initial: InitialState,
    pub windows: Vec<Window>,
    /// Metrics over the whole mission (every window).
    pub metrics: Metrics,
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
    /// Shallowest and deepest node elevation, metres.
    pub z_min: f64,
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

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelRecord {
    /// Damping rates of E' (1/s): surge, heave, yaw.
    pub damping: crate::vehicle::Damping,
    /// Discrete AUV model coefficients per axis.
    pub auv: crate::vehicle::AuvModel,
    pub usv: crate::vehicle::UsvModel,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InitialState {
    /// "seeded" (drawn from the seed, Algorithm 1 line 5) or "explicit" (from the scenario).
    pub origin: String,
    pub usv: [f64; 2],
    pub auvs: Vec<AuvState>,
}

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AuvState {
    pub position: [f64; 3],
    pub velocity: [f64; 3],
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Window {
    pub index: usize,
    /// Time of step k = 0 of this window, seconds since the start of the mission.
    pub start_time: f64,
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
    pub metrics: Metrics,
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
    pub solve_time_s: f64,
}

/// One acoustic link: AUV `a` to AUV `b`, or to the USV when `b` is None.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Link {
    pub a: usize,
    pub b: Option<usize>,
}

/// The band [lo, hi] (metres) a link's length is kept in: C5_2/C5_3's [d_s − d_t, d_s], with hi
/// lowered for a link that lost line of sight (Algorithm 1, line 20).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Band {
    pub lo: f64,
    pub hi: f64,
}

/// A planned link whose length in the final plan is outside its band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OutOfBand {
    pub k: usize,
    pub link: Link,
    pub length: f64,
    pub band: Band,
}

#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct LinkReport {
    /// Per step k = 0..=K: the planned links (the A2U link first, then the A2A edges in path
    /// order) and their bands. At k = 0 the positions are the window's fixed start, so its links
    /// are reported but not planned.
    pub links: Vec<Vec<Link>>,
    pub bands: Vec<Vec<Band>>,
    /// Every (step, link) of k = 1..=K whose final length is outside its band by more than 1 mm.
    pub out_of_band: Vec<OutOfBand>,
    /// Line-of-sight rounds of Algorithm 1, lines 18–22 (1 = the first P5 solve had LoS on
    /// every link).
    pub los_rounds: usize,
}

/// Mission metrics (per window, and over the mission in `Plan::metrics`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Σ ‖U_n\[k\]‖² over AUVs and steps, (m/s²)².
    pub input_energy: f64,
    /// Area of seafloor swept by the union of the AUVs' sensor swaths, km².
    pub explored_area_km2: f64,
    /// Mean and minimum height above the floor over the AUV waypoints k = 1..=K, metres.
    pub mean_height: f64,
    pub min_height: f64,
    /// Fraction of steps at which every AUV reaches the USV through links in range (≤ d_s) and
    /// in line of sight: must be 1.
    pub connected_fraction: f64,
    /// Fraction of steps at which the planned chain (A2U link + A2A path) has every link in
    /// range and in line of sight.
    pub chain_fraction: f64,
    /// Largest heading rate of any AUV, rad/s.
    pub max_heading_rate: f64,
    /// Solve times, seconds: Step 1, Step 2, Step 3 (per window; summed over the mission).
    pub step1_time_s: f64,
    pub step2_time_s: f64,
    pub step3_time_s: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stage {
    /// "converged", or "max_iterations" when the SCP stopped at its iteration limit with a
    /// feasible iterate.
    pub status: String,
    pub iterations: usize,
    /// Wall-clock time of the stage, seconds.
    pub solve_time_s: f64,
    pub objective: ObjectiveTerms,
    /// Largest violation of a nonconvex constraint at the returned iterate (metres or radians).
    pub max_violation: f64,
    pub usv: UsvPath,
    pub auvs: Vec<AuvPath>,
    /// One record per SCP iteration.
    pub scp: Vec<ScpIteration>,
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
    /// OF1_8: ‖P_USV\[K\] − P_USV\[0\]‖², m² (objective "away"), or OF1_8_2: ‖P_USV\[K\] − dest‖², m².
    pub usv: f64,
    /// OF1_5 (Step 3): Σ_k Σ ‖P_i − P_j‖² over AUV pairs not joined by an A2A edge, m².
    #[serde(default)]
    pub spread: f64,
    /// OF1_3 + OF1_4 as C5_2/C5_3 slacks (Step 3): Σ metres by which planned links are outside
    /// their bands.
    #[serde(default)]
    pub band: f64,
    /// w1·energy + w2·(height or depth) − w8·usv (away) or + w8_2·usv (destination); in Step 3
    /// also − w5·spread + w3·(A2U band) + w4·(A2A band).
    pub total: f64,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UsvPath {
    /// P_USV\[k\], k = 0..=K.
    pub position: Vec<[f64; 2]>,
    /// U_USV\[k\] (velocity, m/s), k = 0..K−1.
    pub input: Vec<[f64; 2]>,
}

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

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScpIteration {
    /// Trust-region radius used by this iteration's convex subproblem, metres.
    pub trust_region: f64,
    /// Merit (objective + penalty·violation) at the reference and at the candidate.
    pub merit_before: f64,
    pub merit_after: f64,
    /// Decrease predicted by the convex model.
    pub predicted: f64,
    /// ρ = actual / predicted decrease.
    pub ratio: f64,
    pub accepted: bool,
    /// Largest true constraint violation of the candidate.
    pub violation: f64,
    /// Clarabel's status, interior-point iterations and time for the subproblem.
    pub solver_status: String,
    #[serde(default)]
    pub solver_iterations: u32,
    pub solver_time_s: f64,
}
