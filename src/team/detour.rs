//! A first-guess course round the obstacles of the keep-out field, for the USV (the AUVs follow
//! it in formation).
//!
//! The SCP only ever improves a reference locally: from a first guess that runs straight
//! through an obstacle, the keep-out rows push each sample out by the nearest way, the two ends
//! of a segment through the middle of a hole pull against each other, and the loop stalls with
//! the USV or an AUV inside (seen with holes of 60 to 100 m on the default mission's course).
//! So over a grid with obstacles the first guess goes round them: a shortest path on the
//! nodes of the keep-out field (A*, 8 neighbours), through nodes outside every obstacle cell,
//! each metre costing more the nearer it passes to an obstacle than `clearance` (the team's
//! extent about the USV), to the free node nearest the straight course's end.

use super::TeamProblem;
use crate::seafloor::obstacles::chamfer;
use crate::seafloor::Seafloor;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Distance (m) beyond the team's extent at which the first guess passes obstacles.
const GUESS_CLEARANCE: f64 = 50.0;

/// Extra cost per metre, relative, of a step that passes at no distance from an obstacle; it
/// falls linearly to 0 at `clearance`.
const NEAR_COST: f64 = 4.0;

/// The USV's first-guess inputs along a course from the start round the obstacles to near
/// `to` (`detour::detour`) at `speed`, keeping the team's extent (the farthest AUV from the
/// USV at the start, plus `GUESS_CLEARANCE`) from them; None if the straight course keeps
/// it already.
pub(super) fn round_obstacles(
    problem: &TeamProblem,
    to: [f64; 2],
    speed: f64,
) -> Option<Vec<[f64; 2]>> {
    let from = problem.start.usv;
    let extent = problem
        .start
        .auvs
        .iter()
        .map(|a| (a.position[0] - from[0]).hypot(a.position[1] - from[1]))
        .fold(0.0, f64::max);
    let course = detour(problem.keep_out, from, to, extent + GUESS_CLEARANCE)?;
    // walk the course at `speed`, one step of δ at a time, stopping at its end
    let dt = problem.scenario.horizon.dt;
    let mut inputs = Vec::with_capacity(problem.layout.k);
    let (mut p, mut leg) = (from, 1);
    for _ in 0..problem.layout.k {
        let mut left = speed * dt;
        let start = p;
        while left > 0.0 && leg < course.len() {
            let q = course[leg];
            let d = (q[0] - p[0]).hypot(q[1] - p[1]);
            if d <= left {
                (p, left, leg) = (q, left - d, leg + 1);
            } else {
                let t = left / d;
                p = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                left = 0.0;
            }
        }
        inputs.push([(p[0] - start[0]) / dt, (p[1] - start[1]) / dt]);
    }
    Some(inputs)
}

/// A course from `from` to near `to` round the obstacles of the keep-out field `keep_out`
/// (every obstacle cell's nodes above the surface, `Seafloor::keep_out`), keeping `clearance`
/// metres from them where it can: the polyline from `from` through grid nodes. None when the
/// straight segment already keeps that clearance (or no node is free), so the straight course
/// will do.
pub(super) fn detour(
    keep_out: &Seafloor,
    from: [f64; 2],
    to: [f64; 2],
    clearance: f64,
) -> Option<Vec<[f64; 2]>> {
    let l = keep_out.lattice();
    let (z, _) = keep_out.nodes();
    // the window of nodes the course may use: the box of `from` and `to`, widened by the
    // course's length and twice the clearance
    let length = (to[0] - from[0]).hypot(to[1] - from[1]);
    let widen = length + 2.0 * clearance;
    let span = |lo: f64, hi: f64, o: f64, d: f64, n: usize| {
        let a = ((lo - widen - o) / d).floor().clamp(0.0, (n - 1) as f64) as usize;
        let b = ((hi + widen - o) / d).ceil().clamp(0.0, (n - 1) as f64) as usize;
        (a, b - a + 1)
    };
    let (i0, nx) = span(from[0].min(to[0]), from[0].max(to[0]), l.x0, l.dx, l.nx);
    let (j0, ny) = span(from[1].min(to[1]), from[1].max(to[1]), l.y0, l.dy, l.ny);
    // wall: a node of an obstacle cell (at or above the surface in the keep-out field)
    let wall: Vec<bool> = (0..nx * ny)
        .map(|k| z[(j0 + k / nx) * l.nx + i0 + k % nx] >= 0.0)
        .collect();
    if !wall.contains(&true) {
        return None;
    }
    // distance of every node to the nearest wall node
    let free: Vec<bool> = wall.iter().map(|w| !w).collect();
    let dist = chamfer(&free, nx, ny, l.dx, l.dy);
    let pos = |k: usize| {
        [
            l.x0 + (i0 + k % nx) as f64 * l.dx,
            l.y0 + (j0 + k / nx) as f64 * l.dy,
        ]
    };
    let nearest = |p: [f64; 2]| {
        let i = ((p[0] - pos(0)[0]) / l.dx)
            .round()
            .clamp(0.0, (nx - 1) as f64) as usize;
        let j = ((p[1] - pos(0)[1]) / l.dy)
            .round()
            .clamp(0.0, (ny - 1) as f64) as usize;
        j * nx + i
    };
    // does the straight course keep the clearance? (its nodes, every half cell)
    let n = (2.0 * length / l.dx.min(l.dy)).ceil().max(1.0) as usize;
    let straight_ok = (0..=n).all(|s| {
        let t = s as f64 / n as f64;
        let k = nearest([
            from[0] + t * (to[0] - from[0]),
            from[1] + t * (to[1] - from[1]),
        ]);
        dist[k] >= clearance
    });
    if straight_ok {
        return None;
    }
    // the start: the nearest node off the walls; the goal: the node nearest `to` that keeps the
    // clearance, or failing that the farthest from any wall
    let start = nearest_where(wall.len(), &pos, from, |k| !wall[k])?;
    let goal = nearest_where(wall.len(), &pos, to, |k| dist[k] >= clearance)
        .or_else(|| (0..nx * ny).max_by(|&a, &b| dist[a].total_cmp(&dist[b])))?;
    let cost = |a: usize, b: usize| {
        let (pa, pb) = (pos(a), pos(b));
        let near = (clearance - dist[a].min(dist[b])).max(0.0) / clearance.max(1e-9);
        (pa[0] - pb[0]).hypot(pa[1] - pb[1]) * (1.0 + NEAR_COST * near)
    };
    let nodes = astar(nx, ny, &wall, start, goal, &pos, cost)?;
    Some(
        std::iter::once(from)
            .chain(nodes.into_iter().map(pos))
            .collect(),
    )
}

