//! Mission set-up around Algorithm 1's loop: the floor a scenario names and where it came from,
//! the initial state (line 5), the check that a window's start is feasible, and the chaining of
//! one window into the next (line 7).

use crate::error::PlanError;
use crate::plan::{AuvState, InitialState, SeafloorRecord};
use crate::scenario::Scenario;
use crate::seafloor::{GridFormat, LoadOptions, Region, Seafloor, Values};
use crate::trajectory::{Start, Trajectory};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Where a floor came from, as the plan records it, and what the loader had to say.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorSource {
    /// "synthetic" or "file".
    pub source: String,
    /// The file's path (absolute when the planner loaded it).
    pub path: Option<String>,
    /// "synthetic", "esri-ascii" or "geotiff".
    pub format: String,
    /// The file's CRS ("none", "EPSG:4326", …).
    pub crs: String,
    /// The sign convention of the file's values (elevation or depth).
    pub values: Values,
    /// [lat, lon] of the local frame's origin for a geographic grid.
    pub origin: Option<[f64; 2]>,
    /// Warnings of the loader (likely sign-convention mistakes, datum assumptions), for the
    /// user; not recorded in the plan.
    pub warnings: Vec<String>,
}

impl FloorSource {
    /// What a scenario names: its grid file (`seafloor.file`, as given), or the synthetic
    /// floor. For a floor loaded by [`scenario_floor`], use the source it returns (which has
    /// the absolute path, the format and the CRS).
    pub fn of_scenario(s: &Scenario) -> FloorSource {
        match &s.seafloor.file {
            Some(f) => FloorSource::file(Some(f.clone())),
            None => FloorSource::synthetic(),
        }
    }

    /// The synthetic floor.
    pub fn synthetic() -> FloorSource {
        FloorSource {
            source: "synthetic".into(),
            path: None,
            format: "synthetic".into(),
            crs: "none".into(),
            values: Values::Elevation,
            origin: None,
            warnings: Vec::new(),
        }
    }

    /// An ESRI ASCII grid file of elevations in metres (no CRS).
    pub fn file(path: Option<String>) -> FloorSource {
        FloorSource {
            source: "file".into(),
            path,
            format: GridFormat::EsriAscii.name().into(),
            ..FloorSource::synthetic()
        }
    }

    /// The plan's record of `floor` loaded from this source: where it came from, its grid and
    /// its fingerprint.
    pub fn record(&self, floor: &Seafloor) -> SeafloorRecord {
        let (z_min, z_max) = floor.z_range();
        SeafloorRecord {
            source: self.source.clone(),
            path: self.path.clone(),
            format: self.format.clone(),
            crs: self.crs.clone(),
            values: self.values,
            origin: self.origin,
            lattice: floor.lattice(),
            z_min,
            z_max,
            fingerprint: floor.fingerprint(),
        }
    }
}

/// The window's start must satisfy the constraints that no input can change at k = 0, over the
/// floor and over its keep-out field `keep_out` (`Seafloor::keep_out`).
pub fn check_start(
    s: &Scenario,
    floor: &Seafloor,
    keep_out: &Seafloor,
    start: &Start,
    window: usize,
) -> Result<(), PlanError> {
    let bad = |why: String| Err(PlanError::InvalidStart { window, why });
    if start.auvs.len() != s.team.auvs {
        return bad(format!(
            "{} AUV states for team.auvs = {}",
            start.auvs.len(),
            s.team.auvs
        ));
    }
    let tol = s.scp.feasibility_tol;
    if let Some(why) = position_problem(floor, start.usv[0], start.usv[1]) {
        return bad(format!("the USV {why}"));
    }
    let [x, y] = start.usv;
    let field = keep_out.elevation(x, y)?;
    if field > tol {
        return bad(format!(
            "the USV at ({x:.1}, {y:.1}) is {}",
            next_to_obstacle(field, floor.elevation(x, y)?)
        ));
    }
    for (n, a) in start.auvs.iter().enumerate() {
        let p = a.position;
        let d =
            ((p[0] - start.usv[0]).powi(2) + (p[1] - start.usv[1]).powi(2) + p[2] * p[2]).sqrt();
        if d > s.acoustic.sonar_range + 1e-9 {
            return bad(format!(
                "AUV {n} is {d:.1} m from the USV, beyond the sonar range d_s = {} m (C1_6 at k = 0)",
                s.acoustic.sonar_range
            ));
        }
        if p[2] > -s.auv.surface_clearance + 1e-9 {
            return bad(format!(
                "AUV {n} is at z = {:.2} m, above −surface_clearance = {} m (C1_4)",
                p[2], -s.auv.surface_clearance
            ));
        }
        if let Some(why) = position_problem(floor, p[0], p[1]) {
            return bad(format!("AUV {n} {why}"));
        }
        let z = floor.elevation(p[0], p[1])?;
        if p[2] < z + s.auv.floor_clearance - tol {
            let (h, eps) = (p[2] - z, s.auv.floor_clearance);
            return bad(if h < 0.0 {
                format!(
                    "AUV {n} at z = {:.2} m is {:.2} m below the floor (z = {z:.2} m); it needs \
                     ε = {eps} m of clearance above it (C2_2)",
                    p[2], -h
                )
            } else {
                format!(
                    "AUV {n} at z = {:.2} m is {h:.2} m above the floor (z = {z:.2} m), less \
                     than ε = {eps} m (C2_2)",
                    p[2]
                )
            });
        }
        let field = keep_out.elevation(p[0], p[1])?;
        if p[2] < field + s.auv.floor_clearance - tol {
            return bad(format!(
                "AUV {n} at ({:.1}, {:.1}, {:.1}) is {}; it needs ε = {} m of clearance above it",
                p[0],
                p[1],
                p[2],
                next_to_obstacle(field, z),
                s.auv.floor_clearance
            ));
        }
        let v = (a.velocity.iter().map(|c| c * c).sum::<f64>()).sqrt();
        if v > s.auv.max_speed + 1e-6 {
            return bad(format!(
                "AUV {n} moves at {v:.3} m/s, above V_max = {} (C1_7)",
                s.auv.max_speed
            ));
        }
    }
    Ok(())
}

