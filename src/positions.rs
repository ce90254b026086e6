//! A plan's positions in the floor's own coordinates (`shoal export PLAN --csv OUT`).
//!
//! The planner works in a metric frame (x east, y north, z up). The plan's seafloor record says
//! how that frame sits on the Earth, so any tool can convert:
//!
//! - **Geographic grid** (`seafloor.origin` set): the frame is the local tangent plane on WGS84 at
//!   `origin` ([`crate::seafloor::geo::LocalFrame`]); latitude and longitude come from its exact
//!   inverse, the same map the floor was loaded with (round trip to 1e-9 m). Longitudes keep the
//!   grid's convention (e.g. 0–360 for a grid given so).
//! - **Projected grid** (a CRS and no origin): the frame is the grid's own coordinates, so
//!   easting = x and northing = y in `seafloor.crs` (the frame's offset is zero).
//! - Otherwise (synthetic floor, a grid without a CRS): the planner's frame only.
//!
//! One row per vehicle and step of every window's final stage (the plan the team executes):
//! `window, k, t_s, vehicle, x_m, y_m, z_m`, then `lat_deg, lon_deg` (8 decimals, about 1 mm) or
//! `easting_m, northing_m`. The USV is at z = 0.

use crate::output::{write_atomic, OutputError};
use crate::plan::{Plan, SeafloorRecord};
use crate::seafloor::geo::LocalFrame;
use std::path::Path;
use thiserror::Error;

/// Errors of exporting a plan's positions.
#[derive(Debug, Error)]
pub enum PositionsError {
    /// The plan's seafloor origin is no valid local-frame origin: not finite, |latitude| above
    /// [`crate::seafloor::geo::MAX_ORIGIN_LATITUDE`] or |longitude| above 360°.
    #[error("the plan's seafloor origin [{lat}, {lon}]: {why}")]
    Origin {
        /// The origin's latitude, degrees.
        lat: f64,
        /// The origin's longitude, degrees.
        lon: f64,
        /// Why the frame was refused.
        why: String,
    },
    /// A vehicle's position cannot be converted to latitude and longitude: it is not finite or
    /// farther than [`crate::seafloor::geo::MAX_FRAME_DISTANCE`] from the origin.
    #[error(
        "{vehicle} at ({x}, {y}) (window {window}, k = {k}) is beyond the local frame's range \
         from the origin: no latitude/longitude"
    )]
    OutOfRange {
        /// The vehicle: "usv", "auv0", "auv1", …
        vehicle: String,
        /// The window's index, 0-based.
        window: usize,
        /// The step within the window, 0..=K.
        k: usize,
        /// The position's x (east) in the planner's frame, metres.
        x: f64,
        /// The position's y (north) in the planner's frame, metres.
        y: f64,
    },
    /// Encoding the CSV failed.
    #[error("cannot write {path}: {why}")]
    Csv {
        /// The output file's path.
        path: String,
        /// The CSV writer's error message.
        why: String,
    },
    /// Writing the output file failed.
    #[error(transparent)]
    Output(#[from] OutputError),
}

/// How the planner's frame sits on the Earth.
#[derive(Debug, Clone, PartialEq)]
pub enum Georef {
    /// No CRS: the planner's frame only.
    Local,
    /// The local tangent plane of a geographic grid.
    Geographic(LocalFrame),
    /// A projected grid's own coordinates; its CRS as the plan records it.
    Projected {
        /// The plan's `seafloor.crs`: `"EPSG:<code>"` or "projected (user-defined)".
        crs: String,
    },
}

impl Georef {
    /// From a plan's seafloor record.
    pub fn of(rec: &SeafloorRecord) -> Result<Georef, PositionsError> {
        Ok(match rec.origin {
            Some([lat, lon]) => Georef::Geographic(LocalFrame::new(lat, lon).map_err(|e| {
                PositionsError::Origin {
                    lat,
                    lon,
                    why: e.to_string(),
                }
            })?),
            None if rec.crs.starts_with("EPSG:") || rec.crs.starts_with("projected") => {
                Georef::Projected {
                    crs: rec.crs.clone(),
                }
            }
            None => Georef::Local,
        })
    }

