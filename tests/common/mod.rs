//! Fixture grids shared by the grid-file tests, written by the crate's own writers.
#![allow(dead_code)]

use shoal::seafloor::{
    load, write_geotiff, Crs, GeoTiffOptions, Lattice, LoadOptions, LoadedFloor, Region,
    SampleType, Seafloor, SeafloorError, TiffCompression, TiffLayout, Values,
};
use std::path::{Path, PathBuf};
use std::process::Command;

pub const UTM: Crs = Crs::Projected {
    epsg: Some(32631),
    citation: None,
};
pub const WGS84: Crs = Crs::Geographic { epsg: Some(4326) };

/// An integral floor (exact in every sample type) with a NODATA hole and an island, on a
/// lattice in UTM-like coordinates: 41 × 31 nodes of 20 × 25 m.
pub fn survey() -> (Lattice, Vec<f64>, Vec<bool>) {
    let l = Lattice {
        nx: 41,
        ny: 31,
        x0: 500_010.0,
        y0: 4_700_012.5,
        dx: 20.0,
        dy: 25.0,
    };
    let mut z = Vec::new();
    let mut nd = Vec::new();
    for j in 0..l.ny {
        for i in 0..l.nx {
            let v = -120.0 + (i as f64 * 0.7).round() - (j as f64 * 1.3).round();
            let island = (i as f64 - 30.0).hypot(j as f64 - 8.0) < 3.0;
            let hole = (5..8).contains(&i) && (20..23).contains(&j);
            z.push(if island { 4.0 } else { v });
            nd.push(hole);
        }
    }
    (l, z, nd)
}

pub fn floor_of(l: &Lattice, z: &[f64], nd: &[bool]) -> Seafloor {
    Seafloor::from_nodes(*l, z.to_vec(), nd.to_vec()).unwrap()
}

pub fn tif(
    dir: &Path,
    name: &str,
    (l, z, nd): (&Lattice, &[f64], &[bool]),
    crs: &Crs,
    sample: SampleType,
    layout: TiffLayout,
) -> PathBuf {
    let p = dir.join(name);
    let opts = GeoTiffOptions {
        sample,
        layout,
        citation: None,
    };
    write_geotiff(&p, l, z, nd, crs, &opts).unwrap();
    p
}

pub fn strips(compression: TiffCompression) -> TiffLayout {
    TiffLayout::Strips {
        rows: 3,
        compression,
    }
}

/// `load` of the part of `path` that `region` asks for, every other option at its default.
pub fn load_region(path: &Path, region: Region) -> Result<LoadedFloor, SeafloorError> {
    load(
        path,
        &LoadOptions {
            region,
            ..LoadOptions::default()
        },
    )
}

/// The lattice of `floor` as a region: what a plan records and `shoal check` reloads.
pub fn nodes_of(floor: &Seafloor) -> Region {
    Region::Nodes {
        x0: floor.x0(),
        y0: floor.y0(),
        nx: floor.nx(),
        ny: floor.ny(),
    }
}

pub fn opts(values: Values) -> LoadOptions {
    LoadOptions {
        values,
        ..LoadOptions::default()
    }
}

/// The `geographic()` grid written as a float32 GeoTIFF (WGS 84, uncompressed strips) named
/// `name` in `dir`.
pub fn geographic_tif(dir: &Path, name: &str) -> PathBuf {
    let (l, z, nd) = geographic();
    tif(
        dir,
        name,
        (&l, &z, &nd),
        &WGS84,
        SampleType::Float32,
        strips(TiffCompression::None),
    )
}

/// A geographic grid: 0.001° nodes around (43.05° N, 5.07° E), values linear in latitude and
/// longitude (so bilinear interpolation is exact in degrees), a NODATA hole and an island.
pub fn geographic() -> (Lattice, Vec<f64>, Vec<bool>) {
    let l = Lattice {
        nx: 141,
        ny: 101,
        x0: 5.0,
        y0: 43.0,
        dx: 0.001,
        dy: 0.001,
    };
    let mut z = Vec::new();
    let mut nd = Vec::new();
    for j in 0..l.ny {
        for i in 0..l.nx {
            let (lon, lat) = (l.x0 + i as f64 * l.dx, l.y0 + j as f64 * l.dy);
            z.push(if (i, j) == (120, 80) {
                3.0
            } else {
                geo_depth(lat, lon)
            });
            nd.push((20..23).contains(&i) && (70..72).contains(&j));
        }
    }
    (l, z, nd)
}

pub fn geo_depth(lat: f64, lon: f64) -> f64 {
    -150.0 + 400.0 * (lat - 43.0) - 300.0 * (lon - 5.0)
}

/// The shoal binary of this build.
pub fn shoal() -> Command {
    Command::new(env!("CARGO_BIN_EXE_shoal"))
}

/// Runs a command: (exit code, stdout, stderr).
pub fn run(cmd: &mut Command) -> (i32, String, String) {
    let out = cmd.output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into(),
        String::from_utf8_lossy(&out.stderr).into(),
    )
}

