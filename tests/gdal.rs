//! Grids read through GDAL (the `gdal` cargo feature). The fixtures are GeoTIFFs written by
//! shoal's own writer and converted with GDAL's command-line tools (Debian's gdal-bin):
//! NetCDF (classic and NetCDF-4 with Deflate), a GMT grid (.grd), BAG, gridded XYZ, a NetCDF of
//! scaled integers, a NetCDF of depths, and a south-up VRT. Loading any of them gives the same
//! floor as the GeoTIFF (same nodes, depths, NODATA holes and land), and a plan over each
//! passes its check.
#![cfg(feature = "gdal")]

mod common;

use common::*;
use shoal::scenario::{self, Scenario};
use shoal::seafloor::{
    info, load, LoadOptions, SampleType, Seafloor, SeafloorError, TiffCompression, Values,
};
use std::path::{Path, PathBuf};
use std::process::Command;

/// `gdal_translate -q ARGS SRC DST`, which must succeed.
fn translate(src: &Path, dst: &Path, args: &[&str]) -> PathBuf {
    let out = Command::new("gdal_translate")
        .arg("-q")
        .args(args)
        .arg(src)
        .arg(dst)
        .output()
        .expect("gdal_translate (Debian's gdal-bin) must be installed for the gdal feature tests");
    assert!(
        out.status.success(),
        "gdal_translate {args:?} {}: {}",
        src.display(),
        String::from_utf8_lossy(&out.stderr)
    );
    dst.to_path_buf()
}

/// Whether this GDAL can write with `driver` ("(rw" in `gdalinfo --formats`).
fn writable(driver: &str) -> bool {
    let out = Command::new("gdalinfo").arg("--formats").output().unwrap();
    String::from_utf8_lossy(&out.stdout).lines().any(|l| {
        let l = l.trim_start();
        l.starts_with(&format!("{driver} ")) && l.contains("(rw")
    })
}

/// A VRT over a single-band `source` with the given geotransform.
fn vrt(dir: &Path, name: &str, source: &str, (w, h): (usize, usize), gt: [f64; 6]) -> PathBuf {
    let p = dir.join(name);
    let gt: Vec<String> = gt.iter().map(|v| format!("{v:.17e}")).collect();
    std::fs::write(
        &p,
        format!(
            r#"<VRTDataset rasterXSize="{w}" rasterYSize="{h}">
  <SRS>EPSG:32631</SRS>
  <GeoTransform>{}</GeoTransform>
  <VRTRasterBand dataType="Float32" band="1">
    <NoDataValue>-99999</NoDataValue>
    <SimpleSource>
      <SourceFilename relativeToVRT="1">{source}</SourceFilename>
      <SourceBand>1</SourceBand>
    </SimpleSource>
  </VRTRasterBand>
</VRTDataset>
"#,
            gt.join(", ")
        ),
    )
    .unwrap();
    p
}

/// One fixture: what it is, the file, its sign convention, the CRS shoal should find.
struct Fixture {
    label: &'static str,
    path: PathBuf,
    values: Values,
    crs: &'static str,
}

