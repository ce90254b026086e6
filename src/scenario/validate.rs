//! Range checks on a deserialised scenario. Types are checked by deserialisation; this checks
//! values (and relations between values) that no type can express.

use super::Scenario;

/// The largest `auv.max_flight_path_angle` accepted, rad: π/2 as a user writes it, rounded up
/// to 1.5708 (from `NO_ANGLE_LIMIT` on, no angle limit).
#[allow(clippy::approx_constant)]
const MAX_ANGLE: f64 = 1.5708;

/// One broken rule: the dotted key at fault (array elements as `key[i]`), its value as written
/// for a person, and what is allowed. `related` names other keys the rule involves (e.g.
/// `acoustic.sonar_range` for `acoustic.max_range ≥ acoustic.sonar_range`); the loaders point at
/// whichever of `key` and `related` was set last, since that is the setting that broke the rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    /// The dotted key at fault, array elements as `key[i]`.
    pub key: String,
    /// Its value, as written for a person.
    pub value: String,
    /// What is allowed, e.g. "must be a positive number …".
    pub allowed: String,
    /// Other dotted keys the rule involves.
    pub related: Vec<String>,
}

impl std::fmt::Display for Violation {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} = {}: {}", self.key, self.value, self.allowed)
    }
}

/// Largest team the planner accepts (the problem size grows with N²).
pub const MAX_AUVS: usize = 64;
/// Finest `acoustic.resolution`, metres: the planner's and the checker's work grow as 1/r, and
/// at 10⁻¹² the planner once grew to 24 GB.
pub const MIN_RESOLUTION: f64 = 0.1;
/// Coarsest `acoustic.resolution`, metres.
pub const MAX_RESOLUTION: f64 = 100.0;
/// Largest horizon, in steps.
pub const MAX_STEPS: usize = 1000;
/// Most windows a mission may have (10 000 windows of the paper's 2 000 s: 231 days).
pub const MAX_WINDOWS: usize = 10_000;
/// Most SCP iterations a stage may take.
pub const MAX_SCP_ITERATIONS: usize = 100_000;
/// Largest synthetic grid, in cells per side.
pub const MAX_CELLS_PER_SIDE: f64 = 10_000.0;
/// Largest number of synthetic seamounts, and of valleys.
pub const MAX_FEATURES: usize = 10_000;
/// Most first courses `usv.courses` may ask for (one every 5°).
pub const MAX_COURSES: usize = 72;
/// Allowed `simulation.step`, seconds: RK4 on the 6-DoF REMUS 100 is stable at full speed with
/// full fins up to 0.1 s and not at 0.3 s; below 1 ms a step only costs time (the model's
/// fastest motions, pitch and yaw under full fins, take tenths of a second).
pub const SIM_STEP: (f64, f64) = (0.001, 0.2);
/// Allowed `navigation.sample_period`, seconds: DVL, compass and depth sensors sample at
/// 0.1–100 Hz.
pub const SAMPLE_PERIOD: (f64, f64) = (0.01, 10.0);
/// Allowed `navigation.acoustic_period`, seconds: a cycle shorter than a second cannot carry
/// a ping over a kilometre (sound travels 1.5 km/s); one longer than an hour leaves dead
/// reckoning uncorrected for a whole mission.
pub const ACOUSTIC_PERIOD: (f64, f64) = (1.0, 3600.0);
/// Allowed standard deviations of `navigation.gps_noise`, `initial_noise` and `range_noise`,
/// metres: the estimators take standard deviations well inside [1e-9, 1e9] m.
pub const POSITION_NOISE: (f64, f64) = (0.001, 1000.0);

