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
mod field;
#[cfg(feature = "gdal")]
mod gdal_crs;
#[cfg(feature = "gdal")]
mod gdal_grid;
pub mod geo;
mod geokeys;
mod geotiff;
mod geotiff_write;
mod info;
mod lattice;
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
pub use lattice::Lattice;
pub use load::{load, Crs, GridFormat, LoadOptions, LoadedFloor, NodeWindow, Region, Values};
pub use obstacles::{SegmentObstacle, KEEP_OUT_LIFT};
pub use synthetic::{SyntheticParams, MAX_SYNTHETIC_FEATURES, MAX_SYNTHETIC_NODES_PER_AXIS};

use sha2::{Digest, Sha256};

/// Largest number of nodes along either axis of a grid.
pub const MAX_NODES_PER_AXIS: usize = 50_000;

/// Largest |z| of a data node, metres. Earth's relief lies within ±11 000 m; the bound catches
/// grids in the wrong unit or with a stray NODATA marker, and keeps the NODATA marker written
/// to files (-99999) apart from any data value.
pub const MAX_ABS_ELEVATION: f64 = 50_000.0;

/// A raster sample as a data elevation: `v` when finite and within ±[`MAX_ABS_ELEVATION`], else
/// the message that locates it (row and column from the top-left, 0-based in) and says what the
/// file's NODATA marker is (`nodata_hint`).
pub(crate) fn raster_elevation(
    v: f64,
    row: usize,
    col: usize,
    nodata_hint: &str,
) -> Result<f64, String> {
    if v.is_finite() && v.abs() <= MAX_ABS_ELEVATION {
        return Ok(v);
    }
    Err(format!(
        "row {}, column {} (from the top-left): value {v}: expected an elevation in metres \
         within ±{MAX_ABS_ELEVATION} or NODATA ({nodata_hint})",
        row + 1,
        col + 1
    ))
}

/// Largest number of samples [`Seafloor::segment_clearance`] will take on one segment.
pub const MAX_SEGMENT_SAMPLES: usize = 10_000_000;

/// The node-centre extent of a grid, metres: [x_min, x_max] × [y_min, y_max].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// x of the westernmost node column, metres.
    pub x_min: f64,
    /// x of the easternmost node column, metres.
    pub x_max: f64,
    /// y of the southernmost node row, metres.
    pub y_min: f64,
    /// y of the northernmost node row, metres.
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
    /// One of the cell's nodes is land (z ≥ 0).
    Land {
        /// Elevation of the cell's highest node, metres (≥ 0).
        highest: f64,
        /// The floor's elevation Z(x, y) at the point asked about, metres.
        at_point: f64,
    },
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
    /// The nodes: size, south-west node and spacing, metres.
    lattice: Lattice,
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
        let l = &self.lattice;
        f.debug_struct("Seafloor")
            .field("nx", &l.nx)
            .field("ny", &l.ny)
            .field("x0", &l.x0)
            .field("y0", &l.y0)
            .field("dx", &l.dx)
            .field("dy", &l.dy)
            .field("z_range", &self.z_range)
            .field("nodata_nodes", &self.nodata.iter().filter(|&&b| b).count())
            .finish()
    }
}

impl Seafloor {
    /// Builds a grid from its nodes on `lattice`: `z[j * nx + i]` at (x0 + i·dx, y0 + j·dy),
    /// j = 0 the southernmost row; `nodata[j * nx + i]` true marks a NODATA node, whose `z`
    /// entry is ignored (it may be NaN) and stored as 0.0.
    ///
    /// Requires 2 ≤ nx, ny ≤ [`MAX_NODES_PER_AXIS`], finite x0 and y0, finite positive dx and
    /// dy, both vectors of length nx·ny, at least one data node, and every data node finite
    /// within ±[`MAX_ABS_ELEVATION`].
    pub fn from_nodes(
        lattice: Lattice,
        mut z: Vec<f64>,
        nodata: Vec<bool>,
    ) -> Result<Seafloor, SeafloorError> {
        let Lattice {
            nx,
            ny,
            x0,
            y0,
            dx,
            dy,
        } = lattice;
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
        if !(lattice.x_max().is_finite() && lattice.y_max().is_finite()) {
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
            lattice,
            z,
            nodata,
            z_range,
            obstacles,
        })
    }

    /// Number of node columns (along x).
    pub fn nx(&self) -> usize {
        self.lattice.nx
    }
    /// Number of node rows (along y).
    pub fn ny(&self) -> usize {
        self.lattice.ny
    }
    /// x of the westernmost node column, metres.
    pub fn x0(&self) -> f64 {
        self.lattice.x0
    }
    /// y of the southernmost node row, metres.
    pub fn y0(&self) -> f64 {
        self.lattice.y0
    }
    /// Node spacing along x, metres.
    pub fn dx(&self) -> f64 {
        self.lattice.dx
    }
    /// Node spacing along y, metres.
    pub fn dy(&self) -> f64 {
        self.lattice.dy
    }

    /// Stored elevation of node (i, j) (0.0 at a NODATA node). Panics if i ≥ nx or j ≥ ny.
    pub fn node(&self, i: usize, j: usize) -> f64 {
        let l = &self.lattice;
        assert!(i < l.nx && j < l.ny, "node ({i}, {j}) outside the grid");
        self.z[l.index(i, j)]
    }

    /// Whether node (i, j) is NODATA. Panics if i ≥ nx or j ≥ ny.
    pub fn is_nodata(&self, i: usize, j: usize) -> bool {
        let l = &self.lattice;
        assert!(i < l.nx && j < l.ny, "node ({i}, {j}) outside the grid");
        self.nodata[l.index(i, j)]
    }

    /// Node-centre extent: [x0, x0 + (nx−1)dx] × [y0, y0 + (ny−1)dy].
    pub fn extent(&self) -> Extent {
        let l = &self.lattice;
        Extent {
            x_min: l.x0,
            x_max: l.x_max(),
            y_min: l.y0,
            y_max: l.y_max(),
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
        self.lattice
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

    /// Hex SHA-256 identifying the grid exactly. Hashed, in order: nx and ny as u64
    /// little-endian; the bits of x0, y0, dx, dy as u64 little-endian; the bits of every
    /// stored node value (0.0 at NODATA nodes) in storage order `j * nx + i`, u64
    /// little-endian; then the NODATA mask in the same order, one byte (0 or 1) per node.
    pub fn fingerprint(&self) -> String {
        let mut h = Sha256::new();
        let l = &self.lattice;
        h.update((l.nx as u64).to_le_bytes());
        h.update((l.ny as u64).to_le_bytes());
        for v in [l.x0, l.y0, l.dx, l.dy] {
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

#[cfg(test)]
mod tests;
