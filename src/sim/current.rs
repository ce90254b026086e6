//! The ocean current of `[current]`: horizontal, constant in time, scaled by an optional depth
//! profile; either uniform at each depth (`velocity`) or varying in x and y, read from two grid
//! files of its east and north components (`file_east`, `file_north`, which then replace
//! `velocity`), interpolated bilinearly.

use crate::plan::Plan;
use crate::scenario::{profile_factor, profile_slope, Current};
use crate::seafloor::{self, Crs, Lattice, LoadOptions, Seafloor, SeafloorError};
use std::path::Path;
use thiserror::Error;

/// Largest current speed a grid may hold inside the mission, m/s (as `current.velocity`'s).
pub const MAX_CURRENT_SPEED: f64 = 3.0;

/// Margin around the plan's positions that the current's grids must cover, metres.
pub const CURRENT_MARGIN: f64 = 200.0;

/// Why the current's grid files could not be used. Every message names the key and the file.
#[derive(Debug, Error)]
pub enum CurrentError {
    /// The file could not be read as a grid.
    #[error("{key} = {path:?}: {source}")]
    Read {
        /// `current.file_east` or `current.file_north`.
        key: &'static str,
        /// The file, as resolved.
        path: String,
        /// Why.
        source: Box<SeafloorError>,
    },
    /// The file is a geographic grid (degrees), not in the planner's metric frame.
    #[error(
        "{key} = {path:?}: the grid's CRS is {crs} (degrees); the current's grids must be in \
         the planner's frame, in metres (a projected grid, or one without a CRS)"
    )]
    Geographic {
        /// `current.file_east` or `current.file_north`.
        key: &'static str,
        /// The file, as resolved.
        path: String,
        /// The grid's CRS.
        crs: String,
    },
    /// The two files are not on the same lattice of nodes.
    #[error(
        "current.file_east = {east:?} and current.file_north = {north:?} must be grids of the \
         same nodes, but the first has {} × {} nodes from ({}, {}) every ({}, {}) m and the \
         second {} × {} nodes from ({}, {}) every ({}, {}) m",
        lattices[0].nx, lattices[0].ny, lattices[0].x0, lattices[0].y0, lattices[0].dx,
        lattices[0].dy, lattices[1].nx, lattices[1].ny, lattices[1].x0, lattices[1].y0,
        lattices[1].dx, lattices[1].dy
    )]
    Lattices {
        /// The east component's file.
        east: String,
        /// The north component's file.
        north: String,
        /// The east grid's lattice, then the north grid's.
        lattices: Box<[Lattice; 2]>,
    },
    /// A grid does not cover the mission (with its margin).
    #[error(
        "{key} = {path:?} covers x from {} to {} m and y from {} to {} m, but the mission (the \
         plan's positions and a {CURRENT_MARGIN} m margin) spans x from {:.1} to {:.1} m and y \
         from {:.1} to {:.1} m",
        extent.x_min, extent.x_max, extent.y_min, extent.y_max,
        bounds[0], bounds[1], bounds[2], bounds[3]
    )]
    Coverage {
        /// `current.file_east` or `current.file_north`.
        key: &'static str,
        /// The file, as resolved.
        path: String,
        /// The grid's node extent.
        extent: seafloor::Extent,
        /// [x_min, x_max, y_min, y_max] of the mission, metres.
        bounds: [f64; 4],
    },
    /// A grid has a NODATA node in a cell the mission reaches.
    #[error(
        "{key} = {path:?}: node ({x}, {y}) is NODATA, inside the mission (x from {:.1} to {:.1} \
         m, y from {:.1} to {:.1} m); the current must be known everywhere there",
        bounds[0], bounds[1], bounds[2], bounds[3]
    )]
    Nodata {
        /// `current.file_east` or `current.file_north`.
        key: &'static str,
        /// The file, as resolved.
        path: String,
        /// The node's x, metres.
        x: f64,
        /// The node's y, metres.
        y: f64,
        /// [x_min, x_max, y_min, y_max] of the mission, metres.
        bounds: [f64; 4],
    },
    /// A node inside the mission has a speed above [`MAX_CURRENT_SPEED`].
    #[error(
        "current.file_east = {east:?} and current.file_north = {north:?}: at node ({x}, {y}) \
         the current is [{u}, {v}] m/s, a speed above {MAX_CURRENT_SPEED} m/s (are the values \
         in m/s?)"
    )]
    Speed {
        /// The east component's file.
        east: String,
        /// The north component's file.
        north: String,
        /// The node's x, metres.
        x: f64,
        /// The node's y, metres.
        y: f64,
        /// East component there, m/s.
        u: f64,
        /// North component there, m/s.
        v: f64,
    },
    /// Only one of the two files is given.
    #[error(
        "{given} = {path:?} needs {missing} too: the current's grid files come as a pair (its \
         east and north components), both or neither"
    )]
    Pair {
        /// The key given.
        given: &'static str,
        /// Its value.
        path: String,
        /// The key missing.
        missing: &'static str,
    },
    /// The bounds are not a finite, ordered rectangle.
    #[error("the mission's bounds {0:?} are not a finite rectangle")]
    Bounds([f64; 4]),
}

