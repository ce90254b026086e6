//! C1_1: the vehicles' dynamics as equality rows (the zero cone), per step k = 0..K:
//! the USV's eq. (9), P_USV[k+1] = P_USV[k] + δ·U_USV[k], and each AUV's discretised
//! eqs. (5)–(8), P[k+1] = P[k] + pv·V[k] + pu·U[k] and V[k+1] = vv·V[k] + vu·U[k] per axis
//! (`vehicle::AuvModel`), with eq. (8)'s ϖ term: the current c moves the AUV's position by
//! δ·c(P\[k\]) over step k, V being the velocity through the water. A uniform current is a
//! constant in b; one that varies with position (a depth profile) is linearised about the
//! reference, c(P̄\[k\]) + J·(P\[k\] − P̄\[k\]) (`CurrentField::at_and_jacobian`), and the plan
//! is re-simulated in the current itself. The window's start (k = 0) is data: its terms move
//! into b.
//!
//! The paper stacks these into the dense C1_2/C1_3 (𝔸, 𝔹); shoal keeps every state as a
//! variable and the dynamics as sparse rows, which is the same problem with a sparse KKT
//! system. The plan itself is re-simulated from the solved inputs (`TeamProblem::extract`), so
//! C1_1 holds exactly in what is written, whatever the solver's residual.

use super::model::Assembly;
use super::TeamProblem;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::ZeroConeT;

/// The zero-cone rows of C1_1 and their cone.
pub(super) fn rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let l = p.layout;
    let (kk, nn) = (l.k, l.n);
    let dt = p.scenario.horizon.dt;
    let p0 = p.start.usv;
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
    let md = &p.auv;
    let varies = p.current.varies();
    for n in 0..nn {
        let x0 = p.start.auvs[n];
        for k in 0..kk {
            // the current over step k: c(P[k]) at the fixed start, else linearised about the
            // reference, c(P̄) + J·(P − P̄) (a uniform current has J = 0 and no entries)
            let at = if k == 0 { x0.position } else { r.auv_p[n][k] };
            let (c, j) = p.current.at_and_jacobian(at);
            for i in 0..3 {
                // P[k+1] − P[k] − pv·V[k] − pu·U[k] − δ·c(P[k]) = 0
                let drift = if k == 0 || !varies {
                    dt * c[i]
                } else {
                    dt * (c[i] - (0..3).map(|jj| j[i][jj] * at[jj]).sum::<f64>())
                };
                let row = m.row(if k == 0 {
                    x0.position[i] + md.pv[i] * x0.velocity[i] + drift
                } else {
                    drift
                });
                m.a.push(row, l.auv_p(n, k + 1) + i, 1.0);
                if k > 0 {
                    if varies {
                        for jj in 0..3 {
                            let own = if jj == i { -1.0 } else { 0.0 };
                            m.a.push(row, l.auv_p(n, k) + jj, own - dt * j[i][jj]);
                        }
                    } else {
                        m.a.push(row, l.auv_p(n, k) + i, -1.0);
                    }
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
}