/// The survey grid (UTM, a NODATA hole, an island) in every format GDAL writes here.
fn projected_fixtures(dir: &Path) -> (PathBuf, Vec<Fixture>) {
    let (l, z, nd) = survey();
    let reference = tif(
        dir,
        "survey.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let mut out = Vec::new();
    let mut add = |label, path, values, crs| {
        out.push(Fixture {
            label,
            path,
            values,
            crs,
        })
    };
    let e = Values::Elevation;
    let utm = "EPSG:32631";
    let nc = |name: &str, args: &[&str]| translate(&reference, &dir.join(name), args);
    add("NetCDF", nc("survey.nc", &["-of", "netCDF"]), e, utm);
    add(
        "NetCDF-4, Deflate",
        nc(
            "survey4.nc",
            &[
                "-of",
                "netCDF",
                "-co",
                "FORMAT=NC4",
                "-co",
                "COMPRESS=DEFLATE",
            ],
        ),
        e,
        utm,
    );
    // GMT's own grid format is a COARDS NetCDF file (.grd); GDAL's "GMT" driver, for the old
    // GMT 3 layout, is not in every build
    let gmt = if writable("GMT") { "GMT" } else { "netCDF" };
    add("GMT .grd", nc("survey.grd", &["-of", gmt]), e, utm);
    if writable("BAG") {
        add("BAG", nc("survey.bag", &["-of", "BAG"]), e, utm);
    } else {
        eprintln!("note: this GDAL cannot write BAG; skipped");
    }
    // XYZ has no NODATA marker: the survey's lines without data are left out, as in real XYZ
    // files, and GDAL reads the missing nodes as NODATA
    let full = nc("full.xyz", &["-of", "XYZ"]);
    let text = std::fs::read_to_string(&full).unwrap();
    let sparse: String = text
        .lines()
        .filter(|line| !line.ends_with(" -99999"))
        .map(|line| format!("{line}\n"))
        .collect();
    assert!(sparse.lines().count() < text.lines().count());
    let xyz = dir.join("survey.xyz");
    std::fs::write(&xyz, sparse).unwrap();
    add("XYZ", xyz, e, "none");
    // integers of decimetres with NetCDF's scale_factor
    let dm: Vec<f64> = z.iter().map(|v| v * 10.0).collect();
    let dm = tif(
        dir,
        "dm.tif",
        (&l, &dm, &nd),
        &UTM,
        SampleType::Int16,
        strips(TiffCompression::None),
    );
    add(
        "NetCDF int16 × 0.1",
        translate(
            &dm,
            &dir.join("dm.nc"),
            &["-of", "netCDF", "-a_scale", "0.1"],
        ),
        e,
        utm,
    );
    // depths (positive down)
    let depth: Vec<f64> = z.iter().map(|v| -v).collect();
    let depth = tif(
        dir,
        "depth.tif",
        (&l, &depth, &nd),
        &UTM,
        SampleType::Int16,
        strips(TiffCompression::Lzw),
    );
    add(
        "NetCDF of depths",
        translate(&depth, &dir.join("depth.nc"), &["-of", "netCDF"]),
        Values::Depth,
        utm,
    );
    // a raster stored south first (positive y step): the rows of a TIFF written upside down,
    // placed by a VRT
    let flipped: Vec<f64> = (0..l.ny)
        .rev()
        .flat_map(|j| z[j * l.nx..(j + 1) * l.nx].to_vec())
        .collect();
    let flipped_nd: Vec<bool> = (0..l.ny)
        .rev()
        .flat_map(|j| nd[j * l.nx..(j + 1) * l.nx].to_vec())
        .collect();
    tif(
        dir,
        "flipped.tif",
        (&l, &flipped, &flipped_nd),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    let gt = [l.x0 - 0.5 * l.dx, l.dx, 0.0, l.y0 - 0.5 * l.dy, 0.0, l.dy];
    add(
        "south-up VRT",
        vrt(dir, "southup.vrt", "flipped.tif", (l.nx, l.ny), gt),
        e,
        utm,
    );
    (reference, out)
}

/// The same nodes (within 1 µm), values (within 1e-9 m), NODATA and land.
fn assert_same_floor(label: &str, a: &Seafloor, b: &Seafloor) {
    let (la, lb) = (a.lattice(), b.lattice());
    assert_eq!((la.nx, la.ny), (lb.nx, lb.ny), "{label}");
    for (x, y) in [
        (la.x0, lb.x0),
        (la.y0, lb.y0),
        (la.dx, lb.dx),
        (la.dy, lb.dy),
    ] {
        assert!((x - y).abs() < 1e-6, "{label}: {la:?} vs {lb:?}");
    }
    let ((za, ma), (zb, mb)) = (a.nodes(), b.nodes());
    assert_eq!(ma, mb, "{label}: NODATA masks differ");
    for (k, (x, y)) in za.iter().zip(zb).enumerate() {
        assert!((x - y).abs() < 1e-9, "{label}: node {k}: {x} vs {y}");
    }
    assert_eq!(a.obstacle_counts(), b.obstacle_counts(), "{label}");
}

/// Speeds for the small survey grid (as tests/geo_plan.rs plans over it): a slow vehicle, no
/// cruise floor.
const SLOW: &[&str] = &["auv.max_speed=0.5", "auv.min_speed=0", "usv.max_speed=0.3"];

/// [`common::small`] over `floor`, read with the sign convention `values`.
fn small_with(floor: &Path, values: Values, extra: &[&str]) -> Scenario {
    let mut set = extra.to_vec();
    if values == Values::Depth {
        set.push("seafloor.values=\"depth\"");
    }
    common::small(floor, &set)
}

#[test]
fn every_format_gives_the_geotiffs_floor_and_a_plan_over_each_passes_its_check() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, fixtures) = projected_fixtures(dir.path());
    let want = load(&reference, &LoadOptions::default()).unwrap();
    let want_info = info(&reference, Values::Elevation).unwrap();
    assert_eq!(want.floor.obstacle_counts(), (9, 25));
    let (l, _, _) = survey();
    let (cx, cy) = (l.x0 + 400.0, l.y0 + 375.0);
    let initial = scenario::Initial {
        usv: [cx, cy],
        auvs: vec![[cx + 40.0, cy, -60.0], [cx, cy + 50.0, -60.0]],
    };
    let mut plan_over_tif = small_with(&reference, Values::Elevation, SLOW);
    plan_over_tif.initial = Some(initial.clone());
    let (tif_plan, tif_window) = plan_and_check(&plan_over_tif).expect("a plan");
    for f in &fixtures {
        let got = load(&f.path, &opts(f.values)).unwrap_or_else(|e| panic!("{}: {e}", f.label));
        assert_eq!(got.format.name(), "gdal", "{}", f.label);
        assert_eq!(got.crs.to_string(), f.crs, "{}", f.label);
        assert!(got.warnings.is_empty(), "{}: {:?}", f.label, got.warnings);
        assert_same_floor(f.label, &got.floor, &want.floor);
        // `shoal seafloor info` reads the same
        let i = info(&f.path, f.values).unwrap();
        assert_eq!(
            (i.data_nodes, i.nodata_nodes, i.land_nodes, i.z_range),
            (
                want_info.data_nodes,
                want_info.nodata_nodes,
                want_info.land_nodes,
                want_info.z_range
            ),
            "{}",
            f.label
        );
        assert!(i.driver.is_some(), "{}", f.label);
        // a plan over it: the same mission window, the same plan, and it passes its check
        let mut s = small_with(&f.path, f.values, SLOW);
        s.initial = Some(initial.clone());
        let (p, window) = plan_and_check(&s).expect("a plan");
        assert_same_floor(f.label, &window, &tif_window);
        assert_eq!(p.seafloor.format, "gdal");
        assert_eq!(p.seafloor.crs, f.crs);
        assert_eq!(p.windows.len(), tif_plan.windows.len());
    }
}

