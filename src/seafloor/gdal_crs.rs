//! The CRS of a grid file read through GDAL, from its PROJJSON: the horizontal part of a
//! compound CRS (BAG: projected + vertical), the source of a bound one; projected (metres) or
//! geographic (degrees), with its EPSG code when it has one (GDAL is asked to identify it),
//! otherwise its name and PROJ string as the citation.

use super::gdal_grid::message;
use super::load::Crs;
use gdal::Dataset;

/// The CRS of the dataset from its PROJJSON; None when the file has no CRS.
pub(crate) fn crs_of(ds: &Dataset, name: &str, warnings: &mut Vec<String>) -> Result<Crs, String> {
    let Ok(mut srs) = ds.spatial_ref() else {
        return Ok(Crs::None);
    };
    if !srs.is_compound() {
        // adds the EPSG code to a CRS that matches one but does not say so (it may fail)
        let _ = srs.auto_identify_epsg();
    }
    let json = srs
        .to_projjson()
        .map_err(|e| format!("GDAL cannot describe the CRS: {}", message(&e)))?;
    let proj = srs.to_proj4().unwrap_or_default();
    let value: serde_json::Value =
        serde_json::from_str(&json).map_err(|e| format!("the CRS's PROJJSON: {e}"))?;
    crs_from_projjson(&value, &proj, name, warnings)
}

/// The horizontal CRS of a PROJJSON object: projected (metres) or geographic (degrees).
fn crs_from_projjson(
    v: &serde_json::Value,
    proj: &str,
    name: &str,
    warnings: &mut Vec<String>,
) -> Result<Crs, String> {
    let kind = v["type"].as_str().unwrap_or("");
    let crs_name = v["name"].as_str().unwrap_or("unnamed").to_string();
    match kind {
        "CompoundCRS" => {
            let horizontal = v["components"]
                .as_array()
                .and_then(|c| c.first())
                .ok_or_else(|| format!("the compound CRS {crs_name:?} has no components"))?;
            crs_from_projjson(horizontal, proj, name, warnings)
        }
        "BoundCRS" => crs_from_projjson(&v["source_crs"], proj, name, warnings),
        "ProjectedCRS" | "DerivedProjectedCRS" | "EngineeringCRS" => {
            units(v, "metre", 1.0, &crs_name)?;
            let epsg = epsg_code(v);
            let citation = if epsg.is_some() || proj.is_empty() {
                crs_name
            } else {
                format!("{crs_name} ({})", proj.trim())
            };
            Ok(Crs::Projected {
                epsg,
                citation: Some(citation),
            })
        }
        "GeographicCRS" => {
            units(v, "degree", std::f64::consts::PI / 180.0, &crs_name)?;
            let epsg = epsg_code(v);
            if epsg != Some(4326) {
                let what = epsg.map_or(format!("{crs_name:?}"), |c| format!("EPSG:{c}"));
                warnings.push(format!(
                    "{name}: geographic CRS {what} is taken as WGS84 (EPSG:4326); datum \
                     shifts (a few metres at most for modern datums) are ignored"
                ));
            }
            Ok(Crs::Geographic { epsg })
        }
        other => Err(format!(
            "the CRS {crs_name:?} is a {other}: expected a projected CRS (metres) or a \
             geographic one (degrees)"
        )),
    }
}

/// The EPSG code of a PROJJSON object ("id" or the first EPSG entry of "ids"), if it fits.
fn epsg_code(v: &serde_json::Value) -> Option<u16> {
    let ids = match (&v["id"], v["ids"].as_array()) {
        (id @ serde_json::Value::Object(_), _) => vec![id],
        (_, Some(ids)) => ids.iter().collect(),
        _ => Vec::new(),
    };
    ids.into_iter()
        .find(|id| id["authority"].as_str() == Some("EPSG"))
        .and_then(|id| match &id["code"] {
            serde_json::Value::Number(n) => n.as_u64(),
            serde_json::Value::String(s) => s.parse().ok(),
            _ => None,
        })
        .and_then(|c| u16::try_from(c).ok())
}

