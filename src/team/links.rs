//! The link bands of P5 (Step 3, C5_2/C5_3): Step 2's planned acoustic links, each kept in its
//! band [d_s − d_t, d_s] at every step, softly, with the paper's OF1_3 (A2U) and OF1_4 (A2A)
//! pricing the metres outside. Everything of this constraint family is here: the link set, its
//! rows, its true value and its naming in messages.
//!
//! - upper end, a second-order cone per planned link and step: ‖P_a − P_b‖ ≤ hi + σ, σ ≥ 0
//!   (the USV end at z = 0);
//! - lower end, nonconvex, linearised about the reference: n̂ᵀ(P_a − P_b) ≥ lo − ν, ν ≥ 0, with
//!   n̂ the reference's unit direction (n̂ᵀd ≤ ‖d‖, so the model is conservative);
//! - objective: w3·(100σ + ν) for the A2U link (OF1_3), w4·(100σ + ν) for A2A edges (OF1_4)
//!   ([`ABOVE_FACTOR`]: out of range is worse than too close).
//!
//! Departures from the paper:
//! - The bands are on lengths in metres (the paper writes a squared norm beside d_s).
//! - The bands are soft: AUVs depart from random points at rest, and two picked as path
//!   neighbours can start 250 m apart; a hard band would make P5 infeasible. Every (step, link)
//!   left outside its band is reported in the plan (`links.out_of_band`); the hard requirement,
//!   that every AUV reaches the USV through links in range and in line of sight at every step,
//!   is verified after Step 3 and by `shoal check`.
//!
//! Links at k = 0 join the window's fixed start and are not variables.

use super::layout::Layout;
use super::model::Assembly;
use super::ranges::RANGE_MARGIN;
use super::TeamProblem;
use crate::linearise::link_length;
use crate::plan::{Band, Graph, Link};
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::SecondOrderConeT;

/// Per step k = 0..=K: the A2U link first, then the A2A edges of the path, and a band for each.
/// Every step has the same number of links (N), so P5's sparsity pattern is fixed per window.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkSet {
    /// The links of each step.
    pub links: Vec<Vec<Link>>,
    /// The band of each link of each step.
    pub bands: Vec<Vec<Band>>,
}

impl LinkSet {
    /// The chain of Step 2 with every band [top − d_t, top] (C5_2, C5_3: top = d_s; ours:
    /// ρ·d_s, `acoustic.link_margin`).
    pub fn from_graph(g: &Graph, top: f64, band_tolerance: f64) -> LinkSet {
        let band = Band {
            lo: (top - band_tolerance).max(0.0),
            hi: top,
        };
        let links: Vec<Vec<Link>> = g
            .a2u
            .iter()
            .zip(&g.a2a)
            .map(|(&a2u, edges)| {
                std::iter::once(Link { a: a2u, b: None })
                    .chain(edges.iter().map(|e| Link {
                        a: e[0],
                        b: Some(e[1]),
                    }))
                    .collect()
            })
            .collect();
        let bands = links.iter().map(|l| vec![band; l.len()]).collect();
        LinkSet { links, bands }
    }

    /// Links per step.
    pub fn per_step(&self) -> usize {
        self.links.first().map_or(0, Vec::len)
    }

    /// True when AUVs i and j are joined by an A2A edge at step k.
    pub fn adjacent(&self, k: usize, i: usize, j: usize) -> bool {
        self.links[k].iter().any(|l| {
            l.b.is_some_and(|b| (l.a == i && b == j) || (l.a == j && b == i))
        })
    }

    /// The unweighted OF1_3 and OF1_4 of a trajectory: Σ [`priced_outside`] for the A2U links
    /// and for the A2A links, k = 1..=K, each band's upper end raised to the link's least
    /// length `least[k][l]` (see [`priced_band`]).
    pub fn band_terms(&self, t: &Trajectory, least: &[Vec<f64>]) -> (f64, f64) {
        let (mut a2u, mut a2a) = (0.0, 0.0);
        for k in 1..self.links.len().min(t.auv_p.first().map_or(0, Vec::len)) {
            for (li, (link, band)) in self.links[k].iter().zip(&self.bands[k]).enumerate() {
                let band = priced_band(*band, least_at(least, k, li));
                let off = priced_outside(length(t, k, *link), band);
                if link.b.is_none() {
                    a2u += off;
                } else {
                    a2a += off;
                }
            }
        }
        (a2u, a2a)
    }
}

/// The two ends of a link at step k (the USV end at the surface, z = 0).
pub fn ends(t: &Trajectory, k: usize, link: Link) -> ([f64; 3], [f64; 3]) {
    let a = t.auv_p[link.a][k];
    let b = match link.b {
        Some(j) => t.auv_p[j][k],
        None => [t.usv_p[k][0], t.usv_p[k][1], 0.0],
    };
    (a, b)
}

/// Length of a link at step k, metres.
pub fn length(t: &Trajectory, k: usize, link: Link) -> f64 {
    let (a, b) = ends(t, k, link);
    dist2(a, b).sqrt()
}

/// "A2U link AUV 2–USV" or "A2A edge AUV 1–AUV 4": how messages name a link.
pub fn describe(link: Link) -> String {
    match link.b {
        None => format!("A2U link AUV {}–USV", link.a),
        Some(b) => format!("A2A edge AUV {}–AUV {b}", link.a),
    }
}

