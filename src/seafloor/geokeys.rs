//! GeoTIFF georeferencing: the GeoKeyDirectory (the CRS and the raster type) and the tags that
//! place the grid (ModelPixelScale + ModelTiepoint, or ModelTransformation).

use super::load::Crs;
use super::Lattice;

/// Largest |coordinate| of a GeoTIFF's georeferencing, as for ESRI ASCII headers.
const MAX_COORDINATE: f64 = 1e12;

/// GeoKey identifiers (GeoTIFF 1.1, OGC 19-008r4).
pub(crate) mod key {
    pub const MODEL_TYPE: u16 = 1024;
    pub const RASTER_TYPE: u16 = 1025;
    pub const CITATION: u16 = 1026;
    pub const GEOGRAPHIC_TYPE: u16 = 2048;
    pub const GEOG_ANGULAR_UNITS: u16 = 2054;
    pub const PROJECTED_TYPE: u16 = 3072;
    pub const PROJ_LINEAR_UNITS: u16 = 3076;
    pub const VERTICAL_UNITS: u16 = 4099;
}
/// EPSG codes of the units accepted, and GeoTIFF's "user-defined".
const METRE: u16 = 9001;
const DEGREE: u16 = 9102;
const USER_DEFINED: u16 = 32767;

/// (tiepoint [I, J, X, Y], pixel scale x, pixel scale y) from ModelPixelScale +
/// ModelTiepoint, or from a ModelTransformation without rotation.
pub(crate) fn georeference(
    scale: Option<Vec<f64>>,
    ties: Option<Vec<f64>>,
    transform: Option<Vec<f64>>,
) -> Result<([f64; 4], f64, f64), String> {
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    match (scale, ties, transform) {
        (Some(s), Some(t), _) => {
            if s.len() < 2 || !finite(&s[..2]) || s[0] <= 0.0 || s[1] == 0.0 {
                return Err(format!(
                    "ModelPixelScale (33550) = {s:?}: expected a positive x and a non-zero y \
                     cell size"
                ));
            }
            if t.len() < 6 || !finite(&t[..6]) {
                return Err(format!(
                    "ModelTiepoint (33922) = {t:?}: expected (I, J, K, X, Y, Z), finite"
                ));
            }
            Ok(([t[0], t[1], t[3], t[4]], s[0], s[1]))
        }
        (None, Some(t), None) if t.len() > 6 => Err(format!(
            "georeferenced by {} control points (ModelTiepoint without ModelPixelScale): \
             not supported; resample the grid onto a regular one (e.g. gdalwarp)",
            t.len() / 6
        )),
        (_, _, Some(m)) => {
            if m.len() < 16 || !finite(&m) {
                return Err("ModelTransformation (34264): expected 16 finite numbers".into());
            }
            if m[1] != 0.0 || m[4] != 0.0 {
                return Err(format!(
                    "the grid is rotated or sheared (ModelTransformation terms {} and {}): \
                     not supported; warp it onto a north-up grid first (e.g. gdalwarp)",
                    m[1], m[4]
                ));
            }
            if m[0] <= 0.0 || m[5] == 0.0 {
                return Err(format!(
                    "ModelTransformation (34264): cell size {} × {}: expected a positive x and \
                     a non-zero y",
                    m[0], -m[5]
                ));
            }
            Ok(([0.0, 0.0, m[3], m[7]], m[0], -m[5]))
        }
        (s, t, None) => {
            let missing: Vec<&str> = [
                s.is_none().then_some("ModelPixelScale (33550)"),
                t.is_none().then_some("ModelTiepoint (33922)"),
            ]
            .into_iter()
            .flatten()
            .collect();
            Err(format!(
                "no georeferencing: the GeoTIFF tag{} {} {} missing (a plain TIFF, or a \
                 world file that shoal does not read)",
                if missing.len() > 1 { "s" } else { "" },
                missing.join(" and "),
                if missing.len() > 1 { "are" } else { "is" }
            ))
        }
    }
}

/// The lattice must be finite, within ±1e12, and (for degrees) on the globe.
pub(crate) fn check_lattice(l: &Lattice, crs: &Crs) -> Result<(), String> {
    let (x1, y1) = (l.x_max(), l.y_max());
    let all = [l.x0, l.y0, x1, y1, l.dx, l.dy];
    if !all
        .iter()
        .all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE)
    {
        return Err(format!(
            "the georeferencing gives nodes from ({}, {}) to ({x1}, {y1}): expected finite \
             coordinates within ±{MAX_COORDINATE:e}",
            l.x0, l.y0
        ));
    }
    if let Crs::Geographic { .. } = crs {
        if l.y0 < -90.0 - 1e-9 || y1 > 90.0 + 1e-9 || l.x0 < -360.0 || x1 > 360.0 {
            return Err(format!(
                "a geographic grid with node latitudes from {} to {y1} and longitudes from {} \
                 to {x1}: expected degrees (latitude within ±90, longitude within ±360)",
                l.y0, l.x0
            ));
        }
    }
    Ok(())
}