/// The current as a field over the water column.
#[derive(Debug, Clone, PartialEq)]
pub struct CurrentField {
    velocity: [f64; 2],
    profile: Vec<[f64; 2]>,
    /// The east and north components' grids, on one lattice, when given.
    grids: Option<Box<(Seafloor, Seafloor)>>,
}

impl CurrentField {
    /// The field of a scenario's `[current]`, uniform at each depth (`velocity`; the grid
    /// files, if any, are ignored: see [`CurrentField::load`]).
    pub fn new(c: &Current) -> CurrentField {
        CurrentField {
            velocity: c.velocity,
            profile: c.profile.clone(),
            grids: None,
        }
    }

    /// The field of a scenario's `[current]` with its grid files, if it names them
    /// (`file_east` and `file_north`, relative paths from `base_dir`), which then replace
    /// `velocity`. The grids must be on one lattice, in metres, and cover `bounds` =
    /// [x_min, x_max, y_min, y_max] (the mission, see [`mission_bounds`]) with no NODATA node
    /// and no speed above [`MAX_CURRENT_SPEED`] in the cells that meet it. Without the files,
    /// the same as [`CurrentField::new`]. Only one of the two files is an error too.
    pub fn load(
        c: &Current,
        base_dir: &Path,
        bounds: [f64; 4],
    ) -> Result<CurrentField, CurrentError> {
        let (east, north) = match (&c.file_east, &c.file_north) {
            (None, None) => return Ok(CurrentField::new(c)),
            (Some(e), Some(n)) => (base_dir.join(e), base_dir.join(n)),
            (Some(f), None) => return Err(pair("current.file_east", f, "current.file_north")),
            (None, Some(f)) => return Err(pair("current.file_north", f, "current.file_east")),
        };
        let [x_min, x_max, y_min, y_max] = bounds;
        if !(bounds.iter().all(|b| b.is_finite()) && x_min <= x_max && y_min <= y_max) {
            return Err(CurrentError::Bounds(bounds));
        }
        let u = read_grid("current.file_east", &east, bounds)?;
        let v = read_grid("current.file_north", &north, bounds)?;
        let (lu, lv) = (u.lattice(), v.lattice());
        if !same_lattice(&lu, &lv) {
            return Err(CurrentError::Lattices {
                east: east.display().to_string(),
                north: north.display().to_string(),
                lattices: Box::new([lu, lv]),
            });
        }
        let (i0, i1, j0, j1) = nodes_meeting(&lu, bounds);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let (x, y) = (lu.x0 + i as f64 * lu.dx, lu.y0 + j as f64 * lu.dy);
                let (a, b) = (u.node(i, j), v.node(i, j));
                if a.hypot(b) > MAX_CURRENT_SPEED {
                    return Err(CurrentError::Speed {
                        east: east.display().to_string(),
                        north: north.display().to_string(),
                        x,
                        y,
                        u: a,
                        v: b,
                    });
                }
            }
        }
        Ok(CurrentField {
            velocity: c.velocity,
            profile: c.profile.clone(),
            grids: Some(Box::new((u, v))),
        })
    }

    /// Still water.
    pub fn still() -> CurrentField {
        CurrentField {
            velocity: [0.0; 2],
            profile: Vec::new(),
            grids: None,
        }
    }

    /// Whether the field comes from grid files.
    pub fn is_gridded(&self) -> bool {
        self.grids.is_some()
    }

    /// The current's velocity at `p` = [x, y, z] (m, z up), m/s in shoal's frame (x east,
    /// y north, z up; the vertical component is 0). From grids, the bilinear value at (x, y)
    /// (beyond the grids, which cover the mission and its margin, the value at the nearest
    /// point of their extent; 0 at a non-finite position).
    pub fn at(&self, p: [f64; 3]) -> [f64; 3] {
        let f = profile_factor(&self.profile, (-p[2]).max(0.0));
        let [u, v] = match &self.grids {
            None => self.velocity,
            Some(g) => {
                let e = g.0.extent();
                let (x, y) = (p[0].clamp(e.x_min, e.x_max), p[1].clamp(e.y_min, e.y_max));
                [
                    g.0.elevation(x, y).unwrap_or(0.0),
                    g.1.elevation(x, y).unwrap_or(0.0),
                ]
            }
        };
        [f * u, f * v, 0.0]
    }
}

