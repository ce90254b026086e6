//! Unit tests of the grid and its queries (`Seafloor`).

use super::*;
use proptest::prelude::*;

/// A grid from a function of the node position.
fn grid(
    nx: usize,
    ny: usize,
    x0: f64,
    y0: f64,
    dx: f64,
    dy: f64,
    f: impl Fn(f64, f64) -> f64,
) -> Seafloor {
    let l = Lattice::new(nx, ny, x0, y0, dx, dy);
    let z = (0..nx * ny).map(|k| f(l.x(k % nx), l.y(k / nx))).collect();
    Seafloor::from_nodes(l, z, vec![false; nx * ny]).unwrap()
}

fn bumpy() -> Seafloor {
    grid(7, 5, -3.7, 2.1, 0.3, 0.7, |x, y| {
        -50.0 + 3.0 * (x * 1.3).sin() + 2.0 * (y * 2.1).cos() + 0.1 * x * y
    })
}

#[test]
fn exact_at_nodes() {
    let f = bumpy();
    for j in 0..f.ny() {
        for i in 0..f.nx() {
            let (x, y) = (f.x0() + i as f64 * f.dx(), f.y0() + j as f64 * f.dy());
            assert_eq!(f.elevation(x, y).unwrap(), f.node(i, j), "node ({i}, {j})");
            assert_eq!(f.elevation_and_gradient(x, y).unwrap().0, f.node(i, j));
        }
    }
}

#[test]
fn plane_is_reproduced_with_its_slope() {
    let plane = |x: f64, y: f64| -80.0 + 0.013 * x - 0.021 * y;
    let f = grid(6, 4, -10.0, 5.0, 2.5, 4.0, plane);
    let e = f.extent();
    for a in 0..=40 {
        for b in 0..=30 {
            let x = e.x_min + (e.x_max - e.x_min) * a as f64 / 40.0;
            let y = e.y_min + (e.y_max - e.y_min) * b as f64 / 30.0;
            let (z, g) = f.elevation_and_gradient(x, y).unwrap();
            assert!(
                (z - plane(x, y)).abs() < 1e-12,
                "({x}, {y}): {z} vs {}",
                plane(x, y)
            );
            assert!(
                (g[0] - 0.013).abs() < 1e-14 && (g[1] + 0.021).abs() < 1e-14,
                "{g:?}"
            );
            assert_eq!(f.elevation(x, y).unwrap(), z);
        }
    }
}

#[test]
fn cell_edges_belong_to_the_north_east_cell_and_the_border_to_the_last_cell() {
    // z = x² along x, so each cell has its own x-slope: cell i spans [i, i+1], slope 2i+1.
    let f = grid(4, 3, 0.0, 0.0, 1.0, 1.0, |x, _| -10.0 + x * x);
    let gx = |x: f64| f.elevation_and_gradient(x, 1.0).unwrap().1[0];
    assert_eq!(gx(0.0), 1.0);
    assert_eq!(gx(1.0), 3.0); // interior edge: the cell to the east
    assert_eq!(gx(2.0), 5.0);
    assert_eq!(gx(3.0), 5.0); // east border: the last cell
    assert_eq!(gx(1.0 - 1e-12), 3.0); // snapped onto the node line
    assert_eq!(gx(0.999), 1.0);
}

proptest! {
    #[test]
    fn gradient_matches_central_differences(
        nx in 2usize..6, ny in 2usize..6,
        x0 in -1000.0f64..1000.0, y0 in -1000.0f64..1000.0,
        dx in 0.5f64..50.0, dy in 0.5f64..50.0,
        seed in proptest::collection::vec(-500.0f64..0.0, 36),
        ci in 0usize..5, cj in 0usize..5,
        t in 0.05f64..0.95, s in 0.05f64..0.95,
    ) {
        let z = seed[..nx * ny].to_vec();
        let f = Seafloor::from_nodes(Lattice::new(nx, ny, x0, y0, dx, dy), z, vec![false; nx * ny]).unwrap();
        let (i, j) = (ci % (nx - 1), cj % (ny - 1));
        let x = x0 + (i as f64 + t) * dx;
        let y = y0 + (j as f64 + s) * dy;
        let (hx, hy) = (1e-3 * dx, 1e-3 * dy);
        let fd = [
            (f.elevation(x + hx, y).unwrap() - f.elevation(x - hx, y).unwrap()) / (2.0 * hx),
            (f.elevation(x, y + hy).unwrap() - f.elevation(x, y - hy).unwrap()) / (2.0 * hy),
        ];
        let (_, g) = f.elevation_and_gradient(x, y).unwrap();
        for d in 0..2 {
            prop_assert!((g[d] - fd[d]).abs() <= 1e-6 * (1.0 + g[d].abs()), "{g:?} vs {fd:?}");
        }
    }
}

