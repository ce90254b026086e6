//! Where a grid's CRS comes from: the file itself (a GeoTIFF's GeoKeys), a `.prj` sidecar next
//! to an ESRI ASCII grid (WKT), or a declaration (`seafloor.crs = "EPSG:4326"`, `--crs`), which
//! gives the CRS of a file that has none and must agree with the CRS of a file that has one.
//! Nothing declared: the coordinates are taken as metres (and a grid that looks like degrees
//! gets a warning).
//!
//! # Declarations
//!
//! `"EPSG:<code>"` (case-insensitive). Codes 4000–4999 (EPSG's block of geographic 2D CRSs, e.g.
//! 4326 WGS 84, 4258 ETRS89, 4269 NAD83, 4283 GDA94) and 7844 (GDA2020) are geographic, in
//! degrees; the geocentric 4936 and 4978 are refused; every other code is a projected CRS in
//! metres (e.g. 326zz/327zz, WGS 84 / UTM zone zz N/S). Geographic CRSs other than 4326 are taken
//! as WGS84, as for GeoTIFFs.
//!
//! # `.prj` sidecars
//!
//! `grid.prj` (or `grid.PRJ`) beside `grid.asc`, holding OGC or ESRI WKT (version 1 or 2). The
//! outer node decides the kind: `GEOGCS`/`GEOGCRS`/`GEODCRS` geographic, `PROJCS`/`PROJCRS`
//! projected. The code is the outer node's `AUTHORITY["EPSG", …]` or `ID["EPSG", …]`; without
//! one, a WGS 84 geographic CRS is EPSG:4326 and a WGS 84 UTM zone (`WGS 84 / UTM zone 56S`,
//! `WGS_1984_UTM_Zone_56S`) EPSG:326zz/327zz; anything else is recorded as user-defined (a
//! projected CRS with its WKT name). Units other than metres (projected) or degrees (geographic)
//! are refused.

mod wkt;

pub(crate) use wkt::crs_of_wkt;
pub use wkt::wkt_of;

use super::geokeys::check_lattice;
use super::load::{Crs, GridFormat};
use super::{Lattice, SeafloorError};
use std::path::{Path, PathBuf};

/// Where a grid's CRS came from.
#[derive(Debug, Clone, PartialEq)]
pub enum CrsSource {
    /// The grid file itself (a GeoTIFF's GeoKeys).
    File,
    /// A `.prj` sidecar beside the grid file.
    Sidecar(PathBuf),
    /// A declaration: `seafloor.crs` in the scenario, or `--crs`.
    Declared,
    /// Nothing gives one: the coordinates are taken as metres. `looks_like_degrees`: the
    /// coordinates would fit a grid in degrees.
    Guessed {
        /// True when the coordinates would fit a grid in degrees.
        looks_like_degrees: bool,
    },
}

impl std::fmt::Display for CrsSource {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CrsSource::File => write!(f, "from the file"),
            CrsSource::Sidecar(p) => write!(f, "from the sidecar {}", p.display()),
            CrsSource::Declared => write!(f, "declared (seafloor.crs or --crs)"),
            CrsSource::Guessed {
                looks_like_degrees: false,
            } => write!(
                f,
                "guessed: no CRS in the file, no .prj sidecar, none declared; coordinates taken \
                 as metres"
            ),
            CrsSource::Guessed {
                looks_like_degrees: true,
            } => write!(
                f,
                "guessed: no CRS in the file, no .prj sidecar, none declared; coordinates taken \
                 as metres although they look like degrees (declare seafloor.crs = \
                 \"EPSG:4326\" or --crs EPSG:4326 if they are)"
            ),
        }
    }
}

/// Parses a declared CRS, `"EPSG:<code>"` (see the module docs for which codes are
/// geographic). The error says what is allowed.
pub fn parse_crs(text: &str) -> Result<Crs, String> {
    let t = text.trim();
    let code = t
        .get(..5)
        .filter(|p| p.eq_ignore_ascii_case("epsg:"))
        .and_then(|_| t[5..].trim().parse::<u32>().ok())
        .filter(|&c| c > 0)
        .ok_or_else(|| {
            format!(
                "{text:?}: expected \"EPSG:<code>\", e.g. \"EPSG:4326\" (WGS 84 latitude and \
                 longitude) or \"EPSG:32756\" (WGS 84 / UTM zone 56S)"
            )
        })?;
    let epsg = u16::try_from(code)
        .ok()
        .filter(|&c| c != 32767)
        .ok_or_else(|| {
            format!("{text:?}: EPSG code {code} is not supported (codes up to 65535, not 32767)")
        })?;
    Ok(match epsg {
        4936 | 4978 => {
            return Err(format!(
                "{text:?}: a geocentric CRS is not supported; expected a geographic (degrees) \
                 or projected (metres) one"
            ))
        }
        4000..=4999 | 7844 => Crs::Geographic { epsg: Some(epsg) },
        _ => Crs::Projected {
            epsg: Some(epsg),
            citation: None,
        },
    })
}

