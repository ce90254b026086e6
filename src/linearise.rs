//! The nonconvex pieces of P2 and P5 as smooth functions with exact gradients, so the SCP can
//! linearise them about a reference: the seafloor clearance C2_2 along a segment, the concave
//! USV objective OF1_8, a link's length and OF1_5; and the heading-rate function of C1_14,
//! whose value the SCP measures (`team::heading` builds its convex model).
//!
//! Every gradient here is checked against central finite differences by property tests.

use crate::seafloor::{Seafloor, SeafloorError};

/// Heading-rate constraint C1_14 between consecutive horizontal velocities a = V_h[k−1] and
/// b = V_h\[k\]: the angle between them must not exceed θ = ψ̇_max·δ (for θ < 90°).
///
/// With ĥ = a/‖a‖ and n̂ = ĥ rotated by +90°, the angle condition is |n̂·b| ≤ tan θ · (ĥ·b), i.e.
/// the two functions
///
///   g₊(a, b) = ( (a × b) − t (a·b) ) / ‖a‖ ≤ 0,   g₋(a, b) = ( −(a × b) − t (a·b) ) / ‖a‖ ≤ 0,
///
/// with t = tan θ and a × b = a_x b_y − a_y b_x, in m/s. `team::heading` uses max(g₊, g₋) in the
/// SCP's violation measure and builds the convex model from restrictions (no gradient of g is
/// needed: a linearisation about ā's direction was too poor at low speed).
///
/// This replaces the paper's C2_3/C2_4 (eq. (11)), which bound each velocity component by a
/// multiple of the same component one step earlier: a component that is zero (the AUVs start at
/// rest) would then stay zero for ever.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Heading {
    /// t = tan θ.
    pub tan: f64,
}

impl Heading {
    /// θ is capped at 85°: beyond 90° the cone is no longer convex, and the restriction to 85° is
    /// conservative (a plan that keeps it satisfies the real limit).
    pub fn new(max_heading_rate: f64, dt: f64) -> Heading {
        let theta = (max_heading_rate * dt).min(85f64.to_radians());
        Heading { tan: theta.tan() }
    }

    /// max(g₊, g₋): positive when the turn from a to b exceeds θ (or b points backwards).
    /// `a` must be nonzero.
    pub fn violation(&self, a: [f64; 2], b: [f64; 2]) -> f64 {
        let na = (a[0] * a[0] + a[1] * a[1]).sqrt();
        let cross = a[0] * b[1] - a[1] * b[0];
        let dot = a[0] * b[0] + a[1] * b[1];
        (cross.abs() - self.tan * dot) / na
    }
}

/// Seafloor clearance C2_2 at the point x_s = (1 − s)·P_a + s·P_b of a segment:
/// g = Z(x_s, y_s) + ε − z_s ≤ 0. Returns g and the gradient of Z at (x_s, y_s), from which
/// ∂g/∂P_a = (1 − s)(∇Z, −1) and ∂g/∂P_b = s(∇Z, −1).
pub fn floor_sample(
    floor: &Seafloor,
    clearance: f64,
    pa: [f64; 3],
    pb: [f64; 3],
    s: f64,
) -> Result<(f64, [f64; 2]), SeafloorError> {
    let p = lerp(pa, pb, s);
    let (z, grad) = floor.elevation_and_gradient(p[0], p[1])?;
    Ok((z + clearance - p[2], grad))
}

pub fn lerp(a: [f64; 3], b: [f64; 3], s: f64) -> [f64; 3] {
    [
        a[0] + s * (b[0] - a[0]),
        a[1] + s * (b[1] - a[1]),
        a[2] + s * (b[2] - a[2]),
    ]
}

/// Number of intervals the segment a→b is cut into at resolution r: the rule of the paper's 𝓛_r
/// as implemented by `Seafloor::segment_clearance` (n = max(1, ⌈horizontal length / r⌉)).
pub fn segment_intervals(a: [f64; 3], b: [f64; 3], resolution: f64) -> usize {
    let l = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
    ((l / resolution).ceil() as usize).max(1)
}

