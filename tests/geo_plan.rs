//! Planning over GeoTIFF floors, end to end: `shoal plan --seafloor x.tif` then `shoal check`,
//! the plan's seafloor record, the sign convention, starts on land or outside the grid, and
//! `shoal seafloor info` / `export`.

mod common;

use common::*;
use shoal::mission::scenario_floor;
use shoal::scenario::{self, Scenario};
use shoal::seafloor::{load, LoadOptions, SampleType, TiffCompression};
use std::path::Path;

#[test]
fn cli_plans_over_a_geographic_geotiff_and_check_passes() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = geographic();
    let floor = tif(
        dir.path(),
        "gebco.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float32,
        strips(TiffCompression::Deflate),
    );
    let out = dir.path().join("out");
    let (code, stdout, stderr) = plan_small(&floor, &out, &[]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    let plan_json = out.join("plan.json");
    let (code, stdout, _) = run(shoal().arg("check").arg(&plan_json));
    assert_eq!(code, 0, "{stdout}");
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&plan_json).unwrap()).unwrap();
    let rec = &json["seafloor"];
    assert_eq!(rec["format"], "geotiff");
    assert_eq!(rec["crs"], "EPSG:4326");
    assert_eq!(rec["values"], "elevation");
    let origin = rec["origin"].as_array().unwrap();
    assert!((origin[0].as_f64().unwrap() - 43.05).abs() < 1e-12);
    assert!((origin[1].as_f64().unwrap() - 5.07).abs() < 1e-12);
    // only the mission window was loaded: ±2.6 km around the start, not the 11 km grid
    assert!(rec["nx"].as_u64().unwrap() < 80, "{rec}");
    // another floor is refused
    let other = tif(
        dir.path(),
        "other.tif",
        (&l, &z.iter().map(|v| v - 1.0).collect::<Vec<_>>(), &nd),
        &WGS84,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let (code, _, stderr) = run(shoal()
        .arg("check")
        .arg(&plan_json)
        .arg("--seafloor")
        .arg(&other));
    assert_eq!(code, 2);
    assert!(
        stderr.contains("not the floor the plan was made on"),
        "{stderr}"
    );
    // a plan written before the new seafloor fields still reads and checks
    let mut old = json.clone();
    for k in ["format", "crs", "values", "origin"] {
        old["seafloor"].as_object_mut().unwrap().remove(k);
    }
    let p: shoal::plan::Plan = serde_json::from_value(old).unwrap();
    assert_eq!((p.seafloor.crs.as_str(), p.seafloor.origin), ("none", None));
}

#[test]
fn plans_over_projected_depth_and_esri_grids_pass_their_check() {
    let dir = tempfile::tempdir().unwrap();
    // a projected (UTM) grid: the frame is the grid's own coordinates, so the start is given
    let s = utm_survey_scenario(dir.path());
    let (p, _) = plan_and_check(&s).expect("plan over the UTM grid");
    assert_eq!(
        (p.seafloor.format.as_str(), p.seafloor.crs.as_str()),
        ("geotiff", "EPSG:32631")
    );
    // the same grid as positive depths in int16, and as ESRI ASCII: the same floor
    let (l, z, nd) = survey();
    let depth: Vec<f64> = z.iter().map(|v| -v).collect();
    let d = tif(
        dir.path(),
        "depth.tif",
        (&l, &depth, &nd),
        &UTM,
        SampleType::Int16,
        strips(TiffCompression::Lzw),
    );
    let mut sd = s.clone();
    sd.seafloor.file = Some(d.display().to_string());
    sd.seafloor.values = shoal::seafloor::Values::Depth;
    let (pd, _) = plan_and_check(&sd).expect("plan over the depth grid");
    assert_eq!(pd.seafloor.fingerprint, p.seafloor.fingerprint);
    assert_eq!(pd.seafloor.values, shoal::seafloor::Values::Depth);
    let asc = dir.path().join("utm.asc");
    load(&dir.path().join("utm.tif"), &LoadOptions::default())
        .unwrap()
        .floor
        .write_esri_ascii(&asc)
        .unwrap();
    let mut sa = s.clone();
    sa.seafloor.file = Some(asc.display().to_string());
    let (pa, _) = plan_and_check(&sa).expect("plan over the ESRI grid");
    assert_eq!(pa.seafloor.fingerprint, p.seafloor.fingerprint);
    assert_eq!(pa.seafloor.format, "esri-ascii");
}

