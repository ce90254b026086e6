//! Scenario: every parameter of a planning run, with defaults equal to the paper's experiment
//! (Section V: N = 5 AUVs, K = 20 steps, δ = 100 s, d_s = 150 m). Where the paper gives no number
//! the default is ours and the comment says why.
//!
//! Loading: [`load`] (a file), [`default_with`] (the embedded default, i.e. the text of
//! [`default_toml`]) and [`from_toml_str`] take `--set key=value` overrides, deserialise, and
//! check every range rule of [`validate`]. Errors ([`ScenarioError`]) name the file (or the
//! override, or `embedded default`), the line, the dotted key and what is allowed.

use serde::{Deserialize, Serialize};

mod load;
pub mod plausible;
mod sampling;
mod schema;
mod sim;
mod template;
mod toml_path;
mod validate;

pub use load::{
    default_with, from_toml_str, load, with_overrides, ScenarioError, EMBEDDED_DEFAULT,
};
pub use sampling::Sampling;
pub use sim::{profile_factor, profile_slope, Current, Navigation, Simulation};
pub use template::default_toml;
pub use validate::{
    validate, whole_multiple as validate_whole_multiple, Violation, ACOUSTIC_PERIOD, MAX_AUVS,
    MAX_CELLS_PER_SIDE, MAX_FEATURES, MAX_STEPS, POSITION_NOISE, SAMPLE_PERIOD, SIM_STEP,
};

/// A full, resolved scenario. Every field has a default, so an empty file is a valid scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scenario {
    /// Seed of every random draw (initial AUV positions, synthetic seafloor).
    pub seed: u64,
    /// Number of receding-horizon windows planned one after another (Algorithm 1, for_1).
    pub windows: usize,
    /// `[team]`: the AUV group.
    pub team: Team,
    /// `[horizon]`: steps per window and sampling time.
    pub horizon: Horizon,
    /// `[acoustic]`: sonar range, link bands and line-of-sight sampling.
    pub acoustic: Acoustic,
    /// `[auv]`: AUV limits and the coefficients of the dynamics, eqs. (5)–(8).
    pub auv: Auv,
    /// `[usv]`: the USV's speed limit and objective.
    pub usv: Usv,
    /// `[weights]`: weights of the objective OF1.
    pub weights: Weights,
    /// `[seafloor]`: a grid file or the synthetic floor.
    pub seafloor: SeafloorSpec,
    /// `[scp]`: settings of the sequential convex programming solver of P2 and P5.
    pub scp: Scp,
    /// `[current]`: the ocean current `shoal simulate` flies the plan in (the planner ignores it).
    pub current: Current,
    /// `[navigation]`: the sensors and acoustic modems of `shoal simulate`.
    pub navigation: Navigation,
    /// `[simulation]`: how `shoal simulate` integrates the vehicles.
    pub simulation: Simulation,
    /// `[sampling]`: the RRT-like baseline planner (`shoal plan --method rrt-like`).
    pub sampling: Sampling,
    /// Explicit initial state; when absent it is drawn from `seed` (Algorithm 1, line 5).
    pub initial: Option<Initial>,
}

/// The AUV group 𝒢 = {1, …, N}.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Team {
    /// N, the number of AUVs (paper: 5 and 7).
    pub auvs: usize,
}

/// The receding horizon: K steps of δ seconds per window.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Horizon {
    /// K, time steps per window (paper: 20).
    pub steps: usize,
    /// δ, sampling time in seconds (paper: 100 s).
    pub dt: f64,
    /// Ours: every window that another follows ends with each AUV able to slow below v_min on
    /// the grid in the next window's first step (`team::bounds`). On by default, which missions
    /// with the lanes chain need; with per-step chains it cost 7 % of the explored area over 5
    /// windows (N = 5, seeds 1–5).
    pub terminal_margin: bool,
}

