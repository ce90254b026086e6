//! The seafloor: a depth field z = Z(x, y) over a regular grid, with bilinear interpolation,
//! its gradient, and the segment query 𝓛_r of the paper (Notations; C1_12, C1_13).
//!
//! # Conventions
//!
//! - x east, y north, z up, metres; the sea surface is z = 0 and the floor is at z < 0.
//! - The grid has `nx × ny` nodes at (x0 + i·dx, y0 + j·dy); row j = 0 is the southernmost.
//!   The field is defined on the node-centre [`Extent`] only, a closed rectangle.
//! - Between nodes the floor is the bilinear interpolant of the four nodes of the cell.
//!
//! # Rules callers rely on
//!
//! - **Outside the grid** a query is an error, [`SeafloorError::OutsideGrid`], whose message
//!   states the extent. The planner keeps every AUV inside the grid with hard bounds.
//! - **NaN or infinite** query arguments are an error ([`SeafloorError::NonFinite`]), never a
//!   panic and never a NaN result.
//! - **NODATA** nodes are stored as z = 0.0 (the sea surface) and flagged in a mask, so the
//!   bilinear field stays finite and continuous, and the clearance constraint z ≥ Z + ε can
//!   never hold over them for an AUV below the surface. [`Seafloor::is_obstacle`] tells them
//!   apart. A grid must hold at least one node with data.
//! - **Land** is simply z ≥ 0; a cell touching land or NODATA is an obstacle.
//! - **Which cell** a point belongs to: per axis, the cell whose lower node is the largest node
//!   at or below the point, except on the last node line, which belongs to the last cell. So a
//!   point on an interior cell edge belongs to the cell to its north/east, and on the north/east
//!   border to the last cell. A coordinate within 1e-9 cell of a node line is snapped onto it,
//!   so node coordinates computed as x0 + i·dx give the node value exactly. The gradient, the
//!   obstacle test and the value all use that one cell.
//! - **Elevations** of data nodes must lie within ±[`MAX_ABS_ELEVATION`] metres.
//!
//! Grids come from [`Seafloor::from_nodes`], [`Seafloor::synthetic`] (the paper's Fig. 4(a)),
//! an ESRI ASCII file ([`Seafloor::read_esri_ascii`]) or any grid file through [`load`]: ESRI
//! ASCII or GeoTIFF (and, with the `gdal` cargo feature, NetCDF, BAG, XYZ and the other formats
//! GDAL reads), elevations or depths, projected or geographic (resampled onto the local
//! tangent plane of [`geo`]), cut to the mission window. [`info`] describes a grid file without
//! loading it.

mod crop;
mod crs;
mod error;
mod esri_ascii;
#[cfg(feature = "gdal")]
mod gdal_crs;
#[cfg(feature = "gdal")]
mod gdal_grid;
pub mod geo;
mod geokeys;
mod geotiff;
mod geotiff_write;
mod info;
mod load;
pub(crate) mod obstacles;
mod resample;
mod synthetic;

pub use crop::{
    crop_floor, export_grid, latlon_box_in_frame, CropRegion, ExportOptions, ExportedGrid,
};
pub use crs::{parse_crs, wkt_of, CrsSource};
pub use error::SeafloorError;
pub use geotiff_write::{write_geotiff, GeoTiffOptions, SampleType, TiffCompression, TiffLayout};
pub use info::{info, info_with_crs, GridInfo};
pub use load::{
    load, Crs, GridFormat, Lattice, LoadOptions, LoadedFloor, NodeWindow, Region, Values,
};
pub use obstacles::{SegmentObstacle, KEEP_OUT_LIFT};
pub use synthetic::{SyntheticParams, MAX_SYNTHETIC_FEATURES, MAX_SYNTHETIC_NODES_PER_AXIS};

use sha2::{Digest, Sha256};

/// Largest number of nodes along either axis of a grid.
pub const MAX_NODES_PER_AXIS: usize = 50_000;

/// Largest |z| of a data node, metres. Earth's relief lies within ±11 000 m; the bound catches
/// grids in the wrong unit or with a stray NODATA marker, and keeps the NODATA marker written
/// to files (-99999) apart from any data value.
pub const MAX_ABS_ELEVATION: f64 = 50_000.0;

/// Largest number of samples [`Seafloor::segment_clearance`] will take on one segment.
pub const MAX_SEGMENT_SAMPLES: usize = 10_000_000;

