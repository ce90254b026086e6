//! Where each variable of P2 sits in the solver's vector x (states, inputs and slacks; the
//! dynamics are equality rows, so x holds every state, not only the inputs).
//!
//! Per window: USV positions P_USV[1..=K] and inputs U_USV[0..K), then one block per AUV holding
//! P_n[1..=K], V_n[1..=K], U_n[0..K), the floor slacks ν_f[1..=K], heading slacks ν_h[1..=K]
//! and the squared steps of each segment's ends, τ_n[1..=K] then τ'_n[1..=K] (`team::trust`; the
//! floor rows' curvature term).
//! Step k = 0 is the window's fixed start and is not a variable. P5 (Step 3) appends, per step
//! k = 1..=K and planned link l, the slacks of its band: σ (above the upper end, C5_2/C5_3's
//! "< d_s") and ν (below the lower end, "> d_s − d_t"). Over a grid with obstacles come next
//! the slacks ν_u[1..=K] of the USV's keep-out rows; then, per planned link l and step k, the
//! slack ν_los[l][k] of its line-of-sight rows (P5 only, over every grid); after them, per
//! bridge b (P5's `bridges`), the slacks σ_b of its range and ν_b of its line of sight; then,
//! per lane pair i and step k, the shortfall h[i][k] of P5's lanes term (`lanes`), then, with
//! the lanes, per AUV n and step k, its height a[n][k] above the survey altitude, and last, per
//! AUV n and step k, the slacks of the vehicle's envelope (`depth`, `climb`, `cruise`).

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Layout {
    /// K, steps per window.
    pub k: usize,
    /// N, number of AUVs.
    pub n: usize,
    /// Planned acoustic links per step (0 for P2; N for P5: one A2U link and N − 1 A2A edges).
    pub links: usize,
    /// Whether the grid has obstacles, so that the USV has keep-out rows and their slacks.
    pub obstacles: bool,
    /// Bridges of the window (P5's `bridges`; 0 for P2), over all its steps.
    pub bridges: usize,
    /// Lane pairs of P5's lanes term (`lanes`; N − 1 with it, else 0).
    pub lane_pairs: usize,
    /// Whether the AUVs keep a separation (`separation`), with a slack per AUV and segment.
    pub separation: bool,
}

impl Layout {
    const AUV_BLOCK: usize = 13;

    pub fn variables(&self) -> usize {
        self.separation_base() + if self.separation { self.n * self.k } else { 0 }
    }
    /// Slacks per AUV and step of the vehicle's envelope: `depth`, `climb`, `cruise`.
    const ENVELOPE: usize = 3;
    fn separation_base(&self) -> usize {
        self.envelope_base() + Self::ENVELOPE * self.n * self.k
    }
    fn envelope_base(&self) -> usize {
        self.altitude_base()
            + if self.lane_pairs > 0 {
                self.n * self.k
            } else {
                0
            }
    }
    fn envelope(&self, n: usize, k: usize, which: usize) -> usize {
        debug_assert!(n < self.n && k >= 1 && k <= self.k);
        self.envelope_base() + Self::ENVELOPE * (n * self.k + (k - 1)) + which
    }
    /// ν_d\[n\]\[k\]: how far AUV n is below its depth rating at step k (`depth`), m.
    pub fn depth_slack(&self, n: usize, k: usize) -> usize {
        self.envelope(n, k, 0)
    }
    /// ν_γ\[n\]\[k\]: how far AUV n's vertical speed exceeds its flight-path angle's share
    /// at step k (`climb`), m/s.
    pub fn climb_slack(&self, n: usize, k: usize) -> usize {
        self.envelope(n, k, 1)
    }
    /// ν_c\[n\]\[k\]: how far AUV n's horizontal speed falls short of the cruise floor at
    /// step k (`cruise`), m/s.
    pub fn cruise_slack(&self, n: usize, k: usize) -> usize {
        self.envelope(n, k, 2)
    }
    /// ν_s\[n\]\[k\]: slack of AUV n's separation rows of segment k − 1 → k (`separation`),
    /// k = 1..=K.
    pub fn separation_slack(&self, n: usize, k: usize) -> usize {
        debug_assert!(self.separation && n < self.n && k >= 1 && k <= self.k);
        self.separation_base() + n * self.k + (k - 1)
    }
    fn altitude_base(&self) -> usize {
        self.lane_base() + self.lane_pairs * (self.k - 1)
    }
    /// a\[n\]\[k\]: how far AUV n flies above the survey altitude at step k (`lanes`, with its
    /// lane pairs), k = 1..=K.
    pub fn lane_altitude(&self, n: usize, k: usize) -> usize {
        debug_assert!(self.lane_pairs > 0 && n < self.n && k >= 1 && k <= self.k);
        self.altitude_base() + n * self.k + (k - 1)
    }
    fn lane_base(&self) -> usize {
        self.bridge_base() + 2 * self.bridges
    }
    /// h\[i\]\[k\]: how far lane pair i's cross-track gap falls short of the swath at step k
    /// (`lanes`), k = 1..K (not at k = K, where C1_6 gathers the team).
    pub fn lane_shortfall(&self, i: usize, k: usize) -> usize {
        debug_assert!(i < self.lane_pairs && k >= 1 && k < self.k);
        self.lane_base() + i * (self.k - 1) + (k - 1)
    }
    fn bridge_base(&self) -> usize {
        self.los_base() + self.k * self.links
    }
    fn los_base(&self) -> usize {
        self.keep_out_base() + if self.obstacles { self.k } else { 0 }
    }
    fn keep_out_base(&self) -> usize {
        self.link_base() + 2 * self.links * self.k
    }
    fn link_base(&self) -> usize {
        4 * self.k + Self::AUV_BLOCK * self.k * self.n
    }
    /// The scale of every variable for the solver (x = scale ∘ x̃, `ConicSolver::with_scale`):
    /// `position` (metres) for positions, the squared steps τ (metres, of the order of a
    /// step) and the lanes' shortfalls and altitudes (metres), 1 for the rest (velocities and inputs are of order 10⁻² to 1 in SI
    /// units already, as are the slacks).
    ///
    /// Unscaled, positions of 10²–10³ m sit beside inputs of 10⁻² m/s², and Clarabel's
    /// tolerances hold for its equilibrated problem, which leaves the small variables poorly
    /// resolved (docs/design-decisions.md, "Positions in units of d_s").
    pub fn scale(&self, position: f64) -> Vec<f64> {
        let mut d = vec![1.0; self.variables()];
        for k in 1..=self.k {
            d[self.usv_p(k)..self.usv_p(k) + 2].fill(position);
            for n in 0..self.n {
                d[self.auv_p(n, k)..self.auv_p(n, k) + 3].fill(position);
                d[self.end_square(n, k)] = position;
                d[self.start_square(n, k)] = position;
            }
            for i in 0..if k < self.k { self.lane_pairs } else { 0 } {
                d[self.lane_shortfall(i, k)] = position;
            }
            if self.lane_pairs > 0 {
                for n in 0..self.n {
                    d[self.lane_altitude(n, k)] = position;
                }
            }
        }
        d
    }