/// Acoustic links, A2U (AUV–USV) and A2A (AUV–AUV): range, link-length bands and
/// line-of-sight sampling.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Acoustic {
    /// d_s, sonar (acoustic modem) range in metres (paper: 150 m).
    pub sonar_range: f64,
    /// d_t, tolerance of the link-length band [d_s − d_t, d_s] of C5_2/C5_3, metres.
    pub band_tolerance: f64,
    /// d_max, largest allowed AUV–USV distance at any step (C1_5), metres. Must be ≥ d_s.
    pub max_range: f64,
    /// r, resolution of the segment / line-of-sight sampling 𝓛_r, metres.
    pub resolution: f64,
    /// ρ, the link margin: P5 keeps each planned link in the band [ρ·d_s − d_t, ρ·d_s], its top
    /// a fraction ρ of the sonar range (ours; the paper's band tops at d_s, ρ = 1). A modem
    /// hears fewer pings the nearer a link is to d_s (docs/simulation.md); 0 < ρ ≤ 1.
    pub link_margin: f64,
    /// How much a link's upper band bound is lowered each time it loses line of sight
    /// (Algorithm 1, line 20: d_s,ij = d_s − ε), metres.
    pub los_shrink: f64,
    /// Largest number of P5 solves per window in the line-of-sight loop (Algorithm 1, lines
    /// 17–22).
    pub los_rounds: usize,
    /// How Step 2's P4 picks the A2A chain: the longest per step (the paper), one per window
    /// in cross-track order (ours, the default), or the longest per window.
    pub graph: A2aGraph,
}

/// How P4 (Step 2) picks the A2A graph of a window (`step2::p4_window` says why).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum A2aGraph {
    /// The paper: the longest Hamiltonian path of each step's positions; the
    /// chain's order may change from one step to the next.
    PerStep,
    /// One chain for the whole window: the Hamiltonian path with the fewest (step, edge) pairs
    /// out of range or blocked, and the longest of those summed over the window's steps.
    Window,
    /// One chain for the whole window, in the order of the AUVs' cross-track offsets from the
    /// USV's track (each link joins neighbouring lanes); ours, the default.
    Lanes,
}

/// How the AUV dynamics are discretised over a step of δ seconds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Discretisation {
    /// Exact zero-order-hold discretisation of eqs. (5)–(7) (our default; always stable).
    Zoh,
    /// The paper's forward Euler, eq. (8); refused when |1 − δ·E'| > 1 (unstable).
    Euler,
}

/// AUV limits and the coefficients of the simplified dynamics, eqs. (5)–(8) (defaults: REMUS
/// 100). Hydrodynamic coefficients follow Fossen's sign convention: added masses and dampings
/// are ≤ 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Auv {
    /// V_max of C1_7, m/s.
    pub max_speed: f64,
    /// ψ̇_max of C1_14, rad/s.
    pub max_heading_rate: f64,
    /// Horizontal speed (m/s) below which heading is undefined and C1_14 is not applied.
    pub min_heading_speed: f64,
    /// Depth rating, metres: every AUV waypoint keeps z ≥ −max_depth (`team::depth`).
    pub max_depth: f64,
    /// γ_max, rad: the flight-path angle through the water stays within it,
    /// |V_z| ≤ tan(γ_max)·‖V_h‖ (`team::climb`).
    pub max_flight_path_angle: f64,
    /// Cruise floor, m/s: the horizontal speed through the water stays at least this from
    /// step 1 on (`team::cruise`); 0 turns the floor off.
    pub min_speed: f64,
    /// The slowest horizontal speed through the water at which the vehicle holds its depth in
    /// level flight, m/s: climbing needs more (`team::climb`).
    pub level_speed: f64,
    /// The climb rate (m/s) the vehicle gains per m/s of horizontal speed through the water
    /// above `level_speed`: from step 1 on V_z ≤ climb_per_speed·(‖V_h‖ − level_speed)
    /// (`team::climb`).
    pub climb_per_speed: f64,
    /// ε of C2_2: clearance above the seafloor, metres.
    pub floor_clearance: f64,
    /// C1_4: AUVs stay at least this far below the surface (z ≤ −surface_clearance), metres.
    pub surface_clearance: f64,
    /// Least distance between any two AUVs, at every step k ≥ 1 and along the segments between
    /// steps, metres (ours; the paper has none: `team::separation`). 0 turns it off.
    pub min_separation: f64,
    /// Width of the seafloor swath each AUV's sensor covers (side-scan / multibeam), metres;
    /// used for the explored-area metric only.
    pub swath_width: f64,
    /// Highest altitude above the floor at which the sensor's swath counts as explored sea
    /// floor, metres: a segment k−1 → k adds its swath to the explored area only when both its
    /// ends are at most this high (explored-area metric only).
    pub survey_altitude: f64,
    /// Exact zero-order hold of eqs. (5)–(7) or the paper's forward Euler, eq. (8).
    pub discretisation: Discretisation,
    /// m, rigid-body mass, kg.
    pub mass: f64,
    /// γ_v̇x (X_u̇), surge added mass, kg (negative by Fossen's sign convention).
    pub added_mass_surge: f64,
    /// γ_v̇z (Z_ẇ), heave added mass, kg (negative).
    pub added_mass_heave: f64,
    /// γ_vx (X_u), linear surge damping, kg/s (negative).
    pub damping_surge: f64,
    /// γ_vz (Z_w), linear heave damping, kg/s (negative).
    pub damping_heave: f64,
    /// J_z, yaw moment of inertia, kg·m².
    pub inertia_yaw: f64,
    /// N_ṙ, yaw added inertia, kg·m² (negative).
    pub added_inertia_yaw: f64,
    /// γ_ωz (N_r), linear yaw damping, kg·m²/s (negative).
    pub damping_yaw: f64,
}