    /// The names of the columns [`to_crs`](Self::to_crs) fills.
    pub fn columns(&self) -> &'static [&'static str] {
        match self {
            Georef::Local => &[],
            Georef::Geographic(_) => &["lat_deg", "lon_deg"],
            Georef::Projected { .. } => &["easting_m", "northing_m"],
        }
    }

    /// (x, y) of the planner's frame in the grid's CRS: [lat, lon] degrees, or [easting,
    /// northing] metres; None for [`Georef::Local`] or beyond the local frame's range.
    pub fn to_crs(&self, x: f64, y: f64) -> Option<[f64; 2]> {
        match self {
            Georef::Local => None,
            Georef::Geographic(f) => f.to_geographic(x, y),
            Georef::Projected { .. } => Some([x, y]),
        }
    }

    /// What the extra columns are, in words.
    pub fn describe(&self) -> String {
        match self {
            Georef::Local => "the planner's frame only (the floor has no CRS)".into(),
            Georef::Geographic(f) => {
                let [lat, lon] = f.origin();
                format!(
                    "latitude and longitude (degrees, WGS84) from the local tangent plane at \
                     ({lat}, {lon})"
                )
            }
            Georef::Projected { crs } => format!("easting and northing in {crs}"),
        }
    }
}

/// One position of one vehicle.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// The window's index, 0-based.
    pub window: usize,
    /// The step within the window, 0..=K.
    pub k: usize,
    /// Time since the start of the mission, seconds.
    pub t: f64,
    /// "usv", "auv0", "auv1", …
    pub vehicle: String,
    /// (x, y, z) in the planner's frame, metres (x east, y north, z up; the USV at z = 0).
    pub position: [f64; 3],
    /// In the grid's CRS (see [`Georef::to_crs`]).
    pub crs: Option<[f64; 2]>,
}

/// Every position of the plan's final stages, window by window, step by step, the USV first.
pub fn rows(plan: &Plan, g: &Georef) -> Result<Vec<Row>, PositionsError> {
    let dt = plan.scenario.horizon.dt;
    let mut out = Vec::new();
    for w in &plan.windows {
        let st = &w.final_;
        let steps = st.usv.position.len();
        for k in 0..steps {
            let usv = st.usv.position[k];
            let vehicles = std::iter::once(("usv".to_string(), [usv[0], usv[1], 0.0])).chain(
                st.auvs
                    .iter()
                    .enumerate()
                    .filter_map(|(n, a)| Some((format!("auv{n}"), *a.position.get(k)?))),
            );
            for (vehicle, p) in vehicles {
                let crs = match g.to_crs(p[0], p[1]) {
                    None if *g != Georef::Local => {
                        return Err(PositionsError::OutOfRange {
                            vehicle,
                            window: w.index,
                            k,
                            x: p[0],
                            y: p[1],
                        })
                    }
                    c => c,
                };
                out.push(Row {
                    window: w.index,
                    k,
                    t: w.start_time + k as f64 * dt,
                    vehicle,
                    position: p,
                    crs,
                });
            }
        }
    }
    Ok(out)
}

/// Writes the plan's positions as CSV (see the module docs), atomically. Returns the rows
/// written and how the plan is georeferenced.
pub fn write_csv(plan: &Plan, path: &Path) -> Result<(usize, Georef), PositionsError> {
    let g = Georef::of(&plan.seafloor)?;
    let rows = rows(plan, &g)?;
    let err = |e: csv::Error| PositionsError::Csv {
        path: path.display().to_string(),
        why: e.to_string(),
    };
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut header = vec!["window", "k", "t_s", "vehicle", "x_m", "y_m", "z_m"];
    header.extend(g.columns());
    w.write_record(&header).map_err(err)?;
    for r in &rows {
        let mut rec = vec![
            r.window.to_string(),
            r.k.to_string(),
            r.t.to_string(),
            r.vehicle.clone(),
            r.position[0].to_string(),
            r.position[1].to_string(),
            r.position[2].to_string(),
        ];
        match (&g, r.crs) {
            (Georef::Geographic(_), Some([lat, lon])) => {
                rec.extend([format!("{lat:.8}"), format!("{lon:.8}")])
            }
            (_, Some([e, n])) => rec.extend([e.to_string(), n.to_string()]),
            (_, None) => {}
        }
        w.write_record(&rec).map_err(err)?;
    }
    let bytes = w.into_inner().map_err(|e| PositionsError::Csv {
        path: path.display().to_string(),
        why: e.to_string(),
    })?;
    write_atomic(path, &bytes)?;
    Ok((rows.len(), g))
}
