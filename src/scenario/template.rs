//! The default scenario as a commented TOML file (what `shoal init` writes). Keys, their order
//! and their values come from `Scenario::default()` (via [`super::schema`]); only the comments
//! are written here.

use super::schema::{self, Schema};
use super::Scenario;
use toml_edit::{TableLike, Value};

/// What each key (and section) means: meaning, unit, the paper's symbol, what is allowed.
/// Keys are dotted; sections are listed under their own name.
pub(crate) fn doc(key: &str) -> Option<&'static str> {
    Some(match key {
        "seed" => {
            "Seed of every random draw: the initial AUV positions when [initial] is absent \
             (Algorithm 1, line 5: P_n[0] = rand) and the synthetic seafloor. Integer ≥ 0."
        }
        "windows" => {
            "Number of receding-horizon windows 𝒯 = 1, 2, … planned one after another \
             (Algorithm 1, for_1); each starts where the previous one ended. Integer ≥ 1."
        }
        "team" => "The AUV group 𝒢 = {1, …, N}.",
        "team.auvs" => "N: number of AUVs (paper, Section V: 5 in Fig. 4, also 7). 1 to 64.",
        "horizon" => {
            "The receding horizon: time steps k ∈ 𝒦 = {1, …, K} of δ seconds; one window \
             spans 𝒯 = K·δ (paper: 20 × 100 s)."
        }
        "horizon.steps" => "K: time steps per window (paper: 20). 1 to 1000.",
        "horizon.dt" => "δ: sampling time, seconds (paper: 100 s). > 0.",
        "horizon.terminal_margin" => {
            "Ours: each window that another follows ends with every AUV's coast point inside \
             the grid by the distance it needs to slow below v_min (so the next window cannot \
             start with an AUV at the edge moving out). On by default: missions with \
             acoustic.graph = \"lanes\" need it; with \"per_step\" chains it cost 7 % of the \
             explored area over 5 windows."
        }
        "acoustic" => "Acoustic links: A2U (AUV–USV) and A2A (AUV–AUV) communication.",
        "acoustic.sonar_range" => {
            "d_s: sonar (acoustic modem) range, metres (paper: 150 m). C1_6 keeps every AUV \
             within d_s of the USV at k = 0 and k = K; OF1_3 / OF1_4 keep linked pairs near \
             d_s. > 0."
        }
        "acoustic.band_tolerance" => {
            "d_t: tolerance of the link-length band [d_s − d_t, d_s] of C5_2 / C5_3, metres \
             (ours: the paper gives no value; 20 % of d_s). 0 < d_t < d_s."
        }
        "acoustic.link_margin" => {
            "ρ: P5 keeps each planned link in the band [ρ·d_s − d_t, ρ·d_s] (ours; the paper's \
             band tops at d_s, ρ = 1). A modem hears a ping at distance d with probability \
             about 0.9·(1 − (d/d_s)⁶): 0.66 at 0.8·d_s, 0.42 at 0.9·d_s, none at d_s; links \
             planned at d_s are barely heard when flown (docs/simulation.md). d_t < ρ·d_s, \
             ρ ≤ 1."
        }
        "acoustic.max_range" => {
            "d_max: largest AUV–USV distance at any step (C1_5), metres (ours: the paper gives \
             no value). Must be ≥ d_s."
        }
        "acoustic.resolution" => {
            "r: sampling step of the segment / line-of-sight query 𝓛_r of C1_13, metres. > 0."
        }
        "acoustic.los_shrink" => {
            "How much a link that lost line of sight has its band's upper end lowered per round, \
             metres (Algorithm 1, line 20: d_s,ij = d_s − ε; ours: d_t / 2). > 0."
        }
        "acoustic.los_rounds" => {
            "Largest number of P5 solves per window in the line-of-sight loop (Algorithm 1, \
             lines 17–22). 1 to 100."
        }
        "acoustic.graph" => {
            "How Step 2 (P4) picks the A2A chain: \"lanes\" (ours, the default: one chain per \
             window, the AUVs in cross-track order; explores more, is faster at N ≥ 20 and \
             stops nearer the converged optimum, see docs/design-decisions.md), \"per_step\" (the \
             paper: the longest Hamiltonian path of each step) or \"window\" (ours: one chain \
             per window, the longest summed over its steps)."
        }
        "auv" => {
            "AUV limits, and the coefficients of the simplified dynamics, eqs. (5)–(8): \
             E' = diag{γ_vx/(m − γ_v̇x), γ_vz/(m − γ_v̇z), γ_ωz/J_z}. Defaults: REMUS 100 \
             (Prestero 2001; Fossen 2021, §8.4). Hydrodynamic coefficients follow Fossen's \
             sign convention: added masses and dampings are ≤ 0."
        }
        "auv.max_speed" => "V_max (V_n_max of C1_7): largest AUV speed, m/s. > 0.",
        "auv.max_heading_rate" => {
            "ψ̇_max of C1_14: largest heading rate, rad/s (ours: 0.5 rad per 100 s step). > 0."
        }
        "auv.min_heading_speed" => {
            "Horizontal speed, m/s, below which the heading ψ = atan(V_y / V_x) is undefined \
             and C1_14 is not applied. 0 ≤ value < max_speed."
        }
        "auv.max_depth" => {
            "Depth rating, metres: every AUV keeps z ≥ −max_depth at each step (ours; the \
             paper has none). Default: the REMUS 100's 100 m rating (Hydroid/Kongsberg \
             specification sheet). > surface_clearance."
        }
        "auv.max_flight_path_angle" => {
            "γ_max, rad: the AUVs' flight-path angle through the water stays within it, \
             |V_z| ≤ tan(γ_max)·‖V_h‖ (ours; the paper has none). Default 0.3 rad (17°): a \
             REMUS keeps its pitch within about ±15–20° (Prestero 2001). 0 < value ≤ 1.5708; \
             1.57 or more: no limit (a hovering vehicle, as the paper's)."
        }
        "auv.level_speed" => {
            "The slowest horizontal speed through the water, m/s, at which the AUV holds its \
             depth in level flight: from step 1 on it climbs at most \
             climb_per_speed·(‖V_h‖ − level_speed) (ours; the paper has none). Default 1.15 m/s: \
             Prestero's REMUS 100 holds depth down to 1.144 m/s. 0 ≤ value ≤ 1000; above min_speed \
             the climb line takes min_speed."
        }
        "auv.climb_per_speed" => {
            "Climb rate (m/s) the AUV gains per m/s of horizontal speed through the water above \
             level_speed. Default 0.8: below every sustained climb of Prestero's REMUS 100 \
             (+4.8° at 1.25 m/s, +15° at 1.4, +27° at 1.5). 0 < value ≤ 1000; a large value \
             leaves only max_flight_path_angle."
        }
        "auv.min_speed" => {
            "Cruise floor, m/s: from step 1 on every AUV's horizontal speed through the water \
             stays at least this (ours; the paper has none), held along each step's segment. \
             Default 1.25 m/s: a REMUS 100 cruises at ~1.5 m/s and Prestero's model holds \
             its depth only above 1.144 m/s; simulated flights sank at 1.03 m/s. 0 turns the floor off. min_heading_speed ≤ value < \
             max_speed, or 0."
        }
        "auv.floor_clearance" => {
            "ε of C2_2: clearance kept above the seafloor, z ≥ Z(x, y) + ε, metres. ≥ 0."
        }
        "auv.min_separation" => {
            "Least distance kept between any two AUVs, at every step k ≥ 1 and along the \
             segments between steps, metres (ours; the paper has none). The default is the \
             worst case of MOOS-IvP's collision avoidance (BHV_AvoidCollision's \
             min_util_cpa_dist = 10 m). 0 turns it off. ≥ 0."
        }
        "auv.swath_width" => {
            "Width of the seafloor swath one AUV's sensor covers, metres (ours; for the \
             explored-area metric only). > 0."
        }
        "auv.survey_altitude" => {
            "Highest altitude above the floor at which a swath counts as explored, metres \
             (ours; for the explored-area metric only): a segment adds its swath only when both \
             its ends are at most this high. > 0."
        }
        "auv.surface_clearance" => {
            "C1_4: AUVs stay under water, z ≤ −surface_clearance, metres. ≥ 0."
        }
        "auv.discretisation" => {
            "\"zoh\": exact zero-order hold of eqs. (5)–(7) (ours; always stable); \"euler\": \
             the paper's forward Euler, eq. (8), refused when unstable (|1 − δ·E'| > 1)."
        }
        "auv.mass" => "m: rigid-body mass, kg. > 0.",
        "auv.added_mass_surge" => "γ_v̇x (X_u̇): surge added mass, kg. ≤ 0.",
        "auv.added_mass_heave" => "γ_v̇z (Z_ẇ): heave added mass, kg. ≤ 0.",
        "auv.damping_surge" => {
            "γ_vx (X_u): linear surge damping, kg/s (Prestero's quadratic drag linearised at \
             1.5 m/s). ≤ 0."
        }
        "auv.damping_heave" => {
            "γ_vz (Z_w): linear heave damping, kg/s (linearised at 0.1 m/s). ≤ 0."
        }
        "auv.inertia_yaw" => "J_z: yaw moment of inertia, kg·m². > 0.",
        "auv.added_inertia_yaw" => "N_ṙ: yaw added inertia, kg·m². ≤ 0.",
        "auv.damping_yaw" => {
            "γ_ωz (N_r): linear yaw damping, kg·m²/s (linearised at 0.1 rad/s). ≤ 0."
        }
        "usv" => {
            "The USV (mother ship) at the surface, eq. (9): P_USV[k+1] = P_USV[k] + δ·U_USV[k]."
        }
        "usv.max_speed" => {
            "Largest USV speed ‖U_USV‖, m/s (ours: slower than the AUVs so they can keep up). > 0."
        }
        "usv.objective" => {
            "\"away\": OF1_8, move away from the start point (weight w8); \"destination\": \
             OF1_8_2, go towards `destination` (weight w8_2)."
        }
        "usv.destination" => {
            "P_USV[∞] of OF1_8_2: [x, y], metres (x east, y north). Used when \
             objective = \"destination\"."
        }
        "usv.initial_heading" => {
            "Direction, rad from +x towards +y, of the first-guess USV path about which the \
             concave OF1_8 is first linearised (its gradient is zero where the USV has not \
             moved). With objective = \"away\" the first window keeps close to it: the SCP \
             does not choose the heading, so set it to the direction to explore (or let \
             `courses` try more)."
        }
        "usv.courses" => {
            "Courses the first window tries with objective = \"away\": initial_heading and \
             courses − 1 more, evenly spaced round the compass (from 3 on, one more between the \
             best and its neighbours); each first guess gets one SCP iteration and Step 1 \
             starts from the best. 1: initial_heading alone. Integer 1–72."
        }
        "usv.away_from" => {
            "What OF1_8 measures \"away\" from. \"track\" (ours, default): the nearest point \
             of the path the USV has travelled since the mission's start, so each window \
             heads for new ground; \"window\": the window's own start (the paper), so a long \
             mission may wander back. The same in the first window."
        }
        "weights" => {
            "Weights w1..w8 of OF1 (problem P1) and w8_2 of OF1_8_2. All ≥ 0. The paper gives \
             no values; ours are in physical units."
        }
        "weights.w1" => {
            "w1 · OF1_1: input energy Σ‖𝒰[k]‖², per (m/s²)² (per AUV: see scaling)."
        }
        "weights.w2" => {
            "w2 · OF1_2: keeps the AUVs deep, near the floor, per metre (per AUV: see scaling \
             and of1_2)."
        }
        "weights.of1_2" => {
            "What OF1_2 sums over AUVs and steps: \"height\" = z − Z(x, y), the height above the \
             floor (ours, default: stays near the floor without pulling AUVs sideways into \
             valleys); \"depth\" = z, the paper's 𝔷X taken literally."
        }
        "weights.w3" => {
            "w3 · OF1_3 (Step 3): A2U link length outside its band [d_s − d_t, d_s], per metre \
             (the penalty on C5_2's slack; ours: 10³, heavily penalised)."
        }
        "weights.w4" => {
            "w4 · OF1_4 (Step 3): A2A link length outside its band [d_s − d_t, d_s], per metre \
             (the penalty on C5_3's slack; ours: 10³, heavily penalised)."
        }
        "weights.w5" => {
            "w5 · OF1_5 (Step 3): spread of non-adjacent AUVs (rewarded), per m² (per AUV: see scaling)."
        }
        "weights.w6" => "w6 · OF1_6: number of A2A edges (fixed by Step 2, so a constant).",
        "weights.w7" => "w7 · OF1_7: number of A2U edges (fixed by Step 2, so a constant).",
        "weights.w8" => {
            "w8 · OF1_8: squared distance of the USV from its start (rewarded), per m² on the \
             paper's window of 20 steps of 100 s (see w8_scaling). Used when usv.objective = \
             \"away\"."
        }
        "weights.w8_2" => {
            "w8_2 · OF1_8_2: squared distance of the USV to usv.destination, per m². Used when \
             usv.objective = \"destination\"."
        }
        "weights.w_lanes" => {
            "w_lanes · the lanes term (Step 3; ours, not in the paper): per metre by which an \
             AUV's cross-track gap to its chain neighbour falls short of auv.swath_width, and by \
             which an AUV flies above auv.survey_altitude, per step (per AUV: see scaling), so \
             that the team sweeps lanes a swath apart at survey altitude instead of gathering at \
             the corridor's edges. With acoustic.graph = \"lanes\" only; 0 turns it off."
        }
        "weights.scaling" => {
            "\"per_auv\" (ours, default): w1 and w2 weigh OF1_1 and OF1_2 averaged over the N \
             AUVs, w5 weighs OF1_5 per AUV, so the team's terms balance the USV's OF1_8 alike \
             at every N; \"sum\": the paper's sums, under which a bigger team moves less."
        }
        "weights.w8_scaling" => {
            "\"energy\" (ours, default): w8 weighs OF1_8 × (20·(100 s)²)/(K·δ²), so that going a \
             distance in K steps of δ is worth its input energy (c²·d²/(K·δ²) for an AUV holding \
             speed against its damping c) as on the paper's window, where the factor is 1; \
             \"none\": per m² (the paper), under which a window of few or short steps barely \
             moves."
        }
        "seafloor" => {
            "The seafloor Z(x, y), whose obstacles p_Ω^3D enter C1_12 / C1_13 (C2_2 in Step 1): \
             a grid file (ESRI ASCII or GeoTIFF), or the synthetic floor of Fig. 4(a) below. \
             NODATA and land (z ≥ 0) cells are obstacles. Only the mission window (what the \
             vehicles can reach from their start in every window) is loaded from a file."
        }
        "seafloor.file" => {
            "Path of a grid file (relative paths from this file's directory): ESRI ASCII \
             (.asc; its CRS from a .prj sidecar or `crs`, otherwise metres) or GeoTIFF (.tif, \
             .tiff; float32/64, int16/32, uint16; its CRS from the GeoKeys); with the gdal cargo \
             feature, any grid GDAL reads (NetCDF .nc as GEBCO's, GMT .grd, BAG, XYZ). A \
             projected grid (e.g. UTM) is used in its own coordinates, so give [initial] \
             positions inside it; a geographic grid (degrees, EPSG:4326) is resampled onto the \
             local tangent plane at `origin`. When absent the synthetic floor below is \
             generated."
        }
        "seafloor.values" => {
            "Sign convention of the file's values: \"elevation\" (metres, negative below sea \
             level, as GEBCO; default) or \"depth\" (metres, positive down; negated on load). A \
             grid that is mostly of the other sign gets a warning."
        }
        "seafloor.origin" => {
            "Mission origin [latitude, longitude], degrees (WGS84), of a geographic grid: the \
             point (0, 0) of the planner's frame (x east, y north, metres, on the local tangent \
             plane; length error 4 mm at 10 km and 0.5 m at 50 km from it). Default: the grid's \
             centre (`shoal seafloor info FILE` prints it). Only for geographic grids. \
             |latitude| ≤ 85."
        }
        "seafloor.crs" => {
            "The grid file's CRS, \"EPSG:<code>\", for a file that has none: an ESRI ASCII \
             grid without a .prj sidecar (otherwise read in metres). EPSG:4000–4999 (e.g. \
             EPSG:4326, WGS 84 latitude and longitude) are geographic, in degrees; others \
             projected, in metres (e.g. EPSG:32756, UTM zone 56S). For a GeoTIFF or a grid \
             with a sidecar it must agree with the file's own CRS (a conflict is an error). \
             `shoal seafloor info FILE` shows the CRS and where it comes from."
        }
        "seafloor.synthetic" => {
            "Synthetic floor (Fig. 4(a)): a sloping plane with Gaussian seamounts and valleys \
             drawn from `seed`. Used when `file` is absent."
        }
        "seafloor.synthetic.size" => {
            "[x, y] extent, metres; the grid is centred on the origin (the USV's start). > 0, \
             and size / cell ≤ 10000."
        }
        "seafloor.synthetic.cell" => "Grid cell size, metres. > 0.",
        "seafloor.synthetic.base_depth" => "Floor elevation at the origin, metres (negative).",
        "seafloor.synthetic.slope" => "Regional slope [dZ/dx, dZ/dy], metres per metre.",
        "seafloor.synthetic.seamounts" => "Number of seamounts (Gaussian bumps). 0 to 10000.",
        "seafloor.synthetic.valleys" => "Number of valleys (Gaussian troughs). 0 to 10000.",
        "seafloor.synthetic.relief" => {
            "[lo, hi] range of bump heights / trough depths, metres. 0 < lo ≤ hi."
        }
        "seafloor.synthetic.radius" => {
            "[lo, hi] range of bump / trough radii (Gaussian σ), metres. 0 < lo ≤ hi."
        }
        "seafloor.synthetic.depth_range" => {
            "[deepest, shallowest] elevations the floor is rescaled into, metres. \
             deepest < shallowest < 0."
        }
        "scp" => {
            "Sequential convex programming (SCvx-style trust region) that solves the \
             non-convex P2 (Step 1) and P5 (Step 3). Ours: the paper does not give its solver \
             settings."
        }
        "scp.max_iterations" => "Largest number of SCP iterations per window and stage. ≥ 1.",
        "scp.tolerance" => {
            "Convergence: stop when the predicted decrease of the merit function is below this \
             fraction of the objective's size, 1 + Σ|weighted term| (and the violation is \
             below feasibility_tol). > 0."
        }
        "scp.feasibility_tol" => {
            "Largest true constraint violation accepted at convergence (metres, radians). > 0."
        }
        "scp.trust_region" => "Initial trust-region radius on horizontal moves, metres. > 0.",
        "scp.min_trust_region" => {
            "Smallest trust-region radius before the SCP gives up, metres. \
             0 < value < trust_region."
        }
        "scp.penalty" => "λ: penalty weight of the merit function on constraint violation. > 0.",
        "scp.momentum" => {
            "Momentum steps (ours): after good steps the model is built about the reference \
             extrapolated along its last step, and its candidate kept if it lowers the merit; \
             converged runs end sooner, default-tolerance runs take longer. true or false."
        }
        "scp.step1_tolerance" => {
            "Step 1 (P2) only: its own tolerance (when absent: tolerance). Step 1's tail is a \
             slow turn of the whole team; run to 1e-7 it closes most of the gap of small teams \
             to the converged optimum, for several times the window's time. > 0."
        }
        "scp.step1_max_iterations" => {
            "Step 1 (P2) only: its own max_iterations (when absent: max_iterations). ≥ 1."
        }
        "current" => {
            "The ocean current (ours): the MPC planner plans the AUVs' velocities through the \
             water in it (eq. (8)'s ϖ term; not from grid files), and `shoal simulate` flies \
             the plan in it: horizontal, constant in time; uniform at each depth (velocity), or \
             varying in x and y from two grid files (file_east, file_north)."
        }
        "current.velocity" => {
            "[east, north] velocity at the surface, m/s (default: a weak 0.1 m/s tidal current, \
             across the default first course; shelf currents are typically 0.1–0.5 m/s). \
             Finite; speed ≤ 3 m/s."
        }
        "current.profile" => {
            "Depth profile: [[depth, factor], …], depths in metres (≥ 0, increasing), the \
             current at depth d being velocity × the factor interpolated in d (held beyond the \
             ends), e.g. [[0, 1.0], [100, 0.3]]. Empty: uniform. Factors finite, |factor| ≤ 10."
        }
        "current.file_east" => {
            "Grid file of the current's east component u(x, y), m/s (read by `shoal simulate`; \
             relative paths from the plan file's directory): ESRI ASCII (.asc) or \
             GeoTIFF (.tif, .tiff), in the planner's frame (metres; not geographic). With \
             file_north the grids replace velocity: the current at (x, y, depth d) is [u, v] \
             interpolated bilinearly, times the profile's factor at d. Both or neither; the \
             grids must share one lattice, cover the mission with a 200 m margin, with no \
             NODATA there and speeds ≤ 3 m/s."
        }
        "current.file_north" => {
            "Grid file of the current's north component v(x, y), m/s, on the same lattice as \
             file_east (see there)."
        }
        "navigation" => {
            "The sensors and acoustic modems of `shoal simulate` (ours; each default a typical \
             value for a REMUS 100-class vehicle, sources in the comments of the code and in \
             docs/simulation.md): dead reckoning from a DVL, a compass / AHRS and a depth \
             sensor; GPS on the USV; one-way travel-time acoustic ranges."
        }
        "navigation.sample_period" => {
            "Sampling period of the DVL, heading, depth sensor and GPS, seconds. From 0.01 to \
             10, and acoustic_period is a whole number of them."
        }
        "navigation.dvl_noise" => {
            "DVL velocity noise, m/s, 1σ per axis and sample (a 1.2 MHz DVL: ~1 cm/s). From 0 \
             to 1."
        }
        "navigation.dvl_scale" => {
            "DVL scale-factor error, a fraction, 1σ drawn once per AUV (±0.2 %: Teledyne RDI \
             Workhorse Navigator 1200 kHz). 0 ≤ value < 0.1."
        }
        "navigation.dvl_max_altitude" => {
            "Highest altitude for DVL bottom lock, metres (1.2 MHz: ~30 m); above it the DVL \
             measures the velocity through the water and dead reckoning misses the current. > 0."
        }
        "navigation.heading_noise" => {
            "Compass / AHRS heading noise, rad, 1σ per sample. From 0 to 0.5."
        }
        "navigation.heading_bias" => {
            "Compass / AHRS heading bias, rad, 1σ drawn once per AUV (default 1°: a \
             calibrated magnetic compass). 0 ≤ value < 0.5."
        }
        "navigation.depth_noise" => {
            "Depth (pressure) sensor noise, metres, 1σ per sample. From 0 to 100."
        }
        "navigation.gps_noise" => {
            "USV GPS noise, metres, 1σ per horizontal axis. From 0.001 to 1000."
        }
        "navigation.initial_noise" => {
            "Error of each AUV's start position (its GPS fix before the dive), metres, 1σ per \
             axis. From 0.001 to 1000."
        }
        "navigation.acoustic_period" => {
            "Acoustic cycle, seconds: every link pings once per cycle, and the estimators solve \
             for every vehicle's position once per cycle. From 1 to 3600; horizon.dt is a whole \
             number of cycles."
        }
        "navigation.sound_speed" => "Speed of sound, m/s (travel time × speed = range). > 0.",
        "navigation.range_noise" => "Acoustic range noise, metres, 1σ. From 0.001 to 1000.",
        "navigation.packet_success" => {
            "Probability that a ping is received at short range. 0 < value ≤ 1."
        }
        "navigation.range_falloff" => {
            "Reception at range d is packet_success·(1 − (d/d_s)^range_falloff) below d_s = \
             acoustic.sonar_range, and 0 beyond it or without line of sight (the floor's segment \
             query on the executed positions). > 0."
        }
        "navigation.estimate_biases" => {
            "Whether the estimators estimate each AUV's compass bias and DVL scale error as \
             unknowns (true: with the priors heading_bias and dvl_scale; an estimate that stays \
             consistent over a mission) or treat them as noise drawn anew each acoustic cycle \
             (false: overconfident over many cycles)."
        }
        "simulation" => "How `shoal simulate` flies a plan (ours).",
        "simulation.step" => {
            "Fixed step of the RK4 integrator of the 6-DoF vehicle model, seconds. From 0.001 \
             to 0.2, and navigation.sample_period is a whole number of steps."
        }
        "sampling" => {
            "The RRT-like baseline of the paper's Section V, `shoal plan --method rrt-like` \
             (docs/baseline.md); the MPC planner ignores it."
        }
        "sampling.samples" => {
            "𝔯: valid random samples drawn from every node of the tree at each step, its \
             children. 1 ≤ samples ≤ 1000."
        }
        "sampling.tree_budget" => {
            "Nodes the tree keeps per step; a step with more children keeps the best by score \
             so far (the paper's full tree has Σ_k 𝔯^k nodes). 1 ≤ tree_budget ≤ 100000."
        }
        "sampling.attempts" => {
            "Draws per AUV before one sample is given up. 1 ≤ attempts ≤ 100000."
        }
        "initial" => {
            "Explicit initial state (Algorithm 1, lines 4–5). When absent, the USV starts at \
             the origin and the AUVs are drawn from `seed` within d_s of it (C1_6 at k = 0). \
             Remove the leading '# ' of the lines below to use it."
        }
        "initial.usv" => "P_USV[0] = [x, y], metres.",
        "initial.auvs" => {
            "P_n[0] = [x, y, z], metres, one per AUV (exactly team.auvs of them), z < 0; the \
             AUVs start at rest. Leave it out (or empty) to draw them from `seed` within d_s of \
             initial.usv, as without an initial state (a start on a real grid for any team \
             size)."
        }
        _ => return None,
    })
}