impl CurrentField {
    /// Whether the field changes with position (a depth profile of two or more pairs, or
    /// grids): the planner then linearises it about its reference.
    pub fn varies(&self) -> bool {
        self.grids.is_some() || self.profile.len() >= 2
    }

    /// The current at `p` and its Jacobian J\[i\]\[j\] = ∂c_i/∂p_j (1/s): the depth profile's
    /// slope times the surface value on z (z = −depth; none above the surface), the grids'
    /// bilinear gradient times the profile's factor on x and y (none beyond the grids'
    /// extent, where the value is held). Piecewise linear in z and bilinear in (x, y): the
    /// Jacobian is that of the piece holding `p`.
    pub fn at_and_jacobian(&self, p: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
        let d = (-p[2]).max(0.0);
        let f = profile_factor(&self.profile, d);
        let df_dz = if p[2] < 0.0 {
            -profile_slope(&self.profile, d)
        } else {
            0.0
        };
        let ([u, v], [gu, gv]) = match &self.grids {
            None => (self.velocity, [[0.0; 2]; 2]),
            Some(g) => {
                let e = g.0.extent();
                let inside =
                    (e.x_min..=e.x_max).contains(&p[0]) && (e.y_min..=e.y_max).contains(&p[1]);
                let (x, y) = (p[0].clamp(e.x_min, e.x_max), p[1].clamp(e.y_min, e.y_max));
                let (u, gu) = g.0.elevation_and_gradient(x, y).unwrap_or((0.0, [0.0; 2]));
                let (v, gv) = g.1.elevation_and_gradient(x, y).unwrap_or((0.0, [0.0; 2]));
                let (gu, gv) = if inside {
                    (gu, gv)
                } else {
                    ([0.0; 2], [0.0; 2])
                };
                ([u, v], [gu, gv])
            }
        };
        (
            [f * u, f * v, 0.0],
            [
                [f * gu[0], f * gu[1], u * df_dz],
                [f * gv[0], f * gv[1], v * df_dz],
                [0.0; 3],
            ],
        )
    }
}

/// The current the MPC planner plans in, for a scenario's `[current]`: its `velocity` and
/// `profile`, what `shoal simulate` flies by default. The grid files (`file_east`,
/// `file_north`), read relative to a plan file's directory, are not planned for: with them
/// the planner plans in still water, as before it knew the current, and says so in the plan's
/// warnings.
pub fn planned(c: &Current) -> Current {
    if c.file_east.is_some() || c.file_north.is_some() {
        Current {
            velocity: [0.0; 2],
            profile: Vec::new(),
            file_east: None,
            file_north: None,
        }
    } else {
        c.clone()
    }
}

/// Still water as a `[current]` (what plans that do not model the current record).
pub fn still() -> Current {
    Current {
        velocity: [0.0; 2],
        profile: Vec::new(),
        file_east: None,
        file_north: None,
    }
}

/// The bounding box [x_min, x_max, y_min, y_max] of every position of `plan` (each window's
/// final and Step 1 paths, the AUVs' and the USV's, and the initial state), widened by
/// `margin` metres.
pub fn mission_bounds(plan: &Plan, margin: f64) -> [f64; 4] {
    let initial = std::iter::once(plan.initial.usv).chain(
        plan.initial
            .auvs
            .iter()
            .map(|a| [a.position[0], a.position[1]]),
    );
    match crate::plan::bbox(initial.chain(plan.positions())) {
        Some(b) => [b[0] - margin, b[1] + margin, b[2] - margin, b[3] + margin],
        None => [f64::NAN; 4],
    }
}

