//! The convex model of P2 about a reference trajectory, as Clarabel data. The sequence of
//! (row, column) entries never depends on values, so the pattern built at the first iteration
//! serves every later one (only values change).
//!
//! Rows, in cone order:
//! - zero cone: USV dynamics eq. (9), AUV dynamics (discretised eqs. (5)–(7)) — C1_1;
//! - nonnegative: underwater C1_4, grid bounds, linearised floor clearance C2_2 (segment
//!   samples, over the keep-out field), the USV's linearised keep-out rows (over a grid with
//!   obstacles), linearised heading rate C1_14, slacks ν ≥ 0;
//! - second-order cones: USV speed, AUV speed C1_7, AUV–USV range C1_5 (k < K) and C1_6 (k = K),
//!   trust region on AUV horizontal positions (and on the USV's over a grid with obstacles),
//!   C1_14's "slow" alternatives (`heading`).

use super::heading::Piece;
use super::TeamProblem;
use crate::conic::Triplets;
use crate::linearise::{floor_sample, segment_intervals, usv_away};
use crate::planner::PlanError;
use crate::scenario::{DepthObjective, UsvObjective};
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::{self, NonnegativeConeT, SecondOrderConeT, ZeroConeT};

/// b of a padding row (0·x − ν + s = 1): always satisfied, never binding.
pub(super) const INACTIVE: f64 = 1.0;

pub(crate) struct Assembly {
    pub p: Triplets,
    pub q: Vec<f64>,
    pub a: Triplets,
    pub b: Vec<f64>,
    pub cones: Vec<SupportedConeT<f64>>,
    /// Constant of the model objective (so model merit = ½xᵀPx + qᵀx + constant).
    pub constant: f64,
    /// Groups of convex constraints by name, each with the rows whose b (a bound) disables the
    /// group when made huge: what `ConicSolver::diagnose` needs to name an infeasible one.
    pub groups: Vec<(&'static str, Vec<usize>)>,
}

impl Assembly {
    pub(crate) fn row(&mut self, b: f64) -> usize {
        self.b.push(b);
        self.b.len() - 1
    }
    /// x_min ≤ x ≤ x_max and y_min ≤ y ≤ y_max for the (x, y) at columns `col`, `col + 1`.
    fn grid_bounds(&mut self, col: usize, ext: &crate::seafloor::Extent) {
        for (c, lo, hi) in [(col, ext.x_min, ext.x_max), (col + 1, ext.y_min, ext.y_max)] {
            let row = self.row(hi);
            self.a.push(row, c, 1.0);
            self.group(GRID, row);
            let row = self.row(-lo);
            self.a.push(row, c, -1.0);
            self.group(GRID, row);
        }
    }

