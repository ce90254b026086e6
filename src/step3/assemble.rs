//! P5's additions to the team problem's convex model (`team::assemble` calls these):
//!
//! - C5_2/C5_3 upper end, a second-order cone per planned link and step:
//!   ‖P_a − P_b‖ ≤ hi + σ, σ ≥ 0 (the USV end at z = 0);
//! - C5_2/C5_3 lower end, nonconvex, linearised about the reference: n̂ᵀ(P_a − P_b) ≥ lo − ν,
//!   ν ≥ 0, with n̂ the reference's unit direction (n̂ᵀd ≤ ‖d‖, so the model is conservative);
//! - objective: w3·(100σ + ν) for the A2U link (OF1_3), w4·(100σ + ν) for A2A edges (OF1_4)
//!   (`links::ABOVE_FACTOR`: out of range is worse than too close), and
//!   −w5·OF1_5 (concave) linearised: −w5·(‖d̄‖² + 2d̄ᵀ(d − d̄)) per non-adjacent pair.
//!
//! The paper writes the bands on squared lengths next to d_s in metres; these are lengths.
//! Links at k = 0 join the window's fixed start and are not variables.

use super::links::{ends, ABOVE_FACTOR};
use crate::linearise::{link_length, spread};
use crate::plan::Link;
use crate::team::assemble::{Assembly, RANGE_MARGIN};
use crate::team::TeamProblem;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

impl TeamProblem<'_> {
    /// The weight of a link's band slacks: w3 (A2U) or w4 (A2A).
    fn band_weight(&self, link: Link) -> f64 {
        let w = &self.scenario.weights;
        if link.b.is_none() {
            w.w3
        } else {
            w.w4
        }
    }

    /// Columns of the 3 coordinates of a link end at step k (None: the USV's fixed z = 0).
    pub(crate) fn end_columns(&self, k: usize, auv: Option<usize>) -> [Option<usize>; 3] {
        let l = self.layout;
        match auv {
            Some(n) => std::array::from_fn(|i| Some(l.auv_p(n, k) + i)),
            None => [Some(l.usv_p(k)), Some(l.usv_p(k) + 1), None],
        }
    }

    /// Band-slack penalties and the linearised OF1_5 (after P2's terms: q entries add up).
    pub(crate) fn p5_objective(&self, r: &Trajectory, m: &mut Assembly) {
        let Some(set) = &self.links else { return };
        let l = self.layout;
        let w5 = self.scenario.weights.w5;
        for k in 1..=l.k {
            for (li, &link) in set.links[k].iter().enumerate() {
                let w = self.band_weight(link);
                m.q[l.band_upper_slack(li, k)] = ABOVE_FACTOR * w;
                m.q[l.band_lower_slack(li, k)] = w;
            }
            for i in 0..l.n {
                for j in i + 1..l.n {
                    if set.adjacent(k, i, j) {
                        continue;
                    }
                    let (pi, pj) = (r.auv_p[i][k], r.auv_p[j][k]);
                    let d: [f64; 3] = std::array::from_fn(|c| pi[c] - pj[c]);
                    // w5·(value + g·(d − d̄)) with d = P_i − P_j
                    let (value, g) = spread(d);
                    for c in 0..3 {
                        m.q[l.auv_p(i, k) + c] += w5 * g[c];
                        m.q[l.auv_p(j, k) + c] -= w5 * g[c];
                    }
                    m.constant += w5 * (value - (g[0] * d[0] + g[1] * d[1] + g[2] * d[2]));
                }
            }
        }
    }

    /// Nonnegative-cone rows: the linearised lower ends and σ, ν ≥ 0.
    pub(crate) fn p5_rows(&self, r: &Trajectory, m: &mut Assembly) {
        let Some(set) = &self.links else { return };
        let l = self.layout;
        for k in 1..=l.k {
            for (li, (&link, band)) in set.links[k].iter().zip(&set.bands[k]).enumerate() {
                let (a, b) = ends(r, k, link);
                let (_, n) = link_length(std::array::from_fn(|c| a[c] - b[c]));
                // −n̂ᵀP_a + n̂ᵀP_b − ν ≤ −lo
                let row = m.row(-band.lo);
                for (c, col) in self.end_columns(k, Some(link.a)).iter().enumerate() {
                    m.a.push(row, col.expect("AUV end"), -n[c]);
                }
                for (c, col) in self.end_columns(k, link.b).iter().enumerate() {
                    if let Some(col) = col {
                        m.a.push(row, *col, n[c]);
                    }
                }
                m.a.push(row, l.band_lower_slack(li, k), -1.0);
                for col in [l.band_upper_slack(li, k), l.band_lower_slack(li, k)] {
                    let row = m.row(0.0);
                    m.a.push(row, col, -1.0);
                }
            }
        }
    }

    /// Second-order cones: ‖P_a − P_b‖ ≤ hi + σ.
    pub(crate) fn p5_cones(&self, m: &mut Assembly) {
        let Some(set) = &self.links else { return };
        let l = self.layout;
        for k in 1..=l.k {
            for (li, (&link, band)) in set.links[k].iter().zip(&set.bands[k]).enumerate() {
                // tightened like C1_6, so the solver's residual cannot leave a link at the top
                // of its band a hair beyond d_s
                let row = m.row(band.hi - RANGE_MARGIN);
                m.a.push(row, l.band_upper_slack(li, k), -1.0);
                let ca = self.end_columns(k, Some(link.a));
                let cb = self.end_columns(k, link.b);
                for c in 0..3 {
                    let row = m.row(0.0);
                    if let Some(col) = ca[c] {
                        m.a.push(row, col, -1.0);
                    }
                    if let Some(col) = cb[c] {
                        m.a.push(row, col, 1.0);
                    }
                }
                m.cones.push(SecondOrderConeT(4));
            }
        }
    }
}