fn pair(given: &'static str, path: &str, missing: &'static str) -> CurrentError {
    CurrentError::Pair {
        given,
        path: path.to_string(),
        missing,
    }
}

/// A grid file's raw node values (the seafloor's readers, as elevations: no sign flip), in the
/// planner's frame, checked to cover `bounds` with no NODATA node in a cell that meets them.
fn read_grid(key: &'static str, path: &Path, bounds: [f64; 4]) -> Result<Seafloor, CurrentError> {
    let name = path.display().to_string();
    let loaded =
        seafloor::load(path, &LoadOptions::default()).map_err(|source| CurrentError::Read {
            key,
            path: name.clone(),
            source: Box::new(source),
        })?;
    if let Crs::Geographic { .. } = loaded.crs {
        return Err(CurrentError::Geographic {
            key,
            path: name,
            crs: loaded.crs.to_string(),
        });
    }
    let g = loaded.floor;
    let e = g.extent();
    if !(e.x_min <= bounds[0]
        && bounds[1] <= e.x_max
        && e.y_min <= bounds[2]
        && bounds[3] <= e.y_max)
    {
        return Err(CurrentError::Coverage {
            key,
            path: name,
            extent: e,
            bounds,
        });
    }
    let l = g.lattice();
    let (i0, i1, j0, j1) = nodes_meeting(&l, bounds);
    for j in j0..=j1 {
        for i in i0..=i1 {
            if g.is_nodata(i, j) {
                return Err(CurrentError::Nodata {
                    key,
                    path: name,
                    x: l.x0 + i as f64 * l.dx,
                    y: l.y0 + j as f64 * l.dy,
                    bounds,
                });
            }
        }
    }
    Ok(g)
}

/// The node index ranges (i0, i1, j0, j1), inclusive, of the cells that meet `bounds` (which
/// the lattice covers).
fn nodes_meeting(l: &Lattice, bounds: [f64; 4]) -> (usize, usize, usize, usize) {
    let axis = |lo: f64, hi: f64, o: f64, d: f64, n: usize| {
        let a = ((lo - o) / d).floor().max(0.0) as usize;
        let b = ((hi - o) / d).ceil().max(0.0) as usize;
        (a.min(n - 1), b.min(n - 1))
    };
    let (i0, i1) = axis(bounds[0], bounds[1], l.x0, l.dx, l.nx);
    let (j0, j1) = axis(bounds[2], bounds[3], l.y0, l.dy, l.ny);
    (i0, i1, j0, j1)
}