#[test]
fn starts_on_land_over_nodata_or_outside_the_grid_are_refused_with_position_and_reason() {
    let dir = tempfile::tempdir().unwrap();
    let (l, mut z, mut nd) = geographic();
    // an island under the origin (the grid centre, node (70, 50)) and a hole east of it
    for j in 48..=52 {
        for i in 68..=72 {
            z[j * l.nx + i] = 2.0;
        }
    }
    for j in 40..=60 {
        for i in 80..=84 {
            nd[j * l.nx + i] = true;
        }
    }
    let f = tif(
        dir.path(),
        "island.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let msg = |s: &Scenario| match plan_and_check(s) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("planned"),
    };
    let m = msg(&small(&f, &[]));
    assert!(
        m.contains("the USV at (0.0, 0.0) is on land (the floor there is at z = +2.0 m)"),
        "{m}"
    );
    // the CLI says the same, exit 2
    let (code, _, stderr) = run(shoal()
        .args(["plan", "--seafloor"])
        .arg(&f)
        .arg("-o")
        .arg(dir.path().join("o")));
    assert_eq!(code, 2);
    assert!(stderr.contains("is on land"), "{stderr}");
    // an AUV over the hole (native nodes 5.080–5.084° E, 43.04–43.06° N: x ≈ 815–1140 m,
    // grown by a cell)
    let mut s = small(&f, &[]);
    s.initial = Some(scenario::Initial {
        usv: [600.0, -500.0],
        auvs: vec![[600.0, -450.0, -40.0], [740.0, -500.0, -40.0]],
    });
    let m = msg(&s);
    assert!(
        m.contains("AUV 1 at (740.0, -500.0) is over a NODATA cell"),
        "{m}"
    );
    // near the grid's edge, just outside it
    s.initial = Some(scenario::Initial {
        usv: [0.0, 5700.0],
        auvs: vec![[0.0, 5650.0, -40.0], [50.0, 5650.0, -40.0]],
    });
    let m = msg(&s);
    assert!(
        m.contains("the USV at (0.0, 5700.0) is outside the seafloor grid, which covers"),
        "{m}"
    );
    // far away: the mission area does not reach the grid
    s.initial = Some(scenario::Initial {
        usv: [0.0, 50_000.0],
        auvs: vec![[0.0, 50_050.0, -40.0], [50.0, 50_000.0, -40.0]],
    });
    let m = msg(&s);
    assert!(
        m.contains("island.tif") && m.contains("does not overlap the grid"),
        "{m}"
    );
}

#[test]
fn cli_seafloor_info_and_export() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = geographic();
    let z: Vec<f64> = z.iter().map(|v| v.round()).collect();
    let f = tif(
        dir.path(),
        "g.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Int16,
        strips(TiffCompression::None),
    );
    let (code, stdout, stderr) = run(shoal().args(["seafloor", "info"]).arg(&f));
    assert_eq!(code, 0, "{stderr}");
    for needle in [
        "141 × 101 nodes",
        "EPSG:4326",
        "seafloor.origin = [43.050000, 5.070000]",
        "6 NODATA",
        "1 land",
    ] {
        assert!(stdout.contains(needle), "{needle}:\n{stdout}");
    }
    let (code, _, stderr) = run(shoal()
        .args(["seafloor", "info", "--values", "depth"])
        .arg(&f));
    assert_eq!(code, 0);
    assert!(
        stderr.contains("warning:") && stderr.contains("\"elevation\""),
        "{stderr}"
    );
    // export of the synthetic floor as GeoTIFF reads back bit-exactly
    let out = dir.path().join("synthetic.tif");
    let (code, _, stderr) = run(shoal().args(["seafloor", "export", "-o"]).arg(&out));
    assert_eq!(code, 0, "{stderr}");
    let s = Scenario::default();
    let made = shoal::seafloor::Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    assert_eq!(
        load(&out, &LoadOptions::default())
            .unwrap()
            .floor
            .fingerprint(),
        made.fingerprint()
    );
    // export of a geographic scenario's floor: the metric mission window, in its local frame
    let out = dir.path().join("window.tif");
    let (code, _, stderr) = run(shoal()
        .args([
            "seafloor",
            "export",
            "--set",
            &format!("seafloor.file={:?}", f.display().to_string()),
            "-o",
        ])
        .arg(&out));
    assert_eq!(code, 0, "{stderr}");
    let back = load(&out, &LoadOptions::default()).unwrap();
    assert_eq!(back.crs.to_string(), "projected (user-defined)");
    let s = small(&f, &["team.auvs=5", "horizon.steps=20"]);
    let (planned, _) = scenario_floor(&s, Path::new("")).unwrap();
    assert_eq!(back.floor.fingerprint(), planned.fingerprint());
    let (code, stdout, _) = run(shoal().args(["seafloor", "info"]).arg(&out));
    assert_eq!(code, 0);
    assert!(stdout.contains("shoal local tangent plane"), "{stdout}");
}

