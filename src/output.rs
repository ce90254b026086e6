//! Writing plans: `plan.json` and one CSV per vehicle beside it. Every file is written to a
//! temporary file in the target directory and renamed into place, so no command leaves a
//! half-written output.

use crate::plan::Plan;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// Errors of writing output files and reading plan files.
#[derive(Debug, Error)]
pub enum OutputError {
    /// Creating the directory, writing the temporary file or renaming it into place failed, or
    /// the plan could not be serialised.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file's path.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// A plan file (or another of shoal's outputs) could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file's path.
        path: PathBuf,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// A file is not valid JSON, has no "format" field or another format than
    /// [`crate::plan::FORMAT`], or does not deserialise as a [`Plan`].
    #[error("{path} is not a shoal plan: {why}")]
    Parse {
        /// The file's path.
        path: PathBuf,
        /// What is wrong with it.
        why: String,
    },
    /// A file is not a simulation record (sim.json) of `shoal simulate`.
    #[error("{path} is not a sim.json of `shoal simulate`: {why}")]
    SimRecord {
        /// The file's path.
        path: PathBuf,
        /// What is wrong with it.
        why: String,
    },
    /// An output folder's manifest cannot be trusted: damaged, not a regular file, or naming a
    /// file outside the folder or one the command does not write. It is never obeyed.
    #[error(
        "{path} cannot be trusted: {why}; shoal removes only files it wrote inside its output \
         folder. Delete the manifest if the folder holds no output of shoal's you want replaced"
    )]
    Manifest {
        /// The manifest's path.
        path: PathBuf,
        /// What is wrong with it.
        why: String,
    },
    /// The output directory given exists and is a file.
    #[error("the output {path} exists and is not a directory; give the directory to write the plan, CSVs and figures in")]
    NotADirectory {
        /// The path given.
        path: PathBuf,
    },
}

/// Write `bytes` to `path` atomically (temporary file in the same directory, then rename),
/// creating its directory if missing.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    let err = |source| OutputError::Write {
        path: path.to_path_buf(),
        source,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(err)?;
    }
    crate::atomic_file::write(path, bytes).map_err(err)
}

/// Write the plan as pretty JSON.
pub fn write_plan(plan: &Plan, path: &Path) -> Result<(), OutputError> {
    let json = serde_json::to_vec_pretty(plan).map_err(|e| OutputError::Write {
        path: path.to_path_buf(),
        source: std::io::Error::other(e),
    })?;
    write_atomic(path, &json)
}

/// Read a plan file, refusing other formats with a clear message. An output set that a killed
/// `shoal plan` left half moved into the file's folder is completed first
/// ([`crate::output_set::settle`]), so the plan read is the one its folder's other files
/// belong to.
pub fn read_plan(path: &Path) -> Result<Plan, OutputError> {
    crate::output_set::settle(crate::atomic_file::folder_of(path));
    let text = std::fs::read_to_string(path).map_err(|source| OutputError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    parse_plan(&text, path)
}

/// A plan from the text of a plan file (`path` names it in errors), refusing other formats
/// with the same messages as [`read_plan`]; for plans held in memory (the Python package's
/// `Plan.from_json`).
pub fn parse_plan(text: &str, path: &Path) -> Result<Plan, OutputError> {
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| OutputError::Parse {
        path: path.to_path_buf(),
        why: e.to_string(),
    })?;
    match value.get("format").and_then(|f| f.as_str()) {
        Some(crate::plan::FORMAT) => {}
        Some(other) => {
            return Err(OutputError::Parse {
                path: path.to_path_buf(),
                why: format!(
                    "format \"{other}\" is not \"{}\", the format this shoal ({}) reads; plan \
                     the scenario again with this version (`shoal plan`)",
                    crate::plan::FORMAT,
                    env!("CARGO_PKG_VERSION")
                ),
            })
        }
        None => {
            return Err(OutputError::Parse {
                path: path.to_path_buf(),
                why: "no \"format\" field".into(),
            })
        }
    }
    serde_json::from_value(value).map_err(|e| OutputError::Parse {
        path: path.to_path_buf(),
        why: e.to_string(),
    })
}

