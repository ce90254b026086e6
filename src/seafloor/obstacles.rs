//! Obstacles as the planner sees them: the first sample of a segment over an obstacle cell
//! ([`Seafloor::segment_obstacle`]), and the keep-out field ([`Seafloor::keep_out`]) that the
//! planner's constraints use in place of the floor.
//!
//! # The keep-out field
//!
//! A cell touching a NODATA or land node is an obstacle (see the module docs of
//! [`crate::seafloor`]). Over such a cell the bilinear floor lies between the data depth and the
//! surface, so a floor-clearance constraint alone would let an AUV sit in a cell with one NODATA
//! corner, and says nothing to the USV at the surface. The keep-out field is the same grid with
//! every node of every obstacle cell (a *wall* node) raised to
//!
//!   max(its own elevation, [`KEEP_OUT_LIFT`] + d),
//!
//! d its chamfer distance in metres (along grid lines and diagonals) to the nearest node of no
//! obstacle cell; other nodes keep their value, and no node is NODATA. Hence:
//!
//! - at every point of an obstacle cell (edges included) the keep-out field is at least
//!   [`KEEP_OUT_LIFT`] above the surface: "z ≥ field + ε" cannot hold there for an AUV, nor
//!   "field ≤ 0" for the USV, and a line of sight (z ≤ 0 along it) is blocked;
//! - inside an obstacle region the field rises by 1 m per metre towards its middle, so the
//!   gradient of a linearised constraint points out of it by the shortest way;
//! - the field is nowhere below the floor (a land node higher than the wall keeps its height),
//!   so a plan that keeps to it keeps to the floor;
//! - the price is at most one cell of conservatism: a cell next to an obstacle cell shares wall
//!   nodes, so its field ramps up to the wall and the vehicles keep out of part of it.

use super::field::segment_point;
use super::{Obstacle, Seafloor, SeafloorError, MAX_ABS_ELEVATION};

/// How far above the surface (metres) the keep-out field lifts the edge of an obstacle. Any
/// positive height keeps every vehicle out; 1 m is well above the SCP's feasibility tolerance
/// (1e-3 m by default), so a plan accepted within that tolerance is still out of every obstacle.
pub const KEEP_OUT_LIFT: f64 = 1.0;

/// The first sample of the segment query 𝓛_r that lies over an obstacle cell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SegmentObstacle {
    /// The sample point on the segment.
    pub at: [f64; 3],
    /// Where along the segment: `at` = a + fraction·(b − a).
    pub fraction: f64,
    /// What makes its cell an obstacle.
    pub obstacle: Obstacle,
}

impl Seafloor {
    /// The first sample of 𝓛_r on a → b (the samples of [`Seafloor::segment_clearance`], from
    /// `a`) over an obstacle cell, if any. The same argument rules and errors as
    /// `segment_clearance`.
    pub fn segment_obstacle(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
    ) -> Result<Option<SegmentObstacle>, SeafloorError> {
        let n = self.segment_intervals(a, b, resolution)?;
        if !self.obstacles {
            return Ok(None);
        }
        for k in 0..=n {
            let fraction = k as f64 / n as f64;
            let at = segment_point(a, b, fraction);
            if let Some(obstacle) = self.obstacle(at[0], at[1])? {
                return Ok(Some(SegmentObstacle {
                    at,
                    fraction,
                    obstacle,
                }));
            }
        }
        Ok(None)
    }

    /// The keep-out field of this grid (see the module docs): a copy when the grid has no
    /// obstacle.
    pub fn keep_out(&self) -> Seafloor {
        if !self.obstacles {
            return self.clone();
        }
        let l = self.lattice;
        let (nx, ny) = (l.nx, l.ny);
        let obstacle_node = |k: usize| self.nodata[k] || self.z[k] >= 0.0;
        let mut wall = vec![false; nx * ny];
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let k = j * nx + i;
                let corners = [k, k + 1, k + nx, k + nx + 1];
                if corners.iter().any(|&c| obstacle_node(c)) {
                    corners.iter().for_each(|&c| wall[c] = true);
                }
            }
        }
        let d = chamfer(&wall, nx, ny, l.dx, l.dy);
        let z: Vec<f64> = (0..nx * ny)
            .map(|k| {
                if !wall[k] {
                    return self.z[k];
                }
                let own = if self.nodata[k] {
                    f64::NEG_INFINITY
                } else {
                    self.z[k]
                };
                own.max((KEEP_OUT_LIFT + d[k]).min(MAX_ABS_ELEVATION))
            })
            .collect();
        let z_range = z
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        Seafloor {
            lattice: l,
            z,
            nodata: vec![false; nx * ny],
            z_range,
            obstacles: z_range.1 >= 0.0,
        }
    }
}