/// What the USV's objective term rewards: OF1_8 or OF1_8_2.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum UsvObjective {
    /// OF1_8: move away from the start point (concave; linearised each SCP iteration).
    Away,
    /// OF1_8_2: go towards `destination` (convex).
    Destination,
}

/// The USV (mother ship) at the surface, eq. (9): P_USV\[k+1\] = P_USV\[k\] + δ·U_USV\[k\].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Usv {
    /// Speed limit of eq. (9)'s velocity input, m/s.
    pub max_speed: f64,
    /// OF1_8 (move away from the start, weight w8) or OF1_8_2 (go towards `destination`,
    /// weight w8_2).
    pub objective: UsvObjective,
    /// P_USV[∞] of OF1_8_2, metres (x east, y north). Used when objective = "destination".
    pub destination: [f64; 2],
    /// Direction (rad, from +x towards +y) of the first guess of the USV path, about which the
    /// concave OF1_8 is first linearised (its gradient at "not moved" is zero).
    pub initial_heading: f64,
    /// Courses the first window tries with objective = "away": `initial_heading` and
    /// `courses − 1` more, evenly spaced round the compass, and from three on one more at the
    /// vertex of the parabola through the best one's merit and its neighbours'. Each first guess
    /// gets one SCP iteration of P2 and Step 1 starts from the course whose iterate has the
    /// least merit.
    /// 1 (the default): `initial_heading` alone.
    pub courses: usize,
    /// What OF1_8 ("away") measures the USV's distance from: the track it has travelled since
    /// the mission's start (ours, default) or the window's start point (the paper's literal form).
    pub away_from: AwayFrom,
}

/// What OF1_8 measures "away" from. Both are the paper's −‖P_USV\[K\] − P_USV\[0\]‖² in the
/// first window; they differ in the later ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum AwayFrom {
    /// −min over the USV's track (every earlier window's path, and this window's start) of
    /// ‖P_USV\[K\] − q‖²: each window is rewarded for ground farther from any the team has been
    /// over, so a long mission does not wander back over the water it has seen.
    Track,
    /// −‖P_USV\[K\] − P_USV\[0\]‖² with P_USV\[0\] the window's own start (the paper): each window
    /// forgets the earlier ones and may head back.
    Window,
}

/// How w1, w2 and w5 weigh their sums over the team (ours; the paper gives no weights).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WeightScaling {
    /// w1, w2 and w5 weigh OF1_1, OF1_2 and OF1_5 divided by N, each AUV's share (default):
    /// the trade-off between an AUV's input energy, its height and the USV's OF1_8 is the same
    /// at every N. OF1_5 sums over the pairs that are not linked, so an AUV's share of it grows
    /// with the number of AUVs it is not linked to: a bigger team spreads wider.
    PerAuv,
    /// The paper's sums: the team's terms grow with N (energy and height like N, spread like
    /// N²) while OF1_8 does not, so weights that suit 5 AUVs stop a team of 20.
    Sum,
}

/// The form of OF1_2 (Section III-A: "enforces the AUVs to navigate close to the sea floor").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DepthObjective {
    /// Σ (z − Z(x, y)): height above the floor. With C2_2 active it is ε wherever the AUV is, so
    /// it keeps the AUVs on the floor without pulling them sideways towards deeper ground.
    Height,
    /// Σ z, the paper's 𝔷X literally: also rewards moving horizontally to deeper floor, so AUVs
    /// leave their course to sit in valleys, and the SCP crawls downhill a trust radius at a time.
    Depth,
}