/// The `.prj` sidecar of a grid file, if there is one.
pub(crate) fn sidecar_of(path: &Path) -> Option<PathBuf> {
    ["prj", "PRJ"]
        .iter()
        .map(|e| path.with_extension(e))
        .find(|p| p.is_file())
}

/// The CRS a grid is read in, and where it came from: the file's own (`file_crs`, for an ESRI
/// ASCII grid from its `.prj` sidecar), checked against or replaced by `declared`. Pushes the
/// warnings the user should hear (a datum taken as WGS84, coordinates that look like degrees).
pub(crate) fn resolve(
    path: &Path,
    format: GridFormat,
    file_crs: Crs,
    native: &Lattice,
    declared: Option<&str>,
    warnings: &mut Vec<String>,
) -> Result<(Crs, CrsSource), SeafloorError> {
    let name = path.display().to_string();
    let own = match (&file_crs, format) {
        (Crs::None, GridFormat::EsriAscii) => match sidecar_of(path) {
            Some(prj) => {
                let text = std::fs::read_to_string(&prj).map_err(|source| SeafloorError::Io {
                    path: prj.display().to_string(),
                    source,
                })?;
                let crs = crs_of_wkt(&text).map_err(|reason| SeafloorError::Region {
                    path: prj.display().to_string(),
                    reason: format!("the .prj sidecar of {name}: {reason}"),
                })?;
                Some((crs, CrsSource::Sidecar(prj)))
            }
            None => None,
        },
        (Crs::None, _) => None,
        _ => Some((file_crs, CrsSource::File)),
    };
    let declared =
        declared
            .map(parse_crs)
            .transpose()
            .map_err(|reason| SeafloorError::InvalidQuery {
                what: "seafloor.crs",
                reason,
            })?;
    let (crs, source) = match (own, declared) {
        (None, None) => (
            Crs::None,
            CrsSource::Guessed {
                looks_like_degrees: format == GridFormat::EsriAscii && looks_like_degrees(native),
            },
        ),
        (None, Some(d)) => (d, CrsSource::Declared),
        (Some(own), None) => own,
        (Some((crs, source)), Some(d)) => reconcile(&name, crs, source, d)?,
    };
    if let CrsSource::Guessed {
        looks_like_degrees: true,
    } = source
    {
        warnings.push(format!(
            "{name}: the coordinates look like degrees (x from {} to {}, y from {} to {}, cells \
             of {}), but nothing gives the grid's CRS (no .prj sidecar, no seafloor.crs) and it \
             is read in metres; if they are degrees, declare seafloor.crs = \"EPSG:4326\" (or \
             --crs EPSG:4326)",
            native.x0,
            native.x_max(),
            native.y0,
            native.y_max(),
            native.dx
        ));
    }
    if !matches!(source, CrsSource::File | CrsSource::Guessed { .. }) {
        if let Crs::Geographic { epsg } = crs {
            if epsg != Some(4326) {
                let what = epsg.map_or("a user-defined datum".to_string(), |c| format!("EPSG:{c}"));
                warnings.push(format!(
                    "{name}: geographic CRS {what} is taken as WGS84 (EPSG:4326); datum shifts \
                     (a few metres at most for modern datums) are ignored"
                ));
            }
        }
        check_lattice(native, &crs).map_err(|reason| SeafloorError::Region {
            path: name.clone(),
            reason: format!("CRS {crs} ({source}): {reason}"),
        })?;
    }
    Ok((crs, source))
}

/// The file's CRS and a declared one: the same kind and no two different codes, or an error
/// naming both.
fn reconcile(
    name: &str,
    own: Crs,
    source: CrsSource,
    declared: Crs,
) -> Result<(Crs, CrsSource), SeafloorError> {
    let conflict = |own: &Crs| SeafloorError::CrsConflict {
        path: name.to_string(),
        declared: declared.to_string(),
        file_crs: own.to_string(),
        file_source: source.to_string(),
    };
    match (&own, &declared) {
        (Crs::Geographic { epsg: a }, Crs::Geographic { epsg: b })
        | (Crs::Projected { epsg: a, .. }, Crs::Projected { epsg: b, .. }) => match (a, b) {
            (Some(a), Some(b)) if a != b => Err(conflict(&own)),
            (Some(_), _) => Ok((own, source)),
            (None, _) => Ok((
                match own {
                    Crs::Projected { citation, .. } => Crs::Projected { epsg: *b, citation },
                    _ => declared.clone(),
                },
                CrsSource::Declared,
            )),
        },
        _ => Err(conflict(&own)),
    }
}

/// Whether a lattice's coordinates would fit a grid in degrees.
pub(crate) fn looks_like_degrees(l: &Lattice) -> bool {
    l.dx < 0.1
        && l.dy < 0.1
        && l.x0 >= -360.0
        && l.x_max() <= 360.0
        && l.y0 >= -90.0
        && l.y_max() <= 90.0
}

#[cfg(test)]
mod tests;
