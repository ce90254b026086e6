//! Bounds on positions, linear rows: C1_4, every AUV at least the surface clearance below the
//! surface (the paper's z < ε, with a clearance so that an AUV is never at the surface), and
//! the grid bounds: every vehicle stays over the seafloor grid, the only floor known (for the
//! USV too: past the edge, OF1_8 would drag the team off the map).
//!
//! Ours, for the receding horizon: a terminal margin from the grid's edge, with
//! `horizon.terminal_margin` (on by default) in every window but a mission's last
//! (`TeamProblem::with_terminal`). The next window starts from this one's last
//! state, and an AUV's momentum carries it on: with the default REMUS model, a step of
//! δ = 100 s moves it pv·V\[K\] ≈ 6.5 s × V\[K\] before any input acts. An AUV that ends a
//! window at the edge moving out at 1.5 m/s must then reverse within one step, which C1_14
//! forbids unless it is slower than v_min: the next window is infeasible (issue 22's lanes
//! chain found it: N = 5, seed 5, window 2, "AUV 3 turns 1.976 rad more than ψ̇_max·δ between
//! steps 0 and 1"). So each AUV's coast point c = P\[K\] + (pv − pu·vv/vu)·V\[K\], where it
//! is one step later if it brakes to rest (P\[K+1\] = c + (pu/vu)·V\[K+1\]), stays inside
//! the grid by (pu/vu)·v_min per axis: from there it can slow below v_min in the next window's
//! first step, turn freely and stay on the grid.

use super::model::{Assembly, INACTIVE};
use super::ranges::RANGE_MARGIN;
use super::TeamProblem;
use crate::seafloor::Extent;
use crate::trajectory::Trajectory;

/// How far (metres) beyond the reach of the hard rows a grid bound must lie to be padding: the
/// trust-region and speed cones hold to the solver's feasibility tolerance (10⁻⁷ relative), far
/// below this.
const REDUNDANT_MARGIN: f64 = 1.0;

/// How an infeasible C1_4 is named.
const UNDERWATER: &str = "C1_4 (AUVs stay below the surface clearance)";
/// How infeasible grid bounds are named.
const GRID: &str = "the grid bounds (every vehicle stays over the seafloor grid)";
/// How an infeasible terminal margin is named.
const TERMINAL: &str =
    "the terminal margin (every AUV can slow down, or turn round, on the grid after the window)";

/// The true violation of C1_4 and of the grid bounds by AUV n at step k, metres: how far it is
/// above the surface clearance, or outside the grid. The model holds both hard, so only a
/// first guess can violate them.
/// At k = K of a window with a terminal margin it includes how far the coast point is beyond
/// the margin.
pub(super) fn violation(p: &TeamProblem, t: &Trajectory, n: usize, k: usize) -> f64 {
    let a = t.auv_p[n][k];
    let e = p.floor.extent();
    let mut out = (e.x_min - a[0])
        .max(a[0] - e.x_max)
        .max(e.y_min - a[1])
        .max(a[1] - e.y_max);
    if p.terminal && k == p.layout.k {
        for (i, (lo, hi)) in [(e.x_min, e.x_max), (e.y_min, e.y_max)]
            .into_iter()
            .enumerate()
        {
            if let Some((gain, margin)) = coast(p, i) {
                let c = a[i] + gain * t.auv_v[n][k][i];
                out = out.max(lo + margin - c).max(c - (hi - margin));
            }
        }
    }
    (a[2] + p.scenario.auv.surface_clearance).max(out).max(0.0)
}

/// For axis i: the coast point's velocity gain pv − pu·vv/vu (s) and the terminal margin
/// (m): (pu/vu)·v_min, or with a cruise floor the radius of the first guess's turn (an AUV
/// that cannot slow down turns round instead, `turn_radius`); None for an axis whose velocity
/// no input moves (vu = 0).
fn coast(p: &TeamProblem, i: usize) -> Option<(f64, f64)> {
    let m = &p.auv;
    (m.vu[i] > 0.0).then(|| {
        let lever = m.pu[i] / m.vu[i];
        let margin = match super::guess::turn_radius(p) {
            Some(r) => r,
            None => lever * p.scenario.auv.min_heading_speed,
        };
        (m.pv[i] - lever * m.vv[i], margin)
    })
}

/// How far inside the grid's edge (m, per axis) a first guess keeps every vehicle so that
/// its AUVs meet the terminal margin: the margin plus the coast at `max_speed`; 0 in a
/// window without one.
pub(super) fn guess_inset(p: &TeamProblem) -> f64 {
    if !p.terminal {
        return 0.0;
    }
    (0..2)
        .filter_map(|i| coast(p, i))
        .map(|(gain, margin)| margin + RANGE_MARGIN + gain.abs() * p.scenario.auv.max_speed)
        .fold(0.0, f64::max)
}