/// Every axis of the horizontal CRS must be in `unit` (the conversion factor to metres or
/// radians being `factor`).
fn units(v: &serde_json::Value, unit: &str, factor: f64, crs: &str) -> Result<(), String> {
    let axes = v["coordinate_system"]["axis"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    for a in axes.iter().take(2) {
        let ok = match &a["unit"] {
            serde_json::Value::Null => true,
            serde_json::Value::String(s) => s == unit,
            u => u["conversion_factor"]
                .as_f64()
                .is_some_and(|f| (f - factor).abs() <= 1e-12 * factor),
        };
        if !ok {
            let found = a["unit"]["name"]
                .as_str()
                .map_or_else(|| a["unit"].to_string(), str::to_string);
            return Err(format!(
                "the CRS {crs:?} has coordinates in {found}: only {unit}s are supported \
                 (reproject the grid first, e.g. gdalwarp -t_srs)"
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn crs_from_projjson_takes_the_horizontal_part_and_its_epsg_code() {
        let mut w = Vec::new();
        let utm = json!({"type": "ProjectedCRS", "name": "WGS 84 / UTM zone 31N",
            "coordinate_system": {"axis": [{"unit": "metre"}, {"unit": "metre"}]},
            "id": {"authority": "EPSG", "code": 32631}});
        let bag = json!({"type": "CompoundCRS", "name": "UTM + MLLW",
            "components": [utm.clone(), {"type": "VerticalCRS", "name": "MLLW"}]});
        for v in [&utm, &bag] {
            let c = crs_from_projjson(v, "", "f", &mut w).unwrap();
            assert_eq!(c.to_string(), "EPSG:32631");
        }
        let custom = json!({"type": "ProjectedCRS", "name": "unknown",
            "coordinate_system": {"axis": [{"unit": "metre"}, {"unit": "metre"}]}});
        let c = crs_from_projjson(&custom, "+proj=tmerc +lon_0=4.3", "f", &mut w).unwrap();
        assert_eq!(
            c,
            Crs::Projected {
                epsg: None,
                citation: Some("unknown (+proj=tmerc +lon_0=4.3)".into())
            }
        );
        assert!(w.is_empty());
        let wgs84 = json!({"type": "GeographicCRS", "name": "WGS 84",
            "coordinate_system": {"axis": [{"unit": "degree"}, {"unit": "degree"}]},
            "ids": [{"authority": "EPSG", "code": 4326}]});
        let bound = json!({"type": "BoundCRS", "source_crs": wgs84});
        assert_eq!(
            crs_from_projjson(&bound, "", "f", &mut w).unwrap(),
            Crs::Geographic { epsg: Some(4326) }
        );
        assert!(w.is_empty());
        let ed50 = json!({"type": "GeographicCRS", "name": "ED50",
            "id": {"authority": "EPSG", "code": 4230}});
        crs_from_projjson(&ed50, "", "f", &mut w).unwrap();
        assert!(w[0].contains("EPSG:4230 is taken as WGS84"), "{w:?}");
        let feet = json!({"type": "ProjectedCRS", "name": "NAD83 / Florida East (ftUS)",
            "coordinate_system": {"axis": [{"unit": {"type": "LinearUnit",
                "name": "US survey foot", "conversion_factor": 0.304800609601219}}]}});
        let e = crs_from_projjson(&feet, "", "f", &mut w).unwrap_err();
        assert!(e.contains("US survey foot") && e.contains("metres"), "{e}");
        let geocentric = json!({"type": "GeodeticCRS", "name": "WGS 84 (geocentric)"});
        let e = crs_from_projjson(&geocentric, "", "f", &mut w).unwrap_err();
        assert!(e.contains("GeodeticCRS"), "{e}");
    }
}