/// A coordinate this close to a node line (in cells) is snapped onto it.
const SNAP: f64 = 1e-9;

/// The node-centre extent of a grid, metres: [x_min, x_max] × [y_min, y_max].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    pub x_min: f64,
    pub x_max: f64,
    pub y_min: f64,
    pub y_max: f64,
}

impl std::fmt::Display for Extent {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "x from {} to {} m and y from {} to {} m",
            self.x_min, self.x_max, self.y_min, self.y_max
        )
    }
}

/// What makes a cell an obstacle ([`Seafloor::obstacle`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    /// One of the cell's nodes is NODATA.
    Nodata,
    /// One of the cell's nodes is land: `highest` is the highest node's elevation (≥ 0),
    /// `at_point` the floor's elevation at the point asked about.
    Land { highest: f64, at_point: f64 },
}

impl std::fmt::Display for Obstacle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Obstacle::Nodata => write!(
                f,
                "over a NODATA cell (no depth known there: a hole in the grid or outside the \
                 surveyed area)"
            ),
            Obstacle::Land { at_point, .. } if at_point >= 0.0 => {
                write!(f, "on land (the floor there is at z = {at_point:+.1} m)")
            }
            Obstacle::Land { highest, .. } => write!(
                f,
                "in a grid cell that touches land (a node at z = {highest:+.1} m); such cells \
                 are obstacles"
            ),
        }
    }
}

/// The result of the segment query 𝓛_r: the smallest clearance z − Z(x, y) over the samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentClearance {
    /// Smallest z_sample − Z(x_sample, y_sample), metres (negative: the segment is below the
    /// floor there).
    pub min_clearance: f64,
    /// The sample point on the segment (not on the floor) where the minimum occurs; the floor
    /// there is at `at[2] - min_clearance`. The first such sample from `a` on ties.
    pub at: [f64; 3],
    /// Where along the segment: `at` = a + fraction·(b − a), fraction in [0, 1].
    pub fraction: f64,
}

/// A seafloor elevation grid. See the module documentation for the rules it follows.
#[derive(Clone, PartialEq)]
pub struct Seafloor {
    nx: usize,
    ny: usize,
    x0: f64,
    y0: f64,
    dx: f64,
    dy: f64,
    /// Node elevations, `z[j * nx + i]`; 0.0 at NODATA nodes.
    z: Vec<f64>,
    /// `nodata[j * nx + i]` is true at a NODATA node.
    nodata: Vec<bool>,
    /// (min, max) of z over data nodes.
    z_range: (f64, f64),
    /// Whether any node is NODATA or land (z ≥ 0), i.e. the grid has an obstacle cell.
    obstacles: bool,
}

impl std::fmt::Debug for Seafloor {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Seafloor")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("x0", &self.x0)
            .field("y0", &self.y0)
            .field("dx", &self.dx)
            .field("dy", &self.dy)
            .field("z_range", &self.z_range)
            .field("nodata_nodes", &self.nodata.iter().filter(|&&b| b).count())
            .finish()
    }
}