/// Weights w1..w8 of the objective OF1 (problem P1), w8_2 of OF1_8_2 and w_lanes of the lanes
/// term (ours); all ≥ 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Weights {
    /// w1 · OF1_1, input energy Σ‖U‖², per (m/s²)².
    pub w1: f64,
    /// w2 · OF1_2, per metre: Σ height above the floor (default) or Σ z (the paper's literal
    /// form), chosen by `of1_2`.
    pub w2: f64,
    /// What OF1_2 sums: "height" (z − Z(x, y), near the floor) or "depth" (z, the paper's 𝔷X).
    pub of1_2: DepthObjective,
    /// w3 · OF1_3 (Step 3), A2U link off its band, per metre.
    pub w3: f64,
    /// w4 · OF1_4 (Step 3), A2A link off its band, per metre.
    pub w4: f64,
    /// w5 · OF1_5 (Step 3), spread of non-adjacent AUVs, per m².
    pub w5: f64,
    /// w6 · OF1_6, number of A2A edges (fixed by Step 2).
    pub w6: f64,
    /// w7 · OF1_7, number of A2U edges (fixed by Step 2).
    pub w7: f64,
    /// w8 · OF1_8, USV distance from its start (squared), per m².
    pub w8: f64,
    /// w8_2 · OF1_8_2, USV squared distance to the destination, per m².
    pub w8_2: f64,
    /// w_lanes · the lanes term (Step 3; ours, not in the paper): per metre by which a lane
    /// neighbour's cross-track gap falls short of the swath, and by which an AUV flies above
    /// the survey altitude, per step (per AUV: see `scaling`); 0 turns it off.
    pub w_lanes: f64,
    /// Whether w1, w2 and w5 weigh the team's sums per AUV (default) or as the paper's sums.
    pub scaling: WeightScaling,
    /// Whether w8 weighs OF1_8 against the energy a distance costs in this window as in the
    /// paper's (default) or per m² whatever the window (the paper).
    pub w8_scaling: W8Scaling,
}

/// How w8 weighs OF1_8 (ours; the paper gives no weights).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum W8Scaling {
    /// w8 weighs OF1_8 against the input energy it takes to go a distance in the window as on
    /// the paper's window: w8·(K₀·δ₀²)/(K·δ²), K₀ = [`REFERENCE_STEPS`], δ₀ =
    /// [`REFERENCE_DT`] ([`Scenario::w8`]). An AUV holds a speed v against its damping c with
    /// an input c·v at every step, so going d in K steps of δ costs K·(c·d/(K·δ))² =
    /// c²·d²/(K·δ²) of OF1_1, and OF1_8 pays w8·d²: per m², a window of fewer or shorter steps
    /// is paid less for the same energy (draw 1002 of issue 13's sweep, 12 steps of 31 s,
    /// 17× less, and its USV ended 11 m from its start). On the paper's window the factor
    /// is 1.
    Energy,
    /// The paper's OF1_8 per m², whatever the window's steps.
    None,
}

/// K₀, the steps of the paper's window (Section V), for `weights.w8_scaling = "energy"`.
pub const REFERENCE_STEPS: f64 = 20.0;

/// `auv.max_flight_path_angle` at or above which there is no angle limit (1.57 rad, 89.95°, up
/// to π/2 rounded to 1.5708): a vehicle that moves vertically at rest (a hovering AUV, the
/// paper's model).
pub const NO_ANGLE_LIMIT: f64 = 1.57;

/// The default ρ of `acoustic.link_margin` (docs/simulation.md, "Links planned to be heard",
/// has the flown study that chose it).
pub const LINK_MARGIN: f64 = 0.8;
/// δ₀, the paper's sampling time in seconds (Section V), for `weights.w8_scaling = "energy"`.
pub const REFERENCE_DT: f64 = 100.0;

impl Scenario {
    /// R, how far a formation can go in one window, metres: K·δ at the slower of the USV's
    /// limit and the AUVs' (the team moves together).
    pub fn reach(&self) -> f64 {
        self.horizon.steps as f64 * self.horizon.dt * self.usv.max_speed.min(self.auv.max_speed)
    }

