//! The node lattice of a grid: its size, its south-west node and its spacing, the one type
//! behind every grid of the crate ([`super::Seafloor`], the grid files, a plan's seafloor
//! record, the viewer's floor mesh).

use super::NodeWindow;
use serde::{Deserialize, Serialize};

/// Regular nodes: (x0 + i·dx, y0 + j·dy), i < nx, j < ny, j = 0 the southernmost row; in the
/// units of the grid's CRS (metres, or degrees of longitude and latitude).
///
/// Serialized as the six fields `nx`, `ny`, `x0`, `y0`, `dx`, `dy` in that order; a struct that
/// holds one with `#[serde(flatten)]` writes them among its own fields.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Lattice {
    /// Nodes per row (west to east).
    pub nx: usize,
    /// Rows (south to north).
    pub ny: usize,
    /// x of the south-west node (the centre of its cell).
    pub x0: f64,
    /// y of the south-west node.
    pub y0: f64,
    /// Node spacing east, > 0.
    pub dx: f64,
    /// Node spacing north, > 0.
    pub dy: f64,
}

impl Lattice {
    /// The lattice of `nx × ny` nodes from (x0, y0), spacing dx, dy; unchecked (see
    /// [`super::Seafloor::from_nodes`] for what a grid requires).
    pub const fn new(nx: usize, ny: usize, x0: f64, y0: f64, dx: f64, dy: f64) -> Lattice {
        Lattice {
            nx,
            ny,
            x0,
            y0,
            dx,
            dy,
        }
    }

    /// x of node column i: x0 + i·dx.
    pub fn x(&self, i: usize) -> f64 {
        self.x0 + i as f64 * self.dx
    }

    /// y of node row j: y0 + j·dy.
    pub fn y(&self, j: usize) -> f64 {
        self.y0 + j as f64 * self.dy
    }

    /// x of the easternmost node column.
    pub fn x_max(&self) -> f64 {
        self.x(self.nx - 1)
    }

    /// y of the northernmost node row.
    pub fn y_max(&self) -> f64 {
        self.y(self.ny - 1)
    }

    /// Number of nodes, nx·ny.
    pub fn node_count(&self) -> usize {
        self.nx * self.ny
    }

    /// Storage index of node (i, j) in row-major order from the south: j·nx + i.
    pub fn index(&self, i: usize, j: usize) -> usize {
        j * self.nx + i
    }

    /// The lattice of a block of its nodes (same spacing, first node (i0, j0)).
    pub fn block(&self, w: NodeWindow) -> Lattice {
        Lattice {
            nx: w.nx,
            ny: w.ny,
            x0: self.x(w.i0),
            y0: self.y(w.j0),
            dx: self.dx,
            dy: self.dy,
        }
    }
}