const HEADER: &str = "\
# shoal scenario: every parameter of a planning run, with its default value.
#
# Written by `shoal init`. Every key is optional: a missing key takes the value shown here, so
# an empty file is the default scenario. Any key can also be set on the command line with
# `--set key=value`, e.g. --set acoustic.sonar_range=120 --set usv.objective=destination.
#
# Units: metres, seconds, radians, kilograms. Axes: x east, y north, z up; the sea surface is
# z = 0 and the floor is below it (z < 0).
# Symbols (δ, K, N, d_s, d_max, ε, V_max, ψ̇_max, w1..w8, OF1_*, C1_*, C2_*) are those of
# Eskandari, Savkin & Deghat, \"Integrated Localization and Path Planning for an Ocean Exploring
# Team of Autonomous Underwater Vehicles with Consensus Graph Model Predictive Control\".
# Defaults are the paper's Section V values where it gives them, ours otherwise.
";

/// Longest comment line before wrapping.
const WIDTH: usize = 96;

fn comment(out: &mut String, text: &str, prefix: &str) {
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > WIDTH {
            out.push_str(prefix);
            out.push_str("# ");
            out.push_str(&line);
            out.push('\n');
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        out.push_str(prefix);
        out.push_str("# ");
        out.push_str(&line);
        out.push('\n');
    }
}