/// Regression (issue 13): reading NetCDF-4 files, HDF5 printed its error stack on stderr for
/// every optional attribute netCDF-C probes (over 500 lines in these tests) although nothing
/// was wrong. HDF5's automatic printing is now off. The other tests of this file, which read
/// NetCDF-4 files in-process one after another (the noise came from the later reads), are
/// run again in a child process whose stderr is read.
#[test]
fn regression_reading_netcdf4_files_prints_no_hdf5_diagnostics() {
    let me = std::env::current_exe().unwrap();
    let out = Command::new(me)
        .args([
            "--test-threads=1",
            "--skip",
            "regression_reading_netcdf4_files_prints_no_hdf5_diagnostics",
        ])
        .output()
        .unwrap();
    let (stdout, stderr) = (
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr),
    );
    assert!(out.status.success(), "{stdout}\n{stderr}");
    assert!(stdout.contains("3 passed"), "{stdout}");
    let noise = stderr.lines().filter(|l| l.contains("HDF5")).count();
    assert_eq!(noise, 0, "{stderr}");
}

#[test]
fn a_geographic_netcdf_plans_like_its_geotiff_and_the_cli_checks_it() {
    let dir = tempfile::tempdir().unwrap();
    let (l, z, nd) = geographic();
    let g = tif(
        dir.path(),
        "gebco.tif",
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float32,
        strips(TiffCompression::Deflate),
    );
    let nc = translate(&g, &dir.path().join("gebco.nc"), &["-of", "netCDF"]);
    // resampled onto the local tangent plane at the grid's centre: the same floor
    let (a, b) = (
        load(&g, &LoadOptions::default()).unwrap(),
        load(&nc, &LoadOptions::default()).unwrap(),
    );
    assert_eq!(b.crs.to_string(), "EPSG:4326");
    assert_eq!(a.origin, b.origin);
    assert!(b.warnings.is_empty(), "{:?}", b.warnings);
    let (la, lb) = (a.floor.lattice(), b.floor.lattice());
    assert_eq!((la.nx, la.ny, la.dx, la.dy), (lb.nx, lb.ny, lb.dx, lb.dy));
    let ((za, ma), (zb, mb)) = (a.floor.nodes(), b.floor.nodes());
    assert_eq!(ma, mb);
    for (x, y) in za.iter().zip(zb) {
        // float32 values; node positions from NetCDF's coordinate arrays
        assert!((x - y).abs() < 1e-6, "{x} vs {y}");
    }
    assert_eq!(a.floor.obstacle_counts(), b.floor.obstacle_counts());
    let (p, _) = plan_and_check(&small_with(&nc, Values::Elevation, &[])).expect("a plan");
    assert_eq!(
        (p.seafloor.format.as_str(), p.seafloor.crs.as_str()),
        ("gdal", "EPSG:4326")
    );
    // the CLI, end to end: plan, then check from the plan file
    let out = dir.path().join("out");
    let (code, stdout, stderr) = plan_small(&nc, &out, &[]);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    let (code, stdout, _) = run(shoal().arg("check").arg(out.join("plan.json")));
    assert_eq!(code, 0, "{stdout}");
    let (code, stdout, stderr) = run(shoal().args(["seafloor", "info"]).arg(&nc));
    assert_eq!(code, 0, "{stderr}");
    for needle in [
        "netCDF",
        "read with GDAL",
        "141 × 101 nodes",
        "EPSG:4326",
        "seafloor.origin = [43.050000, 5.070000]",
        "6 NODATA",
        "1 land",
    ] {
        assert!(stdout.contains(needle), "{needle}:\n{stdout}");
    }
}