impl Seafloor {
    /// Builds a grid from its nodes: `z[j * nx + i]` at (x0 + i·dx, y0 + j·dy), j = 0 the
    /// southernmost row; `nodata[j * nx + i]` true marks a NODATA node, whose `z` entry is
    /// ignored (it may be NaN) and stored as 0.0.
    ///
    /// Requires 2 ≤ nx, ny ≤ [`MAX_NODES_PER_AXIS`], finite x0 and y0, finite positive dx and
    /// dy, both vectors of length nx·ny, at least one data node, and every data node finite
    /// within ±[`MAX_ABS_ELEVATION`].
    #[allow(clippy::too_many_arguments)]
    pub fn from_nodes(
        nx: usize,
        ny: usize,
        x0: f64,
        y0: f64,
        dx: f64,
        dy: f64,
        mut z: Vec<f64>,
        nodata: Vec<bool>,
    ) -> Result<Seafloor, SeafloorError> {
        let invalid = |reason: String| Err(SeafloorError::InvalidGrid(reason));
        for (name, n) in [("nx", nx), ("ny", ny)] {
            if !(2..=MAX_NODES_PER_AXIS).contains(&n) {
                return invalid(format!(
                    "{name} = {n}: expected 2 to {MAX_NODES_PER_AXIS} nodes"
                ));
            }
        }
        for (name, v) in [("x0", x0), ("y0", y0)] {
            if !v.is_finite() {
                return invalid(format!("{name} = {v}: expected a finite number"));
            }
        }
        for (name, v) in [("dx", dx), ("dy", dy)] {
            if !(v.is_finite() && v > 0.0) {
                return invalid(format!("{name} = {v}: expected a positive number"));
            }
        }
        let x_max = x0 + (nx - 1) as f64 * dx;
        let y_max = y0 + (ny - 1) as f64 * dy;
        if !(x_max.is_finite() && y_max.is_finite()) {
            return invalid("the grid's far corner is not a finite coordinate".to_string());
        }
        let Some(n) = nx.checked_mul(ny) else {
            return invalid(format!("{nx} × {ny} nodes do not fit in memory"));
        };
        if z.len() != n || nodata.len() != n {
            return invalid(format!(
                "{nx} × {ny} = {n} nodes, but {} elevations and {} NODATA flags",
                z.len(),
                nodata.len()
            ));
        }
        let mut z_range = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, (v, &missing)) in z.iter_mut().zip(&nodata).enumerate() {
            if missing {
                *v = 0.0;
                continue;
            }
            if !(v.is_finite() && v.abs() <= MAX_ABS_ELEVATION) {
                return invalid(format!(
                    "node (i = {}, j = {}) has elevation {v}: expected a finite number \
                     within ±{MAX_ABS_ELEVATION} m",
                    k % nx,
                    k / nx
                ));
            }
            z_range = (z_range.0.min(*v), z_range.1.max(*v));
        }
        if z_range.0 > z_range.1 {
            return invalid("every node is NODATA".to_string());
        }
        let obstacles = z_range.1 >= 0.0 || nodata.contains(&true);
        Ok(Seafloor {
            nx,
            ny,
            x0,
            y0,
            dx,
            dy,
            z,
            nodata,
            z_range,
            obstacles,
        })
    }

    pub fn nx(&self) -> usize {
        self.nx
    }
    pub fn ny(&self) -> usize {
        self.ny
    }
    /// x of the westernmost node column, metres.
    pub fn x0(&self) -> f64 {
        self.x0
    }
    /// y of the southernmost node row, metres.
    pub fn y0(&self) -> f64 {
        self.y0
    }
    pub fn dx(&self) -> f64 {
        self.dx
    }
    pub fn dy(&self) -> f64 {
        self.dy
    }

    /// Stored elevation of node (i, j) (0.0 at a NODATA node). Panics if i ≥ nx or j ≥ ny.
    pub fn node(&self, i: usize, j: usize) -> f64 {
        assert!(
            i < self.nx && j < self.ny,
            "node ({i}, {j}) outside the grid"
        );
        self.z[j * self.nx + i]
    }

    /// Whether node (i, j) is NODATA. Panics if i ≥ nx or j ≥ ny.
    pub fn is_nodata(&self, i: usize, j: usize) -> bool {
        assert!(
            i < self.nx && j < self.ny,
            "node ({i}, {j}) outside the grid"
        );
        self.nodata[j * self.nx + i]
    }

    /// Node-centre extent: [x0, x0 + (nx−1)dx] × [y0, y0 + (ny−1)dy].
    pub fn extent(&self) -> Extent {
        Extent {
            x_min: self.x0,
            x_max: self.x0 + (self.nx - 1) as f64 * self.dx,
            y_min: self.y0,
            y_max: self.y0 + (self.ny - 1) as f64 * self.dy,
        }
    }

    /// Whether (x, y) lies in the closed extent (false for NaN).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let e = self.extent();
        (e.x_min..=e.x_max).contains(&x) && (e.y_min..=e.y_max).contains(&y)
    }

    /// (min, max) elevation over all data (non-NODATA) nodes.
    pub fn z_range(&self) -> (f64, f64) {
        self.z_range
    }

    /// The node lattice: size, south-west node and spacing.
    pub fn lattice(&self) -> Lattice {
        Lattice {
            nx: self.nx,
            ny: self.ny,
            x0: self.x0,
            y0: self.y0,
            dx: self.dx,
            dy: self.dy,
        }
    }

    /// Every stored node value (0.0 at NODATA) and the NODATA mask, in storage order
    /// `j * nx + i`.
    pub fn nodes(&self) -> (&[f64], &[bool]) {
        (&self.z, &self.nodata)
    }

    /// Whether the grid has an obstacle cell: a NODATA or a land node (z ≥ 0).
    pub fn has_obstacles(&self) -> bool {
        self.obstacles
    }

    /// Number of NODATA nodes and of land nodes (data, z ≥ 0).
    pub fn obstacle_counts(&self) -> (usize, usize) {
        let nodata = self.nodata.iter().filter(|&&m| m).count();
        let land = self
            .z
            .iter()
            .zip(&self.nodata)
            .filter(|(&z, &m)| !m && z >= 0.0)
            .count();
        (nodata, land)
    }

    /// The cell holding (x, y) and the local coordinates (t, s) ∈ [0, 1]² in it.
    fn locate(&self, x: f64, y: f64) -> Result<Cell, SeafloorError> {
        finite("x", x)?;
        finite("y", y)?;
        if !self.contains(x, y) {
            return Err(SeafloorError::OutsideGrid {
                x,
                y,
                extent: self.extent(),
            });
        }
        let (i, t) = axis((x - self.x0) / self.dx, self.nx);
        let (j, s) = axis((y - self.y0) / self.dy, self.ny);
        let k = j * self.nx + i;
        Ok(Cell {
            k,
            t,
            s,
            z00: self.z[k],
            z10: self.z[k + 1],
            z01: self.z[k + self.nx],
            z11: self.z[k + self.nx + 1],
        })
    }

    /// Bilinear elevation Z(x, y), metres.
    pub fn elevation(&self, x: f64, y: f64) -> Result<f64, SeafloorError> {
        Ok(self.locate(x, y)?.value())
    }

    /// Bilinear elevation and its gradient [∂Z/∂x, ∂Z/∂y] (dimensionless). The gradient is that
    /// of the bilinear patch of the cell holding (x, y) (see the module docs for which cell a
    /// point on a cell edge belongs to).
    pub fn elevation_and_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), SeafloorError> {
        let c = self.locate(x, y)?;
        let gx = ((1.0 - c.s) * (c.z10 - c.z00) + c.s * (c.z11 - c.z01)) / self.dx;
        let gy = ((1.0 - c.t) * (c.z01 - c.z00) + c.t * (c.z11 - c.z10)) / self.dy;
        Ok((c.value(), [gx, gy]))
    }

    /// Whether (x, y) is over an obstacle: any of the four nodes of its cell is NODATA or land
    /// (z ≥ 0).
    pub fn is_obstacle(&self, x: f64, y: f64) -> Result<bool, SeafloorError> {
        let c = self.locate(x, y)?;
        let nx = self.nx;
        Ok([c.k, c.k + 1, c.k + nx, c.k + nx + 1]
            .iter()
            .any(|&k| self.nodata[k] || self.z[k] >= 0.0))
    }

    /// Why the cell holding (x, y) is an obstacle, if it is: a NODATA node, else the highest
    /// land node (z ≥ 0); `at_point` is the floor's elevation at (x, y) itself.
    pub fn obstacle(&self, x: f64, y: f64) -> Result<Option<Obstacle>, SeafloorError> {
        let c = self.locate(x, y)?;
        let nx = self.nx;
        let ks = [c.k, c.k + 1, c.k + nx, c.k + nx + 1];
        if ks.iter().any(|&k| self.nodata[k]) {
            return Ok(Some(Obstacle::Nodata));
        }
        let highest = ks
            .iter()
            .map(|&k| self.z[k])
            .fold(f64::NEG_INFINITY, f64::max);
        Ok((highest >= 0.0).then(|| Obstacle::Land {
            highest,
            at_point: c.value(),
        }))
    }

    /// The paper's 𝓛_r: samples the straight segment a → b at n + 1 evenly spaced points
    /// (endpoints included), n = max(1, ⌈horizontal length / resolution⌉), and returns the
    /// smallest clearance z − Z(x, y) and where it occurs. Both endpoints must be inside the
    /// grid (then so is every sample); `resolution` must be positive and finite, and n at most
    /// [`MAX_SEGMENT_SAMPLES`].
    pub fn segment_clearance(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
    ) -> Result<SegmentClearance, SeafloorError> {
        let n = self.segment_intervals(a, b, resolution)?;
        let sample = |k: usize| -> Result<SegmentClearance, SeafloorError> {
            let fraction = k as f64 / n as f64;
            let at = segment_point(a, b, fraction);
            Ok(SegmentClearance {
                min_clearance: at[2] - self.elevation(at[0], at[1])?,
                at,
                fraction,
            })
        };
        let mut best = sample(0)?;
        for k in 1..=n {
            let c = sample(k)?;
            if c.min_clearance < best.min_clearance {
                best = c;
            }
        }
        Ok(best)
    }

    /// n of 𝓛_r for the segment a → b, after checking its arguments (finite, both ends inside
    /// the grid, a positive resolution, n at most [`MAX_SEGMENT_SAMPLES`]).
    fn segment_intervals(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
    ) -> Result<usize, SeafloorError> {
        for (what, p) in [("segment start", a), ("segment end", b)] {
            for v in p {
                finite(what, v)?;
            }
            if !self.contains(p[0], p[1]) {
                return Err(SeafloorError::OutsideGrid {
                    x: p[0],
                    y: p[1],
                    extent: self.extent(),
                });
            }
        }
        finite("resolution", resolution)?;
        if resolution <= 0.0 {
            return Err(SeafloorError::InvalidQuery {
                what: "resolution",
                reason: format!("expected a positive length in metres, got {resolution}"),
            });
        }
        segment_samples(a, b, resolution)
    }

    /// Hex SHA-256 identifying the grid exactly. Hashed, in order: nx and ny as u64
    /// little-endian; the bits of x0, y0, dx, dy as u64 little-endian; the bits of every
    /// stored node value (0.0 at NODATA nodes) in storage order `j * nx + i`, u64
    /// little-endian; then the NODATA mask in the same order, one byte (0 or 1) per node.
    pub fn fingerprint(&self) -> String {
        let mut h = Sha256::new();
        h.update((self.nx as u64).to_le_bytes());
        h.update((self.ny as u64).to_le_bytes());
        for v in [self.x0, self.y0, self.dx, self.dy] {
            h.update(v.to_bits().to_le_bytes());
        }
        for v in &self.z {
            h.update(v.to_bits().to_le_bytes());
        }
        let mask: Vec<u8> = self.nodata.iter().map(|&b| u8::from(b)).collect();
        h.update(&mask);
        h.finalize().iter().map(|b| format!("{b:02x}")).collect()
    }
}