/// The origin `shoal seafloor info FILE` suggests, as [lat, lon] (or [x, y]), parsed from its
/// "origin" line as printed.
fn suggested_origin(file: &Path) -> [f64; 2] {
    let (code, stdout, stderr) = run(shoal().args(["seafloor", "info"]).arg(file));
    assert_eq!(code, 0, "{stderr}");
    let line = stdout
        .lines()
        .find(|l| l.starts_with("origin"))
        .unwrap_or_else(|| panic!("no origin line:\n{stdout}"));
    let inside = line
        .rsplit_once('[')
        .and_then(|(_, r)| r.split_once(']'))
        .map(|(v, _)| v)
        .unwrap_or_else(|| panic!("{line}"));
    let v: Vec<f64> = inside
        .split(',')
        .map(|x| x.trim().parse().unwrap())
        .collect();
    [v[0], v[1]]
}

/// Whether `shoal plan` starts from the scenario `s`: its floor loads and the start (the USV at
/// the frame's origin, the AUVs drawn about it) passes the planner's start check.
fn plan_starts(s: &Scenario) -> Result<(), String> {
    let (floor, _) = scenario_floor(s, Path::new("")).map_err(|e| e.to_string())?;
    let keep_out = floor.keep_out();
    let init = shoal::mission::initial_state(s, &floor, &keep_out).map_err(|e| e.to_string())?;
    let start = shoal::trajectory::Start {
        usv: init.usv,
        auvs: init.auvs,
    };
    shoal::mission::check_start(s, &floor, &keep_out, &start, 0).map_err(|e| e.to_string())
}

/// Regression: on a geographic grid whose centre is land, `shoal seafloor info` suggested the
/// water node nearest the centre, which touches the island's cells, and `shoal plan` refused
/// it ("is on land", "in a grid cell that touches land"). The suggestion is now a point plan
/// accepts, for a geographic and for a projected grid.
#[test]
fn regression_the_origin_seafloor_info_suggests_is_one_plan_accepts() {
    let dir = tempfile::tempdir().unwrap();
    let (l, mut z, nd) = geographic();
    // an island under the grid centre (node (70, 50)), a lagoon of one water node inside it
    for j in 46..=54 {
        for i in 66..=74 {
            z[j * l.nx + i] = 2.0;
        }
    }
    z[50 * l.nx + 72] = -20.0;
    let f = tif(
        dir.path(),
        "island.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let [lat, lon] = suggested_origin(&f);
    let origin = format!("seafloor.origin=[{lat}, {lon}]");
    let s = small(&f, &[&origin]);
    plan_starts(&s).unwrap_or_else(|e| panic!("{origin}: {e}"));
    // the centre itself is refused, as before
    assert!(plan_starts(&small(&f, &[])).is_err());

    // a projected grid: the suggested [initial] usv
    let (l, mut z, nd) = survey();
    for j in 12..=18 {
        for i in 17..=23 {
            z[j * l.nx + i] = 3.0; // land under the centre node (20, 15)
        }
    }
    let f = tif(
        dir.path(),
        "utm.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Int32,
        strips(TiffCompression::None),
    );
    let [x, y] = suggested_origin(&f);
    let mut s = small(
        &f,
        // a slow vehicle: no cruise floor
        &["auv.max_speed=0.5", "auv.min_speed=0", "usv.max_speed=0.3"],
    );
    s.initial = Some(scenario::Initial {
        usv: [x, y],
        auvs: Vec::new(),
    });
    plan_starts(&s).unwrap_or_else(|e| panic!("usv = [{x}, {y}]: {e}"));
}
