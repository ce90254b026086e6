//! The GEBCO-tile-sized grid both load-timing examples write (geotiff_load, gdal_load).

use shoal::seafloor::Lattice;

/// N from the first argument (default 7200, a GEBCO tile).
pub fn size_from_args() -> usize {
    std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(7200)
}

/// N × N smooth elevations (−4500 … −1500 m, no NODATA) and its two lattices: geographic
/// (15 arc-second cells from 10° W, 30° N) and projected (50 m cells, UTM-like).
pub fn grid(n: usize) -> (Vec<f64>, Vec<bool>, Lattice, Lattice) {
    let z: Vec<f64> = (0..n * n)
        .map(|k| {
            let (i, j) = ((k % n) as f64, (k / n) as f64);
            -3000.0 + 1500.0 * (i * 0.003).sin() * (j * 0.002).cos() - 0.1 * i
        })
        .collect();
    let geo = Lattice {
        nx: n,
        ny: n,
        x0: -10.0 + 1.0 / 480.0,
        y0: 30.0 + 1.0 / 480.0,
        dx: 1.0 / 240.0,
        dy: 1.0 / 240.0,
    };
    let utm = Lattice {
        nx: n,
        ny: n,
        x0: 300_025.0,
        y0: 4_500_025.0,
        dx: 50.0,
        dy: 50.0,
    };
    (z, vec![false; n * n], geo, utm)
}