/// One CSV per vehicle (`usv.csv`, `auv0.csv`, …) in `dir`, one row per window and step, from the
/// last stage of each window. Returns the paths written.
pub fn write_csvs(plan: &Plan, dir: &Path) -> Result<Vec<PathBuf>, OutputError> {
    let mut written = Vec::new();
    let dt = plan.scenario.horizon.dt;
    let mut usv = String::from("window,step,time_s,x_m,y_m,ux_mps,uy_mps\n");
    let n = plan.scenario.team.auvs;
    let mut auvs = vec![
        String::from(
            "window,step,time_s,x_m,y_m,z_m,vx_mps,vy_mps,vz_mps,ux_mps2,uy_mps2,uz_mps2,surge_speed_mps,heading_rad\n"
        );
        n
    ];
    for w in &plan.windows {
        let st = &w.final_; // the plan the team executes (Step 3)
        for (k, p) in st.usv.position.iter().enumerate() {
            let u = st.usv.input.get(k).copied().unwrap_or([f64::NAN; 2]);
            let t = w.start_time + k as f64 * dt;
            let _ = writeln!(
                usv,
                "{},{k},{t},{},{},{},{}",
                w.index, p[0], p[1], u[0], u[1]
            );
        }
        for (a, path) in st.auvs.iter().enumerate() {
            for k in 0..path.position.len() {
                let p = path.position[k];
                let v = path.velocity[k];
                let u = path.input.get(k).copied().unwrap_or([f64::NAN; 3]);
                let h = path.heading[k].map(|h| h.to_string()).unwrap_or_default();
                let t = w.start_time + k as f64 * dt;
                let _ = writeln!(
                    auvs[a],
                    "{},{k},{t},{},{},{},{},{},{},{},{},{},{},{h}",
                    w.index,
                    p[0],
                    p[1],
                    p[2],
                    v[0],
                    v[1],
                    v[2],
                    u[0],
                    u[1],
                    u[2],
                    path.surge_speed[k]
                );
            }
        }
    }
    let path = dir.join("usv.csv");
    write_atomic(&path, usv.replace("NaN", "").as_bytes())?;
    written.push(path);
    for (a, text) in auvs.iter().enumerate() {
        let path = dir.join(format!("auv{a}.csv"));
        write_atomic(&path, text.replace("NaN", "").as_bytes())?;
        written.push(path);
    }
    Ok(written)
}

/// Writes a floor (`shoal seafloor export`) by the file name's extension: a GeoTIFF keeps the
/// source's projected CRS; a floor resampled from a geographic grid is written in its local frame
/// (a user-defined CRS whose citation names the origin). Returns notes for the user (see
/// [`write_grid`]).
pub fn write_floor(
    floor: &crate::seafloor::Seafloor,
    source: &crate::mission::FloorSource,
    out: &Path,
) -> Result<Vec<String>, crate::seafloor::SeafloorError> {
    use crate::seafloor::Crs;
    let (crs, citation) = match (source.origin, source.crs.strip_prefix("EPSG:")) {
        (Some([lat, lon]), _) => (
            Crs::Projected {
                epsg: None,
                citation: None,
            },
            Some(format!(
                "shoal local tangent plane (x east, y north, metres) at {lat}, {lon} (WGS84)"
            )),
        ),
        (None, Some(code)) => (
            Crs::Projected {
                epsg: code.parse().ok(),
                citation: None,
            },
            None,
        ),
        (None, None) => (Crs::None, None),
    };
    write_grid(floor, &crs, citation.as_deref(), out)
}