/// The four nodes of a cell and a point's local coordinates in it.
struct Cell {
    /// Storage index of the south-west node.
    k: usize,
    t: f64,
    s: f64,
    z00: f64,
    z10: f64,
    z01: f64,
    z11: f64,
}

impl Cell {
    /// Bilinear value; the (1 − t)·a + t·b form is exact at t = 0 and t = 1.
    fn value(&self) -> f64 {
        let south = (1.0 - self.t) * self.z00 + self.t * self.z10;
        let north = (1.0 - self.t) * self.z01 + self.t * self.z11;
        (1.0 - self.s) * south + self.s * north
    }
}

/// Cell index and local coordinate along one axis, for u = (coordinate − origin) / spacing in
/// [0, n − 1] (up to rounding).
fn axis(u: f64, n: usize) -> (usize, f64) {
    let r = u.round();
    let u = if (u - r).abs() <= SNAP { r } else { u };
    let i = (u.max(0.0).floor() as usize).min(n - 2);
    (i, (u - i as f64).clamp(0.0, 1.0))
}

fn finite(what: &'static str, value: f64) -> Result<(), SeafloorError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(SeafloorError::NonFinite { what, value })
    }
}

/// n of 𝓛_r: max(1, ⌈horizontal length / resolution⌉), bounded by [`MAX_SEGMENT_SAMPLES`].
fn segment_samples(a: [f64; 3], b: [f64; 3], resolution: f64) -> Result<usize, SeafloorError> {
    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = (length / resolution).ceil().max(1.0);
    if n > MAX_SEGMENT_SAMPLES as f64 {
        return Err(SeafloorError::InvalidQuery {
            what: "resolution",
            reason: format!(
                "{resolution} m would need {n} samples on a {length} m segment \
                 (at most {MAX_SEGMENT_SAMPLES})"
            ),
        });
    }
    Ok(n as usize)
}

