//! Where a grid's CRS comes from: a GeoTIFF's GeoKeys, a `.prj` sidecar beside an ESRI ASCII
//! grid, or a declaration (`seafloor.crs`, `--crs`), which fills in a missing CRS and must agree
//! with the file's own; `shoal seafloor info` says which, and a plan over an ESRI grid in degrees
//! passes its check.

mod common;

use common::*;
use shoal::seafloor::{
    info_with_crs, load, wkt_of, Crs, CrsSource, LoadOptions, LoadedFloor, SampleType,
    SeafloorError, TiffCompression, Values,
};
use std::path::{Path, PathBuf};

fn declared(path: &Path, crs: Option<&str>) -> Result<LoadedFloor, SeafloorError> {
    load(
        path,
        &LoadOptions {
            crs: crs.map(str::to_string),
            ..LoadOptions::default()
        },
    )
}

/// The geographic fixture as an ESRI ASCII grid in degrees (no sidecar) and as a GeoTIFF.
fn degrees(dir: &Path) -> (PathBuf, PathBuf) {
    let (l, z, nd) = geographic();
    let asc = dir.join("degrees.asc");
    floor_of(&l, &z, &nd).write_esri_ascii(&asc).unwrap();
    let t = tif(
        dir,
        "degrees.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float64,
        strips(TiffCompression::None),
    );
    (asc, t)
}

#[test]
fn an_esri_grid_in_degrees_is_geographic_by_declaration_or_sidecar() {
    let dir = tempfile::tempdir().unwrap();
    let (asc, t) = degrees(dir.path());
    let reference = declared(&t, None).unwrap();
    // nothing says: metres, with a warning that names the key
    let guessed = declared(&asc, None).unwrap();
    assert_eq!(guessed.crs, Crs::None);
    assert_eq!(
        guessed.crs_source,
        CrsSource::Guessed {
            looks_like_degrees: true
        }
    );
    assert!(
        guessed
            .warnings
            .iter()
            .any(|w| w.contains("seafloor.crs = \"EPSG:4326\"")),
        "{:?}",
        guessed.warnings
    );
    // declared: the same floor as the GeoTIFF, in the same local frame
    let d = declared(&asc, Some("EPSG:4326")).unwrap();
    assert_eq!(
        (d.crs.clone(), d.crs_source.clone()),
        (WGS84, CrsSource::Declared)
    );
    assert_eq!(d.origin, reference.origin);
    assert_eq!(d.floor.fingerprint(), reference.floor.fingerprint());
    assert!(d.warnings.is_empty(), "{:?}", d.warnings);
    // a WGS 84 sidecar does the same
    let prj = dir.path().join("degrees.prj");
    std::fs::write(&prj, wkt_of(&WGS84).unwrap()).unwrap();
    let s = declared(&asc, None).unwrap();
    assert_eq!(
        (s.crs.clone(), s.crs_source.clone()),
        (WGS84, CrsSource::Sidecar(prj.clone()))
    );
    assert_eq!(s.floor.fingerprint(), reference.floor.fingerprint());
    // another geographic datum is taken as WGS84, with a warning
    std::fs::remove_file(&prj).unwrap();
    let etrs = declared(&asc, Some("EPSG:4258")).unwrap();
    assert!(etrs
        .warnings
        .iter()
        .any(|w| w.contains("EPSG:4258 is taken as WGS84")));
    assert_eq!(etrs.floor.fingerprint(), reference.floor.fingerprint());
}

#[test]
fn a_declaration_that_conflicts_with_the_file_is_an_error_naming_both() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    let utm = tif(
        dir.path(),
        "utm.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let ok = declared(&utm, Some("EPSG:32631")).unwrap();
    assert_eq!((ok.crs, ok.crs_source), (UTM, CrsSource::File));
    for other in ["EPSG:4326", "EPSG:32632"] {
        let e = declared(&utm, Some(other)).unwrap_err();
        assert!(matches!(e, SeafloorError::CrsConflict { .. }), "{e:?}");
        let m = e.to_string();
        assert!(
            m.contains("utm.tif")
                && m.contains(&format!("declared CRS {other}"))
                && m.contains("own CRS EPSG:32631 (from the file)"),
            "{m}"
        );
    }
    // against a sidecar
    let (asc, _) = degrees(dir.path());
    std::fs::write(asc.with_extension("prj"), wkt_of(&WGS84).unwrap()).unwrap();
    let m = declared(&asc, Some("EPSG:32756")).unwrap_err().to_string();
    assert!(
        m.contains("EPSG:32756")
            && m.contains("EPSG:4326 (from the sidecar")
            && m.contains("degrees.prj"),
        "{m}"
    );
    // a malformed declaration names the key
    let m = declared(&utm, Some("UTM31")).unwrap_err().to_string();
    assert!(
        m.starts_with("seafloor.crs: \"UTM31\": expected \"EPSG:<code>\""),
        "{m}"
    );
}