/// Why a point off every obstacle cell is kept out of all the same: `field` is the keep-out
/// field there and `z` the floor.
fn next_to_obstacle(field: f64, z: f64) -> String {
    format!(
        "next to an obstacle cell (NODATA or land): the planner keeps every vehicle out of \
         obstacle cells with a keep-out field that rises from the floor (here z = {z:.1} m) \
         to above the surface over them, here z = {field:.1} m (at most one cell of margin; \
         move the start away from the obstacle)"
    )
}

/// Why a vehicle cannot start at (x, y): outside the grid, or in an obstacle cell (NODATA,
/// land). The text starts with the position.
fn position_problem(floor: &Seafloor, x: f64, y: f64) -> Option<String> {
    let at = format!("at ({x:.1}, {y:.1})");
    if !floor.contains(x, y) {
        return Some(format!(
            "{at} is outside the seafloor grid, which covers {}",
            floor.extent()
        ));
    }
    match floor.obstacle(x, y) {
        Ok(None) => None,
        Ok(Some(o)) => Some(format!("{at} is {o}")),
        Err(e) => Some(format!("{at}: {e}")),
    }
}

/// Algorithm 1, line 5: USV at the origin (or at `initial.usv` when `[initial]` lists no AUV);
/// AUVs at seeded random points in the half ball of radius d_s below it, at least
/// surface_clearance below the surface, within the depth rating (`auv.max_depth`), ε above the
/// floor's keep-out field `keep_out` (`Seafloor::keep_out`: the floor itself away from
/// obstacles) and `auv.min_separation` from every AUV drawn before (`team::separation`), at
/// rest. Or the explicit `[initial]` of the scenario.
pub fn initial_state(
    s: &Scenario,
    floor: &Seafloor,
    keep_out: &Seafloor,
) -> Result<InitialState, PlanError> {
    let usv = s.initial.as_ref().map_or([0.0, 0.0], |init| init.usv);
    if let Some(init) = s.initial.as_ref().filter(|init| !init.auvs.is_empty()) {
        return Ok(InitialState {
            origin: "explicit".into(),
            usv: init.usv,
            auvs: init
                .auvs
                .iter()
                .map(|p| AuvState {
                    position: *p,
                    velocity: [0.0; 3],
                })
                .collect(),
        });
    }
    if let Some(why) = position_problem(floor, usv[0], usv[1]) {
        return Err(PlanError::InvalidStart {
            window: 0,
            why: format!(
                "the USV {why} (without [initial] the USV starts at the origin of the frame; \
                 give [initial] positions inside the grid)"
            ),
        });
    }
    let mut rng = ChaCha8Rng::seed_from_u64(s.seed);
    let ds = s.acoustic.sonar_range;
    let mut auvs = Vec::with_capacity(s.team.auvs);
    const TRIES: usize = 100_000;
    for n in 0..s.team.auvs {
        let mut found = None;
        for _ in 0..TRIES {
            let d = [
                rng.gen_range(-ds..ds),
                rng.gen_range(-ds..ds),
                rng.gen_range(-ds..0.0),
            ];
            // below the surface clearance and within the depth rating
            let depth = -d[2];
            if d.iter().map(|c| c * c).sum::<f64>() > ds * ds
                || depth < s.auv.surface_clearance
                || depth > s.auv.max_depth
            {
                continue;
            }
            let p = [usv[0] + d[0], usv[1] + d[1], d[2]];
            if !floor.contains(p[0], p[1]) || floor.is_obstacle(p[0], p[1])? {
                continue;
            }
            let crowded = auvs.iter().any(|a: &AuvState| {
                let q = a.position;
                let d2: f64 = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum();
                d2 < s.auv.min_separation.powi(2)
            });
            if crowded {
                continue;
            }
            if p[2] >= keep_out.elevation(p[0], p[1])? + s.auv.floor_clearance {
                found = Some(p);
                break;
            }
        }
        let Some(p) = found else {
            let z0 = floor.elevation(usv[0], usv[1]).unwrap_or(f64::NAN);
            return Err(PlanError::NoInitialPosition(format!(
                "no point for AUV {n} in {TRIES} draws within d_s = {ds} m of the USV, at least \
                 {} m below the surface, at most {} m deep, {} m above the floor and {} m from \
                 the AUVs drawn before (floor under the USV: z = {z0:.1} m)",
                s.auv.surface_clearance,
                s.auv.max_depth,
                s.auv.floor_clearance,
                s.auv.min_separation
            )));
        };
        auvs.push(AuvState {
            position: p,
            velocity: [0.0; 3],
        });
    }
    Ok(InitialState {
        origin: "seeded".into(),
        usv,
        auvs,
    })
}