fn value_text(v: &Value) -> String {
    // Arrays of arrays are written one element per line.
    if let Value::Array(a) = v {
        if a.iter().any(|e| matches!(e, Value::Array(_))) {
            let mut s = String::from("[\n");
            for e in a.iter() {
                s.push_str("  ");
                s.push_str(&value_text(e));
                s.push_str(",\n");
            }
            s.push(']');
            return s;
        }
    }
    let mut v = v.clone();
    v.decor_mut().clear();
    v.to_string().trim().to_string()
}

/// Write `key = value`, commented out (every line prefixed with "# ") when `off`.
fn assignment(out: &mut String, key: &str, v: &Value, off: bool) {
    let text = format!("{key} = {}", value_text(v));
    for line in text.lines() {
        if off {
            out.push_str("# ");
        }
        out.push_str(line);
        out.push('\n');
    }
}

fn section(out: &mut String, path: &str, t: &dyn TableLike, present: Option<&dyn TableLike>) {
    let off = present.is_none();
    // Values first, then sub-tables (TOML requires it).
    for (k, item) in t.iter() {
        if item.is_table_like() {
            continue;
        }
        let key = join(path, k);
        out.push('\n');
        if let Some(d) = doc(&key) {
            comment(out, d, "");
        }
        let absent = off || present.is_some_and(|p| p.get(k).is_none());
        if let Some(v) = item.as_value() {
            assignment(out, k, v, absent);
        }
    }
    for (k, item) in t.iter() {
        let Some(sub) = item.as_table_like() else {
            continue;
        };
        let key = join(path, k);
        let sub_present = present
            .and_then(|p| p.get(k))
            .and_then(|i| i.as_table_like());
        out.push('\n');
        if let Some(d) = doc(&key) {
            comment(out, d, "");
        }
        if sub_present.is_none() {
            out.push_str("# ");
        }
        out.push_str(&format!("[{key}]\n"));
        section(out, &key, sub, sub_present);
    }
}

fn join(path: &str, k: &str) -> String {
    if path.is_empty() {
        k.to_string()
    } else {
        format!("{path}.{k}")
    }
}

/// The default scenario as a commented TOML file: every key with its default value and a
/// comment giving its meaning, unit and symbol in the paper, grouped by section. Optional keys
/// (`seafloor.file`, `seafloor.origin`, `seafloor.crs`, the `[initial]` section) are shown
/// commented out, with an example.
pub fn default_toml() -> String {
    let full = Schema::new();
    let defaults = schema::to_document(&Scenario::default());
    let mut out = String::from(HEADER);
    section(
        &mut out,
        "",
        full.root(),
        Some(defaults.as_table() as &dyn TableLike),
    );
    out
}
