//! `shoal seafloor export`: crops and resampled crops of grid files in their own CRS (`--from`)
//! and of the scenario's floor, written as ESRI ASCII (with a .prj sidecar) or GeoTIFF and read
//! back; errors that name the option.

mod common;

use common::*;
use shoal::seafloor::{
    export_grid, load, CropRegion, Crs, CrsSource, ExportOptions, LoadOptions, SampleType,
    Seafloor, SeafloorError, TiffCompression,
};
use std::path::Path;

fn utm_tif(dir: &Path) -> std::path::PathBuf {
    let (l, z, nd) = survey();
    tif(
        dir,
        "utm.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Int32,
        strips(TiffCompression::Deflate),
    )
}

fn export(path: &Path, region: CropRegion, cell: Option<f64>) -> Result<Seafloor, SeafloorError> {
    let opts = ExportOptions {
        region,
        cell,
        ..ExportOptions::default()
    };
    export_grid(path, &opts).map(|g| g.floor)
}

#[test]
fn a_crop_reloads_with_the_same_depths_and_crs() {
    let dir = tempfile::tempdir().unwrap();
    let src = utm_tif(dir.path());
    let (l, z, nd) = survey();
    let original = floor_of(&l, &z, &nd);
    let region = [l.x0 + 95.0, l.y0 + 100.0, l.x0 + 505.0, l.y0 + 400.0];
    let g = export_grid(
        &src,
        &ExportOptions {
            region: CropRegion::Native(region),
            ..ExportOptions::default()
        },
    )
    .unwrap();
    assert_eq!(
        (g.crs.clone(), g.crs_source.clone()),
        (UTM, CrsSource::File)
    );
    // nodes 5..=25 in x (20 m) and 4..=16 in y (25 m)
    assert_eq!((g.floor.nx(), g.floor.ny()), (21, 13));
    assert_eq!((g.floor.x0(), g.floor.y0()), (l.x0 + 100.0, l.y0 + 100.0));
    for (name, ext) in [("crop", "asc"), ("crop", "tif")] {
        let out = dir.path().join(format!("{name}.{ext}"));
        let notes = shoal::output::write_grid(&g.floor, &g.crs, None, &out).unwrap();
        let back = load(&out, &LoadOptions::default()).unwrap();
        assert_eq!(back.crs, UTM, "{ext}");
        if ext == "asc" {
            assert_eq!(
                back.crs_source,
                CrsSource::Sidecar(dir.path().join("crop.prj"))
            );
            assert!(notes[0].contains("crop.prj (EPSG:32631)"), "{notes:?}");
        }
        let b = &back.floor;
        for j in 0..b.ny() {
            for i in 0..b.nx() {
                let (x, y) = (b.x0() + i as f64 * b.dx(), b.y0() + j as f64 * b.dy());
                assert_eq!(
                    b.node(i, j),
                    original.elevation(x, y).unwrap(),
                    "{ext} {i} {j}"
                );
                let (oi, oj) = (i + 5, j + 4);
                assert_eq!(b.is_nodata(i, j), original.is_nodata(oi, oj));
            }
        }
    }
}

#[test]
fn a_resampled_crop_interpolates_and_keeps_every_obstacle() {
    let dir = tempfile::tempdir().unwrap();
    let src = utm_tif(dir.path());
    let (l, z, nd) = survey();
    let original = floor_of(&l, &z, &nd);
    let e = original.extent();
    for cell in [7.0, 20.0, 55.0] {
        let r = export(
            &src,
            CropRegion::Native([e.x_min, e.y_min, e.x_max, e.y_max]),
            Some(cell),
        )
        .unwrap();
        assert_eq!(
            (r.dx(), r.dy(), r.x0() % cell, r.y0() % cell),
            (cell, cell, 0.0, 0.0)
        );
        let mut checked = 0;
        for j in 0..r.ny() {
            for i in 0..r.nx() {
                let (x, y) = (r.x0() + i as f64 * cell, r.y0() + j as f64 * cell);
                if !r.is_obstacle(x, y).unwrap() && !original.is_obstacle(x, y).unwrap() {
                    let want = original.elevation(x, y).unwrap();
                    assert!((r.node(i, j) - want).abs() < 1e-9, "{cell}: {x} {y}");
                    checked += 1;
                }
            }
        }
        assert!(checked > r.nx() * r.ny() / 2, "{cell}: {checked}");
        // every point over a source obstacle is over a resampled obstacle
        let re = r.extent();
        for a in 0..200 {
            for b in 0..150 {
                let x = re.x_min + (re.x_max - re.x_min) * a as f64 / 199.0;
                let y = re.y_min + (re.y_max - re.y_min) * b as f64 / 149.0;
                if original.is_obstacle(x, y).unwrap() {
                    assert!(r.is_obstacle(x, y).unwrap(), "{cell}: ({x}, {y})");
                }
            }
        }
    }
}