/// Chamfer distance (metres) of every node of an nx × ny lattice to the nearest node outside
/// the set `inside` (0 outside it), by the classic two passes over the 8 neighbours (steps dx,
/// dy and √(dx² + dy²)); +∞ everywhere if every node is inside.
pub(crate) fn chamfer(inside: &[bool], nx: usize, ny: usize, dx: f64, dy: f64) -> Vec<f64> {
    let mut d: Vec<f64> = inside
        .iter()
        .map(|&w| if w { f64::INFINITY } else { 0.0 })
        .collect();
    let diag = dx.hypot(dy);
    // (di, dj, step) of the neighbours visited before a node in the forward pass; the backward
    // pass uses their mirror images
    let before = [(-1, 0, dx), (-1, -1, diag), (0, -1, dy), (1, -1, diag)];
    let mut relax = |i: usize, j: usize, sign: isize| {
        let k = j * nx + i;
        if d[k] == 0.0 {
            return;
        }
        for &(di, dj, step) in &before {
            let (ni, nj) = (i as isize + sign * di, j as isize + sign * dj);
            if ni < 0 || nj < 0 || ni >= nx as isize || nj >= ny as isize {
                continue;
            }
            let v = d[nj as usize * nx + ni as usize] + step;
            if v < d[k] {
                d[k] = v;
            }
        }
    };
    for j in 0..ny {
        for i in 0..nx {
            relax(i, j, 1);
        }
    }
    for j in (0..ny).rev() {
        for i in (0..nx).rev() {
            relax(i, j, -1);
        }
    }
    d
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seafloor::Lattice;
    use proptest::prelude::*;

    /// 12 × 9 nodes of 10 × 20 m at −40 m with NODATA nodes and land nodes at the given
    /// (i, j).
    fn grid(nodata: &[(usize, usize)], land: &[(usize, usize, f64)]) -> Seafloor {
        let (nx, ny) = (12, 9);
        let mut z = vec![-40.0; nx * ny];
        let mut m = vec![false; nx * ny];
        for &(i, j) in nodata {
            m[j * nx + i] = true;
        }
        for &(i, j, h) in land {
            z[j * nx + i] = h;
        }
        Seafloor::from_nodes(Lattice::new(nx, ny, 100.0, -50.0, 10.0, 20.0), z, m).unwrap()
    }

    #[test]
    fn a_grid_without_obstacles_is_its_own_keep_out_field() {
        let f = grid(&[], &[]);
        assert!(!f.has_obstacles());
        assert_eq!(f.keep_out(), f);
        assert_eq!(
            f.segment_obstacle([100.0, -50.0, -1.0], [210.0, 110.0, 0.0], 1.0)
                .unwrap(),
            None
        );
    }

    #[test]
    fn walls_rise_with_the_distance_to_open_water() {
        // one NODATA node at (5, 4): its 4 cells are obstacles, their 9 nodes walls
        let f = grid(&[(5, 4)], &[]);
        let k = f.keep_out();
        assert!(f.has_obstacles() && k.has_obstacles());
        assert!(!k.is_nodata(5, 4));
        // ring nodes are one step from open water, the centre two
        assert_eq!(k.node(4, 4), KEEP_OUT_LIFT + 10.0);
        assert_eq!(k.node(5, 3), KEEP_OUT_LIFT + 20.0);
        assert_eq!(k.node(4, 3), KEEP_OUT_LIFT + 10.0);
        assert_eq!(k.node(5, 4), k.node(5, 3));
        assert_eq!(k.node(5, 4), KEEP_OUT_LIFT + 20.0);
        assert_eq!(k.node(3, 4), -40.0); // open water is untouched
                                         // a high land node keeps its height
        let f = grid(&[], &[(2, 2, 300.0)]);
        let k = f.keep_out();
        assert_eq!(k.node(2, 2), 300.0);
        assert_eq!(k.node(1, 2), KEEP_OUT_LIFT + 10.0);
    }

    #[test]
    fn every_node_a_wall_stays_finite() {
        let f = Seafloor::from_nodes(
            Lattice::new(2, 2, 0.0, 0.0, 1.0, 1.0),
            vec![-1.0, 1.0, -1.0, -1.0],
            vec![false; 4],
        )
        .unwrap();
        let k = f.keep_out();
        assert_eq!(k.nodes().0, &[MAX_ABS_ELEVATION; 4]);
    }

    #[test]
    fn segment_obstacle_finds_the_first_sample_over_an_obstacle_cell() {
        let f = grid(&[(5, 4)], &[(9, 1, 0.0)]);
        // along y = 30 (node row 4) from x = 100 eastwards: cells 4 and 5 touch the hole
        let hit = f
            .segment_obstacle([100.0, 30.0, -10.0], [210.0, 30.0, -10.0], 5.0)
            .unwrap()
            .unwrap();
        assert_eq!((hit.at, hit.fraction), ([140.0, 30.0, -10.0], 8.0 / 22.0));
        assert_eq!(hit.obstacle, Obstacle::Nodata);
        let hit = f
            .segment_obstacle([210.0, -30.0, 0.0], [100.0, -30.0, 0.0], 5.0)
            .unwrap()
            .unwrap();
        assert_eq!(hit.at, [195.0, -30.0, 0.0]); // x = 200 belongs to the cell east of it
        assert!(matches!(hit.obstacle, Obstacle::Land { .. }));
        // errors as segment_clearance
        assert!(matches!(
            f.segment_obstacle([0.0, 0.0, 0.0], [110.0, 0.0, 0.0], 5.0),
            Err(SeafloorError::OutsideGrid { .. })
        ));
        assert!(matches!(
            f.segment_obstacle([100.0, 0.0, 0.0], [110.0, 0.0, 0.0], 0.0),
            Err(SeafloorError::InvalidQuery { .. })
        ));
    }

    proptest! {
        /// The promises of the module docs, at random points of random grids: over an
        /// obstacle cell the field is at least KEEP_OUT_LIFT; it is never below the floor;
        /// and it equals the floor in cells with no wall node.
        #[test]
        fn the_keep_out_field_walls_off_every_obstacle_cell(
            seed in proptest::collection::vec((-60.0f64..20.0, 0u8..8), 48),
            points in proptest::collection::vec((0.0f64..1.0, 0.0f64..1.0), 40),
        ) {
            let (nx, ny) = (8, 6);
            // about one node in 8 NODATA, and land where the draw is ≥ 0
            let z: Vec<f64> = seed.iter().map(|s| s.0).collect();
            let m: Vec<bool> = seed.iter().map(|s| s.1 == 0).collect();
            prop_assume!(m.iter().any(|&b| !b));
            let f = Seafloor::from_nodes(Lattice::new(nx, ny, -30.0, 70.0, 7.0, 11.0), z, m).unwrap();
            let k = f.keep_out();
            let e = f.extent();
            for (u, v) in points {
                let x = e.x_min + u * (e.x_max - e.x_min);
                let y = e.y_min + v * (e.y_max - e.y_min);
                let (zk, zf) = (k.elevation(x, y).unwrap(), f.elevation(x, y).unwrap());
                prop_assert!(zk >= zf, "({x}, {y}): field {zk} below the floor {zf}");
                if f.is_obstacle(x, y).unwrap() {
                    prop_assert!(zk >= KEEP_OUT_LIFT, "({x}, {y}): field {zk} over an obstacle");
                } else if !k.is_obstacle(x, y).unwrap() {
                    prop_assert_eq!(zk, zf);
                }
            }
        }
    }
}