/// The terminal margin of AUV n (module documentation), when the window has one: its coast
/// point inside the grid by (pu/vu)·v_min on each horizontal axis, tightened by
/// `RANGE_MARGIN` (at most to the grid's centre line).
pub(super) fn terminal(p: &TeamProblem, m: &mut Assembly, n: usize, ext: &Extent) {
    if !p.terminal {
        return;
    }
    let (kk, l) = (p.layout.k, p.layout);
    for (i, (lo, hi)) in [(ext.x_min, ext.x_max), (ext.y_min, ext.y_max)]
        .into_iter()
        .enumerate()
    {
        let Some((gain, margin)) = coast(p, i) else {
            continue;
        };
        let margin = (margin + RANGE_MARGIN).min(0.5 * (hi - lo));
        for (sign, bound) in [(1.0, hi - margin), (-1.0, -(lo + margin))] {
            let row = m.row(bound);
            m.a.push(row, l.auv_p(n, kk) + i, sign);
            m.a.push(row, l.auv_v(n, kk) + i, sign * gain);
            m.group(TERMINAL, row);
        }
    }
}

/// C1_4 for AUV n at step k: z ≤ −surface clearance (tightened by `RANGE_MARGIN`).
pub(super) fn underwater(p: &TeamProblem, m: &mut Assembly, n: usize, k: usize) {
    let z = p.layout.auv_p(n, k) + 2;
    let row = m.row(-p.scenario.auv.surface_clearance - RANGE_MARGIN);
    m.a.push(row, z, 1.0);
    m.group(UNDERWATER, row);
}

/// x_min ≤ x ≤ x_max and y_min ≤ y ≤ y_max for the (x, y) at columns `col`, `col + 1`, a
/// vehicle's position that the model's hard rows keep within `reach` (metres, horizontally) of
/// `centre`. A bound more than `reach` + [`REDUNDANT_MARGIN`] from `centre` cannot bind: its row
/// is padding (`INACTIVE`, zero coefficient, so the pattern stays).
///
/// Why not keep every row: a bound kilometres away is a slack of kilometres beside slacks of
/// metres, and the interior-point method starts far from centred. On the default window at
/// N = 5 the ten models of the SCP took 23–32 interior-point iterations each with every grid
/// row and 19–27 with the redundant ones padded, for the same optima (docs/design-decisions.md, "Far
/// grid bounds").
pub(super) fn grid(m: &mut Assembly, col: usize, ext: &Extent, centre: [f64; 2], reach: f64) {
    let far = reach + REDUNDANT_MARGIN;
    for (i, lo, hi) in [(0, ext.x_min, ext.x_max), (1, ext.y_min, ext.y_max)] {
        let c = centre[i];
        for (sign, bound, room) in [(1.0, hi, hi - c), (-1.0, -lo, c - lo)] {
            // a non-finite reference (room NaN) keeps the row
            let live = room.partial_cmp(&far) != Some(std::cmp::Ordering::Greater);
            let row = m.row(if live { bound } else { INACTIVE });
            m.a.push(row, col + i, if live { sign } else { 0.0 });
            m.group(GRID, row);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn extent() -> Extent {
        Extent {
            x_min: -1000.0,
            x_max: 1000.0,
            y_min: 0.0,
            y_max: 500.0,
        }
    }

    /// The four rows of `grid` as (coefficient, b), in the order x ≤ x_max, −x ≤ −x_min,
    /// y ≤ y_max, −y ≤ −y_min.
    fn rows(centre: [f64; 2], reach: f64) -> Vec<(f64, f64)> {
        let mut m = Assembly::new(2);
        grid(&mut m, 0, &extent(), centre, reach);
        assert_eq!((m.b.len(), m.a.len()), (4, 4), "the pattern never changes");
        (0..4).map(|i| (m.a.vals[i], m.b[i])).collect()
    }

    #[test]
    fn grid_bounds_beyond_reach_are_padding_and_the_rest_hold() {
        // 900 m from x_max, 1100 m from x_min, 100 m from y_max, 400 m from y_min; reach 300 m
        let r = rows([100.0, 400.0], 300.0);
        assert_eq!(r[0], (0.0, INACTIVE));
        assert_eq!(r[1], (0.0, INACTIVE));
        assert_eq!(r[2], (1.0, 500.0));
        assert_eq!(r[3], (0.0, INACTIVE));
        // within the margin of the reach: kept
        let r = rows([100.0, 400.0], 400.0 - 0.5 * REDUNDANT_MARGIN);
        assert_eq!(r[3], (-1.0, 0.0));
        // a centre outside the grid keeps the bound it breaks
        let r = rows([1200.0, 250.0], 10.0);
        assert_eq!(r[0], (1.0, 1000.0));
        assert_eq!(r[1], (0.0, INACTIVE));
    }

    #[test]
    fn grid_bounds_hold_for_an_unbounded_reach_or_a_non_finite_centre() {
        for r in [
            rows([0.0, 250.0], f64::INFINITY),
            rows([f64::NAN, f64::NAN], 1.0),
        ] {
            assert_eq!(
                r,
                vec![(1.0, 1000.0), (-1.0, 1000.0), (1.0, 500.0), (-1.0, 0.0)]
            );
        }
    }
}