/// The rectangle of the planner's frame that the mission can reach, [x_min, x_max, y_min,
/// y_max], metres: the bounding box of the start (the explicit `[initial]` positions, or the
/// USV at the origin with the AUVs within d_s of it), widened by twice the distance the fastest
/// vehicle covers at its speed limit over every window (speed limits hold at the samples; the
/// factor 2 covers the path between samples), plus d_max and the swath width.
pub fn mission_area(s: &Scenario) -> [f64; 4] {
    let mut pts: Vec<[f64; 2]> = Vec::new();
    let d = s.acoustic.sonar_range;
    match &s.initial {
        Some(init) if !init.auvs.is_empty() => {
            pts.push(init.usv);
            pts.extend(init.auvs.iter().map(|p| [p[0], p[1]]));
        }
        // AUVs drawn within d_s of the USV's start
        Some(init) => {
            let [x, y] = init.usv;
            pts.extend([[x - d, y - d], [x + d, y + d]]);
        }
        None => pts.extend([[-d, -d], [d, d]]),
    }
    let span = (s.windows * s.horizon.steps) as f64 * s.horizon.dt;
    let reach = 2.0 * span * s.auv.max_speed.max(s.usv.max_speed)
        + s.acoustic.max_range.max(s.acoustic.sonar_range)
        + s.auv.swath_width;
    let fold = |f: fn(f64, f64) -> f64, d: usize, init: f64| pts.iter().map(|p| p[d]).fold(init, f);
    [
        fold(f64::min, 0, f64::INFINITY) - reach,
        fold(f64::max, 0, f64::NEG_INFINITY) + reach,
        fold(f64::min, 1, f64::INFINITY) - reach,
        fold(f64::max, 1, f64::NEG_INFINITY) + reach,
    ]
}

/// The seafloor a scenario names: the grid file (a relative path is taken from `base_dir`, the
/// scenario file's directory), cut to the [`mission_area`], or the synthetic floor. Returns it
/// with its source record (and the loader's warnings).
pub fn scenario_floor(
    s: &Scenario,
    base_dir: &std::path::Path,
) -> Result<(Seafloor, FloorSource), PlanError> {
    match &s.seafloor.file {
        Some(f) => {
            let path = base_dir.join(f);
            let [x_min, x_max, y_min, y_max] = mission_area(s);
            let opts = LoadOptions {
                values: s.seafloor.values,
                origin: s.seafloor.origin,
                crs: s.seafloor.crs.clone(),
                region: Region::Area {
                    x_min,
                    x_max,
                    y_min,
                    y_max,
                },
            };
            let l = crate::seafloor::load(&path, &opts)?;
            // recorded absolute, so that `shoal check` finds it from any working directory
            let recorded = std::fs::canonicalize(&path).unwrap_or(path);
            let source = FloorSource {
                source: "file".into(),
                path: Some(recorded.display().to_string()),
                format: l.format.name().into(),
                crs: l.crs.to_string(),
                values: l.values,
                origin: l.origin,
                warnings: l.warnings,
            };
            Ok((l.floor, source))
        }
        None => Ok((
            Seafloor::synthetic(&s.seafloor.synthetic, s.seed)?,
            FloorSource::synthetic(),
        )),
    }
}

/// Algorithm 1, line 7: the next window starts where `t` ends, and its first guess continues
/// the USV's last course (`heading` when the USV stood still at the end).
pub fn next_window(t: &Trajectory, heading: Option<f64>) -> (Start, Option<f64>) {
    let last = t.usv_u.last().copied().unwrap_or([0.0; 2]);
    let heading = if last[0].hypot(last[1]) > 1e-6 {
        Some(last[1].atan2(last[0]))
    } else {
        heading
    };
    (t.end(), heading)
}