#[test]
fn unusable_files_give_errors_that_name_the_file_and_the_problem() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let err = |p: &Path| load(p, &LoadOptions::default()).unwrap_err();
    let (l, z, nd) = survey();
    let reference = tif(
        d,
        "survey.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Float32,
        strips(TiffCompression::None),
    );
    // a rotated grid
    let rotated = vrt(
        d,
        "rotated.vrt",
        "survey.tif",
        (l.nx, l.ny),
        [500_000.0, 20.0, 2.0, 4_700_800.0, 0.0, -25.0],
    );
    let e = err(&rotated).to_string();
    assert!(
        e.contains("rotated.vrt") && e.contains("rotated") && e.contains("gdalwarp"),
        "{e}"
    );
    // a NetCDF of two variables: GDAL sees subdatasets, not a grid
    let two = d.join("two.tif");
    let status = Command::new("gdal_translate")
        .args(["-q", "-b", "1", "-b", "1"])
        .arg(&reference)
        .arg(&two)
        .status()
        .unwrap();
    assert!(status.success());
    let two = translate(&two, &d.join("two.nc"), &["-of", "netCDF"]);
    let e = err(&two).to_string();
    assert!(
        e.contains("two.nc") && e.contains("2 subdatasets") && e.contains("Band2"),
        "{e}"
    );
    // an XYZ file with its NODATA marker written as a value
    let xyz = translate(&reference, &d.join("full.xyz"), &["-of", "XYZ"]);
    let e = err(&xyz).to_string();
    assert!(
        e.contains("full.xyz") && e.contains("-99999") && e.contains("no NODATA value"),
        "{e}"
    );
    // not a grid, and no file at all
    let junk = d.join("junk.dem");
    std::fs::write(&junk, "not a grid").unwrap();
    let e = err(&junk);
    assert!(matches!(e, SeafloorError::Gdal { .. }), "{e}");
    assert!(e.to_string().contains("not recognized"), "{e}");
    let e = err(&d.join("missing.nc"));
    assert!(
        matches!(e, SeafloorError::Io { .. }) && e.to_string().contains("missing.nc"),
        "{e}"
    );
    // shoal writes .asc and .tif only
    let (code, _, stderr) = run(shoal()
        .args(["seafloor", "export", "-o"])
        .arg(d.join("out.nc")));
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("out.nc"), "{stderr}");
}