    /// Record `row` as a bound of the group `name`.
    fn group(&mut self, name: &'static str, row: usize) {
        match self.groups.iter_mut().find(|g| g.0 == name) {
            Some(g) => g.1.push(row),
            None => self.groups.push((name, vec![row])),
        }
    }
}

const UNDERWATER: &str = "C1_4 (AUVs stay below the surface clearance)";
const GRID: &str = "the grid bounds (every vehicle stays over the seafloor grid)";
const USV_SPEED: &str = "the USV speed limit of eq. (9)";
const AUV_SPEED: &str = "C1_7 (AUV speed limit)";
const RANGE_MAX: &str = "C1_5 (every AUV within d_max of the USV)";
const RANGE_END: &str = "C1_6 (every AUV within d_s of the USV at k = K)";
const TRUST: &str = "the trust region about the previous iterate";

impl TeamProblem<'_> {
    pub(super) fn assemble(
        &self,
        r: &Trajectory,
        radius: f64,
        penalty: f64,
    ) -> Result<Assembly, PlanError> {
        let l = self.layout;
        let (kk, nn) = (l.k, l.n);
        let s = self.scenario;
        let dt = s.horizon.dt;
        let w = &s.weights;
        let mut m = Assembly {
            p: Triplets::default(),
            q: vec![0.0; l.variables()],
            a: Triplets::default(),
            b: Vec::new(),
            cones: Vec::new(),
            constant: 0.0,
            groups: Vec::new(),
        };

        // ---- objective: w1·OF1_1 + w2·OF1_2 ± USV term + λ·slacks ----
        for n in 0..nn {
            for k in 0..kk {
                for i in 0..3 {
                    m.p.push(l.auv_u(n, k) + i, l.auv_u(n, k) + i, 2.0 * w.w1); // OF1_1
                }
            }
            for k in 1..=kk {
                let p = l.auv_p(n, k);
                m.q[p + 2] = w.w2; // OF1_2: Σ z …
                if s.weights.of1_2 == DepthObjective::Height {
                    // … − Z(x, y), linearised about the reference: height above the floor
                    let x = r.auv_p[n][k];
                    let (zr, grad) = self.floor_linearisation(x);
                    m.q[p] = -w.w2 * grad[0];
                    m.q[p + 1] = -w.w2 * grad[1];
                    m.constant -= w.w2 * (zr - grad[0] * x[0] - grad[1] * x[1]);
                }
                m.q[l.floor_slack(n, k)] = penalty;
                m.q[l.heading_slack(n, k)] = penalty * dt; // m/s → m over one step
            }
        }
        if l.obstacles {
            for k in 1..=kk {
                m.q[l.usv_slack(k)] = penalty;
                for li in 0..l.links {
                    m.q[l.los_slack(li, k)] = penalty;
                }
            }
        }
        let pk = l.usv_p(kk);
        let p0 = self.start.usv;
        match s.usv.objective {
            UsvObjective::Away => {
                // −w8·‖P[K] − P[0]‖², concave: linearised about the reference (OF1_8)
                let d_ref = sub2(r.usv_p[kk], p0);
                let (value, grad) = usv_away(d_ref);
                for i in 0..2 {
                    m.p.push(pk + i, pk + i, 0.0);
                    m.q[pk + i] = w.w8 * grad[i];
                }
                m.constant += w.w8 * (value - grad[0] * d_ref[0] - grad[1] * d_ref[1])
                    - w.w8 * (grad[0] * p0[0] + grad[1] * p0[1]);
            }
            UsvObjective::Destination => {
                // w8_2·‖P[K] − P∞‖² (OF1_8_2), convex
                let dest = s.usv.destination;
                for i in 0..2 {
                    m.p.push(pk + i, pk + i, 2.0 * w.w8_2);
                    m.q[pk + i] = -2.0 * w.w8_2 * dest[i];
                }
                m.constant += w.w8_2 * (dest[0] * dest[0] + dest[1] * dest[1]);
            }
        }

        self.p5_objective(r, &mut m); // Step 3 only

        // ---- zero cone: dynamics C1_1 ----
        let first = m.b.len();
        for k in 0..kk {
            for i in 0..2 {
                // P_USV[k+1] − P_USV[k] − δ·U_USV[k] = 0   (eq. (9))
                let row = m.row(if k == 0 { p0[i] } else { 0.0 });
                m.a.push(row, l.usv_p(k + 1) + i, 1.0);
                if k > 0 {
                    m.a.push(row, l.usv_p(k) + i, -1.0);
                }
                m.a.push(row, l.usv_u(k) + i, -dt);
            }
        }
        let md = &self.auv;
        for n in 0..nn {
            let x0 = self.start.auvs[n];
            for k in 0..kk {
                for i in 0..3 {
                    // P[k+1] − P[k] − pv·V[k] − pu·U[k] = 0
                    let row = m.row(if k == 0 {
                        x0.position[i] + md.pv[i] * x0.velocity[i]
                    } else {
                        0.0
                    });
                    m.a.push(row, l.auv_p(n, k + 1) + i, 1.0);
                    if k > 0 {
                        m.a.push(row, l.auv_p(n, k) + i, -1.0);
                        m.a.push(row, l.auv_v(n, k) + i, -md.pv[i]);
                    }
                    m.a.push(row, l.auv_u(n, k) + i, -md.pu[i]);
                    // V[k+1] − vv·V[k] − vu·U[k] = 0
                    let row = m.row(if k == 0 {
                        md.vv[i] * x0.velocity[i]
                    } else {
                        0.0
                    });
                    m.a.push(row, l.auv_v(n, k + 1) + i, 1.0);
                    if k > 0 {
                        m.a.push(row, l.auv_v(n, k) + i, -md.vv[i]);
                    }
                    m.a.push(row, l.auv_u(n, k) + i, -md.vu[i]);
                }
            }
        }
        m.cones.push(ZeroConeT(m.b.len() - first));

        // ---- nonnegative cone ----
        let first = m.b.len();
        let ext = self.floor.extent();
        for n in 0..nn {
            for k in 1..=kk {
                let z = l.auv_p(n, k) + 2;
                // C1_4: z ≤ −surface clearance
                let row = m.row(-s.auv.surface_clearance - RANGE_MARGIN);
                m.a.push(row, z, 1.0);
                m.group(UNDERWATER, row);
                // grid bounds: the floor is only known inside the grid
                m.grid_bounds(l.auv_p(n, k), &ext);
            }
        }
        // the USV stays over the known map too: past the edge, OF1_8 would drag the team out
        for k in 1..=kk {
            m.grid_bounds(l.usv_p(k), &ext);
        }
        self.floor_rows(r, &mut m)?;
        self.usv_rows(r, &mut m)?; // over a grid with obstacles
        self.los_rows(r, &mut m)?; // Step 3 over a grid with obstacles
        let pieces = self.heading_pieces(r);
        self.heading_rows(r, &pieces, &mut m);
        self.p5_rows(r, &mut m); // Step 3 only
        for n in 0..nn {
            for k in 1..=kk {
                for col in [l.floor_slack(n, k), l.heading_slack(n, k)] {
                    let row = m.row(0.0);
                    m.a.push(row, col, -1.0);
                }
            }
        }
        if l.obstacles {
            for k in 1..=kk {
                let slacks = (0..l.links).map(|li| l.los_slack(li, k));
                for col in std::iter::once(l.usv_slack(k)).chain(slacks) {
                    let row = m.row(0.0);
                    m.a.push(row, col, -1.0);
                }
            }
        }
        m.cones.push(NonnegativeConeT(m.b.len() - first));

        // ---- second-order cones ----
        for k in 0..kk {
            // ‖U_USV[k]‖ ≤ USV max speed (eq. (9))
            let row = m.row(s.usv.max_speed * (1.0 - SPEED_MARGIN));
            m.group(USV_SPEED, row);
            for i in 0..2 {
                let row = m.row(0.0);
                m.a.push(row, l.usv_u(k) + i, 1.0);
            }
            m.cones.push(SecondOrderConeT(3));
        }
        for n in 0..nn {
            for k in 1..=kk {
                // C1_7: ‖V_n[k]‖ ≤ V_max
                let row = m.row(s.auv.max_speed * (1.0 - SPEED_MARGIN));
                m.group(AUV_SPEED, row);
                for i in 0..3 {
                    let row = m.row(0.0);
                    m.a.push(row, l.auv_v(n, k) + i, 1.0);
                }
                m.cones.push(SecondOrderConeT(4));
                // C1_5 (k < K): ‖P_n − P_USV‖ ≤ d_max; C1_6 (k = K): ≤ d_s
                let (range, group) = if k == kk {
                    (s.acoustic.sonar_range, RANGE_END)
                } else {
                    (s.acoustic.max_range, RANGE_MAX)
                };
                let row = m.row(range - RANGE_MARGIN);
                m.group(group, row);
                for i in 0..3 {
                    let row = m.row(0.0);
                    m.a.push(row, l.auv_p(n, k) + i, 1.0);
                    if i < 2 {
                        m.a.push(row, l.usv_p(k) + i, -1.0);
                    }
                }
                m.cones.push(SecondOrderConeT(4));
                // trust region: ‖P_n,xy[k] − P̄_n,xy[k]‖ ≤ Δ
                let row = m.row(radius);
                m.group(TRUST, row);
                for i in 0..2 {
                    let row = m.row(r.auv_p[n][k][i]);
                    m.a.push(row, l.auv_p(n, k) + i, 1.0);
                }
                m.cones.push(SecondOrderConeT(3));
            }
        }
        if l.obstacles {
            // the USV's keep-out rows are linearised too: trust region on its positions
            for k in 1..=kk {
                let row = m.row(radius);
                m.group(TRUST, row);
                for i in 0..2 {
                    let row = m.row(r.usv_p[k][i]);
                    m.a.push(row, l.usv_p(k) + i, 1.0);
                }
                m.cones.push(SecondOrderConeT(3));
            }
        }
        self.heading_cones(&pieces, &mut m);
        self.p5_cones(&mut m); // Step 3 only
        Ok(m)
    }