#[test]
fn outside_and_non_finite_queries_are_errors() {
    let f = bumpy();
    let e = f.extent();
    for (x, y) in [
        (e.x_max + 1e-9, e.y_min),
        (e.x_min, e.y_min - 1.0),
        (1e300, 3.0),
    ] {
        let err = f.elevation(x, y).unwrap_err();
        assert!(matches!(err, SeafloorError::OutsideGrid { .. }), "{err}");
        assert!(
            err.to_string()
                .contains(&format!("x from {} to {}", e.x_min, e.x_max)),
            "{err}"
        );
        assert!(matches!(
            f.elevation_and_gradient(x, y),
            Err(SeafloorError::OutsideGrid { .. })
        ));
        assert!(matches!(
            f.is_obstacle(x, y),
            Err(SeafloorError::OutsideGrid { .. })
        ));
        assert!(!f.contains(x, y));
    }
    for (x, y) in [
        (f64::NAN, 3.0),
        (-3.0, f64::NAN),
        (f64::INFINITY, 3.0),
        (-3.0, f64::NEG_INFINITY),
    ] {
        assert!(matches!(
            f.elevation(x, y),
            Err(SeafloorError::NonFinite { .. })
        ));
        assert!(matches!(
            f.elevation_and_gradient(x, y),
            Err(SeafloorError::NonFinite { .. })
        ));
        assert!(matches!(
            f.is_obstacle(x, y),
            Err(SeafloorError::NonFinite { .. })
        ));
        assert!(!f.contains(x, y));
    }
    let (a, b) = ([-3.0, 3.0, -60.0], [-2.0, 4.0, -60.0]);
    assert!(matches!(
        f.segment_clearance([f64::NAN, 3.0, -60.0], b, 1.0),
        Err(SeafloorError::NonFinite { .. })
    ));
    assert!(matches!(
        f.segment_clearance(a, [-2.0, 4.0, f64::NAN], 1.0),
        Err(SeafloorError::NonFinite { .. })
    ));
    assert!(matches!(
        f.segment_clearance(a, [-20.0, 4.0, -60.0], 1.0),
        Err(SeafloorError::OutsideGrid { .. })
    ));
    assert!(matches!(
        f.segment_clearance(a, b, f64::NAN),
        Err(SeafloorError::NonFinite { .. })
    ));
    assert!(matches!(
        f.segment_clearance(a, b, 0.0),
        Err(SeafloorError::InvalidQuery { .. })
    ));
    assert!(matches!(
        f.segment_clearance(a, b, -1.0),
        Err(SeafloorError::InvalidQuery { .. })
    ));
    assert!(matches!(
        f.segment_clearance(a, b, 1e-300),
        Err(SeafloorError::InvalidQuery { .. })
    ));
}

#[test]
fn nodata_and_land_are_obstacles() {
    // 4 × 3 nodes; node (3, 2) is NODATA, node (0, 0) is land.
    let mut z = vec![-30.0; 12];
    z[0] = 0.0;
    z[11] = f64::NAN; // ignored at a NODATA node
    let mut nodata = vec![false; 12];
    nodata[11] = true;
    let f = Seafloor::from_nodes(Lattice::new(4, 3, 0.0, 0.0, 10.0, 10.0), z, nodata).unwrap();
    assert_eq!(f.node(3, 2), 0.0);
    assert!(f.is_nodata(3, 2) && !f.is_nodata(2, 2));
    assert_eq!(f.z_range(), (-30.0, 0.0));
    assert!(f.is_obstacle(5.0, 5.0).unwrap()); // cell (0, 0) touches land
    assert!(f.is_obstacle(25.0, 15.0).unwrap()); // cell (2, 1) touches NODATA
    assert!(f.is_obstacle(30.0, 20.0).unwrap()); // the NODATA node itself
    assert!(!f.is_obstacle(15.0, 5.0).unwrap());
    assert!(!f.is_obstacle(15.0, 15.0).unwrap());
    // Over NODATA the field rises to the surface, finitely and continuously.
    assert_eq!(f.elevation(30.0, 20.0).unwrap(), 0.0);
    assert_eq!(f.elevation(25.0, 15.0).unwrap(), -30.0 * 0.75);
    let c = f
        .segment_clearance([15.0, 15.0, -5.0], [30.0, 20.0, -5.0], 1.0)
        .unwrap();
    assert_eq!((c.min_clearance, c.fraction), (-5.0, 1.0));
}

