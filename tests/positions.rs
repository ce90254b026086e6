//! A plan's positions in the floor's own coordinates (`shoal export PLAN --csv`): latitude and
//! longitude over a geographic grid, easting/northing over a projected one.

mod common;

use common::*;
use shoal::positions::{rows, Georef};
use shoal::scenario;
use shoal::seafloor::geo::{meridional_radius, prime_vertical_radius};

/// Latitude/longitude of the frame point (x, y) near the origin, to first order in the
/// distance: the equirectangular map with the WGS84 radii of curvature at the origin, an
/// independent check of the frame's inverse. It leaves out the tangent plane's curvature term,
/// about d²·tan φ / (2R) (0.7 mm, 6e-9°, at 100 m and 43° N).
fn near_origin(lat0: f64, lon0: f64, x: f64, y: f64) -> [f64; 2] {
    let m = meridional_radius(lat0);
    let n = prime_vertical_radius(lat0) * lat0.to_radians().cos();
    [lat0 + (y / m).to_degrees(), lon0 + (x / n).to_degrees()]
}

#[test]
fn positions_over_a_geographic_grid_are_given_in_latitude_and_longitude() {
    let dir = tempfile::tempdir().unwrap();
    let f = geographic_tif(dir.path(), "gebco.tif");
    for (origin, extra) in [
        ([43.05, 5.07], vec![]),
        ([43.04, 5.06], vec!["seafloor.origin=[43.04, 5.06]"]),
    ] {
        let mut s = small(&f, &extra);
        s.initial = Some(scenario::Initial {
            usv: [0.0, 0.0],
            auvs: vec![[60.0, 0.0, -40.0], [0.0, -80.0, -40.0]],
        });
        let (p, _) = plan_scenario(&s).unwrap();
        let g = Georef::of(&p.seafloor).unwrap();
        assert_eq!(g.columns(), ["lat_deg", "lon_deg"]);
        let r = rows(&p, &g).unwrap();
        assert_eq!(r.len(), (5 + 1) * 3);
        // k = 0: the USV at the frame's origin is at the mission origin
        assert_eq!((r[0].vehicle.as_str(), r[0].k, r[0].window), ("usv", 0, 0));
        let [lat, lon] = r[0].crs.unwrap();
        assert!(
            (lat - origin[0]).abs() < 1e-9 && (lon - origin[1]).abs() < 1e-9,
            "{lat} {lon}"
        );
        // AUV 0 is 60 m east of it, AUV 1 80 m south
        for (row, (x, y)) in r[1..3].iter().zip([(60.0, 0.0), (0.0, -80.0)]) {
            let [lat, lon] = row.crs.unwrap();
            let [elat, elon] = near_origin(origin[0], origin[1], x, y);
            assert!(
                (lat - elat).abs() < 1e-8 && (lon - elon).abs() < 1e-8,
                "{row:?}"
            );
        }
        // every row: the frame's forward map gives the planner's position back
        let frame = shoal::seafloor::geo::LocalFrame::new(origin[0], origin[1]).unwrap();
        for row in &r {
            let [lat, lon] = row.crs.unwrap();
            let [x, y] = frame.to_local(lat, lon);
            assert!((x - row.position[0]).abs() < 1e-6 && (y - row.position[1]).abs() < 1e-6);
        }
    }
}

#[test]
fn cli_exports_positions_as_csv() {
    let dir = tempfile::tempdir().unwrap();
    let f = geographic_tif(dir.path(), "gebco.tif");
    let out = dir.path().join("out");
    let status = shoal()
        .args([
            "plan",
            "--no-plot",
            "--set",
            "team.auvs=2",
            "--set",
            "horizon.steps=5",
            "--set",
            "windows=2",
            "--seafloor",
        ])
        .arg(&f)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        status.status.success(),
        "{}",
        String::from_utf8_lossy(&status.stderr)
    );
    let csv_path = out.join("positions.csv");
    let o = shoal()
        .arg("export")
        .arg(out.join("plan.json"))
        .arg("--csv")
        .arg(&csv_path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        stdout.contains("36 rows") && stdout.contains("latitude and longitude"),
        "{stdout}"
    );
    let mut rd = csv::Reader::from_path(&csv_path).unwrap();
    let header: Vec<String> = rd.headers().unwrap().iter().map(str::to_string).collect();
    assert_eq!(
        header,
        ["window", "k", "t_s", "vehicle", "x_m", "y_m", "z_m", "lat_deg", "lon_deg"]
    );
    let records: Vec<csv::StringRecord> = rd.records().map(Result::unwrap).collect();
    assert_eq!(records.len(), 2 * 6 * 3);
    let first = &records[0];
    assert_eq!(&first[3], "usv");
    assert_eq!((&first[7], &first[8]), ("43.05000000", "5.07000000"));
    // window 1 starts at t = K·δ = 500 s, where window 0 ended
    let w1 = records.iter().find(|r| &r[0] == "1").unwrap();
    assert_eq!((&w1[1], &w1[2]), ("0", "500"));
    // the positions are those of the plan
    let p = shoal::output::read_plan(&out.join("plan.json")).unwrap();
    let auv1_k3: Vec<f64> = records
        .iter()
        .find(|r| &r[0] == "0" && &r[1] == "3" && &r[3] == "auv1")
        .map(|r| (4..7).map(|c| r[c].parse().unwrap()).collect())
        .unwrap();
    assert_eq!(auv1_k3, p.windows[0].final_.auvs[1].position[3]);
    // a missing plan is an error naming it
    let o = shoal()
        .args(["export", "nope.json", "--csv"])
        .arg(dir.path().join("x.csv"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("nope.json"));
}

#[test]
fn positions_over_a_projected_grid_are_its_easting_and_northing() {
    let dir = tempfile::tempdir().unwrap();
    let s = utm_survey_scenario(dir.path());
    let (p, _) = plan_scenario(&s).unwrap();
    let g = Georef::of(&p.seafloor).unwrap();
    assert_eq!(
        g,
        Georef::Projected {
            crs: "EPSG:32631".into()
        }
    );
    assert_eq!(g.columns(), ["easting_m", "northing_m"]);
    for row in rows(&p, &g).unwrap() {
        assert_eq!(row.crs, Some([row.position[0], row.position[1]]));
    }
    // the synthetic floor has no CRS: the planner's frame only
    let mut p2 = p.clone();
    p2.seafloor.crs = "none".into();
    let g = Georef::of(&p2.seafloor).unwrap();
    assert_eq!((g.clone(), g.columns().len()), (Georef::Local, 0));
    assert!(rows(&p2, &g).unwrap().iter().all(|r| r.crs.is_none()));
}