/// The range of every integer key, as [`validate`] checks it: (dotted key, least, largest).
/// The deserialiser's errors for such a key (a negative or fractional number) name the range
/// from here rather than "a non-negative integer".
pub(crate) const INTEGER_RANGES: &[(&str, u64, Option<u64>)] = &[
    ("seed", 0, None),
    ("windows", 1, Some(MAX_WINDOWS as u64)),
    ("team.auvs", 1, Some(MAX_AUVS as u64)),
    ("horizon.steps", 1, Some(MAX_STEPS as u64)),
    ("acoustic.los_rounds", 1, Some(100)),
    ("usv.courses", 1, Some(MAX_COURSES as u64)),
    ("seafloor.synthetic.seamounts", 0, Some(MAX_FEATURES as u64)),
    ("seafloor.synthetic.valleys", 0, Some(MAX_FEATURES as u64)),
    ("scp.max_iterations", 1, Some(MAX_SCP_ITERATIONS as u64)),
    (
        "scp.step1_max_iterations",
        1,
        Some(MAX_SCP_ITERATIONS as u64),
    ),
    ("sampling.samples", 1, Some(1000)),
    ("sampling.tree_budget", 1, Some(100_000)),
    ("sampling.attempts", 1, Some(100_000)),
];

/// "an integer from 1 to 64" or "an integer ≥ 1": what the integer key `key` allows, if it is
/// one of [`INTEGER_RANGES`].
pub(crate) fn integer_text(key: &str) -> Option<String> {
    let (_, lo, hi) = INTEGER_RANGES.iter().find(|(k, _, _)| *k == key)?;
    Some(match hi {
        Some(hi) => format!("an integer from {lo} to {hi}"),
        None => format!("an integer ≥ {lo}"),
    })
}

#[derive(Default)]
struct Checker {
    out: Vec<Violation>,
}