/// Whether two lattices have the same nodes (to a millionth of a cell).
fn same_lattice(a: &Lattice, b: &Lattice) -> bool {
    let close = |p: f64, q: f64, d: f64| (p - q).abs() <= 1e-6 * d;
    a.nx == b.nx
        && a.ny == b.ny
        && close(a.dx, b.dx, a.dx)
        && close(a.dy, b.dy, a.dy)
        && close(a.x0, b.x0, a.dx)
        && close(a.y0, b.y0, a.dy)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A field of grids u = a + b·x + c·y on 3 × 3 nodes every 100 m from (0, 0).
    fn linear(u: [f64; 3], v: [f64; 3], profile: Vec<[f64; 2]>) -> CurrentField {
        let l = Lattice {
            nx: 3,
            ny: 3,
            x0: 0.0,
            y0: 0.0,
            dx: 100.0,
            dy: 100.0,
        };
        let grid = |c: [f64; 3]| {
            let z = (0..9)
                .map(|k| c[0] + c[1] * (k % 3) as f64 * 100.0 + c[2] * (k / 3) as f64 * 100.0)
                .collect();
            Seafloor::from_nodes(l, z, vec![false; 9]).unwrap()
        };
        CurrentField {
            velocity: [9.0, 9.0],
            profile,
            grids: Some(Box::new((grid(u), grid(v)))),
        }
    }

    #[test]
    fn grids_are_sampled_bilinearly_and_replace_the_velocity() {
        let f = linear([0.1, 1e-3, 0.0], [-0.2, 0.0, 2e-3], Vec::new());
        let w = f.at([150.0, 50.0, -10.0]);
        assert!((w[0] - 0.25).abs() < 1e-12, "{w:?}");
        assert!((w[1] - -0.1).abs() < 1e-12, "{w:?}");
        assert_eq!(w[2], 0.0);
        // nodes exactly
        assert_eq!(f.at([100.0, 200.0, 0.0])[..2], [0.2, 0.2]);
    }

    #[test]
    fn bilinear_in_the_cell_not_just_linear() {
        // u = x·y / 10⁴ at the nodes: bilinear reproduces it exactly inside the cells
        let l = Lattice {
            nx: 2,
            ny: 2,
            x0: 0.0,
            y0: 0.0,
            dx: 100.0,
            dy: 100.0,
        };
        let u = Seafloor::from_nodes(l, vec![0.0, 0.0, 0.0, 1.0], vec![false; 4]).unwrap();
        let v = Seafloor::from_nodes(l, vec![0.5; 4], vec![false; 4]).unwrap();
        let f = CurrentField {
            velocity: [0.0; 2],
            profile: Vec::new(),
            grids: Some(Box::new((u, v))),
        };
        let w = f.at([30.0, 60.0, -1.0]);
        assert!((w[0] - 0.18).abs() < 1e-12, "{w:?}");
        assert!((w[1] - 0.5).abs() < 1e-12, "{w:?}");
    }

    #[test]
    fn the_profile_scales_the_grids_and_beyond_them_the_border_holds() {
        let f = linear(
            [0.1, 1e-3, 0.0],
            [0.0, 0.0, 0.0],
            vec![[0.0, 1.0], [100.0, 0.5]],
        );
        let w = f.at([0.0, 0.0, -50.0]);
        assert!((w[0] - 0.075).abs() < 1e-12, "{w:?}");
        // east of the grid: the value at x = 200
        assert!((f.at([900.0, 100.0, 0.0])[0] - 0.3).abs() < 1e-12);
        assert_eq!(f.at([f64::NAN, 0.0, 0.0]), [0.0, 0.0, 0.0]);
    }

    #[test]
    fn without_files_load_is_new() {
        let c = Current::default();
        let f = CurrentField::load(&c, Path::new("nowhere"), [0.0; 4]).unwrap();
        assert_eq!(f, CurrentField::new(&c));
        assert!(!f.is_gridded());
    }

    #[test]
    fn nodes_meeting_takes_the_cells_around_the_bounds() {
        let l = Lattice {
            nx: 11,
            ny: 11,
            x0: 0.0,
            y0: 0.0,
            dx: 10.0,
            dy: 10.0,
        };
        assert_eq!(nodes_meeting(&l, [15.0, 30.0, 0.0, 99.0]), (1, 3, 0, 10));
    }
}

#[cfg(test)]
mod jacobian_tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The Jacobian of a depth-profiled current agrees with central finite differences
        /// away from the profile's nodes and the surface.
        #[test]
        fn the_jacobian_matches_finite_differences(
            u in -1.0..1.0f64, v in -1.0..1.0f64, x in -500.0..500.0f64, y in -500.0..500.0f64,
            z in -150.0..-0.5f64, f0 in 0.0..1.5f64, f1 in 0.0..1.5f64, f2 in 0.0..1.5f64,
        ) {
            let c = Current {
                velocity: [u, v],
                profile: vec![[0.0, f0], [30.0, f1], [80.0, f2]],
                file_east: None,
                file_north: None,
            };
            let field = CurrentField::new(&c);
            prop_assert!(field.varies());
            for node in [0.0, 30.0, 80.0] {
                prop_assume!((-z - node).abs() > 1e-3);
            }
            let p = [x, y, z];
            let (c0, j) = field.at_and_jacobian(p);
            prop_assert_eq!(c0, field.at(p));
            let h = 1e-5;
            for col in 0..3 {
                let (mut a, mut b) = (p, p);
                a[col] += h;
                b[col] -= h;
                let (ca, cb) = (field.at(a), field.at(b));
                for row in 0..3 {
                    let fd = (ca[row] - cb[row]) / (2.0 * h);
                    prop_assert!((fd - j[row][col]).abs() < 1e-7, "J[{row}][{col}] {} against {fd}", j[row][col]);
                }
            }
        }
    }

    /// A uniform current does not vary, and its Jacobian is zero.
    #[test]
    fn a_uniform_current_is_constant() {
        let field = CurrentField::new(&Current::default());
        assert!(!field.varies());
        let (c, j) = field.at_and_jacobian([1.0, 2.0, -30.0]);
        assert_eq!(c, [0.0, 0.1, 0.0]);
        assert_eq!(j, [[0.0; 3]; 3]);
    }
}