/// The concave USV term −‖d‖² of OF1_8 (d = P_USV\[K\] − P_USV\[0\]) linearised about d̄:
/// returns (value at d̄, gradient −2d̄).
pub fn usv_away(d_ref: [f64; 2]) -> (f64, [f64; 2]) {
    (
        -(d_ref[0] * d_ref[0] + d_ref[1] * d_ref[1]),
        [-2.0 * d_ref[0], -2.0 * d_ref[1]],
    )
}

/// The nearest point to `p` of the polyline through `track` (one point: that point).
/// `track` must not be empty.
pub fn nearest_on_track(p: [f64; 2], track: &[[f64; 2]]) -> [f64; 2] {
    let mut best = (f64::INFINITY, track[0]);
    for (i, a) in track.iter().enumerate() {
        let b = track.get(i + 1).unwrap_or(a);
        let (ab, ap) = ([b[0] - a[0], b[1] - a[1]], [p[0] - a[0], p[1] - a[1]]);
        let len2 = ab[0] * ab[0] + ab[1] * ab[1];
        let t = if len2 > 0.0 {
            ((ap[0] * ab[0] + ap[1] * ab[1]) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let c = [a[0] + t * ab[0], a[1] + t * ab[1]];
        let d2 = (p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2);
        if d2 < best.0 {
            best = (d2, c);
        }
    }
    best.1
}

/// OF1_8 measured from the USV's track (`usv.away_from = "track"`): −min over the polyline
/// through `track` of ‖p − q‖², linearised about p̄: returns (value at p̄, gradient −2(p̄ − c)),
/// c the nearest point of the track (the gradient of the squared distance to a convex set,
/// here the nearest segment's). With `track` one point P\[0\] it is [`usv_away`] of p̄ − P\[0\],
/// the paper's term.
pub fn usv_away_track(p: [f64; 2], track: &[[f64; 2]]) -> (f64, [f64; 2]) {
    let c = nearest_on_track(p, track);
    usv_away([p[0] - c[0], p[1] - c[1]])
}

/// The length ‖d‖ of a link (d = P_a − P_b) and its gradient, the unit direction n̂, about d̄:
/// the lower end of C5_2/C5_3 is linearised as ‖d̄‖ + n̂ᵀ(d − d̄) = n̂ᵀd. Below 1 µm the
/// direction is undefined and the x axis is used (the linearisation is then merely valid).
pub fn link_length(d_ref: [f64; 3]) -> (f64, [f64; 3]) {
    let len = (d_ref[0] * d_ref[0] + d_ref[1] * d_ref[1] + d_ref[2] * d_ref[2]).sqrt();
    let n = if len > 1e-6 {
        d_ref.map(|c| c / len)
    } else {
        [1.0, 0.0, 0.0]
    };
    (len, n)
}

/// The concave OF1_5 term −‖d‖² of a non-adjacent pair (d = P_i − P_j) linearised about d̄:
/// returns (value at d̄, gradient −2d̄).
pub fn spread(d_ref: [f64; 3]) -> (f64, [f64; 3]) {
    (
        -(d_ref[0] * d_ref[0] + d_ref[1] * d_ref[1] + d_ref[2] * d_ref[2]),
        d_ref.map(|c| -2.0 * c),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::seafloor::Lattice;
    use proptest::prelude::*;
    use std::sync::OnceLock;

    fn default_floor() -> &'static Seafloor {
        static FLOOR: OnceLock<Seafloor> = OnceLock::new();
        FLOOR.get_or_init(|| Seafloor::synthetic(&Default::default(), 1).unwrap())
    }

    fn fd2(f: impl Fn([f64; 2]) -> f64, x: [f64; 2], h: f64) -> [f64; 2] {
        [
            (f([x[0] + h, x[1]]) - f([x[0] - h, x[1]])) / (2.0 * h),
            (f([x[0], x[1] + h]) - f([x[0], x[1] - h])) / (2.0 * h),
        ]
    }

    fn fd3(f: impl Fn([f64; 3]) -> f64, x: [f64; 3], h: f64) -> [f64; 3] {
        std::array::from_fn(|i| {
            let (mut a, mut b) = (x, x);
            a[i] += h;
            b[i] -= h;
            (f(a) - f(b)) / (2.0 * h)
        })
    }

    proptest! {
        /// Step 3's linearisations (band lower end, OF1_5) against central differences.
        #[test]
        fn link_gradients_match_finite_differences(
            x in -300.0..300.0f64, y in -300.0..300.0f64, z in -150.0..150.0f64,
        ) {
            let d = [x, y, z];
            prop_assume!(x.hypot(y).hypot(z) > 1.0);
            let norm = |d: [f64; 3]| (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
            let (v, g) = link_length(d);
            prop_assert!((v - norm(d)).abs() < 1e-9);
            let fd = fd3(norm, d, 1e-4);
            for i in 0..3 {
                prop_assert!((g[i] - fd[i]).abs() < 1e-6, "{g:?} vs {fd:?}");
            }
            let (v, g) = spread(d);
            let f = |d: [f64; 3]| -norm(d).powi(2);
            prop_assert!((v - f(d)).abs() < 1e-9 * v.abs().max(1.0));
            let fd = fd3(f, d, 1e-3);
            for i in 0..3 {
                prop_assert!((g[i] - fd[i]).abs() < 1e-4 * g[i].abs().max(1.0), "{g:?} vs {fd:?}");
            }
        }

        #[test]
        fn heading_violation_is_positive_exactly_when_the_turn_is_too_sharp(
            psi in -3.1..3.1f64, turn in -1.5..1.5f64, speed in 0.2..2.0f64,
        ) {
            let h = Heading::new(0.005, 100.0); // θ = 0.5 rad
            let a = [psi.cos(), psi.sin()];
            let b = [speed * (psi + turn).cos(), speed * (psi + turn).sin()];
            let v = h.violation(a, b);
            if turn.abs() < 0.5 - 1e-6 { prop_assert!(v < 0.0); }
            if turn.abs() > 0.5 + 1e-6 { prop_assert!(v > 0.0); }
        }

        /// ∂g/∂P_b of the floor sample (s·(∇Z, −1)) against central differences, on the default
        /// synthetic floor, away from cell edges where the bilinear gradient jumps.
        #[test]
        fn floor_sample_gradient_matches_finite_differences(
            ax in -2000.0..2000.0f64, ay in -2000.0..2000.0f64,
            bx in -2000.0..2000.0f64, by in -2000.0..2000.0f64, s in 0.05..1.0f64,
        ) {
            let floor = default_floor();
            let pa = [ax, ay, -60.0];
            let pb = [bx, by, -70.0];
            let p = lerp(pa, pb, s);
            let cell = floor.dx();
            let frac = |v: f64, o: f64| ((v - o) / cell).rem_euclid(1.0);
            let h = 1e-4;
            let margin = 2.0 * h * s / cell + 1e-6;
            prop_assume!([frac(p[0], floor.x0()), frac(p[1], floor.y0())]
                .iter().all(|f| *f > margin && *f < 1.0 - margin));
            let (_, grad) = floor_sample(floor, 5.0, pa, pb, s).unwrap();
            let g = |q: [f64; 3]| floor_sample(floor, 5.0, pa, q, s).unwrap().0;
            let analytic = [s * grad[0], s * grad[1], -s];
            for i in 0..3 {
                let (mut up, mut dn) = (pb, pb);
                up[i] += h;
                dn[i] -= h;
                let fd = (g(up) - g(dn)) / (2.0 * h);
                prop_assert!((fd - analytic[i]).abs() < 1e-6, "axis {i}: fd {fd} vs {}", analytic[i]);
            }
        }

        /// The same for both ends of a segment over the keep-out field of a grid with NODATA
        /// nodes (`Seafloor::keep_out`), the field the planner's floor, USV and line-of-sight
        /// rows linearise: ∂g/∂P_a = (1 − s)(∇Z, −1), ∂g/∂P_b = s(∇Z, −1).
        #[test]
        fn keep_out_sample_gradient_matches_finite_differences(
            holes in proptest::collection::vec((0usize..12, 0usize..10), 1..6),
            a in proptest::array::uniform3(0.0..1.0f64),
            b in proptest::array::uniform3(0.0..1.0f64),
            s in 0.05..0.95f64,
        ) {
            let (nx, ny, d) = (12, 10, 20.0);
            let z = (0..nx * ny).map(|k| -60.0 + (k % nx) as f64 - 0.5 * (k / nx) as f64).collect();
            let mut nodata = vec![false; nx * ny];
            for (i, j) in holes {
                nodata[j * nx + i] = true;
            }
            let field = Seafloor::from_nodes(Lattice::new(nx, ny, 0.0, 0.0, d, d), z, nodata)
                .unwrap()
                .keep_out();
            let at = |u: [f64; 3]| [u[0] * 220.0, u[1] * 180.0, -100.0 * u[2]];
            let (pa, pb) = (at(a), at(b));
            let p = lerp(pa, pb, s);
            let h = 1e-4;
            let frac = |v: f64| (v / d).rem_euclid(1.0);
            let margin = 2.0 * h / d + 1e-6;
            prop_assume!([frac(p[0]), frac(p[1])].iter().all(|f| *f > margin && *f < 1.0 - margin));
            let (_, grad) = floor_sample(&field, 0.25, pa, pb, s).unwrap();
            for (end, weight) in [(0, 1.0 - s), (1, s)] {
                let g = |q: [f64; 3]| {
                    let (x, y) = if end == 0 { (q, pb) } else { (pa, q) };
                    floor_sample(&field, 0.25, x, y, s).unwrap().0
                };
                let base = if end == 0 { pa } else { pb };
                let analytic = [weight * grad[0], weight * grad[1], -weight];
                for i in 0..3 {
                    let (mut up, mut dn) = (base, base);
                    up[i] += h;
                    dn[i] -= h;
                    let fd = (g(up) - g(dn)) / (2.0 * h);
                    prop_assert!(
                        (fd - analytic[i]).abs() < 1e-6 * (1.0 + analytic[i].abs()),
                        "end {end} axis {i}: fd {fd} vs {}", analytic[i]
                    );
                }
            }
        }

        #[test]
        fn usv_away_track_gradient_matches_finite_differences(
            x in -3e3..3e3f64, y in -3e3..3e3f64, bx in -2e3..2e3f64, by in -2e3..2e3f64,
        ) {
            // the squared distance to one segment (a convex set) is differentiable everywhere
            let track = [[0.0, 0.0], [bx, by]];
            let (_, g) = usv_away_track([x, y], &track);
            let f = fd2(|p| usv_away_track(p, &track).0, [x, y], 1e-3);
            prop_assert!((g[0] - f[0]).abs() < 1e-4 * (1.0 + f[0].abs()));
            prop_assert!((g[1] - f[1]).abs() < 1e-4 * (1.0 + f[1].abs()));
        }

        #[test]
        fn the_track_distance_is_the_least_over_its_points(
            x in -3e3..3e3f64, y in -3e3..3e3f64, turn in -3.0..3.0f64,
        ) {
            // an L-shaped track, sampled every 0.1 m: no sample is nearer than the nearest point
            let track = [[0.0, 0.0], [1000.0, 0.0], [1000.0 + 500.0 * turn.cos(), 500.0 * turn.sin()]];
            let d2 = -usv_away_track([x, y], &track).0;
            let mut least = f64::INFINITY;
            for s in track.windows(2) {
                for i in 0..=10_000 {
                    let t = i as f64 / 10_000.0;
                    let q = [s[0][0] + t * (s[1][0] - s[0][0]), s[0][1] + t * (s[1][1] - s[0][1])];
                    least = least.min((x - q[0]).powi(2) + (y - q[1]).powi(2));
                }
            }
            prop_assert!(d2 <= least + 1e-9 * (1.0 + least));
            prop_assert!(least.sqrt() - d2.sqrt() < 0.1);
        }

        #[test]
        fn usv_away_gradient_matches_finite_differences(dx in -3e3..3e3f64, dy in -3e3..3e3f64) {
            let (_, g) = usv_away([dx, dy]);
            let f = fd2(|d| usv_away(d).0, [dx, dy], 1e-3);
            prop_assert!((g[0] - f[0]).abs() < 1e-4 * (1.0 + f[0].abs()));
            prop_assert!((g[1] - f[1]).abs() < 1e-4 * (1.0 + f[1].abs()));
        }
    }
}