#[test]
fn sidecars_and_declarations_are_checked_against_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = survey();
    let asc = dir.path().join("survey.asc");
    floor_of(&l, &z, &nd).write_esri_ascii(&asc).unwrap();
    // metres declared geographic: refused, with the coordinates
    let m = declared(&asc, Some("EPSG:4326")).unwrap_err().to_string();
    assert!(
        m.contains("survey.asc") && m.contains("expected degrees"),
        "{m}"
    );
    // a UTM sidecar: projected, the grid's own coordinates
    let prj = dir.path().join("survey.prj");
    std::fs::write(&prj, wkt_of(&UTM).unwrap()).unwrap();
    let f = declared(&asc, None).unwrap();
    assert_eq!((f.crs, f.floor.x0()), (UTM, l.x0));
    // a sidecar shoal cannot name: user-defined, with its WKT name
    std::fs::write(
        &prj,
        "PROJCS[\"Local survey grid\",GEOGCS[\"GRS 1980\"],UNIT[\"metre\",1]]",
    )
    .unwrap();
    let f = declared(&asc, None).unwrap();
    assert_eq!(
        f.crs,
        Crs::Projected {
            epsg: None,
            citation: Some("Local survey grid".into())
        }
    );
    let f = declared(&asc, Some("EPSG:32631")).unwrap();
    assert_eq!(
        (f.crs.to_string(), f.crs_source),
        ("EPSG:32631".into(), CrsSource::Declared)
    );
    // an unreadable sidecar: the error names it
    std::fs::write(&prj, "PROJCS[\"feet\",UNIT[\"foot\",0.3048]]").unwrap();
    let m = declared(&asc, None).unwrap_err().to_string();
    assert!(m.contains("survey.prj") && m.contains("only metres"), "{m}");
}

#[test]
fn info_shows_the_crs_and_where_it_came_from() {
    let dir = tempfile::tempdir().unwrap();
    let (asc, t) = degrees(dir.path());
    let line = |text: &str| {
        text.lines()
            .find(|l| l.starts_with("CRS source"))
            .unwrap_or_default()
            .to_string()
    };
    let i = info_with_crs(&t, Values::Elevation, None).unwrap();
    assert_eq!(line(&i.to_string()), "CRS source  from the file");
    let i = info_with_crs(&asc, Values::Elevation, None).unwrap();
    assert!(
        line(&i.to_string()).contains("guessed")
            && line(&i.to_string()).contains("look like degrees")
    );
    let (code, stdout, _) = run(shoal()
        .args(["seafloor", "info", "--crs", "EPSG:4326"])
        .arg(&asc));
    assert_eq!(code, 0);
    assert!(
        stdout.contains("CRS         EPSG:4326 (geographic"),
        "{stdout}"
    );
    assert!(line(&stdout).contains("declared"), "{stdout}");
    assert!(
        stdout.contains("seafloor.origin = [43.050000, 5.070000]"),
        "{stdout}"
    );
    std::fs::write(asc.with_extension("prj"), wkt_of(&WGS84).unwrap()).unwrap();
    let (code, stdout, _) = run(shoal().args(["seafloor", "info"]).arg(&asc));
    assert_eq!(code, 0);
    assert!(
        line(&stdout).contains("from the sidecar") && line(&stdout).contains("degrees.prj"),
        "{stdout}"
    );
    let (code, _, stderr) = run(shoal()
        .args(["seafloor", "info", "--crs", "EPSG:32631"])
        .arg(&t));
    assert_eq!(code, 2);
    assert!(
        stderr.contains("conflicts with the grid's own CRS EPSG:4326"),
        "{stderr}"
    );
}

#[test]
fn a_plan_over_an_esri_grid_declared_in_degrees_passes_its_check() {
    let dir = tempfile::tempdir().unwrap();
    let (asc, _) = degrees(dir.path());
    let out = dir.path().join("out");
    let (code, stdout, stderr) = plan_small(
        &asc,
        &out,
        &["--no-plot", "--set", "seafloor.crs=\"EPSG:4326\""],
    );
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    let plan = shoal::output::read_plan(&out.join("plan.json")).unwrap();
    assert_eq!(
        (plan.seafloor.format.as_str(), plan.seafloor.crs.as_str()),
        ("esri-ascii", "EPSG:4326")
    );
    assert_eq!(plan.seafloor.origin, Some([43.05, 5.07]));
    // `shoal check` reloads the grid with the scenario's declaration
    let (code, stdout, _) = run(shoal().arg("check").arg(out.join("plan.json")));
    assert_eq!(code, 0, "{stdout}");
}
