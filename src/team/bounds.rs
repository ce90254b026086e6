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

use super::model::Assembly;
use super::ranges::RANGE_MARGIN;
use super::TeamProblem;
use crate::seafloor::Extent;
use crate::trajectory::Trajectory;

/// How an infeasible C1_4 is named.
const UNDERWATER: &str = "C1_4 (AUVs stay below the surface clearance)";
/// How infeasible grid bounds are named.
const GRID: &str = "the grid bounds (every vehicle stays over the seafloor grid)";
/// How an infeasible terminal margin is named.
const TERMINAL: &str = "the terminal margin (every AUV can slow down on the grid after the window)";

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
/// (pu/vu)·v_min (m); None for an axis whose velocity no input moves (vu = 0).
fn coast(p: &TeamProblem, i: usize) -> Option<(f64, f64)> {
    let m = &p.auv;
    (m.vu[i] > 0.0).then(|| {
        let lever = m.pu[i] / m.vu[i];
        (
            m.pv[i] - lever * m.vv[i],
            lever * p.scenario.auv.min_heading_speed,
        )
    })
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