#[test]
fn a_geographic_grid_is_cropped_in_degrees_and_resampled_in_metres() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = geographic();
    let src = tif(
        dir.path(),
        "gebco.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float64,
        strips(TiffCompression::None),
    );
    // a latitude/longitude box (south, west, north, east): the native nodes inside it
    let crop = export(
        &src,
        CropRegion::LatLon([43.0205, 5.0305, 43.0605, 5.0905]),
        None,
    )
    .unwrap();
    assert_eq!((crop.nx(), crop.ny()), (60, 40));
    assert!((crop.x0() - 5.031).abs() < 1e-12 && (crop.y0() - 43.021).abs() < 1e-12);
    // the same box in the grid's own units (lon, lat), and with longitudes of another turn
    let same = export(
        &src,
        CropRegion::Native([5.0305, 43.0205, 5.0905, 43.0605]),
        None,
    )
    .unwrap();
    assert_eq!(same, crop);
    let turned = export(
        &src,
        CropRegion::LatLon([43.0205, 365.0305, 43.0605, 365.0905]),
        None,
    );
    assert_eq!(turned.unwrap().fingerprint(), crop.fingerprint());
    // 50 m cells: degrees at the box's centre latitude; values of the linear field exact
    let r = export(
        &src,
        CropRegion::LatLon([43.0205, 5.0305, 43.0605, 5.0905]),
        Some(50.0),
    )
    .unwrap();
    let frame = shoal::seafloor::geo::LocalFrame::new(43.0405, 5.0605).unwrap();
    let [me, mn] = frame.metres_per_degree();
    assert!((r.dx() * me - 50.0).abs() < 1e-9 && (r.dy() * mn - 50.0).abs() < 1e-9);
    for j in 0..r.ny() {
        for i in 0..r.nx() {
            let (lon, lat) = (r.x0() + i as f64 * r.dx(), r.y0() + j as f64 * r.dy());
            if !r.is_obstacle(lon, lat).unwrap() {
                assert!((r.node(i, j) - geo_depth(lat, lon)).abs() < 1e-6, "{i} {j}");
            }
        }
    }
    // written as .asc with its WGS 84 sidecar, it loads as a geographic grid again
    let out = dir.path().join("box.asc");
    shoal::output::write_grid(&crop, &WGS84, None, &out).unwrap();
    let back = load(&out, &LoadOptions::default()).unwrap();
    assert_eq!(back.crs, Crs::Geographic { epsg: Some(4326) });
    assert!(back.origin.is_some());
    // --region-latlon needs a geographic grid
    let e = export(
        &utm_tif(dir.path()),
        CropRegion::LatLon([43.0, 5.0, 43.1, 5.1]),
        None,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("--region-latlon") && e.contains("EPSG:32631"),
        "{e}"
    );
}

#[test]
fn a_region_outside_the_grid_is_refused_naming_the_option() {
    let dir = tempfile::tempdir().unwrap();
    let src = utm_tif(dir.path());
    let e = export(&src, CropRegion::Native([0.0, 0.0, 100.0, 100.0]), None)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("utm.tif: --region: ")
            && e.contains("not inside the grid, which covers x from 500010 to 500810"),
        "{e}"
    );
    let e = export(&src, CropRegion::All, Some(-5.0))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--cell: -5: expected a positive number of metres"),
        "{e}"
    );
    // the CLI says the same, exit 2, and writes nothing
    let out = dir.path().join("x.asc");
    let (code, _, stderr) = run(shoal()
        .args(["seafloor", "export", "--from"])
        .arg(&src)
        .args(["--region", "0,0,100,100", "-o"])
        .arg(&out));
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--region") && stderr.contains("not inside the grid"),
        "{stderr}"
    );
    assert!(!out.exists());
    let (code, _, stderr) = run(shoal()
        .args(["seafloor", "export", "--region", "1,2,3", "-o"])
        .arg(&out));
    assert_eq!(code, 2);
    assert!(stderr.contains("expected four finite numbers"), "{stderr}");
}