/// Writes a grid by the file name's extension, as one output set with its sidecar
/// ([`crate::output_set`]): a GeoTIFF with its CRS (and citation), or an ESRI ASCII grid with a
/// `.prj` sidecar when shoal knows the CRS's WKT ([`crate::seafloor::wkt_of`]: WGS 84 and its UTM
/// zones). A `.prj` left beside the output by an earlier grid is removed when the new grid has
/// none, so it cannot mislabel it. Returns what the user should hear about the sidecar.
pub fn write_grid(
    floor: &crate::seafloor::Seafloor,
    crs: &crate::seafloor::Crs,
    citation: Option<&str>,
    out: &Path,
) -> Result<Vec<String>, crate::seafloor::SeafloorError> {
    use crate::seafloor::{Crs, GridFormat, SeafloorError};
    let io = |path: &Path, source: std::io::Error| SeafloorError::Io {
        path: path.display().to_string(),
        source,
    };
    let from_output = |e: OutputError| match e {
        OutputError::Write { path, source } => io(&path, source),
        other => io(out, std::io::Error::other(other.to_string())),
    };
    let format = GridFormat::from_path(out);
    // shoal writes .asc and .tif only; GDAL converts those to anything else
    if !matches!(format, Some(GridFormat::GeoTiff | GridFormat::EsriAscii)) {
        return Err(SeafloorError::Format {
            path: out.display().to_string(),
        });
    }
    let name = out
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| io(out, std::io::Error::other("not a file name in UTF-8")))?;
    let set = crate::output_set::OutputSet::begin_kind(
        crate::atomic_file::folder_of(out),
        crate::output_set::Kind::Grid(name.to_string()),
    )
    .map_err(from_output)?;
    let staged = set.dir().join(name);
    let prj = out.with_extension("prj");
    let mut notes = Vec::new();
    match format {
        Some(GridFormat::GeoTiff) => floor.write_geotiff(&staged, crs, citation)?,
        _ => {
            floor.write_esri_ascii(&staged)?;
            match crate::seafloor::wkt_of(crs) {
                Some(wkt) => {
                    write_atomic(&staged.with_extension("prj"), wkt.as_bytes())
                        .map_err(from_output)?;
                    notes.push(format!("wrote {} ({crs})", prj.display()));
                }
                None => {
                    if prj.is_file() {
                        notes.push(format!(
                            "removed {}, left by an earlier grid: it does not describe this one",
                            prj.display()
                        ));
                    }
                    let keep = match crs {
                        Crs::None => None,
                        Crs::Projected { epsg: Some(c), .. }
                        | Crs::Geographic { epsg: Some(c) } => Some(format!(
                            "declare seafloor.crs = \"EPSG:{c}\" when you use it, or export \
                                 a GeoTIFF (.tif)"
                        )),
                        _ => Some("export a GeoTIFF (.tif) to keep it".to_string()),
                    };
                    if let Some(keep) = keep {
                        notes.push(format!(
                            "{} has no CRS: an ESRI ASCII grid holds none, and shoal writes a \
                             .prj sidecar only for EPSG:4326 and the WGS 84 UTM zones; the \
                             grid's CRS is {crs}: {keep}",
                            out.display()
                        ));
                    }
                }
            }
        }
    }
    set.commit(None).map_err(from_output)?;
    Ok(notes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_plan_names_the_source_and_refuses_other_formats() {
        let name = Path::new("in memory.json");
        for (text, want) in [
            ("{", "in memory.json is not a shoal plan: EOF while parsing"),
            (
                "{}",
                "in memory.json is not a shoal plan: no \"format\" field",
            ),
            (
                "{\"format\": \"shoal-plan/1\"}",
                "format \"shoal-plan/1\" is not \"shoal-plan/5\"",
            ),
            (
                "{\"format\": \"shoal-plan/5\"}",
                "in memory.json is not a shoal plan: missing field",
            ),
        ] {
            let e = parse_plan(text, name).unwrap_err().to_string();
            assert!(e.contains(want), "{text}: {e}");
        }
    }
}
