//! The planned acoustic links of a window (Step 2's output as P5 uses it) and their bands.

use crate::plan::{Band, Graph, Link};
use crate::trajectory::Trajectory;

/// Per step k = 0..=K: the A2U link first, then the A2A edges of the path, and a band for each.
/// Every step has the same number of links (N), so P5's sparsity pattern is fixed per window.
#[derive(Debug, Clone, PartialEq)]
pub struct LinkSet {
    pub links: Vec<Vec<Link>>,
    pub bands: Vec<Vec<Band>>,
}

impl LinkSet {
    /// The chain of Step 2 with every band [d_s − d_t, d_s] (C5_2, C5_3).
    pub fn from_graph(g: &Graph, sonar_range: f64, band_tolerance: f64) -> LinkSet {
        let band = Band {
            lo: sonar_range - band_tolerance,
            hi: sonar_range,
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

    /// The unweighted P5 terms of a trajectory: OF1_5 (Σ ‖P_i − P_j‖² over pairs not joined by
    /// an A2A edge), and Σ `priced_outside` for A2U links and A2A links, k = 1..=K.
    pub fn terms(&self, t: &Trajectory) -> (f64, f64, f64) {
        let (mut spread, mut a2u, mut a2a) = (0.0, 0.0, 0.0);
        let n = t.auv_p.len();
        for k in 1..self.links.len().min(t.auv_p.first().map_or(0, Vec::len)) {
            for i in 0..n {
                for j in i + 1..n {
                    if !self.adjacent(k, i, j) {
                        spread += dist2(t.auv_p[i][k], t.auv_p[j][k]);
                    }
                }
            }
            for (link, band) in self.links[k].iter().zip(&self.bands[k]) {
                let off = priced_outside(length(t, k, *link), *band);
                if link.b.is_none() {
                    a2u += off;
                } else {
                    a2a += off;
                }
            }
        }
        (spread, a2u, a2a)
    }

    /// True when AUVs i and j are joined by an A2A edge at step k.
    pub fn adjacent(&self, k: usize, i: usize, j: usize) -> bool {
        self.links[k].iter().any(|l| {
            l.b.is_some_and(|b| (l.a == i && b == j) || (l.a == j && b == i))
        })
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

/// How much more a metre above a band costs than a metre below it. Above d_s a link is out of
/// range and the chain breaks; below d_s − d_t the team only spreads less. With one price for
/// both, P5 traded range for spread: at N = 15 (seed 1) the chain broke at step 14.
pub const ABOVE_FACTOR: f64 = 100.0;

/// `ABOVE_FACTOR`·(metres above the band) + (metres below it): what w3/w4 price.
pub fn priced_outside(len: f64, band: Band) -> f64 {
    ABOVE_FACTOR * (len - band.hi).max(0.0) + (band.lo - len).max(0.0)
}

/// Metres by which `len` is outside `band` (0 inside).
pub fn outside(len: f64, band: Band) -> f64 {
    (len - band.hi).max(0.0) + (band.lo - len).max(0.0)
}

fn dist2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (0..3).map(|i| (a[i] - b[i]).powi(2)).sum()
}