/// The node (of `nodes`) satisfying `ok` nearest `p` (None if none does).
fn nearest_where(
    nodes: usize,
    pos: &impl Fn(usize) -> [f64; 2],
    p: [f64; 2],
    ok: impl Fn(usize) -> bool,
) -> Option<usize> {
    (0..nodes).filter(|&k| ok(k)).min_by(|&a, &b| {
        let (qa, qb) = (pos(a), pos(b));
        let da = (qa[0] - p[0]).hypot(qa[1] - p[1]);
        let db = (qb[0] - p[0]).hypot(qb[1] - p[1]);
        da.total_cmp(&db)
    })
}

/// A queue entry: estimated total cost, node (smallest cost first).
#[derive(PartialEq)]
struct Entry(f64, usize);
impl Eq for Entry {}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// A* from `start` to `goal` over the nodes not in `wall`, 8 neighbours, with the edge `cost`
/// (at least the Euclidean length, so the straight-line heuristic is admissible). The nodes of
/// the path after `start`, up to `goal`.
fn astar(
    nx: usize,
    ny: usize,
    wall: &[bool],
    start: usize,
    goal: usize,
    pos: &impl Fn(usize) -> [f64; 2],
    cost: impl Fn(usize, usize) -> f64,
) -> Option<Vec<usize>> {
    let h = |k: usize| {
        let (p, g) = (pos(k), pos(goal));
        (p[0] - g[0]).hypot(p[1] - g[1])
    };
    let mut best = vec![f64::INFINITY; nx * ny];
    let mut from = vec![usize::MAX; nx * ny];
    let mut open = BinaryHeap::new();
    best[start] = 0.0;
    open.push(Entry(h(start), start));
    while let Some(Entry(_, k)) = open.pop() {
        if k == goal {
            let mut path = vec![goal];
            let mut c = goal;
            while from[c] != start && from[c] != usize::MAX {
                c = from[c];
                path.push(c);
            }
            path.reverse();
            return Some(path);
        }
        let (i, j) = ((k % nx) as isize, (k / nx) as isize);
        for (di, dj) in [
            (-1, -1),
            (0, -1),
            (1, -1),
            (-1, 0),
            (1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
        ] {
            let (a, b) = (i + di, j + dj);
            if a < 0 || b < 0 || a >= nx as isize || b >= ny as isize {
                continue;
            }
            let m = b as usize * nx + a as usize;
            if wall[m] {
                continue;
            }
            let c = best[k] + cost(k, m);
            if c < best[m] {
                best[m] = c;
                from[m] = k;
                open.push(Entry(c + h(m), m));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 km × 1 km floor at −50 m, 20 m cells, with a NODATA disc of 100 m at (1000, 500).
    fn holed() -> Seafloor {
        let (nx, ny, d) = (101, 51, 20.0);
        let nodata: Vec<bool> = (0..nx * ny)
            .map(|k| {
                let (x, y) = ((k % nx) as f64 * d, (k / nx) as f64 * d);
                (x - 1000.0).hypot(y - 500.0) <= 100.0
            })
            .collect();
        let lattice = crate::seafloor::Lattice::new(nx, ny, 0.0, 0.0, d, d);
        Seafloor::from_nodes(lattice, vec![-50.0; nx * ny], nodata).unwrap()
    }

    #[test]
    fn the_course_goes_round_a_hole_with_its_clearance() {
        let f = holed();
        let k = f.keep_out();
        // far from the hole: no detour
        assert_eq!(detour(&k, [100.0, 100.0], [1900.0, 100.0], 100.0), None);
        // straight through the middle: round it, 100 m clear of its walls where it can
        let path = detour(&k, [100.0, 500.0], [1900.0, 500.0], 100.0).unwrap();
        assert_eq!(path[0], [100.0, 500.0]);
        let end = *path.last().unwrap();
        assert!(
            (end[0] - 1900.0).abs() <= 20.0 && (end[1] - 500.0).abs() <= 20.0,
            "{end:?}"
        );
        for w in path.windows(2) {
            let (a, b) = ([w[0][0], w[0][1], 0.0], [w[1][0], w[1][1], 0.0]);
            assert!(f.segment_obstacle(a, b, 1.0).unwrap().is_none(), "{w:?}");
        }
        let closest = path
            .iter()
            .map(|p| (p[0] - 1000.0).hypot(p[1] - 500.0))
            .fold(f64::INFINITY, f64::min);
        assert!(closest > 200.0, "{closest}");
    }
}