#[test]
fn cli_exports_crops_of_files_and_of_the_scenario_floor() {
    let dir = tempfile::tempdir().unwrap();
    let src = utm_tif(dir.path());
    let (l, _, _) = survey();
    // a grid file, cropped and resampled, as depths
    let out = dir.path().join("crop.tif");
    let region = format!("{},{},{},{}", l.x0, l.y0, l.x0 + 400.0, l.y0 + 300.0);
    let (code, stdout, stderr) = run(shoal()
        .args([
            "seafloor", "export", "--values", "depth", "--cell", "10", "--from",
        ])
        .arg(&src)
        .args(["--region", &region, "-o"])
        .arg(&out));
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stdout.contains("41 × 30 nodes") && stdout.contains("CRS EPSG:32631 (from the file)"),
        "{stdout}"
    );
    let back = load(&out, &LoadOptions::default()).unwrap();
    assert_eq!((back.crs, back.floor.dx()), (UTM, 10.0));
    // depths were negated: the survey's elevations are negative, so these are mostly positive
    assert!(back.floor.z_range().1 > 100.0, "{:?}", back.floor.z_range());
    // the scenario's (synthetic) floor, cropped around the origin and resampled
    let out = dir.path().join("syn.asc");
    let (code, stdout, stderr) = run(shoal()
        .args([
            "seafloor",
            "export",
            "--region",
            "-500,-500,500,500",
            "--cell",
            "50",
            "-o",
        ])
        .arg(&out));
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("21 × 21 nodes, 50 m cells"), "{stdout}");
    let f = load(&out, &LoadOptions::default()).unwrap();
    assert_eq!((f.floor.x0(), f.floor.y0()), (-500.0, -500.0));
    assert!(matches!(f.crs_source, CrsSource::Guessed { .. }));
    let (code, _, stderr) = run(shoal()
        .args([
            "seafloor",
            "export",
            "--region-latlon",
            "43,5,43.1,5.1",
            "-o",
        ])
        .arg(&out));
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--region-latlon: the scenario's floor is not from a geographic grid"),
        "{stderr}"
    );
    // --values and --crs apply to --from only; --from excludes a scenario
    let (code, _, _) = run(shoal().args(["seafloor", "export", "--values", "depth"]));
    assert_eq!(code, 2);
    let (code, _, _) = run(shoal()
        .args(["seafloor", "export", "mission.toml", "--from"])
        .arg(&src));
    assert_eq!(code, 2);
}

#[test]
fn a_scenario_floor_from_a_geographic_grid_is_cropped_by_a_latlon_box() {
    let dir = tempfile::tempdir().unwrap();
    let src = geographic_tif(dir.path(), "g.tif");
    let out = dir.path().join("box.tif");
    let (code, stdout, stderr) = run(shoal()
        .args(["seafloor", "export", "--set"])
        .arg(format!("seafloor.file={:?}", src.display().to_string()))
        .args(["--region-latlon", "43.045,5.065,43.055,5.075", "-o"])
        .arg(&out));
    assert_eq!(code, 0, "{stderr}");
    // the box is ≈ 814 × 1112 m around the origin (the grid centre, 43.05° N 5.07° E)
    let f = load(&out, &LoadOptions::default()).unwrap().floor;
    let e = f.extent();
    assert!(
        e.x_min > -420.0 && e.x_max < 420.0 && e.y_min > -570.0 && e.y_max < 570.0,
        "{e}"
    );
    assert!(
        e.x_max - e.x_min > 600.0 && e.y_max - e.y_min > 900.0,
        "{e}: {stdout}"
    );
}