#[test]
fn z_range_ignores_nodata() {
    let f = Seafloor::from_nodes(
        Lattice::new(2, 2, 0.0, 0.0, 1.0, 1.0),
        vec![-5.0, -7.0, 99.0, -6.0],
        vec![false, false, true, false],
    )
    .unwrap();
    assert_eq!(f.z_range(), (-7.0, -5.0));
}

#[test]
fn from_nodes_rejects_bad_grids() {
    let ok = |nx: usize, ny: usize| (vec![-1.0; nx * ny], vec![false; nx * ny]);
    let (z, m) = ok(2, 2);
    let unit = Lattice::new(2, 2, 0.0, 0.0, 1.0, 1.0);
    let build = |l: Lattice, z: &[f64], m: &[bool]| Seafloor::from_nodes(l, z.to_vec(), m.to_vec());
    let cases: Vec<(&str, Result<Seafloor, SeafloorError>)> = vec![
        (
            "nx = 1",
            build(
                Lattice::new(1, 2, 0.0, 0.0, 1.0, 1.0),
                &[-1.0; 2],
                &[false; 2],
            ),
        ),
        (
            "ny = 0",
            build(Lattice::new(2, 0, 0.0, 0.0, 1.0, 1.0), &[], &[]),
        ),
        (
            "nx = 50001",
            build(Lattice::new(50_001, 2, 0.0, 0.0, 1.0, 1.0), &[], &[]),
        ),
        (
            "x0 = NaN",
            build(Lattice::new(2, 2, f64::NAN, 0.0, 1.0, 1.0), &z, &m),
        ),
        (
            "dx = 0",
            build(Lattice::new(2, 2, 0.0, 0.0, 0.0, 1.0), &z, &m),
        ),
        (
            "dy = -1",
            build(Lattice::new(2, 2, 0.0, 0.0, 1.0, -1.0), &z, &m),
        ),
        (
            "dx = inf",
            build(Lattice::new(2, 2, 0.0, 0.0, f64::INFINITY, 1.0), &z, &m),
        ),
        (
            "far corner",
            build(Lattice::new(2, 2, 1.7e308, 0.0, 1e308, 1.0), &z, &m),
        ),
        ("3 elevations", build(unit, &[-1.0; 3], &m)),
        ("5 NODATA flags", build(unit, &z, &[false; 5])),
        (
            "elevation NaN",
            build(unit, &[-1.0, f64::NAN, -1.0, -1.0], &m),
        ),
        (
            "elevation -60000",
            build(unit, &[-1.0, -6e4, -1.0, -1.0], &m),
        ),
        ("every node is NODATA", build(unit, &z, &[true; 4])),
    ];
    for (name, r) in cases {
        let err = r.expect_err(name);
        assert!(
            matches!(err, SeafloorError::InvalidGrid(_)),
            "{name}: {err}"
        );
    }
    assert!(Seafloor::from_nodes(unit, z, m).is_ok());
}

#[test]
fn segment_clearance_is_the_minimum_over_its_samples() {
    let f = bumpy();
    let cases = [
        ([-3.6, 2.2, -49.0], [-2.0, 4.8, -47.0], 0.05),
        ([-2.0, 4.8, -47.0], [-3.6, 2.2, -49.0], 0.3),
        ([-3.7, 2.1, -45.0], [-1.95, 4.9, -55.0], 0.01),
        ([-3.0, 3.0, -45.0], [-3.0, 3.0, -52.0], 1.0), // vertical: n = 1
        ([-3.0, 3.0, -45.0], [-2.99, 3.0, -52.0], 100.0), // shorter than r: n = 1
    ];
    for (a, b, r) in cases {
        let got = f.segment_clearance(a, b, r).unwrap();
        let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
        let n = ((len / r).ceil() as usize).max(1);
        let (mut min, mut at_k) = (f64::INFINITY, 0);
        for k in 0..=n {
            let u = k as f64 / n as f64;
            let p: Vec<f64> = (0..3).map(|d| a[d] + u * (b[d] - a[d])).collect();
            let c = p[2] - f.elevation(p[0], p[1]).unwrap();
            if c < min {
                (min, at_k) = (c, k);
            }
        }
        assert!((got.min_clearance - min).abs() < 1e-12, "{got:?} vs {min}");
        assert_eq!(got.fraction, at_k as f64 / n as f64);
        let floor = f.elevation(got.at[0], got.at[1]).unwrap();
        assert_eq!(got.at[2] - floor, got.min_clearance);
    }
}