/// How much more a metre above a band costs than a metre below it. Above d_s a link is out of
/// range and the chain breaks; below d_s − d_t the team only spreads less. With one price for
/// both, P5 traded range for spread: at N = 15 (seed 1) the chain broke at step 14.
pub const ABOVE_FACTOR: f64 = 100.0;

/// The band whose metres OF1_3/OF1_4 price: `band` with its upper end raised to `least`, the
/// least length the link can have at its step from the window's start (`bridges::least_lengths`).
/// A link whose ends start far apart cannot be in range for its first steps whatever the plan;
/// pricing the metres no plan can avoid at `ABOVE_FACTOR`·w made P5's objective 10⁸ (issue 13's
/// draw 1016) and swamped every other term, the violations' penalties included. The band the
/// plan records, and `links.out_of_band`, keep the paper's [d_s − d_t, d_s].
pub fn priced_band(band: Band, least: f64) -> Band {
    Band {
        lo: band.lo,
        hi: band.hi.max(least),
    }
}

/// `least[k][li]`, 0 where not given.
pub(super) fn least_at(least: &[Vec<f64>], k: usize, li: usize) -> f64 {
    least.get(k).and_then(|l| l.get(li)).copied().unwrap_or(0.0)
}

/// `ABOVE_FACTOR`·(metres above the band) + (metres below it): what w3/w4 price.
pub fn priced_outside(len: f64, band: Band) -> f64 {
    ABOVE_FACTOR * (len - band.hi).max(0.0) + (band.lo - len).max(0.0)
}

/// Metres by which `len` is outside `band` (0 inside): the true violation of the band.
pub fn outside(len: f64, band: Band) -> f64 {
    (len - band.hi).max(0.0) + (band.lo - len).max(0.0)
}

pub(super) fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum()
}

/// Columns of the 3 coordinates of a link end at step k (None: the USV's fixed z = 0).
pub(super) fn end_columns(l: Layout, k: usize, auv: Option<usize>) -> [Option<usize>; 3] {
    match auv {
        Some(n) => std::array::from_fn(|i| Some(l.auv_p(n, k) + i)),
        None => [Some(l.usv_p(k)), Some(l.usv_p(k) + 1), None],
    }
}

/// The weight of a link's band slacks: w3 (A2U) or w4 (A2A).
fn band_weight(p: &TeamProblem, link: Link) -> f64 {
    let w = &p.scenario.weights;
    if link.b.is_none() {
        w.w3
    } else {
        w.w4
    }
}

/// The band slacks' prices in the model objective: w·(`ABOVE_FACTOR`·σ + ν).
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly) {
    let Some(set) = &p.links else { return };
    let l = p.layout;
    for k in 1..=l.k {
        for (li, &link) in set.links[k].iter().enumerate() {
            let w = band_weight(p, link);
            m.q[l.band_upper_slack(li, k)] = ABOVE_FACTOR * w;
            m.q[l.band_lower_slack(li, k)] = w;
        }
    }
}

/// Nonnegative-cone rows: the linearised lower ends and σ, ν ≥ 0.
pub(super) fn lower_rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) {
    let Some(set) = &p.links else { return };
    let l = p.layout;
    for k in 1..=l.k {
        for (li, (&link, band)) in set.links[k].iter().zip(&set.bands[k]).enumerate() {
            let (a, b) = ends(r, k, link);
            let (_, n) = link_length(std::array::from_fn(|c| a[c] - b[c]));
            // −n̂ᵀP_a + n̂ᵀP_b − ν ≤ −lo
            let row = m.row(-band.lo);
            for (c, col) in end_columns(l, k, Some(link.a)).iter().enumerate() {
                m.a.push(row, col.expect("AUV end"), -n[c]);
            }
            for (c, col) in end_columns(l, k, link.b).iter().enumerate() {
                if let Some(col) = col {
                    m.a.push(row, *col, n[c]);
                }
            }
            m.a.push(row, l.band_lower_slack(li, k), -1.0);
            for col in [l.band_upper_slack(li, k), l.band_lower_slack(li, k)] {
                m.nonnegative(col);
            }
        }
    }
}

/// Second-order cones: ‖P_a − P_b‖ ≤ hi + σ (hi raised to the link's least length, see
/// [`priced_band`]).
pub(super) fn upper_cones(p: &TeamProblem, m: &mut Assembly) {
    let Some(set) = &p.links else { return };
    let l = p.layout;
    for k in 1..=l.k {
        for (li, (&link, band)) in set.links[k].iter().zip(&set.bands[k]).enumerate() {
            let band = priced_band(*band, least_at(&p.least, k, li));
            // tightened like C1_6, so the solver's residual cannot leave a link at the top of
            // its band a hair beyond d_s
            cone(
                l,
                m,
                k,
                link,
                band.hi - RANGE_MARGIN,
                l.band_upper_slack(li, k),
            );
        }
    }
}

/// The cone ‖P_a − P_b‖ ≤ `hi` + σ of `link` at step k, σ in column `slack` (a planned link's
/// upper end here, a bridge's range in `bridges`).
pub(super) fn cone(l: Layout, m: &mut Assembly, k: usize, link: Link, hi: f64, slack: usize) {
    let row = m.row(hi);
    m.a.push(row, slack, -1.0);
    let ca = end_columns(l, k, Some(link.a));
    let cb = end_columns(l, k, link.b);
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
