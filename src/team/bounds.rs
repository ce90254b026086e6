//! Bounds on positions, linear rows: C1_4, every AUV at least the surface clearance below the
//! surface (the paper's z < ε, with a clearance so that an AUV is never at the surface), and
//! the grid bounds: every vehicle stays over the seafloor grid, the only floor known (for the
//! USV too: past the edge, OF1_8 would drag the team off the map).

use super::model::Assembly;
use super::ranges::RANGE_MARGIN;
use super::TeamProblem;
use crate::seafloor::Extent;
use crate::trajectory::Trajectory;

/// How an infeasible C1_4 is named.
const UNDERWATER: &str = "C1_4 (AUVs stay below the surface clearance)";
/// How infeasible grid bounds are named.
const GRID: &str = "the grid bounds (every vehicle stays over the seafloor grid)";

/// The true violation of C1_4 and of the grid bounds by AUV n at step k, metres: how far it is
/// above the surface clearance, or outside the grid. The model holds both hard, so only a
/// first guess can violate them.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> f64 {
    let a = t.auv_p[n][k];
    let e = p.floor.extent();
    let out = (e.x_min - a[0])
        .max(a[0] - e.x_max)
        .max(e.y_min - a[1])
        .max(a[1] - e.y_max);
    (a[2] + p.scenario.auv.surface_clearance).max(out).max(0.0)
}

/// C1_4 for AUV n at step k: z ≤ −surface clearance (tightened by `RANGE_MARGIN`).
pub(super) fn underwater(p: &TeamProblem, m: &mut Assembly, n: usize, k: usize) {
    let z = p.layout.auv_p(n, k) + 2;
    let row = m.row(-p.scenario.auv.surface_clearance - RANGE_MARGIN);
    m.a.push(row, z, 1.0);
    m.group(UNDERWATER, row);
}

/// x_min ≤ x ≤ x_max and y_min ≤ y ≤ y_max for the (x, y) at columns `col`, `col + 1`.
pub(super) fn grid(m: &mut Assembly, col: usize, ext: &Extent) {
    for (c, lo, hi) in [(col, ext.x_min, ext.x_max), (col + 1, ext.y_min, ext.y_max)] {
        let row = m.row(hi);
        m.a.push(row, c, 1.0);
        m.group(GRID, row);
        let row = m.row(-lo);
        m.a.push(row, c, -1.0);
        m.group(GRID, row);
    }
}
