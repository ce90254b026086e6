//! The objective of the window problem: P2's OF2 = w1·OF1_1 + w2·OF1_2 − w8·OF1_8 (or with
//! w8_2·OF1_8_2 added instead), and P5's OF5 = OF2 − w5·OF1_5 plus the link bands' prices
//! w3·OF1_3 and w4·OF1_4 (`spread`, `links`): the true terms of a trajectory and their convex
//! model.
//!
//! Departures from the paper, each for a reason:
//! - OF1_8 does not depend on k, so it enters once (w8 absorbs the paper's factor K).
//! - OF1_8 measures the USV's distance from the nearest point of the path it has travelled in
//!   earlier windows (or from this window's start): `usv.away_from = "track"`, the default.
//!   In the first window that is the paper's ‖P_USV\[K\] − P_USV\[0\]‖²; in later ones the paper's
//!   form (`"window"`) lets each window head back over water already seen.
//! - OF1_1 sums the AUV inputs only: the USV's input is a velocity, not a per-mass force.
//! - By default (`weights.scaling = "per_auv"`) w1, w2 and w5 weigh OF1_1, OF1_2 and OF1_5
//!   divided by N: with the paper's sums the team's terms grow with N and OF1_8 does not, and
//!   a team of 20 barely moves.
//! - OF1_2 is the height above the floor, Σ (z − Z(x, y)), by default (`weights.of1_2 =
//!   "height"`); the paper's Σ z (`"depth"`) rewards depth, not hugging the floor. The height
//!   term and the concave OF1_8 are linearised about the reference in the model.

use super::model::Assembly;
use super::{spread, TeamProblem};
use crate::linearise::usv_away_track;
use crate::scenario::{DepthObjective, UsvObjective};
use crate::trajectory::Trajectory;

/// The unweighted objective terms for a trajectory (P2's, plus P5's when links are set).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Terms {
    /// OF1_1: Σ ‖U_n\[k\]‖², (m/s²)².
    pub energy: f64,
    /// Σ z.
    pub depth: f64,
    /// Σ (z − Z(x, y)).
    pub height: f64,
    /// OF1_8's squared distance ‖P_USV\[K\] − c‖² from the nearest point c of the track
    /// (positive; the objective subtracts it), or OF1_8_2 (‖P_USV\[K\] − P∞‖²), m².
    pub usv: f64,
    /// OF1_5: Σ_k Σ ‖P_i − P_j‖² over pairs not joined by an A2A edge at k, m².
    pub spread: f64,
    /// OF1_3 as C5_2's slack: Σ_k metres by which the A2U link is outside its band.
    pub band_a2u: f64,
    /// OF1_4 as C5_3's slack: Σ_k Σ metres by which A2A edges are outside their bands.
    pub band_a2a: f64,
    /// The lanes term (ours, `lanes`): Σ_k Σ metres by which lane neighbours' cross-track gaps
    /// fall short of the swath, and by which the AUVs fly above the survey altitude (0 without
    /// it).
    pub lanes: f64,
}

/// Unweighted objective terms of `t` (OF1_1, OF1_2, OF1_8 or OF1_8_2, and P5's).
pub(super) fn terms(p: &TeamProblem, t: &Trajectory) -> Terms {
    let energy = t
        .auv_u
        .iter()
        .flatten()
        .map(|u| u.iter().map(|c| c * c).sum::<f64>())
        .sum();
    let depth = t
        .auv_p
        .iter()
        .flat_map(|p| p[1..].iter())
        .map(|p| p[2])
        .sum();
    let height = t
        .auv_p
        .iter()
        .flat_map(|p| p[1..].iter())
        .map(|q| q[2] - p.floor_linearisation(*q).0)
        .sum();
    let (spread, band_a2u, band_a2a) = match &p.links {
        Some(links) => {
            let (a2u, a2a) = links.band_terms(t, &p.least);
            (spread::value(links, t), a2u, a2a)
        }
        None => (0.0, 0.0, 0.0),
    };
    let lanes = super::lanes::value(p, t);
    let usv = usv_unweighted(p, t.usv_p[p.layout.k]);
    Terms {
        energy,
        depth,
        height,
        usv,
        spread,
        band_a2u,
        band_a2a,
        lanes,
    }
}

