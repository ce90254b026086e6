//! Load timings for a GEBCO-tile-sized NetCDF grid read through GDAL (BENCHMARKS.md, "Large
//! grids"). Needs the `gdal` feature and gdal-bin's gdal_translate:
//!
//! `cargo run --release --features gdal --example gdal_load [N]` writes an N × N float32 grid
//! (default 7200, about 200 MB) as a GeoTIFF with shoal's writer, converts it with
//! gdal_translate to NetCDF (classic, as GEBCO's global grid; and NetCDF-4 with Deflate), for a
//! geographic grid (15 arc-second cells) and a projected one (50 m cells), then times a full
//! scan (`seafloor info`) and the mission-window load the planner does, against the same
//! window from the GeoTIFF. Not a test: it needs ~1 GB of disk and memory.

mod large_grid;

use shoal::seafloor::{
    info, load, write_geotiff, Crs, GeoTiffOptions, LoadOptions, Region, SampleType,
    TiffCompression, TiffLayout, Values,
};
use std::path::Path;
use std::process::Command;
use std::time::Instant;

fn main() {
    let n = large_grid::size_from_args();
    let dir = tempfile::tempdir().expect("temporary directory");
    let (z, nodata, geo, utm) = large_grid::grid(n);
    let cases = [
        ("geographic", geo, Crs::Geographic { epsg: Some(4326) }),
        (
            "projected",
            utm,
            Crs::Projected {
                epsg: Some(32630),
                citation: None,
            },
        ),
    ];
    let classic: &[&str] = &["-of", "netCDF"];
    let nc4: &[&str] = &[
        "-of",
        "netCDF",
        "-co",
        "FORMAT=NC4",
        "-co",
        "COMPRESS=DEFLATE",
    ];
    println!("grid {n} × {n} float32\n");
    println!("| grid | file | size | info (full scan) | mission window load | window nodes |");
    println!("|---|---|---|---|---|---|");
    for (what, lattice, crs) in cases {
        let tif = dir.path().join(format!("{what}.tif"));
        let opts = GeoTiffOptions {
            sample: SampleType::Float32,
            layout: TiffLayout::Strips {
                rows: 0,
                compression: TiffCompression::None,
            },
            citation: None,
        };
        write_geotiff(&tif, &lattice, &z, &nodata, &crs, &opts).expect("write");
        // The default scenario's mission area: ±8.6 km around the start (the grid centre).
        let (cx, cy) = match crs {
            Crs::Geographic { .. } => (0.0, 0.0),
            _ => (
                0.5 * (lattice.x0 + lattice.x_max()),
                0.5 * (lattice.y0 + lattice.y_max()),
            ),
        };
        let r = 8600.0;
        let area = LoadOptions {
            region: Region::Area {
                x_min: cx - r,
                x_max: cx + r,
                y_min: cy - r,
                y_max: cy + r,
            },
            ..LoadOptions::default()
        };
        let reference = load(&tif, &area).expect("GeoTIFF window").floor;
        let files = [
            ("GeoTIFF (pure Rust)", tif.clone()),
            (
                "NetCDF classic",
                translate(&tif, dir.path(), what, "nc", classic),
            ),
            (
                "NetCDF-4, Deflate",
                translate(&tif, dir.path(), what, "nc4.nc", nc4),
            ),
        ];
        for (kind, path) in files {
            let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0) as f64 / 1e6;
            let t = Instant::now();
            let i = info(&path, Values::Elevation).expect("info");
            let scan = t.elapsed().as_secs_f64();
            assert_eq!(i.data_nodes, n * n);
            let mut times = Vec::new();
            let mut w = None;
            for _ in 0..3 {
                let t = Instant::now();
                w = Some(load(&path, &area).expect("window"));
                times.push(t.elapsed().as_secs_f64() * 1e3);
            }
            let w = w.unwrap().floor;
            assert_eq!(w.lattice().nx, reference.lattice().nx);
            let worst = w
                .nodes()
                .0
                .iter()
                .zip(reference.nodes().0)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-6, "{kind}: the window differs by {worst} m");
            let (lo, hi) = times
                .iter()
                .fold((f64::INFINITY, 0.0f64), |(l, h), &t| (l.min(t), h.max(t)));
            println!(
                "| {what} | {kind} | {size:.0} MB | {scan:.2} s | {lo:.1}–{hi:.1} ms | {} × {} |",
                w.nx(),
                w.ny()
            );
        }
    }
}

/// `gdal_translate -q ARGS tif DIR/WHAT.EXT`.
fn translate(tif: &Path, dir: &Path, what: &str, ext: &str, args: &[&str]) -> std::path::PathBuf {
    let out = dir.join(format!("{what}.{ext}"));
    let t = Instant::now();
    let status = Command::new("gdal_translate")
        .arg("-q")
        .args(args)
        .arg(tif)
        .arg(&out)
        .status()
        .expect("gdal_translate (gdal-bin) on the PATH");
    assert!(status.success(), "gdal_translate {args:?}");
    eprintln!(
        "gdal_translate {} → {}: {:.1} s",
        args.join(" "),
        out.display(),
        t.elapsed().as_secs_f64()
    );
    out
}
