use super::*;
use proptest::prelude::*;

/// nx × ny nodes from (x0, y0) at spacing d, z = f(x, y), NODATA where `hole(i, j)`.
fn grid(
    (nx, ny, x0, y0, d): (usize, usize, f64, f64, f64),
    f: impl Fn(f64, f64) -> f64,
    hole: impl Fn(usize, usize) -> bool,
) -> Seafloor {
    let mut z = Vec::new();
    let mut nd = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            z.push(f(x0 + i as f64 * d, y0 + j as f64 * d));
            nd.push(hole(i, j));
        }
    }
    Seafloor::from_nodes(Lattice::new(nx, ny, x0, y0, d, d), z, nd).unwrap()
}

fn plane(x: f64, y: f64) -> f64 {
    -100.0 + 0.01 * x - 0.02 * y
}

#[test]
fn a_crop_keeps_the_nodes_and_their_values() {
    let f = grid((30, 20, 1000.0, 2000.0, 10.0), plane, |i, j| {
        (i, j) == (12, 7)
    });
    let c = crop_floor(&f, Some([1051.0, 2030.0, 1200.0, 2100.0]), None, "f").unwrap();
    assert_eq!((c.nx(), c.ny(), c.x0(), c.y0()), (15, 8, 1060.0, 2030.0));
    for j in 0..c.ny() {
        for i in 0..c.nx() {
            assert_eq!(c.node(i, j), f.node(i + 6, j + 3));
            assert_eq!(c.is_nodata(i, j), f.is_nodata(i + 6, j + 3));
        }
    }
    // the whole grid is the grid; the same cell on aligned nodes changes nothing
    assert_eq!(crop_floor(&f, None, None, "f").unwrap(), f);
    assert_eq!(crop_floor(&f, None, Some(10.0), "f").unwrap(), f);
}

#[test]
fn resampling_a_plane_is_exact_away_from_obstacles() {
    let f = grid((40, 40, 0.0, 0.0, 10.0), plane, |_, _| false);
    for cell in [3.0, 7.5, 10.0, 25.0] {
        let r = crop_floor(&f, Some([5.0, 5.0, 385.0, 300.0]), Some(cell), "f").unwrap();
        assert_eq!((r.dx(), r.x0() % cell, r.y0() % cell), (cell, 0.0, 0.0));
        for j in 0..r.ny() {
            for i in 0..r.nx() {
                let (x, y) = (r.x0() + i as f64 * cell, r.y0() + j as f64 * cell);
                assert!((r.node(i, j) - plane(x, y)).abs() < 1e-9, "{cell} {i} {j}");
            }
        }
    }
}

#[test]
fn bad_requests_name_the_option() {
    let f = grid((10, 10, 0.0, 0.0, 10.0), plane, |i, _| i < 5);
    let err = |r: Option<[f64; 4]>, c: Option<f64>| crop_floor(&f, r, c, "floor").unwrap_err();
    for (r, c, option, says) in [
        (
            Some([-10.0, 0.0, 50.0, 50.0]),
            None,
            "region",
            "not inside the grid, which covers x from 0 to 90",
        ),
        (
            Some([0.0, 0.0, 95.0, 50.0]),
            None,
            "region",
            "not inside the grid",
        ),
        (Some([50.0, 0.0, 10.0, 50.0]), None, "region", "xmin < xmax"),
        (
            Some([0.0, 0.0, f64::NAN, 50.0]),
            None,
            "region",
            "four finite numbers",
        ),
        (
            Some([11.0, 11.0, 19.0, 50.0]),
            None,
            "region",
            "at least 2 × 2",
        ),
        (
            Some([0.0, 0.0, 50.0, 50.0]),
            Some(0.0),
            "cell",
            "positive number of metres",
        ),
        (
            Some([0.0, 0.0, 50.0, 50.0]),
            Some(60.0),
            "cell",
            "smaller cell",
        ),
        (
            Some([0.0, 0.0, 50.0, 90.0]),
            Some(1e-4),
            "cell",
            "use a larger cell",
        ),
        (
            Some([0.0, 0.0, 30.0, 90.0]),
            None,
            "region",
            "every node of the region is NODATA",
        ),
    ] {
        let e = err(r, c);
        assert!(
            matches!(e, SeafloorError::Crop { option: o, .. } if o == option),
            "{e}"
        );
        let msg = e.to_string();
        assert!(
            msg.starts_with(&format!("floor: --{option}: ")) && msg.contains(says),
            "{msg}"
        );
    }
}

const MAX_N: usize = 25;

fn obstacle_grid() -> impl Strategy<Value = (Seafloor, f64, [f64; 4])> {
    (
        4usize..MAX_N,
        4usize..MAX_N,
        prop::collection::vec(0u8..40, MAX_N * MAX_N),
        0.2f64..4.0,
        (0.0f64..0.3, 0.0f64..0.3, 0.7f64..1.0, 0.7f64..1.0),
    )
        .prop_map(|(nx, ny, kinds, scale, (a, b, c, d))| {
            let dx = 10.0;
            let kind = |i: usize, j: usize| kinds[j * MAX_N + i];
            let mut f = grid(
                (nx, ny, 3.0, -7.0, dx),
                |x, y| -50.0 + 0.1 * x - 0.05 * y,
                |i, j| kind(i, j) == 0,
            );
            // land at kind 1
            let (z, nd) = f.nodes();
            let z: Vec<f64> = z
                .iter()
                .enumerate()
                .map(|(k, &v)| if kind(k % nx, k / nx) == 1 { 2.0 } else { v })
                .collect();
            let mut nd = nd.to_vec();
            nd[0] = false;
            f = Seafloor::from_nodes(Lattice::new(nx, ny, 3.0, -7.0, dx, dx), z, nd).unwrap();
            let e = f.extent();
            let (w, h) = (e.x_max - e.x_min, e.y_max - e.y_min);
            let region = [
                e.x_min + a * w,
                e.y_min + b * h,
                e.x_min + c * w,
                e.y_min + d * h,
            ];
            (f, scale * dx, region)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(500))]

    /// Every point of the resampled grid's extent over a source obstacle cell (NODATA or land)
    /// is over an obstacle cell of the resampled grid too: 7 × 7 points per source cell, its
    /// corners and edges included.
    #[test]
    fn obstacles_never_shrink((f, cell, region) in obstacle_grid()) {
        let Ok(r) = crop_floor(&f, Some(region), Some(cell), "f") else {
            return Ok(()); // a region too small for the cell
        };
        for j in 0..f.ny() - 1 {
            for i in 0..f.nx() - 1 {
                for (u, v) in (0..7).flat_map(|a| (0..7).map(move |b| (a as f64 / 6.0, b as f64 / 6.0))) {
                    let x = f.x0() + (i as f64 + u) * f.dx();
                    let y = f.y0() + (j as f64 + v) * f.dy();
                    if r.contains(x, y) && f.is_obstacle(x, y).unwrap() {
                        prop_assert!(r.is_obstacle(x, y).unwrap(), "({x}, {y}) cell {cell}");
                    }
                }
            }
        }
    }
}