/// The weighted terms of J: w1·OF1_1, w2·OF1_2, the USV term, −w5·OF1_5, w3·OF1_3, w4·OF1_4,
/// w_lanes·lanes (the last four zero without links).
/// The unweighted OF1_8 (−‖P_USV − c‖², c the track's nearest point) or OF1_8_2
/// (‖P_USV − dest‖²) with the USV at `pk`.
fn usv_unweighted(p: &TeamProblem, pk: [f64; 2]) -> f64 {
    let s = p.scenario;
    match s.usv.objective {
        UsvObjective::Away => -usv_away_track(pk, &p.track).0,
        UsvObjective::Destination => {
            let d = s.usv.destination;
            (pk[0] - d[0]).powi(2) + (pk[1] - d[1]).powi(2)
        }
    }
}

/// The USV's unweighted term `usv` weighted as the objective weighs it.
fn usv_weight(p: &TeamProblem, usv: f64) -> f64 {
    match p.scenario.usv.objective {
        UsvObjective::Away => -p.scenario.w8() * usv, // weights.w8_scaling
        UsvObjective::Destination => p.scenario.weights.w8_2 * usv,
    }
}

/// The weighted USV term with the USV at `pk` (`TeamProblem::usv_term`).
pub(super) fn usv_weighted(p: &TeamProblem, pk: [f64; 2]) -> f64 {
    usv_weight(p, usv_unweighted(p, pk))
}

pub(super) fn weighted(p: &TeamProblem, t: &Terms) -> [f64; 7] {
    let w = &p.scenario.weights;
    let usv = usv_weight(p, t.usv);
    let of1_2 = match w.of1_2 {
        DepthObjective::Height => t.height,
        DepthObjective::Depth => t.depth,
    };
    let per_auv = w.per_auv(p.layout.n); // weights.scaling
    [
        w.w1 * per_auv * t.energy,
        w.w2 * per_auv * of1_2,
        usv,
        -w.w5 * per_auv * t.spread,
        w.w3 * t.band_a2u,
        w.w4 * t.band_a2a,
        w.w_lanes * per_auv * t.lanes,
    ]
}

/// The model of OF2 about the reference `r`: w1·OF1_1 (quadratic, exact), w2·OF1_2 (the height
/// term linearised) and the USV term (OF1_8 linearised, or OF1_8_2, convex and exact).
pub(super) fn model(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let l = p.layout;
    let (kk, nn) = (l.k, l.n);
    let s = p.scenario;
    let w = &s.weights;
    // weights.scaling: each AUV's share of OF1_1 and OF1_2
    let (w1, w2) = (w.w1 * w.per_auv(nn), w.w2 * w.per_auv(nn));
    for n in 0..nn {
        for k in 0..kk {
            for i in 0..3 {
                m.p.push(l.auv_u(n, k) + i, l.auv_u(n, k) + i, 2.0 * w1); // OF1_1
            }
        }
        for k in 1..=kk {
            let col = l.auv_p(n, k);
            m.q[col + 2] = w2; // OF1_2: Σ z …
            if s.weights.of1_2 == DepthObjective::Height {
                // … − Z(x, y), linearised about the reference: height above the floor
                let x = r.auv_p[n][k];
                let (zr, grad) = p.floor_linearisation(x);
                m.q[col] = -w2 * grad[0];
                m.q[col + 1] = -w2 * grad[1];
                m.constant -= w2 * (zr - grad[0] * x[0] - grad[1] * x[1]);
            }
        }
    }
    let pk = l.usv_p(kk);
    match s.usv.objective {
        UsvObjective::Away => {
            // −w8·‖P[K] − c‖², c the nearest point of the track (P[0] alone in the first
            // window or with away_from = "window"), concave: linearised about the reference
            // (OF1_8)
            let p_ref = r.usv_p[kk];
            let (value, grad) = usv_away_track(p_ref, &p.track);
            let w8 = s.w8(); // weights.w8_scaling
            for i in 0..2 {
                m.p.push(pk + i, pk + i, 0.0);
                m.q[pk + i] = w8 * grad[i];
            }
            m.constant += w8 * (value - grad[0] * p_ref[0] - grad[1] * p_ref[1]);
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
}