/// The GeoKeyDirectory, parsed: (key, value) pairs; ASCII and double values resolved.
pub(crate) struct GeoKeys {
    shorts: Vec<(u16, u16)>,
    texts: Vec<(u16, String)>,
}

impl GeoKeys {
    pub fn parse(dir: &[u16], doubles: &[f64], ascii: &str) -> Result<GeoKeys, String> {
        let mut keys = GeoKeys {
            shorts: Vec::new(),
            texts: Vec::new(),
        };
        if dir.is_empty() {
            return Ok(keys);
        }
        let bad = |why: &str| format!("GeoKeyDirectory (34735) is malformed: {why}");
        if dir.len() < 4 {
            return Err(bad("shorter than its 4-entry header"));
        }
        let n = dir[3] as usize;
        if dir.len() < 4 + 4 * n {
            return Err(bad(&format!(
                "{n} keys announced, room for {}",
                (dir.len() - 4) / 4
            )));
        }
        for e in dir[4..4 + 4 * n].chunks_exact(4) {
            let (id, loc, count, value) = (e[0], e[1], e[2] as usize, e[3] as usize);
            match loc {
                0 => keys.shorts.push((id, e[3])),
                34737 => {
                    let text = ascii.get(value..value + count).ok_or_else(|| {
                        bad(&format!("key {id}'s text is outside GeoAsciiParams"))
                    })?;
                    keys.texts
                        .push((id, text.trim_end_matches(['|', '\0']).to_string()));
                }
                34736 => {
                    doubles.get(value..value + count).ok_or_else(|| {
                        bad(&format!("key {id}'s value is outside GeoDoubleParams"))
                    })?;
                }
                34735 => {
                    let v = dir.get(value).ok_or_else(|| {
                        bad(&format!("key {id}'s value is outside the directory"))
                    })?;
                    keys.shorts.push((id, *v));
                }
                _ => {} // a tag we do not read: the key is not one we use
            }
        }
        Ok(keys)
    }

    pub fn short(&self, id: u16) -> Option<u16> {
        self.shorts.iter().find(|(k, _)| *k == id).map(|(_, v)| *v)
    }

    fn text(&self, id: u16) -> Option<&str> {
        self.texts
            .iter()
            .find(|(k, _)| *k == id)
            .map(|(_, v)| v.as_str())
    }

    /// The CRS the keys describe; units must be metres (projected) or degrees (geographic).
    pub fn crs(&self, name: &str, warnings: &mut Vec<String>) -> Result<Crs, String> {
        let code = |id: u16| self.short(id).filter(|&c| c != 0 && c != USER_DEFINED);
        let model = match self.short(key::MODEL_TYPE) {
            Some(m) => m,
            None if self.short(key::PROJECTED_TYPE).is_some() => 1,
            None if self.short(key::GEOGRAPHIC_TYPE).is_some() => 2,
            None => 0,
        };
        if let Some(u) = self.short(key::VERTICAL_UNITS) {
            if u != METRE {
                return Err(format!(
                    "VerticalUnitsGeoKey = {u}: elevations must be in metres (EPSG 9001)"
                ));
            }
        }
        let citation = self.text(key::CITATION).map(str::to_string);
        match model {
            0 => Ok(Crs::None),
            1 => {
                if let Some(u) = self.short(key::PROJ_LINEAR_UNITS) {
                    if u != METRE {
                        return Err(format!(
                            "ProjLinearUnitsGeoKey = {u}: only metres (EPSG 9001) are supported"
                        ));
                    }
                }
                Ok(Crs::Projected {
                    epsg: code(key::PROJECTED_TYPE),
                    citation,
                })
            }
            2 => {
                if let Some(u) = self.short(key::GEOG_ANGULAR_UNITS) {
                    if u != DEGREE {
                        return Err(format!(
                            "GeogAngularUnitsGeoKey = {u}: only degrees (EPSG 9102) are supported"
                        ));
                    }
                }
                let epsg = code(key::GEOGRAPHIC_TYPE);
                if epsg != Some(4326) {
                    let what =
                        epsg.map_or("a user-defined datum".to_string(), |c| format!("EPSG:{c}"));
                    warnings.push(format!(
                        "{name}: geographic CRS {what} is taken as WGS84 (EPSG:4326); datum \
                         shifts (a few metres at most for modern datums) are ignored"
                    ));
                }
                Ok(Crs::Geographic { epsg })
            }
            3 => Err(
                "GTModelTypeGeoKey = 3 (geocentric): not supported; expected a projected \
                      (1) or geographic (2) CRS"
                    .into(),
            ),
            m => Err(format!(
                "GTModelTypeGeoKey = {m}: expected 1 (projected) or 2 (geographic)"
            )),
        }
    }
}