#[test]
fn segment_over_a_seamount_reports_its_peak() {
    // A Gaussian seamount peaking at -20 m on node (10, 10) of a -100 m floor.
    let f = grid(21, 21, 0.0, 0.0, 10.0, 10.0, |x, y| {
        -100.0
            + 80.0 * (-((x - 100.0).powi(2) + (y - 100.0).powi(2)) / (2.0 * 30.0f64.powi(2))).exp()
    });
    let c = f
        .segment_clearance([0.0, 100.0, -15.0], [200.0, 100.0, -15.0], 1.0)
        .unwrap();
    assert_eq!(c.at, [100.0, 100.0, -15.0]);
    assert_eq!(c.min_clearance, 5.0);
    assert_eq!(c.fraction, 0.5);
    let low = f
        .segment_clearance([0.0, 100.0, -30.0], [200.0, 100.0, -30.0], 1.0)
        .unwrap();
    assert_eq!(low.min_clearance, -10.0); // the segment cuts through the peak
}

#[test]
fn the_open_segment_leaves_out_its_start() {
    // flat floor at -100 m; a segment from 2 m below the floor up to 10 m above it, 1 m long
    let f = grid(3, 3, 0.0, 0.0, 10.0, 10.0, |_, _| -100.0);
    let (a, b) = ([5.0, 5.0, -102.0], [6.0, 5.0, -90.0]);
    let closed = f.segment_clearance(a, b, 1.0).unwrap();
    assert_eq!((closed.min_clearance, closed.fraction), (-2.0, 0.0));
    let open = f.open_segment_clearance(a, b, 1.0).unwrap();
    assert_eq!((open.min_clearance, open.fraction, open.at), (10.0, 1.0, b));
    // with more samples the first one after a is the worst
    let open = f.open_segment_clearance(a, b, 0.5).unwrap();
    assert_eq!((open.min_clearance, open.fraction), (4.0, 0.5));
}

#[test]
fn fingerprint_sees_every_bit() {
    let f = bumpy();
    let fp = f.fingerprint();
    assert_eq!(fp.len(), 64);
    assert!(fp
        .chars()
        .all(|c| c.is_ascii_hexdigit() && !c.is_ascii_uppercase()));
    assert_eq!(fp, f.clone().fingerprint());
    let rebuild = |k: usize, dz: f64, masked: bool| {
        let mut z = f.z.clone();
        let mut m = f.nodata.clone();
        z[k] = f64::from_bits(z[k].to_bits() + dz as u64);
        m[k] = masked;
        Seafloor::from_nodes(f.lattice, z, m).unwrap().fingerprint()
    };
    assert_eq!(rebuild(3, 0.0, false), fp);
    assert_ne!(rebuild(3, 1.0, false), fp); // one ulp
    assert_ne!(rebuild(3, 0.0, true), fp);
    let shifted = Seafloor::from_nodes(
        Lattice {
            y0: f.lattice.y0 + 1e-9,
            ..f.lattice
        },
        f.z.clone(),
        f.nodata.clone(),
    )
    .unwrap();
    assert_ne!(shifted.fingerprint(), fp);
}

#[test]
fn raster_samples_outside_the_elevation_bound_name_their_place_and_the_nodata_marker() {
    assert_eq!(super::raster_elevation(-100.0, 0, 0, "x"), Ok(-100.0));
    assert_eq!(
        super::raster_elevation(-MAX_ABS_ELEVATION, 0, 0, "x"),
        Ok(-MAX_ABS_ELEVATION)
    );
    let e = super::raster_elevation(-99999.0, 2, 4, "GDAL_NODATA is -9999").unwrap_err();
    assert_eq!(
        e,
        "row 3, column 5 (from the top-left): value -99999: expected an elevation in metres \
         within ±50000 or NODATA (GDAL_NODATA is -9999)"
    );
    assert!(super::raster_elevation(f64::NAN, 0, 0, "x").is_err());
    assert!(super::raster_elevation(f64::INFINITY, 0, 0, "x").is_err());
}