    /// C2_2 linearised at the segment samples of the reference, over the keep-out field (so
    /// that no sample can lie over an obstacle cell). The samples are those of the
    /// paper's 𝓛_r (fractions j/n, j = 1..=n, n = ⌈horizontal length / r⌉); of these, the
    /// `FLOOR_ROWS` with the least clearance on the reference (spread out: a sample next to one
    /// already taken is taken last) get a row, all sharing the group's slack ν_f[n][k]. The SCP
    /// measures the true violation over every sample, so a sample left out this iteration that
    /// the step makes critical is picked up at the next one, and convergence is only declared
    /// when all of them hold. Every row touches P[k−1] and P[k], so the pattern is fixed.
    fn floor_rows(&self, r: &Trajectory, m: &mut Assembly) -> Result<(), PlanError> {
        let l = self.layout;
        // constraint tightening: the model asks for FLOOR_MARGIN more than ε, so the error of the
        // linearisation cannot leave the true constraint (measured with ε) violated at the end
        let eps = self.scenario.auv.floor_clearance + FLOOR_MARGIN;
        let res = self.scenario.acoustic.resolution;
        let mut g = Vec::new();
        for n in 0..l.n {
            for k in 1..=l.k {
                // a first guess may run past the grid's edge: linearise at the nearest point
                // inside (the grid-bound rows bring the candidate back in)
                let (pa, pb) = (self.inside(r.auv_p[n][k - 1]), self.inside(r.auv_p[n][k]));
                let used = segment_intervals(pa, pb, res);
                g.clear();
                for j in 1..=used {
                    let sj = j as f64 / used as f64;
                    g.push((floor_sample(self.keep_out, eps, pa, pb, sj)?.0, j));
                }
                let picks = pick_samples(&mut g, FLOOR_ROWS);
                for slot in 0..FLOOR_ROWS {
                    let row_data = match picks.get(slot) {
                        Some(&j) => {
                            let sj = j as f64 / used as f64;
                            let (gv, grad) = floor_sample(self.keep_out, eps, pa, pb, sj)?;
                            let c = [grad[0], grad[1], -1.0];
                            // ∇g·x − ν ≤ ∇g·x̄ − g(x̄)
                            let ps = crate::linearise::lerp(pa, pb, sj);
                            let mut rhs = c[0] * ps[0] + c[1] * ps[1] + c[2] * ps[2] - gv;
                            if k == 1 {
                                let p0 = self.start.auvs[n].position;
                                rhs -= (1.0 - sj) * (c[0] * p0[0] + c[1] * p0[1] + c[2] * p0[2]);
                            }
                            Some((sj, c, rhs))
                        }
                        None => None,
                    };
                    let (sj, c, rhs) = row_data.unwrap_or((0.0, [0.0; 3], INACTIVE));
                    let row = m.row(rhs);
                    if k > 1 {
                        for i in 0..3 {
                            m.a.push(row, l.auv_p(n, k - 1) + i, (1.0 - sj) * c[i]);
                        }
                    }
                    for i in 0..3 {
                        m.a.push(row, l.auv_p(n, k) + i, sj * c[i]);
                    }
                    m.a.push(row, l.floor_slack(n, k), -1.0);
                }
            }
        }
        Ok(())
    }

