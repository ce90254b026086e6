//! Load and query timings for a GEBCO-tile-sized GeoTIFF (BENCHMARKS.md, "Large grids").
//!
//! `cargo run --release --example geotiff_load [N]` writes an N × N float32 grid (default 7200,
//! about 200 MB) in a temporary directory, as a geographic grid (15 arc-second cells, like a
//! GEBCO tile) and as a projected one (50 m cells), stripped and tiled, then times a full scan
//! (`seafloor info`), the mission-window loads the planner does, a whole-grid load, and depth
//! queries. Not a test: it needs ~1 GB of disk and memory. SHOAL_DROP_CACHES=1 (as root)
//! empties the page cache before each read, for cold-cache timings.

mod large_grid;

use shoal::seafloor::{
    info, load, write_geotiff, Crs, GeoTiffOptions, LoadOptions, Region, SampleType,
    TiffCompression, TiffLayout, Values,
};
use std::time::Instant;

fn main() {
    let n = large_grid::size_from_args();
    let dir = tempfile::tempdir().expect("temporary directory");
    let (z, nodata, geo, utm) = large_grid::grid(n);
    let strips = TiffLayout::Strips {
        rows: 0,
        compression: TiffCompression::None,
    };
    let tiles = TiffLayout::Tiles { size: 256 };
    let cases = [
        (
            "geographic, strips",
            geo,
            Crs::Geographic { epsg: Some(4326) },
            strips,
        ),
        (
            "geographic, tiles 256",
            geo,
            Crs::Geographic { epsg: Some(4326) },
            tiles,
        ),
        (
            "projected, strips",
            utm,
            Crs::Projected {
                epsg: Some(32630),
                citation: None,
            },
            strips,
        ),
        (
            "projected, tiles 256",
            utm,
            Crs::Projected {
                epsg: Some(32630),
                citation: None,
            },
            tiles,
        ),
    ];
    println!("grid {n} × {n} float32\n");
    println!("| file | size | write | info (full scan) | mission window load | window nodes | whole-grid load |");
    println!("|---|---|---|---|---|---|---|");
    for (k, (what, lattice, crs, layout)) in cases.into_iter().enumerate() {
        let path = dir.path().join(format!("grid{k}.tif"));
        let opts = GeoTiffOptions {
            sample: SampleType::Float32,
            layout,
            citation: None,
        };
        let t = Instant::now();
        write_geotiff(&path, &lattice, &z, &nodata, &crs, &opts).expect("write");
        let write = t.elapsed().as_secs_f64();
        let size = std::fs::metadata(&path).map(|m| m.len()).unwrap_or(0) as f64 / 1e6;
        cold();
        let t = Instant::now();
        let i = info(&path, Values::Elevation).expect("info");
        let scan = t.elapsed().as_secs_f64();
        assert_eq!(i.data_nodes, n * n);
        // The default scenario's mission area: ±8.6 km around the start (the grid centre for
        // the geographic grid, the grid's centre coordinates for the projected one).
        let (cx, cy) = match crs {
            Crs::Geographic { .. } => (0.0, 0.0),
            _ => (
                0.5 * (lattice.x0 + lattice.x_max()),
                0.5 * (lattice.y0 + lattice.y_max()),
            ),
        };
        let r = 8600.0;
        let area = Region::Area {
            x_min: cx - r,
            x_max: cx + r,
            y_min: cy - r,
            y_max: cy + r,
        };
        cold();
        let t = Instant::now();
        let w = load(
            &path,
            &LoadOptions {
                region: area,
                ..LoadOptions::default()
            },
        )
        .expect("window");
        let window = t.elapsed().as_secs_f64();
        if k == 0 {
            queries("mission window (geographic, resampled)", &w.floor);
        }
        let whole = match crs {
            Crs::Geographic { .. } => "refused (beyond 250 km)".to_string(),
            _ => {
                cold();
                let t = Instant::now();
                let all = load(&path, &LoadOptions::default()).expect("whole");
                let s = t.elapsed().as_secs_f64();
                assert_eq!(all.floor.nx(), n);
                if k == 2 {
                    queries("whole projected grid", &all.floor);
                }
                format!("{s:.2} s")
            }
        };
        println!(
            "| {what} | {size:.0} MB | {write:.2} s | {scan:.2} s | {:.1} ms | {} × {} | {whole} |",
            window * 1e3,
            w.floor.nx(),
            w.floor.ny()
        );
    }
}

/// With SHOAL_DROP_CACHES=1 (as root), empties the page cache so that the next read comes
/// from disk (`sync; echo 3 > /proc/sys/vm/drop_caches`); otherwise the file is in the page
/// cache, having just been written.
fn cold() {
    if std::env::var("SHOAL_DROP_CACHES").is_ok_and(|v| v == "1") {
        let _ = std::process::Command::new("sync").status();
        let _ = std::fs::write("/proc/sys/vm/drop_caches", "3");
    }
}

/// Times bilinear depth queries on a loaded floor.
fn queries(what: &str, f: &shoal::seafloor::Seafloor) {
    let e = f.extent();
    let m = 1_000_000;
    let t = Instant::now();
    let mut acc = 0.0;
    for k in 0..m {
        let u = (k as f64 * 0.618_033_988_75).fract();
        let v = (k as f64 * 0.754_877_666_2).fract();
        let x = e.x_min + u * (e.x_max - e.x_min);
        let y = e.y_min + v * (e.y_max - e.y_min);
        acc += f
            .elevation_and_gradient(x, y)
            .map(|(z, _)| z)
            .unwrap_or(0.0);
    }
    let s = t.elapsed().as_secs_f64();
    eprintln!(
        "depth query (elevation and gradient at random points) on the {what} ({} × {}): {:.0} ns each ({m} queries, checksum {acc:.3e})",
        f.nx(),
        f.ny(),
        s / m as f64 * 1e9
    );
}