/// The small scenario the grid-file tests plan: 2 AUVs, K = 5, one window over the grid file
/// `floor`, plus `extra` overrides (`key=value`).
pub fn small(floor: &Path, extra: &[&str]) -> shoal::scenario::Scenario {
    let mut set = vec![
        "team.auvs=2".to_string(),
        "horizon.steps=5".to_string(),
        format!("seafloor.file={:?}", floor.display().to_string()),
    ];
    set.extend(extra.iter().map(|s| s.to_string()));
    shoal::scenario::default_with(&set).expect("valid overrides")
}

/// `shoal plan --set team.auvs=2 --set horizon.steps=5 ARGS… --seafloor FLOOR -o OUT`, the
/// small plan of [`small`] from the command line: (exit code, stdout, stderr).
pub fn plan_small(floor: &Path, out: &Path, args: &[&str]) -> (i32, String, String) {
    run(shoal()
        .args(["plan", "--set", "team.auvs=2", "--set", "horizon.steps=5"])
        .args(args)
        .arg("--seafloor")
        .arg(floor)
        .arg("-o")
        .arg(out))
}

/// The survey grid as a tiled int32 UTM GeoTIFF in `dir`, and [`small`] over it with the speeds
/// its 20–25 m cells suit and a start near its middle (a projected grid's frame is its own
/// coordinates, so the start must be given).
pub fn utm_survey_scenario(dir: &Path) -> shoal::scenario::Scenario {
    let (l, z, nd) = survey();
    let utm = tif(
        dir,
        "utm.tif",
        (&l, &z, &nd),
        &UTM,
        SampleType::Int32,
        TiffLayout::Tiles { size: 16 },
    );
    let (cx, cy) = (l.x0 + 400.0, l.y0 + 375.0);
    let mut s = small(
        &utm,
        // a slow vehicle on a small grid: no cruise floor (a REMUS at 1.25 m/s would not fit
        // its 250 m turn on this 800 m survey)
        &["auv.max_speed=0.5", "auv.min_speed=0", "usv.max_speed=0.3"],
    );
    s.initial = Some(shoal::scenario::Initial {
        usv: [cx, cy],
        auvs: vec![[cx + 40.0, cy, -60.0], [cx, cy + 50.0, -60.0]],
    });
    s
}

/// Plans `s` over its scenario floor as `shoal plan` does; returns the plan and the floor.
pub fn plan_scenario(
    s: &shoal::scenario::Scenario,
) -> Result<(shoal::plan::Plan, Seafloor), shoal::PlanError> {
    let (floor, source) = shoal::mission::scenario_floor(s, Path::new(""))?;
    let p = shoal::Planner::new(s, &floor)
        .provenance(shoal::Provenance {
            scenario_source: "test".into(),
            overrides: vec![],
            seafloor: source,
        })
        .run()?;
    Ok((p, floor))
}

/// [`plan_scenario`], then the independent checker must pass the plan, and must rebuild the
/// same floor from the plan alone.
pub fn plan_and_check(
    s: &shoal::scenario::Scenario,
) -> Result<(shoal::plan::Plan, Seafloor), shoal::PlanError> {
    let (p, floor) = plan_scenario(s)?;
    let report = shoal::check::check_plan(&p, &floor);
    assert!(report.passed(), "plan fails its check:\n{}", report.table());
    let rebuilt = shoal::check::load_floor(&p, None).expect("the checker loads the plan's floor");
    assert_eq!(rebuilt.fingerprint(), floor.fingerprint());
    Ok((p, floor))
}

/// What an interrupted command left: its exit code, its stdout, and its stderr after the line
/// that said it was ready.
#[cfg(unix)]
pub struct Interrupted {
    pub code: Option<i32>,
    pub stdout: String,
    pub stderr: String,
}

/// Starts `cmd`, waits until a line of its stderr satisfies `ready`, waits `delay` more, and
/// sends it SIGINT (Ctrl-C). Panics if the command ends before it is ready.
#[cfg(unix)]
pub fn interrupt_when(
    cmd: &mut Command,
    ready: impl Fn(&str) -> bool,
    delay: std::time::Duration,
) -> Interrupted {
    use std::io::{BufRead, Read};
    use std::process::Stdio;
    let mut child = cmd
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    while !ready(&line) {
        line.clear();
        assert!(
            err.read_line(&mut line).unwrap() > 0,
            "ended before it was ready"
        );
    }
    std::thread::sleep(delay);
    // SAFETY: sending a signal to our own child process
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    // read stderr on its own thread, so that neither pipe can fill and stall the child
    let rest = std::thread::spawn(move || {
        let mut rest = String::new();
        err.read_to_string(&mut rest).unwrap();
        rest
    });
    let out = child.wait_with_output().unwrap();
    Interrupted {
        code: out.status.code(),
        stdout: String::from_utf8_lossy(&out.stdout).into(),
        stderr: rest.join().unwrap(),
    }
}