    /// The alternative of C1_14 the model keeps for each AUV n and step k = 1..=K (index
    /// k − 1), about the reference `r` (see `heading`).
    fn heading_pieces(&self, r: &Trajectory) -> Vec<Vec<Piece>> {
        (0..self.layout.n)
            .map(|n| {
                (1..=self.layout.k)
                    .map(|k| {
                        let (a, b) = (h2(r.auv_v[n][k - 1]), h2(r.auv_v[n][k]));
                        self.heading.piece(a, b, k == 1)
                    })
                    .collect()
            })
            .collect()
    }

    /// C1_14's Turn piece where the model keeps it (see `heading`): per AUV and step two rows
    /// on V_h[k−1] and two on V_h[k], all sharing ν_h[n][k] (padding rows elsewhere, so the
    /// pattern is fixed).
    fn heading_rows(&self, r: &Trajectory, pieces: &[Vec<Piece>], m: &mut Assembly) {
        let l = self.layout;
        for n in 0..l.n {
            for k in 1..=l.k {
                let a = h2(r.auv_v[n][k - 1]);
                let b = h2(r.auv_v[n][k]);
                let (rows_a, rows_b) = if pieces[n][k - 1] == Piece::Turn {
                    let (ra, rb) = self.heading.turn_rows(a, b, k == 1);
                    (ra, Some(rb))
                } else {
                    (None, None)
                };
                for (rows, kv) in [(rows_a, k - 1), (rows_b, k)] {
                    for i in 0..2 {
                        let c = rows.map_or([0.0; 2], |r| r[i]);
                        let row = m.row(if rows.is_some() { 0.0 } else { INACTIVE });
                        if kv >= 1 {
                            for (j, cj) in c.iter().enumerate() {
                                m.a.push(row, l.auv_v(n, kv) + j, *cj);
                            }
                        }
                        m.a.push(row, l.heading_slack(n, k), -1.0);
                    }
                }
            }
        }
    }