/// a + fraction·(b − a), kept inside the segment's bounding box despite rounding so that a
/// sample of a segment inside the grid is inside the grid.
fn segment_point(a: [f64; 3], b: [f64; 3], fraction: f64) -> [f64; 3] {
    std::array::from_fn(|d| (a[d] + fraction * (b[d] - a[d])).clamp(a[d].min(b[d]), a[d].max(b[d])))
}

#[cfg(test)]
mod tests {
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
        let z = (0..nx * ny)
            .map(|k| f(x0 + (k % nx) as f64 * dx, y0 + (k / nx) as f64 * dy))
            .collect();
        Seafloor::from_nodes(nx, ny, x0, y0, dx, dy, z, vec![false; nx * ny]).unwrap()
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
            let f = Seafloor::from_nodes(nx, ny, x0, y0, dx, dy, z, vec![false; nx * ny]).unwrap();
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
        let f = Seafloor::from_nodes(4, 3, 0.0, 0.0, 10.0, 10.0, z, nodata).unwrap();
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
            2,
            2,
            0.0,
            0.0,
            1.0,
            1.0,
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
        let cases: Vec<(&str, Result<Seafloor, SeafloorError>)> = vec![
            (
                "nx = 1",
                Seafloor::from_nodes(1, 2, 0.0, 0.0, 1.0, 1.0, vec![-1.0; 2], vec![false; 2]),
            ),
            (
                "ny = 0",
                Seafloor::from_nodes(2, 0, 0.0, 0.0, 1.0, 1.0, vec![], vec![]),
            ),
            (
                "nx = 50001",
                Seafloor::from_nodes(50_001, 2, 0.0, 0.0, 1.0, 1.0, vec![], vec![]),
            ),
            (
                "x0 = NaN",
                Seafloor::from_nodes(2, 2, f64::NAN, 0.0, 1.0, 1.0, z.clone(), m.clone()),
            ),
            (
                "dx = 0",
                Seafloor::from_nodes(2, 2, 0.0, 0.0, 0.0, 1.0, z.clone(), m.clone()),
            ),
            (
                "dy = -1",
                Seafloor::from_nodes(2, 2, 0.0, 0.0, 1.0, -1.0, z.clone(), m.clone()),
            ),
            (
                "dx = inf",
                Seafloor::from_nodes(2, 2, 0.0, 0.0, f64::INFINITY, 1.0, z.clone(), m.clone()),
            ),
            (
                "far corner",
                Seafloor::from_nodes(2, 2, 1.7e308, 0.0, 1e308, 1.0, z.clone(), m.clone()),
            ),
            (
                "3 elevations",
                Seafloor::from_nodes(2, 2, 0.0, 0.0, 1.0, 1.0, vec![-1.0; 3], m.clone()),
            ),
            (
                "5 NODATA flags",
                Seafloor::from_nodes(2, 2, 0.0, 0.0, 1.0, 1.0, z.clone(), vec![false; 5]),
            ),
            (
                "elevation NaN",
                Seafloor::from_nodes(
                    2,
                    2,
                    0.0,
                    0.0,
                    1.0,
                    1.0,
                    vec![-1.0, f64::NAN, -1.0, -1.0],
                    m.clone(),
                ),
            ),
            (
                "elevation -60000",
                Seafloor::from_nodes(
                    2,
                    2,
                    0.0,
                    0.0,
                    1.0,
                    1.0,
                    vec![-1.0, -6e4, -1.0, -1.0],
                    m.clone(),
                ),
            ),
            (
                "every node is NODATA",
                Seafloor::from_nodes(2, 2, 0.0, 0.0, 1.0, 1.0, z.clone(), vec![true; 4]),
            ),
        ];
        for (name, r) in cases {
            let err = r.expect_err(name);
            assert!(
                matches!(err, SeafloorError::InvalidGrid(_)),
                "{name}: {err}"
            );
        }
        assert!(Seafloor::from_nodes(2, 2, 0.0, 0.0, 1.0, 1.0, z, m).is_ok());
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
                + 80.0
                    * (-((x - 100.0).powi(2) + (y - 100.0).powi(2)) / (2.0 * 30.0f64.powi(2))).exp()
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
            Seafloor::from_nodes(f.nx, f.ny, f.x0, f.y0, f.dx, f.dy, z, m)
                .unwrap()
                .fingerprint()
        };
        assert_eq!(rebuild(3, 0.0, false), fp);
        assert_ne!(rebuild(3, 1.0, false), fp); // one ulp
        assert_ne!(rebuild(3, 0.0, true), fp);
        let shifted = Seafloor::from_nodes(
            f.nx,
            f.ny,
            f.x0,
            f.y0 + 1e-9,
            f.dx,
            f.dy,
            f.z.clone(),
            f.nodata.clone(),
        )
        .unwrap();
        assert_ne!(shifted.fingerprint(), fp);
    }
}