    /// The weight of OF1_8 (the USV's squared distance, m²) in the objective: w8·(K₀·δ₀²)/(K·δ²)
    /// with `weights.w8_scaling = "energy"`, w8 with "none".
    pub fn w8(&self) -> f64 {
        match self.weights.w8_scaling {
            W8Scaling::Energy => {
                let (k, dt) = (self.horizon.steps as f64, self.horizon.dt);
                self.weights.w8 * REFERENCE_STEPS * REFERENCE_DT.powi(2) / (k * dt * dt)
            }
            W8Scaling::None => self.weights.w8,
        }
    }
}

impl Weights {
    /// The factor of the team's sums OF1_1, OF1_2 and OF1_5 over `auvs` AUVs in the objective:
    /// 1/N for "per_auv" (1 for an empty team), 1 for "sum".
    pub fn per_auv(&self, auvs: usize) -> f64 {
        match self.scaling {
            WeightScaling::PerAuv => 1.0 / auvs.max(1) as f64,
            WeightScaling::Sum => 1.0,
        }
    }
}

/// Default: no file, the default synthetic floor.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SeafloorSpec {
    /// Path of a grid file: ESRI ASCII (.asc) or GeoTIFF (.tif, .tiff), or with the `gdal`
    /// feature any grid GDAL reads (.nc, .grd, .bag, .xyz, ...), metres. When absent the
    /// synthetic floor below is generated.
    pub file: Option<String>,
    /// The sign convention of the file's values: elevation (negative below sea level, GEBCO)
    /// or depth (positive down; negated on load).
    pub values: crate::seafloor::Values,
    /// Mission origin [latitude, longitude], degrees, of the local metric frame of a
    /// geographic grid (default: the grid's centre). Only for geographic grids.
    pub origin: Option<[f64; 2]>,
    /// The grid file's CRS, `"EPSG:<code>"`: for a file that has none (ESRI ASCII without a .prj
    /// sidecar), or to assert a file's own (a conflict is an error).
    pub crs: Option<String>,
    /// The synthetic floor (Fig. 4(a)), generated from `seed` when `file` is absent.
    pub synthetic: crate::seafloor::SyntheticParams,
}

/// Sequential convex programming (trust region) that solves the nonconvex P2 (Step 1) and P5
/// (Step 3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Scp {
    /// Largest number of SCP iterations per window and stage.
    pub max_iterations: usize,
    /// Convergence: stop when the predicted decrease of the merit function is below this
    /// fraction of the objective's size, 1 + Σ |weighted term| (and the true constraint
    /// violation is below `feasibility_tol`).
    pub tolerance: f64,
    /// Largest true violation (metres, radians) accepted at convergence.
    pub feasibility_tol: f64,
    /// Initial trust-region radius on horizontal moves, metres.
    pub trust_region: f64,
    /// Smallest trust-region radius before the SCP gives up, metres.
    pub min_trust_region: f64,
    /// λ: penalty weight of the merit function on constraint violation.
    pub penalty: f64,
    /// Momentum steps (ours, off by default): after good steps, the model is built about the
    /// reference extrapolated along its last step (Nesterov's sequence), and kept if it lowers
    /// the merit. Converged runs (`tolerance` 10⁻⁷) end 1.3–2.8× sooner, at local optima that
    /// are sometimes better and sometimes worse; at the default tolerance a window takes
    /// 1.3–1.8× longer for a median gain of 0.3–1.5 % (docs/design-decisions.md, "Momentum steps").
    pub momentum: bool,
    /// Step 1 (P2) only: its own `tolerance` (default: `tolerance`). Step 1's tail is a slow
    /// turn of the whole team, and at N ≤ 5 the gap of a default window to its converged run
    /// is that turn's (docs/design-decisions.md, "Step 1's tolerance").
    pub step1_tolerance: Option<f64>,
    /// Step 1 (P2) only: its own `max_iterations` (default: `max_iterations`).
    pub step1_max_iterations: Option<usize>,
}

impl Scp {
    /// The settings Step 1 (P2) runs with: `step1_tolerance` and `step1_max_iterations` in
    /// place of `tolerance` and `max_iterations` where they are set.
    pub fn step1(&self) -> Scp {
        Scp {
            tolerance: self.step1_tolerance.unwrap_or(self.tolerance),
            max_iterations: self.step1_max_iterations.unwrap_or(self.max_iterations),
            ..self.clone()
        }
    }
}