    /// C1_14's "slow" alternatives: per AUV and step k = 1..=K the cone
    /// ‖V_h,n[k]‖ ≤ v_min·(1 − SLOW_MARGIN) + ν_h[n][k] + ν_h[n][k+1], where the slack of pair k
    /// enters when it keeps `SlowAfter` and that of pair k + 1 when it keeps `SlowBefore`; a
    /// speed bound no AUV reaches (2·V_max) where neither does.
    fn heading_cones(&self, pieces: &[Vec<Piece>], m: &mut Assembly) {
        let l = self.layout;
        let loose = 2.0 * self.scenario.auv.max_speed;
        for n in 0..l.n {
            for k in 1..=l.k {
                let after = pieces[n][k - 1] == Piece::SlowAfter;
                let before = k < l.k && pieces[n][k] == Piece::SlowBefore;
                let row = m.row(if after || before {
                    self.heading.slow_bound()
                } else {
                    loose
                });
                m.a.push(row, l.heading_slack(n, k), if after { -1.0 } else { 0.0 });
                if k < l.k {
                    m.a.push(
                        row,
                        l.heading_slack(n, k + 1),
                        if before { -1.0 } else { 0.0 },
                    );
                }
                for i in 0..2 {
                    let row = m.row(0.0);
                    m.a.push(row, l.auv_v(n, k) + i, 1.0);
                }
                m.cones.push(SecondOrderConeT(3));
            }
        }
    }
}

/// Margins by which the convex model tightens the convex bounds (ranges and the surface, in
/// metres; speeds, relative), so that the solver's own residuals (up to about 1e-4 m on
/// positions of a few km, once the plan is re-simulated from its inputs) cannot leave a
/// bound violated beyond the checker's 1e-6 tolerance.
pub(crate) const RANGE_MARGIN: f64 = 1e-3;
const SPEED_MARGIN: f64 = 1e-6;

/// Extra clearance (m) the convex model asks for beyond ε (constraint tightening). 0.5 m, not
/// 0.25 m: the floor's linearisation error over a step of tens of metres is often 0.3–0.7 m,
/// and every step it broke was rejected; at 0.5 m the AUVs run 25 cm higher and the eight-seed
/// sweep of BENCHMARKS.md needs fewer iterations.
pub(super) const FLOOR_MARGIN: f64 = 0.5;

/// Floor rows per segment (see `floor_rows`).
pub(super) const FLOOR_ROWS: usize = 12;

/// Up to `count` sample indices from (g, j) pairs: largest g first, skipping a neighbour (j ± 1)
/// of one already taken until no other sample is left.
pub(super) fn pick_samples(g: &mut [(f64, usize)], count: usize) -> Vec<usize> {
    g.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut picks: Vec<usize> = Vec::with_capacity(count);
    for &(_, j) in g.iter() {
        if picks.len() == count {
            break;
        }
        if !picks.iter().any(|&p| p.abs_diff(j) <= 1) {
            picks.push(j);
        }
    }
    for &(_, j) in g.iter() {
        if picks.len() == count {
            break;
        }
        if !picks.contains(&j) {
            picks.push(j);
        }
    }
    picks
}

pub(super) fn h2(v: [f64; 3]) -> [f64; 2] {
    [v[0], v[1]]
}

fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}