/// `x` for a person: plain, or in scientific notation when tiny or huge (1e-300, not 300
/// zeros).
fn num(x: f64) -> String {
    if x != 0.0 && x.is_finite() && (x.abs() < 1e-4 || x.abs() >= 1e16) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

fn arr(xs: &[f64]) -> String {
    let parts: Vec<String> = xs.iter().map(|x| num(*x)).collect();
    format!("[{}]", parts.join(", "))
}

impl Checker {
    fn push(&mut self, key: &str, value: String, allowed: String, related: &[&str]) {
        self.out.push(Violation {
            key: key.to_string(),
            value,
            allowed,
            related: related.iter().map(|s| s.to_string()).collect(),
        });
    }

    /// A float that must be finite and satisfy `ok`.
    fn float(&mut self, key: &str, x: f64, ok: bool, allowed: impl Into<String>) {
        if !(x.is_finite() && ok) {
            self.push(key, num(x), allowed.into(), &[]);
        }
    }

    fn float_rel(&mut self, key: &str, x: f64, ok: bool, allowed: String, related: &[&str]) {
        if !(x.is_finite() && ok) {
            self.push(key, num(x), allowed, related);
        }
    }

    /// A float in `[lo, hi]` (in `unit`): "allowed from lo to hi unit (what)".
    fn between(&mut self, key: &str, x: f64, (lo, hi): (f64, f64), unit: &str, what: &str) {
        self.float(
            key,
            x,
            (lo..=hi).contains(&x),
            format!("allowed from {} to {} {unit} ({what})", num(lo), num(hi)),
        );
    }

    fn positive(&mut self, key: &str, x: f64, what: &str) {
        self.float(key, x, x > 0.0, format!("must be a positive number {what}"));
    }

    fn non_negative(&mut self, key: &str, x: f64, what: &str) {
        self.float(key, x, x >= 0.0, format!("must be a number ≥ 0 {what}"));
    }

    fn non_positive(&mut self, key: &str, x: f64, what: &str) {
        self.float(
            key,
            x,
            x <= 0.0,
            format!("must be ≤ 0 {what} (Fossen's sign convention: negative)"),
        );
    }

    fn finite(&mut self, key: &str, x: f64, what: &str) {
        self.float(key, x, true, format!("must be a finite number {what}"));
    }

    fn finite_arr(&mut self, key: &str, xs: &[f64], allowed: &str) {
        if xs.iter().any(|x| !x.is_finite()) {
            self.push(key, arr(xs), allowed.to_string(), &[]);
        }
    }

    fn int(&mut self, key: &str, n: usize, ok: bool, allowed: impl Into<String>) {
        if !ok {
            self.push(key, n.to_string(), allowed.into(), &[]);
        }
    }

    /// [lo, hi] with 0 < lo ≤ hi.
    fn range_pair(&mut self, key: &str, p: [f64; 2], what: &str) {
        let ok = p.iter().all(|x| x.is_finite()) && p[0] > 0.0 && p[0] <= p[1];
        if !ok {
            self.push(
                key,
                arr(&p),
                format!("must be [lo, hi] {what} with 0 < lo ≤ hi"),
                &[],
            );
        }
    }
}

/// Check every range rule. Returns all broken rules, in a fixed order (the order of the fields
/// in the file); the loaders report the first.
pub fn validate(s: &Scenario) -> Result<(), Vec<Violation>> {
    let mut c = Checker::default();

    c.int(
        "windows",
        s.windows,
        (1..=MAX_WINDOWS).contains(&s.windows),
        format!("must be an integer from 1 to {MAX_WINDOWS} (number of receding-horizon windows)"),
    );
    c.int(
        "team.auvs",
        s.team.auvs,
        (1..=MAX_AUVS).contains(&s.team.auvs),
        format!("must be an integer from 1 to {MAX_AUVS} (N, the number of AUVs)"),
    );
    c.int(
        "horizon.steps",
        s.horizon.steps,
        (1..=MAX_STEPS).contains(&s.horizon.steps),
        format!("must be an integer from 1 to {MAX_STEPS} (K, time steps per window)"),
    );
    c.positive(
        "horizon.dt",
        s.horizon.dt,
        "of seconds (δ, the sampling time)",
    );

    // Acoustic.
    let a = &s.acoustic;
    c.positive(
        "acoustic.sonar_range",
        a.sonar_range,
        "of metres (d_s, the sonar range)",
    );
    c.float_rel(
        "acoustic.band_tolerance",
        a.band_tolerance,
        a.band_tolerance > 0.0 && a.band_tolerance < a.sonar_range,
        format!(
            "must be a number of metres with 0 < d_t < d_s = acoustic.sonar_range = {}",
            num(a.sonar_range)
        ),
        &["acoustic.sonar_range"],
    );
    c.float_rel(
        "acoustic.link_margin",
        a.link_margin,
        a.link_margin > 0.0
            && a.link_margin <= 1.0
            && a.link_margin * a.sonar_range > a.band_tolerance,
        format!(
            "must be a fraction ρ ≤ 1 with ρ·d_s > d_t (the band [ρ·d_s − d_t, ρ·d_s] of every \
             planned link), here d_s = acoustic.sonar_range = {} and d_t = \
             acoustic.band_tolerance = {}",
            num(a.sonar_range),
            num(a.band_tolerance)
        ),
        &["acoustic.sonar_range", "acoustic.band_tolerance"],
    );
    c.float_rel(
        "acoustic.max_range",
        a.max_range,
        a.max_range >= a.sonar_range,
        format!(
            "must be a number of metres ≥ d_s = acoustic.sonar_range = {} (d_max of C1_5 \
             must be at least the sonar range d_s of C1_6; d_s > d_max is an error)",
            num(a.sonar_range)
        ),
        &["acoustic.sonar_range"],
    );
    c.positive(
        "acoustic.los_shrink",
        a.los_shrink,
        "of metres (how much a blocked link's range is lowered per round)",
    );
    c.int(
        "acoustic.los_rounds",
        a.los_rounds,
        (1..=100).contains(&a.los_rounds),
        "must be an integer from 1 to 100 (P5 solves per window in the line-of-sight loop)",
    );
    c.float(
        "acoustic.resolution",
        a.resolution,
        (MIN_RESOLUTION..=MAX_RESOLUTION).contains(&a.resolution),
        format!(
            "must be a number of metres from {MIN_RESOLUTION} to {MAX_RESOLUTION} (r, step of the \
             sampling 𝓛_r of segments and links: finer than 0.1 m only costs time, the floor \
             being bilinear between its nodes; coarser than 100 m could step over a seamount)"
        ),
    );

    // AUV.
    let v = &s.auv;
    c.positive("auv.max_speed", v.max_speed, "of m/s (V_max of C1_7)");
    c.positive(
        "auv.max_heading_rate",
        v.max_heading_rate,
        "of rad/s (ψ̇_max of C1_14)",
    );
    c.float_rel(
        "auv.min_heading_speed",
        v.min_heading_speed,
        v.min_heading_speed >= 0.0 && v.min_heading_speed < v.max_speed,
        format!(
            "must be a number of m/s with 0 ≤ value < auv.max_speed = {}",
            num(v.max_speed)
        ),
        &["auv.max_speed"],
    );
    c.float_rel(
        "auv.max_depth",
        v.max_depth,
        // (a non-finite clearance is its own key's error)
        v.max_depth > v.surface_clearance || !v.surface_clearance.is_finite(),
        format!(
            "must be a number of metres above auv.surface_clearance = {} (the depth rating)",
            num(v.surface_clearance)
        ),
        &["auv.surface_clearance"],
    );
    c.float(
        "auv.max_flight_path_angle",
        v.max_flight_path_angle,
        v.max_flight_path_angle > 0.0 && v.max_flight_path_angle <= MAX_ANGLE,
        "must be an angle in radians with 0 < value ≤ 1.5708 (π/2 rounded; from 1.57 on: no \
         limit, a vehicle that moves vertically at rest)",
    );
    c.float(
        "auv.level_speed",
        v.level_speed,
        // only the climb line reads it, with a cruise floor, as min(level_speed, min_speed)
        v.level_speed >= 0.0 && v.level_speed <= 1e3,
        "must be a number of m/s with 0 ≤ value ≤ 1000 (above auv.min_speed the climb line \
         takes auv.min_speed)",
    );
    c.float(
        "auv.climb_per_speed",
        v.climb_per_speed,
        v.climb_per_speed > 0.0 && v.climb_per_speed <= 1e3,
        "must be a number with 0 < value ≤ 1000 (m/s of climb per m/s of speed)",
    );
    c.float_rel(
        "auv.min_speed",
        v.min_speed,
        v.min_speed == 0.0 || (v.min_speed >= v.min_heading_speed && v.min_speed < v.max_speed),
        format!(
            "must be 0 (no cruise floor: a vehicle that holds depth at any speed, such as a \
             glider or a hovering AUV) or a number of m/s with auv.min_heading_speed = {} ≤ \
             value < auv.max_speed = {}",
            num(v.min_heading_speed),
            num(v.max_speed)
        ),
        &["auv.min_heading_speed", "auv.max_speed"],
    );
    c.non_negative(
        "auv.floor_clearance",
        v.floor_clearance,
        "metres (ε of C2_2)",
    );
    c.non_negative(
        "auv.surface_clearance",
        v.surface_clearance,
        "metres (C1_4)",
    );
    c.non_negative(
        "auv.min_separation",
        v.min_separation,
        "metres (the least distance between two AUVs; 0 turns it off)",
    );
    c.positive(
        "auv.swath_width",
        v.swath_width,
        "of metres (sensor swath, explored-area metric)",
    );
    c.positive(
        "auv.survey_altitude",
        v.survey_altitude,
        "of metres (highest altitude of a swath counted as explored)",
    );
    c.positive("auv.mass", v.mass, "of kg (m)");
    c.non_positive("auv.added_mass_surge", v.added_mass_surge, "kg (γ_v̇x, X_u̇)");
    c.non_positive("auv.added_mass_heave", v.added_mass_heave, "kg (γ_v̇z, Z_ẇ)");
    c.non_positive("auv.damping_surge", v.damping_surge, "kg/s (γ_vx, X_u)");
    c.non_positive("auv.damping_heave", v.damping_heave, "kg/s (γ_vz, Z_w)");
    c.positive("auv.inertia_yaw", v.inertia_yaw, "of kg·m² (J_z)");
    c.non_positive("auv.added_inertia_yaw", v.added_inertia_yaw, "kg·m² (N_ṙ)");
    // With mass > 0 and added masses ≤ 0 these hold; kept so the model's divisors are
    // guarded here even if the sign rules above are ever relaxed.
    for (key, added, base_key, base) in [
        (
            "auv.added_mass_surge",
            v.added_mass_surge,
            "auv.mass",
            v.mass,
        ),
        (
            "auv.added_mass_heave",
            v.added_mass_heave,
            "auv.mass",
            v.mass,
        ),
        (
            "auv.added_inertia_yaw",
            v.added_inertia_yaw,
            "auv.inertia_yaw",
            v.inertia_yaw,
        ),
    ] {
        if base.is_finite() && added.is_finite() {
            c.float_rel(
                key,
                added,
                base - added > 0.0,
                format!("{base_key} − {key} must be > 0"),
                &[base_key],
            );
        }
    }
    c.non_positive("auv.damping_yaw", v.damping_yaw, "kg·m²/s (γ_ωz, N_r)");

    // USV.
    let u = &s.usv;
    c.positive("usv.max_speed", u.max_speed, "of m/s");
    c.finite_arr(
        "usv.destination",
        &u.destination,
        "must be two finite numbers [x, y] in metres (P_USV[∞] of OF1_8_2)",
    );
    c.finite("usv.initial_heading", u.initial_heading, "of radians");
    c.int(
        "usv.courses",
        u.courses,
        (1..=MAX_COURSES).contains(&u.courses),
        format!("must be an integer from 1 to {MAX_COURSES}"),
    );

    // Weights.
    let w = &s.weights;
    for (key, x, sym) in [
        ("weights.w1", w.w1, "w1 of OF1_1"),
        ("weights.w2", w.w2, "w2 of OF1_2"),
        ("weights.w3", w.w3, "w3 of OF1_3"),
        ("weights.w4", w.w4, "w4 of OF1_4"),
        ("weights.w5", w.w5, "w5 of OF1_5"),
        ("weights.w6", w.w6, "w6 of OF1_6"),
        ("weights.w7", w.w7, "w7 of OF1_7"),
        ("weights.w8", w.w8, "w8 of OF1_8"),
        ("weights.w8_2", w.w8_2, "w8_2 of OF1_8_2"),
        ("weights.w_lanes", w.w_lanes, "w_lanes of the lanes term"),
    ] {
        c.non_negative(key, x, &format!("({sym})"));
    }

    // Seafloor.
    if let Some(f) = &s.seafloor.file {
        if f.trim().is_empty()
            || crate::seafloor::GridFormat::from_path(std::path::Path::new(f)).is_none()
        {
            c.push(
                "seafloor.file",
                format!("{f:?}"),
                "must be the path of a grid file: an ESRI ASCII grid (.asc), a GeoTIFF \
                 (.tif, .tiff), or with the gdal cargo feature a file GDAL reads (.nc, .grd, \
                 .bag, .xyz, ...) (leave the key out to use the synthetic floor)"
                    .to_string(),
                &[],
            );
        }
    } else if s.seafloor.values != crate::seafloor::Values::Elevation {
        c.push(
            "seafloor.values",
            "\"depth\"".to_string(),
            "is allowed only with a grid file (seafloor.file): the synthetic floor is made of \
             elevations, so leave it out (or \"elevation\")"
                .to_string(),
            &["seafloor.file"],
        );
    }
    if let Some(o) = s.seafloor.origin {
        let max = crate::seafloor::geo::MAX_ORIGIN_LATITUDE;
        if !(o[0].is_finite() && o[0].abs() <= max && o[1].is_finite() && o[1].abs() <= 360.0) {
            c.push(
                "seafloor.origin",
                arr(&o),
                format!(
                    "must be [latitude, longitude] in degrees, |latitude| ≤ {max}, \
                     |longitude| ≤ 360"
                ),
                &[],
            );
        } else if s.seafloor.file.is_none() {
            c.push(
                "seafloor.origin",
                arr(&o),
                "is allowed only with a geographic grid file (seafloor.file): the synthetic \
                 floor is already in metres, so leave it out"
                    .to_string(),
                &["seafloor.file"],
            );
        }
    }
    if let Some(text) = &s.seafloor.crs {
        match crate::seafloor::parse_crs(text) {
            Err(reason) => c.push(
                "seafloor.crs",
                format!("{text:?}"),
                format!("must be a CRS: {reason}"),
                &[],
            ),
            Ok(_) if s.seafloor.file.is_none() => c.push(
                "seafloor.crs",
                format!("{text:?}"),
                "is allowed only with a grid file (seafloor.file): the synthetic floor is \
                 already in metres, so leave it out"
                    .to_string(),
                &["seafloor.file"],
            ),
            Ok(crate::seafloor::Crs::Projected { .. }) if s.seafloor.origin.is_some() => c.push(
                "seafloor.origin",
                arr(&s.seafloor.origin.unwrap_or_default()),
                format!(
                    "is allowed only with a geographic grid; seafloor.crs = {text:?} is \
                     projected, and its own coordinates (metres) are the planner's frame, so \
                     leave seafloor.origin out"
                ),
                &["seafloor.crs"],
            ),
            Ok(_) => {}
        }
    }
    let g = &s.seafloor.synthetic;
    if !(g.size.iter().all(|x| x.is_finite() && *x > 0.0)) {
        c.push(
            "seafloor.synthetic.size",
            arr(&g.size),
            "must be two positive numbers [x, y] of metres".to_string(),
            &[],
        );
    }
    c.positive("seafloor.synthetic.cell", g.cell, "of metres");
    if g.cell.is_finite() && g.cell > 0.0 && g.size.iter().all(|x| x.is_finite()) {
        let cells = g.size[0].max(g.size[1]) / g.cell;
        if cells > MAX_CELLS_PER_SIDE {
            c.push(
                "seafloor.synthetic.size",
                arr(&g.size),
                format!(
                    "size / seafloor.synthetic.cell = {} cells per side; at most {} allowed \
                     (enlarge the cell or shrink the area)",
                    num(cells.ceil()),
                    num(MAX_CELLS_PER_SIDE)
                ),
                &["seafloor.synthetic.cell"],
            );
        }
    }
    c.finite(
        "seafloor.synthetic.base_depth",
        g.base_depth,
        "of metres (elevation)",
    );
    c.finite_arr(
        "seafloor.synthetic.slope",
        &g.slope,
        "must be two finite numbers [dZ/dx, dZ/dy]",
    );
    c.int(
        "seafloor.synthetic.seamounts",
        g.seamounts,
        g.seamounts <= MAX_FEATURES,
        format!("must be an integer from 0 to {MAX_FEATURES}"),
    );
    c.int(
        "seafloor.synthetic.valleys",
        g.valleys,
        g.valleys <= MAX_FEATURES,
        format!("must be an integer from 0 to {MAX_FEATURES}"),
    );
    c.range_pair("seafloor.synthetic.relief", g.relief, "of metres");
    c.range_pair("seafloor.synthetic.radius", g.radius, "of metres");
    let d = g.depth_range;
    if !(d.iter().all(|x| x.is_finite()) && d[0] < d[1] && d[1] < 0.0) {
        c.push(
            "seafloor.synthetic.depth_range",
            arr(&d),
            "must be [deepest, shallowest] elevations in metres with deepest < shallowest < 0"
                .to_string(),
            &[],
        );
    }

    // SCP.
    let p = &s.scp;
    c.int(
        "scp.max_iterations",
        p.max_iterations,
        (1..=MAX_SCP_ITERATIONS).contains(&p.max_iterations),
        format!("must be an integer from 1 to {MAX_SCP_ITERATIONS}"),
    );
    c.positive("scp.tolerance", p.tolerance, "(relative decrease)");
    if let Some(n) = p.step1_max_iterations {
        c.int(
            "scp.step1_max_iterations",
            n,
            (1..=MAX_SCP_ITERATIONS).contains(&n),
            format!("must be an integer from 1 to {MAX_SCP_ITERATIONS}"),
        );
    }
    if let Some(t) = p.step1_tolerance {
        c.positive("scp.step1_tolerance", t, "(relative decrease)");
    }
    c.positive(
        "scp.feasibility_tol",
        p.feasibility_tol,
        "(metres, radians)",
    );
    c.positive("scp.trust_region", p.trust_region, "of metres");
    c.float_rel(
        "scp.min_trust_region",
        p.min_trust_region,
        p.min_trust_region > 0.0 && p.min_trust_region < p.trust_region,
        format!(
            "must be a number of metres with 0 < value < scp.trust_region = {}",
            num(p.trust_region)
        ),
        &["scp.trust_region"],
    );
    c.positive(
        "scp.penalty",
        p.penalty,
        "(λ, merit-function penalty weight)",
    );

    // What `shoal simulate` reads ([current], [navigation], [simulation]).
    sim(&mut c, s);

    // The RRT-like baseline ([sampling]).
    let g = &s.sampling;
    c.int(
        "sampling.samples",
        g.samples,
        (1..=1000).contains(&g.samples),
        "must be a whole number with 1 ≤ samples ≤ 1000",
    );
    c.int(
        "sampling.tree_budget",
        g.tree_budget,
        (1..=100_000).contains(&g.tree_budget),
        "must be a whole number with 1 ≤ tree_budget ≤ 100000",
    );
    c.int(
        "sampling.attempts",
        g.attempts,
        (1..=100_000).contains(&g.attempts),
        "must be a whole number with 1 ≤ attempts ≤ 100000",
    );

    // Initial state.
    if let Some(init) = &s.initial {
        c.finite_arr(
            "initial.usv",
            &init.usv,
            "must be two finite numbers [x, y] in metres (P_USV[0])",
        );
        if !init.auvs.is_empty() && init.auvs.len() != s.team.auvs {
            c.push(
                "initial.auvs",
                match init.auvs.len() {
                    1 => "[1 position]".to_string(),
                    n => format!("[{n} positions]"),
                },
                format!(
                    "must list exactly team.auvs = {} AUV positions (or none: drawn from seed \
                     about initial.usv), but lists {}",
                    s.team.auvs,
                    init.auvs.len()
                ),
                &["team.auvs"],
            );
        }
        for (i, p) in init.auvs.iter().enumerate() {
            if !(p.iter().all(|x| x.is_finite()) && p[2] < 0.0) {
                c.push(
                    &format!("initial.auvs[{i}]"),
                    arr(p),
                    "must be [x, y, z], finite metres, with z < 0 (under water)".to_string(),
                    &[],
                );
            }
        }
    }

    if c.out.is_empty() {
        Ok(())
    } else {
        Err(c.out)
    }
}

/// Whether `big` is a whole number (≥ 1) of `small`, to a relative 1e-9.
pub fn whole_multiple(big: f64, small: f64) -> bool {
    let r = big / small;
    r.is_finite() && r >= 1.0 - 1e-9 && (r - r.round()).abs() <= 1e-9 * r.max(1.0)
}

fn sim(c: &mut Checker, s: &Scenario) {
    let cur = &s.current;
    if !(cur.velocity.iter().all(|v| v.is_finite())
        && cur.velocity[0].hypot(cur.velocity[1]) <= 3.0)
    {
        c.push(
            "current.velocity",
            arr(&cur.velocity),
            "must be [east, north] in m/s, finite, with a speed of at most 3 m/s".to_string(),
            &[],
        );
    }
    if cur.file_east.is_some() != cur.file_north.is_some() {
        let (given, f, missing) = match (&cur.file_east, &cur.file_north) {
            (Some(f), _) => ("current.file_east", f.as_str(), "current.file_north"),
            (_, f) => (
                "current.file_north",
                f.as_deref().unwrap_or(""),
                "current.file_east",
            ),
        };
        c.push(
            given,
            format!("{f:?}"),
            format!(
                "needs {missing} too: the current's grid files come as a pair (its east and \
                 north components); allowed are both or neither"
            ),
            &[missing],
        );
    }
    for (key, f) in [
        ("current.file_east", &cur.file_east),
        ("current.file_north", &cur.file_north),
    ] {
        if let Some(f) = f {
            if f.trim().is_empty()
                || crate::seafloor::GridFormat::from_path(std::path::Path::new(f)).is_none()
            {
                c.push(
                    key,
                    format!("{f:?}"),
                    "must be the path of a grid file: an ESRI ASCII grid (.asc) or a GeoTIFF \
                     (.tif, .tiff) (leave both current.file_east and current.file_north out for \
                     a current uniform at each depth)"
                        .to_string(),
                    &[],
                );
            }
        }
    }
    for (i, p) in cur.profile.iter().enumerate() {
        let after = i == 0 || p[0] > cur.profile[i - 1][0];
        if !(p[0].is_finite() && p[0] >= 0.0 && after && p[1].is_finite() && p[1].abs() <= 10.0) {
            c.push(
                &format!("current.profile[{i}]"),
                arr(p),
                "must be [depth, factor]: depth in metres ≥ 0 and greater than the previous \
                 entry's, factor finite with |factor| ≤ 10"
                    .to_string(),
                &[],
            );
        }
    }
    let n = &s.navigation;
    c.between(
        "navigation.sample_period",
        n.sample_period,
        SAMPLE_PERIOD,
        "s",
        "sampling of the DVL, compass, depth sensor and GPS",
    );
    c.float(
        "navigation.dvl_noise",
        n.dvl_noise,
        (0.0..=1.0).contains(&n.dvl_noise),
        "allowed from 0 to 1 m/s (1σ of the DVL's velocity noise)",
    );
    c.float(
        "navigation.dvl_scale",
        n.dvl_scale,
        (0.0..0.1).contains(&n.dvl_scale),
        "must be a fraction with 0 ≤ value < 0.1 (1σ of the DVL's scale-factor error)",
    );
    c.positive(
        "navigation.dvl_max_altitude",
        n.dvl_max_altitude,
        "of metres",
    );
    c.float(
        "navigation.heading_noise",
        n.heading_noise,
        (0.0..=0.5).contains(&n.heading_noise),
        "allowed from 0 to 0.5 rad (1σ of the compass noise)",
    );
    c.float(
        "navigation.heading_bias",
        n.heading_bias,
        (0.0..0.5).contains(&n.heading_bias),
        "must be a number of radians with 0 ≤ value < 0.5 (1σ of the compass bias)",
    );
    c.float(
        "navigation.depth_noise",
        n.depth_noise,
        (0.0..=100.0).contains(&n.depth_noise),
        "allowed from 0 to 100 m (1σ of the depth sensor's noise)",
    );
    c.between(
        "navigation.gps_noise",
        n.gps_noise,
        POSITION_NOISE,
        "m",
        "1σ of the USV's GPS",
    );
    c.between(
        "navigation.initial_noise",
        n.initial_noise,
        POSITION_NOISE,
        "m",
        "1σ of each AUV's start fix",
    );
    c.between(
        "navigation.acoustic_period",
        n.acoustic_period,
        ACOUSTIC_PERIOD,
        "s",
        "the acoustic cycle: one ping per pair and one estimated position per vehicle each cycle",
    );
    if n.sample_period > 0.0
        && n.acoustic_period > 0.0
        && !whole_multiple(n.acoustic_period, n.sample_period)
    {
        c.push(
            "navigation.acoustic_period",
            num(n.acoustic_period),
            format!(
                "must be a whole number of navigation.sample_period = {} s",
                num(n.sample_period)
            ),
            &["navigation.sample_period"],
        );
    }
    c.positive("navigation.sound_speed", n.sound_speed, "of m/s");
    c.between(
        "navigation.range_noise",
        n.range_noise,
        POSITION_NOISE,
        "m",
        "1σ of an acoustic range",
    );
    c.float(
        "navigation.packet_success",
        n.packet_success,
        n.packet_success > 0.0 && n.packet_success <= 1.0,
        "must be a probability with 0 < value ≤ 1",
    );
    c.positive("navigation.range_falloff", n.range_falloff, "(an exponent)");
    let step = s.simulation.step;
    c.between(
        "simulation.step",
        step,
        SIM_STEP,
        "s",
        "the RK4 step of the 6-DoF model: stable up to 0.2 s, and finer than 0.001 s only \
         costs time",
    );
    if step >= SIM_STEP.0
        && step <= SIM_STEP.1
        && n.sample_period > 0.0
        && !whole_multiple(n.sample_period, step)
    {
        c.push(
            "simulation.step",
            num(step),
            format!(
                "must divide navigation.sample_period = {} s into a whole number of steps",
                num(n.sample_period)
            ),
            &["navigation.sample_period"],
        );
    }
}