/// An explicit initial state (Algorithm 1, lines 4–5).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Initial {
    /// USV position [x, y], metres.
    pub usv: [f64; 2],
    /// AUV positions [x, y, z], metres; AUVs start at rest. Empty (or absent): drawn from the
    /// seed within d_s of `usv` (Algorithm 1, line 5, about the USV's given start).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub auvs: Vec<[f64; 3]>,
}

// ---------------------------------------------------------------------------------------------
// Defaults. Paper values where the paper gives them (Section V), ours otherwise (said why).
// ---------------------------------------------------------------------------------------------

impl Default for Scenario {
    fn default() -> Self {
        Scenario {
            seed: 1,
            windows: 1,
            team: Team::default(),
            horizon: Horizon::default(),
            acoustic: Acoustic::default(),
            auv: Auv::default(),
            usv: Usv::default(),
            weights: Weights::default(),
            seafloor: SeafloorSpec::default(),
            scp: Scp::default(),
            current: Current::default(),
            navigation: Navigation::default(),
            simulation: Simulation::default(),
            sampling: Sampling::default(),
            initial: None,
        }
    }
}

impl Default for Team {
    fn default() -> Self {
        Team { auvs: 5 } // Section V, Fig. 4: five AUVs
    }
}

impl Default for Horizon {
    fn default() -> Self {
        // Section V: "20 time slots with a sampling time of 100 seconds"
        Horizon {
            steps: 20,
            dt: 100.0,
            // ours: on, for the lanes chain's missions (docs/method.md, "P2")
            terminal_margin: true,
        }
    }
}

impl Default for Acoustic {
    fn default() -> Self {
        Acoustic {
            sonar_range: 150.0,   // Section V: d_s = 150 m
            band_tolerance: 30.0, // paper gives no d_t; 20 % of d_s
            max_range: 400.0, // paper gives no d_max; a few hundred metres (mid-frequency modems)
            resolution: 5.0,  // 𝓛_r: 5 m, a fifth of the synthetic grid cell
            link_margin: LINK_MARGIN,
            los_shrink: 15.0, // ours: half of d_t per round
            los_rounds: 5,
            // ours: one chain per window in lane order (docs/method.md, "Step 2")
            graph: A2aGraph::Lanes,
        }
    }
}