    /// σ\[l\]\[k\]: how far link l may exceed the upper end of its band at step k, k = 1..=K.
    pub fn band_upper_slack(&self, l: usize, k: usize) -> usize {
        debug_assert!(l < self.links && k >= 1 && k <= self.k);
        self.link_base() + 2 * (l * self.k + (k - 1))
    }
    /// ν\[l\]\[k\]: how far link l may fall below the lower end of its band at step k.
    pub fn band_lower_slack(&self, l: usize, k: usize) -> usize {
        self.band_upper_slack(l, k) + 1
    }
    /// ν_u\[k\]: slack of the USV's keep-out group of segment k−1 → k, k = 1..=K (only with
    /// obstacles).
    pub fn usv_slack(&self, k: usize) -> usize {
        debug_assert!(self.obstacles && k >= 1 && k <= self.k);
        self.keep_out_base() + (k - 1)
    }
    /// ν_los\[l\]\[k\]: slack of the line-of-sight rows of link l at step k, k = 1..=K (P5,
    /// over every grid).
    pub fn los_slack(&self, l: usize, k: usize) -> usize {
        debug_assert!(l < self.links && k >= 1 && k <= self.k);
        self.los_base() + l * self.k + (k - 1)
    }
    /// σ_b: how far bridge b may exceed d_s.
    pub fn bridge_slack(&self, b: usize) -> usize {
        debug_assert!(b < self.bridges);
        self.bridge_base() + 2 * b
    }
    /// ν_b: slack of bridge b's line-of-sight rows.
    pub fn bridge_los_slack(&self, b: usize) -> usize {
        self.bridge_slack(b) + 1
    }
    /// P_USV\[k\], k = 1..=K (2 entries).
    pub fn usv_p(&self, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        2 * (k - 1)
    }
    /// U_USV\[k\], k = 0..K (2 entries).
    pub fn usv_u(&self, k: usize) -> usize {
        debug_assert!(k < self.k);
        2 * self.k + 2 * k
    }
    fn base(&self, n: usize) -> usize {
        debug_assert!(n < self.n);
        4 * self.k + n * Self::AUV_BLOCK * self.k
    }
    /// P_n\[k\], k = 1..=K (3 entries).
    pub fn auv_p(&self, n: usize, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        self.base(n) + 3 * (k - 1)
    }
    /// V_n\[k\], k = 1..=K (3 entries).
    pub fn auv_v(&self, n: usize, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        self.base(n) + 3 * self.k + 3 * (k - 1)
    }
    /// U_n\[k\], k = 0..K (3 entries).
    pub fn auv_u(&self, n: usize, k: usize) -> usize {
        debug_assert!(k < self.k);
        self.base(n) + 6 * self.k + 3 * k
    }
    /// ν_f\[n\]\[k\]: slack of the floor group of segment k−1 → k, k = 1..=K.
    pub fn floor_slack(&self, n: usize, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        self.base(n) + 9 * self.k + (k - 1)
    }
    /// ν_h\[n\]\[k\]: slack of the heading group at step k, k = 1..=K.
    pub fn heading_slack(&self, n: usize, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        self.base(n) + 10 * self.k + (k - 1)
    }
    /// τ\[n\]\[k\] ≥ ‖P_n,xy\[k\] − P̄_n,xy\[k\]‖²/d_s, the squared step of the end of segment
    /// k − 1 → k, for its floor rows, k = 1..=K (`team::trust`).
    pub fn end_square(&self, n: usize, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        self.base(n) + 11 * self.k + (k - 1)
    }
    /// τ'\[n\]\[k\]: the squared step of the start of segment k − 1 → k, P_n\[k − 1\] (for
    /// k = 1, the fixed start's: 0), for its floor rows, k = 1..=K.
    pub fn start_square(&self, n: usize, k: usize) -> usize {
        debug_assert!(k >= 1 && k <= self.k);
        self.base(n) + 12 * self.k + (k - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Positions, the squared steps and the lanes' shortfalls and altitudes, and only those, are
    /// scaled.
    #[test]
    fn scale_marks_the_positions() {
        let l = Layout {
            k: 3,
            n: 2,
            links: 2,
            obstacles: true,
            bridges: 1,
            lane_pairs: 1,
            separation: true,
        };
        let d = l.scale(150.0);
        let mut positions = vec![false; l.variables()];
        for k in 1..=3 {
            positions[l.usv_p(k)] = true;
            positions[l.usv_p(k) + 1] = true;
            for n in 0..2 {
                (0..3).for_each(|i| positions[l.auv_p(n, k) + i] = true);
                positions[l.end_square(n, k)] = true;
                positions[l.start_square(n, k)] = true;
            }
            if k < 3 {
                positions[l.lane_shortfall(0, k)] = true;
            }
            positions[l.lane_altitude(0, k)] = true;
            positions[l.lane_altitude(1, k)] = true;
        }
        for (i, &p) in positions.iter().enumerate() {
            assert_eq!(d[i], if p { 150.0 } else { 1.0 }, "variable {i}");
        }
    }

    /// Every index is used exactly once, for sizes including the edge cases K = 1 and N = 1.
    #[test]
    fn indices_tile_the_variable_vector() {
        for (k, n, links, obstacles, bridges, separation) in [
            (1, 1, 0, false, 0, false),
            (1, 3, 3, true, 1, true),
            (2, 1, 1, false, 0, false),
            (20, 5, 0, true, 0, true),
            (20, 5, 5, false, 7, true),
            (20, 5, 5, true, 3, false),
            (7, 12, 12, false, 0, true),
        ] {
            // the lanes' shortfalls with a chain of two or more (links = N in P5)
            let lane_pairs = if links > 0 { n - 1 } else { 0 };
            let l = Layout {
                k,
                n,
                links,
                obstacles,
                bridges,
                lane_pairs,
                separation,
            };
            let mut seen = vec![0u8; l.variables()];
            let mut mark = |i: usize, w: usize| (i..i + w).for_each(|j| seen[j] += 1);
            for s in 1..=k {
                mark(l.usv_p(s), 2);
            }
            for s in 0..k {
                mark(l.usv_u(s), 2);
            }
            for a in 0..n {
                for s in 1..=k {
                    mark(l.auv_p(a, s), 3);
                    mark(l.auv_v(a, s), 3);
                    mark(l.floor_slack(a, s), 1);
                    mark(l.heading_slack(a, s), 1);
                    mark(l.end_square(a, s), 1);
                    mark(l.start_square(a, s), 1);
                }
                for s in 0..k {
                    mark(l.auv_u(a, s), 3);
                }
            }
            for li in 0..links {
                for s in 1..=k {
                    mark(l.band_upper_slack(li, s), 1);
                    mark(l.band_lower_slack(li, s), 1);
                }
            }
            for s in 1..=k {
                if obstacles {
                    mark(l.usv_slack(s), 1);
                }
                for li in 0..links {
                    mark(l.los_slack(li, s), 1);
                }
            }
            for b in 0..bridges {
                mark(l.bridge_slack(b), 1);
                mark(l.bridge_los_slack(b), 1);
            }
            for i in 0..lane_pairs {
                for s in 1..k {
                    mark(l.lane_shortfall(i, s), 1);
                }
            }
            for a in 0..if lane_pairs > 0 { n } else { 0 } {
                for s in 1..=k {
                    mark(l.lane_altitude(a, s), 1);
                }
            }
            for a in 0..n {
                for s in 1..=k {
                    mark(l.depth_slack(a, s), 1);
                    mark(l.climb_slack(a, s), 1);
                    mark(l.cruise_slack(a, s), 1);
                }
            }
            for a in 0..if separation { n } else { 0 } {
                for s in 1..=k {
                    mark(l.separation_slack(a, s), 1);
                }
            }
            assert!(
                seen.iter().all(|&c| c == 1),
                "K={k} N={n} links={links} obstacles={obstacles} bridges={bridges} \
                 separation={separation}"
            );
        }
    }
}