impl Default for Auv {
    fn default() -> Self {
        // REMUS 100 class. Coefficients: T. Prestero, "Verification of a six-degree of freedom
        // simulation model for the REMUS autonomous underwater vehicle", MIT/WHOI MS thesis, 2001
        // (also the source of Fossen's REMUS 100 model, Handbook of Marine Craft Hydrodynamics,
        // 2nd ed., 2021, §8.4). Prestero gives quadratic drag; the linear damping below is its
        // linearisation d(X_u|u|·u|u|)/du = 2·X_u|u|·u0 at a stated operating speed u0.
        Auv {
            max_speed: 2.0,          // REMUS 100: 2.5 m/s top speed (Fossen), 1.5 m/s cruise
            max_heading_rate: 0.005, // paper gives none; 0.5 rad (29°) per 100 s step
            min_heading_speed: 0.1,  // heading undefined below 0.1 m/s horizontal speed
            // Hydroid/Kongsberg REMUS 100 specification sheet: depth rating 100 m
            max_depth: 100.0,
            // 0.3 rad (17°): a REMUS keeps its pitch within about ±15–20° in operation
            // (Prestero 2001, §5 trials: dives at up to ~20° pitch); the path angle through
            // the water is pitch less angle of attack, a few degrees at cruise
            max_flight_path_angle: 0.3,
            // ours: REMUS 100 cruises at ~1.5 m/s (3 kn, spec sheet); its fins lose authority
            // below ~1 m/s (Prestero 2001: the fin lift grows with u²). The 6-DoF model's trim
            // (docs/simulation.md, "What the vehicle can fly") holds depth down to 1.144 m/s
            // with all its stern plane, 1.37 m/s with a quarter of it spare; flown, plans held
            // at 1.0 m/s sank at their 1.03 m/s legs (seed 4, N = 5: 509 samples below the
            // floor). 1.25 m/s leaves 13 % of the stern plane for control in level flight
            min_speed: 1.25,
            // ours: Prestero's REMUS 100 in trim holds level flight down to 1.144 m/s and
            // climbs at most +0.2° at 1.15, +4.8° at 1.25, +7.7° at 1.3, +15.2° at 1.4, +27.1°
            // at 1.5 m/s (docs/simulation.md, "What the vehicle can fly"): a climb rate of at
            // most 0.8·(v − 1.15) m/s lies below every one of those (0.08 of 0.105 m/s at
            // 1.25, 0.2 of 0.37 at 1.4, 0.28 of 0.68 at 1.5)
            level_speed: 1.15,
            climb_per_speed: 0.8,
            floor_clearance: 5.0, // ε; REMUS survey altitude is typically 3–10 m
            surface_clearance: 2.0, // stay 2 m below the surface (C1_4)
            // MOOS-IvP's BHV_AvoidCollision: min_util_cpa_dist = 10 m by default, the closest
            // point of approach at or inside which a manoeuvre has the least utility
            min_separation: 10.0,
            swath_width: 50.0, // ours: a side-scan swath of ~10× a 5 m altitude
            // ours: that swath at ε = 5 m means a slant range of √(25² + 5²) = 25.5 m, which
            // still covers 2·√(25.5² − 15²) = 41 m (82 %) of ground from 15 m up
            survey_altitude: 15.0,
            discretisation: Discretisation::Zoh,
            mass: 30.51,              // Prestero Table 4.1: m = 30.51 kg
            added_mass_surge: -0.93,  // X_u̇ = −9.30e−1 kg
            added_mass_heave: -35.5,  // Z_ẇ = −3.55e1 kg
            damping_surge: -4.86,     // 2·X_u|u|·u0, X_u|u| = −1.62 kg/m, u0 = 1.5 m/s
            damping_heave: -26.2,     // 2·Z_w|w|·w0, Z_w|w| = −1.31e2 kg/m, w0 = 0.1 m/s
            inertia_yaw: 3.45,        // I_zz = 3.45 kg·m²
            added_inertia_yaw: -4.88, // N_ṙ = −4.88 kg·m²/rad
            damping_yaw: -18.8,       // 2·N_r|r|·r0, N_r|r| = −94 kg·m²/rad², r0 = 0.1 rad/s
        }
    }
}

impl Default for Usv {
    fn default() -> Self {
        Usv {
            max_speed: 1.5, // paper gives none; slower than the AUVs so they can keep up
            objective: UsvObjective::Away,
            destination: [3000.0, 0.0],
            initial_heading: 0.0,
            courses: 1,
            away_from: AwayFrom::Track,
        }
    }
}

impl Default for Weights {
    fn default() -> Self {
        // The paper gives no weights. These are in physical units and chosen so that every term
        // of P2 visibly matters (docs/method.md, "Weights"). They weigh the team's terms per
        // AUV (`scaling = "per_auv"`) and were tuned as the paper's sums for 5 AUVs: w1 = 5 × 10³,
        // w2 = 5 and w5 = 5 × 10⁻⁴ per AUV are 10³, 1 and 10⁻⁴ on the sums at N = 5.
        Weights {
            w1: 5.0e3,
            w2: 5.0,
            of1_2: DepthObjective::Height,
            w3: 1.0e3, // "heavily penalised" band slacks: 1 m off band weighs like 1 (m/s²)² of input
            w4: 1.0e3,
            w5: 5.0e-4,
            w6: 0.0,
            w7: 0.0,
            w8: 1.0e-3,
            w8_2: 1.0e-3,
            // per metre of lane shortfall, per step, per AUV: of 0, 16, 32, 64 and 128, 32 gave
            // the most sea floor at N = 5–20 (docs/method.md, "The lanes term")
            w_lanes: 32.0,
            scaling: WeightScaling::PerAuv,
            w8_scaling: W8Scaling::Energy,
        }
    }
}

impl Default for Scp {
    fn default() -> Self {
        Scp {
            max_iterations: 50,
            // 1e-3, not 1e-4: past it the SCP crept on for as many iterations again, gaining
            // under 1 % of the objective (docs/design-decisions.md, "Solver settings")
            tolerance: 1e-3,
            feasibility_tol: 1e-3,
            trust_region: 200.0,
            min_trust_region: 1e-3,
            penalty: 1.0e3,
            momentum: false,
            step1_tolerance: None,
            step1_max_iterations: None,
        }
    }
}

#[cfg(test)]
mod tests;
