//! The synthetic seafloor of the paper's Fig. 4(a): a gently sloping plane with seeded Gaussian
//! seamounts and valleys, rescaled to a depth range.
//!
//! Generation, for reproducibility (the same `(params, seed)` gives the same bits, hence the
//! same [`Seafloor::fingerprint`], on every machine):
//!
//! 1. Grid: `nx = ⌊size[0] / cell⌋ + 1` nodes (likewise `ny`), spacing `cell`, centred on the
//!    origin: x0 = −(nx − 1)·cell / 2. When `size` is a multiple of `cell` the grid spans
//!    exactly `size`.
//! 2. Random draws from `ChaCha8Rng::seed_from_u64(seed)`, each uniform in [lo, hi) as
//!    lo + u·(hi − lo) with u = (next_u64 >> 11)·2⁻⁵³: for each seamount, then each valley, in
//!    order: centre x and y over the node extent, height (or depth) in `relief`, σ in `radius`.
//! 3. Raw floor at each node: base_depth + slope·(x, y) + Σ ±h·exp(−|p − c|² / 2σ²), with the
//!    exponential computed from IEEE-754 basic operations only (no platform libm).
//! 4. Affine rescaling so that the floor spans exactly `depth_range` = [deepest, shallowest]:
//!    the lowest raw node becomes `deepest`, the highest `shallowest`. This keeps the shapes but
//!    makes `base_depth` immaterial and scales the slope along with the relief.

use super::{Lattice, Seafloor, SeafloorError, MAX_ABS_ELEVATION};
use rand::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// Largest number of nodes along either axis of a synthetic floor.
pub const MAX_SYNTHETIC_NODES_PER_AXIS: usize = 10_000;

/// Largest number of seamounts plus valleys.
pub const MAX_SYNTHETIC_FEATURES: usize = 10_000;

/// Parameters of the synthetic seafloor of Fig. 4(a): a gently sloping floor with seeded
/// seamounts and valleys. Generated from `seed` of the scenario; see the module docs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SyntheticParams {
    /// Extent in x and y, metres; the grid is centred on the origin (the USV's start).
    pub size: [f64; 2],
    /// Grid cell size (node spacing), metres.
    pub cell: f64,
    /// Floor elevation at the origin before rescaling, metres (negative). The rescaling to
    /// `depth_range` makes its value immaterial.
    pub base_depth: f64,
    /// Regional slope [dZ/dx, dZ/dy] before rescaling (dimensionless, metres per metre).
    pub slope: [f64; 2],
    /// Number of seamounts (Gaussian bumps rising from the floor).
    pub seamounts: usize,
    /// Number of valleys (Gaussian troughs).
    pub valleys: usize,
    /// Range [low, high] of bump heights / trough depths before rescaling, metres.
    pub relief: [f64; 2],
    /// Range [low, high] of bump / trough radii (Gaussian σ), metres.
    pub radius: [f64; 2],
    /// [deepest, shallowest], metres, both negative: the floor is mapped affinely to span
    /// exactly this range (it is not clamped).
    pub depth_range: [f64; 2],
}

impl Default for SyntheticParams {
    fn default() -> Self {
        SyntheticParams {
            size: [12_000.0, 12_000.0],
            cell: 25.0,
            base_depth: -100.0,
            slope: [-0.002, 0.001],
            seamounts: 40,
            valleys: 25,
            relief: [15.0, 45.0],
            radius: [150.0, 600.0],
            depth_range: [-140.0, -50.0],
        }
    }
}

impl SyntheticParams {
    /// Checks every parameter; returns the node counts (nx, ny).
    pub fn validate(&self) -> Result<(usize, usize), SeafloorError> {
        let bad =
            |field: &'static str, reason: String| SeafloorError::InvalidSynthetic { field, reason };
        if !(self.cell.is_finite() && self.cell > 0.0) {
            return Err(bad(
                "cell",
                format!("expected a positive length in metres, got {}", self.cell),
            ));
        }
        let mut nodes = [0; 2];
        for (n, (axis, size)) in nodes.iter_mut().zip(["x", "y"].into_iter().zip(self.size)) {
            if !(size.is_finite() && size > 0.0) {
                return Err(bad(
                    "size",
                    format!("expected positive lengths in metres, got {size} along {axis}"),
                ));
            }
            let cells = (size / self.cell + 1e-9).floor();
            if cells < 1.0 {
                return Err(bad(
                    "size",
                    format!(
                        "{size} m along {axis} is less than one cell ({} m); a grid needs at \
                         least 2 × 2 nodes",
                        self.cell
                    ),
                ));
            }
            if cells + 1.0 > MAX_SYNTHETIC_NODES_PER_AXIS as f64 {
                return Err(bad(
                    "size",
                    format!(
                        "{size} m along {axis} at cell {} m needs {} nodes; at most \
                         {MAX_SYNTHETIC_NODES_PER_AXIS} (raise cell or reduce size)",
                        self.cell,
                        cells + 1.0
                    ),
                ));
            }
            *n = cells as usize + 1;
        }
        if !self.base_depth.is_finite() {
            return Err(bad(
                "base_depth",
                format!("expected a finite elevation, got {}", self.base_depth),
            ));
        }
        if !self.slope.iter().all(|s| s.is_finite()) {
            return Err(bad(
                "slope",
                format!("expected finite slopes, got {:?}", self.slope),
            ));
        }
        let [lo, hi] = self.relief;
        if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo <= hi) {
            return Err(bad(
                "relief",
                format!(
                    "expected [low, high] with 0 ≤ low ≤ high metres, got {:?}",
                    self.relief
                ),
            ));
        }
        let [lo, hi] = self.radius;
        if !(lo.is_finite() && hi.is_finite() && 0.0 < lo && lo <= hi) {
            return Err(bad(
                "radius",
                format!(
                    "expected [low, high] with 0 < low ≤ high metres, got {:?}",
                    self.radius
                ),
            ));
        }
        let [deepest, shallowest] = self.depth_range;
        if !(-MAX_ABS_ELEVATION <= deepest && deepest <= shallowest && shallowest < 0.0) {
            return Err(bad(
                "depth_range",
                format!(
                    "expected [deepest, shallowest] with -{MAX_ABS_ELEVATION} ≤ deepest ≤ \
                     shallowest < 0 metres, got {:?}",
                    self.depth_range
                ),
            ));
        }
        if self.seamounts.saturating_add(self.valleys) > MAX_SYNTHETIC_FEATURES {
            return Err(bad(
                "seamounts",
                format!(
                    "{} seamounts and {} valleys; at most {MAX_SYNTHETIC_FEATURES} together",
                    self.seamounts, self.valleys
                ),
            ));
        }
        Ok((nodes[0], nodes[1]))
    }
}

impl Seafloor {
    /// The synthetic floor of Fig. 4(a) for `params` and `seed` (see the module docs of
    /// `seafloor::synthetic` for the exact recipe). Errors name the offending parameter.
    pub fn synthetic(params: &SyntheticParams, seed: u64) -> Result<Seafloor, SeafloorError> {
        let (nx, ny) = params.validate()?;
        let cell = params.cell;
        let x0 = -((nx - 1) as f64 * cell) / 2.0;
        let y0 = -((ny - 1) as f64 * cell) / 2.0;
        let lattice = Lattice::new(nx, ny, x0, y0, cell, cell);
        let xs: Vec<f64> = (0..nx).map(|i| lattice.x(i)).collect();
        let ys: Vec<f64> = (0..ny).map(|j| lattice.y(j)).collect();

        let mut z = Vec::with_capacity(nx * ny);
        for &y in &ys {
            z.extend(
                xs.iter()
                    .map(|&x| params.base_depth + params.slope[0] * x + params.slope[1] * y),
            );
        }

        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let (x_max, y_max) = (xs[nx - 1], ys[ny - 1]);
        let signs = std::iter::repeat(1.0)
            .take(params.seamounts)
            .chain(std::iter::repeat(-1.0).take(params.valleys));
        for sign in signs {
            let cx = uniform(&mut rng, x0, x_max);
            let cy = uniform(&mut rng, y0, y_max);
            let height = sign * uniform(&mut rng, params.relief[0], params.relief[1]);
            let sigma = uniform(&mut rng, params.radius[0], params.radius[1]);
            let two_var = 2.0 * sigma * sigma;
            // exp(−|p − c|²/2σ²) = exp(−(x − cx)²/2σ²) · exp(−(y − cy)²/2σ²); libm (pure Rust,
            // a port of musl) gives the same bits on every platform, the system exp may not
            let ex: Vec<f64> = xs
                .iter()
                .map(|&x| libm::exp(-(x - cx) * (x - cx) / two_var))
                .collect();
            for (row, &y) in z.chunks_mut(nx).zip(&ys) {
                let a = height * libm::exp(-(y - cy) * (y - cy) / two_var);
                if a != 0.0 {
                    for (v, e) in row.iter_mut().zip(&ex) {
                        *v += a * e;
                    }
                }
            }
        }

        let (lo, hi) = z
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
                (lo.min(v), hi.max(v))
            });
        if !(z.iter().all(|v| v.is_finite()) && (hi - lo).is_finite()) {
            return Err(SeafloorError::InvalidSynthetic {
                field: "slope",
                reason: "slope, relief and size give a floor too large to represent".to_string(),
            });
        }
        let [deepest, shallowest] = params.depth_range;
        if hi > lo {
            for v in &mut z {
                let t = (*v - lo) / (hi - lo);
                *v = ((1.0 - t) * deepest + t * shallowest).clamp(deepest, shallowest);
            }
        } else if deepest == shallowest {
            z.fill(deepest);
        } else {
            return Err(SeafloorError::InvalidSynthetic {
                field: "depth_range",
                reason: format!(
                    "the floor is flat before rescaling (no slope, seamounts or valleys), so it \
                     cannot span {:?}; give one depth twice, e.g. [{deepest}, {deepest}]",
                    params.depth_range
                ),
            });
        }
        Seafloor::from_nodes(lattice, z, vec![false; nx * ny])
    }
}

/// Uniform in [lo, hi) from the top 53 bits of one `next_u64` draw.
fn uniform(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    let u = (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64);
    lo + u * (hi - lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn small() -> SyntheticParams {
        SyntheticParams {
            size: [2_000.0, 1_500.0],
            cell: 50.0,
            seamounts: 6,
            valleys: 4,
            ..SyntheticParams::default()
        }
    }

    #[test]
    fn default_floor_is_centred_and_spans_the_depth_range() {
        let p = SyntheticParams::default();
        let f = Seafloor::synthetic(&p, 1).unwrap();
        assert_eq!((f.nx(), f.ny(), f.dx(), f.dy()), (481, 481, 25.0, 25.0));
        let e = f.extent();
        assert_eq!(
            (e.x_min, e.x_max, e.y_min, e.y_max),
            (-6000.0, 6000.0, -6000.0, 6000.0)
        );
        assert_eq!(f.z_range(), (-140.0, -50.0));
        assert!(!f.is_obstacle(0.0, 0.0).unwrap());
    }

    #[test]
    fn same_seed_same_floor_different_seed_different_floor() {
        let p = small();
        let a = Seafloor::synthetic(&p, 7).unwrap();
        assert_eq!(
            a.fingerprint(),
            Seafloor::synthetic(&p, 7).unwrap().fingerprint()
        );
        assert_ne!(
            a.fingerprint(),
            Seafloor::synthetic(&p, 8).unwrap().fingerprint()
        );
        let fewer = SyntheticParams {
            valleys: 3,
            ..small()
        };
        assert_ne!(
            a.fingerprint(),
            Seafloor::synthetic(&fewer, 7).unwrap().fingerprint()
        );
    }

    /// Pins the exact floor: a change here changes every recorded plan's fingerprint, and a
    /// failure on one machine only means the generator is not portable.
    #[test]
    fn floor_is_pinned_bit_for_bit() {
        let f = Seafloor::synthetic(&small(), 42).unwrap();
        assert_eq!(
            f.fingerprint(),
            "24d5b010f60189e7ac733d15ca33df1d87c51f4a7f0d8df99a9f34c2788c5f28"
        );
    }

    #[test]
    fn floor_lies_within_the_depth_range_for_many_seeds_and_shapes() {
        for seed in 0..20 {
            let p = SyntheticParams {
                size: [1_000.0 + 37.0 * seed as f64, 800.0],
                cell: 30.0,
                slope: [0.01 * (seed % 3) as f64, -0.004],
                seamounts: (seed % 5) as usize,
                valleys: (seed % 4) as usize,
                depth_range: [-300.0, -20.0 - seed as f64],
                ..SyntheticParams::default()
            };
            let f = Seafloor::synthetic(&p, seed).unwrap();
            assert_eq!(
                f.z_range(),
                (p.depth_range[0], p.depth_range[1]),
                "seed {seed}"
            );
            let e = f.extent();
            assert_eq!(e.x_min, -e.x_max);
            assert_eq!(e.y_min, -e.y_max);
            assert!(e.x_max - e.x_min <= p.size[0] && e.x_max - e.x_min > p.size[0] - p.cell);
        }
    }

    #[test]
    fn smallest_grids_work() {
        let two = SyntheticParams {
            size: [10.0, 10.0],
            cell: 10.0,
            ..small()
        };
        let f = Seafloor::synthetic(&two, 3).unwrap();
        assert_eq!((f.nx(), f.ny(), f.x0(), f.y0()), (2, 2, -5.0, -5.0));
        assert_eq!(f.z_range(), (-140.0, -50.0));
        assert!(f.elevation(0.0, 0.0).is_ok());
        // Not a multiple of the cell: the grid fits inside size, centred.
        let odd = SyntheticParams {
            size: [25.0, 19.9],
            cell: 10.0,
            ..small()
        };
        let f = Seafloor::synthetic(&odd, 3).unwrap();
        assert_eq!((f.nx(), f.ny(), f.x0(), f.y0()), (3, 2, -10.0, -5.0));
        // size/cell a hair below an integer by rounding still counts the last node.
        let tight = SyntheticParams {
            size: [0.3, 0.3],
            cell: 0.1,
            ..small()
        };
        assert_eq!(Seafloor::synthetic(&tight, 3).unwrap().nx(), 4);
    }

    #[test]
    fn flat_floor_needs_a_single_depth() {
        let flat = SyntheticParams {
            slope: [0.0, 0.0],
            seamounts: 0,
            valleys: 0,
            ..small()
        };
        let err = Seafloor::synthetic(&flat, 1).unwrap_err();
        assert!(
            matches!(
                err,
                SeafloorError::InvalidSynthetic {
                    field: "depth_range",
                    ..
                }
            ),
            "{err}"
        );
        let one = SyntheticParams {
            depth_range: [-80.0, -80.0],
            ..flat
        };
        assert_eq!(
            Seafloor::synthetic(&one, 1).unwrap().z_range(),
            (-80.0, -80.0)
        );
    }

    #[test]
    fn bad_parameters_name_the_field() {
        let cases: Vec<(&str, SyntheticParams)> = vec![
            (
                "cell",
                SyntheticParams {
                    cell: 0.0,
                    ..small()
                },
            ),
            (
                "cell",
                SyntheticParams {
                    cell: f64::NAN,
                    ..small()
                },
            ),
            (
                "cell",
                SyntheticParams {
                    cell: -25.0,
                    ..small()
                },
            ),
            (
                "size",
                SyntheticParams {
                    size: [-1.0, 100.0],
                    ..small()
                },
            ),
            (
                "size",
                SyntheticParams {
                    size: [100.0, f64::INFINITY],
                    ..small()
                },
            ),
            (
                "size",
                SyntheticParams {
                    size: [49.0, 100.0],
                    ..small()
                },
            ),
            (
                "size",
                SyntheticParams {
                    size: [100_000.0, 100.0],
                    cell: 10.0,
                    ..small()
                },
            ),
            (
                "base_depth",
                SyntheticParams {
                    base_depth: f64::NAN,
                    ..small()
                },
            ),
            (
                "slope",
                SyntheticParams {
                    slope: [0.0, f64::NAN],
                    ..small()
                },
            ),
            (
                "slope",
                SyntheticParams {
                    slope: [1e308, 1e308],
                    ..small()
                },
            ),
            (
                "relief",
                SyntheticParams {
                    relief: [45.0, 15.0],
                    ..small()
                },
            ),
            (
                "relief",
                SyntheticParams {
                    relief: [-1.0, 15.0],
                    ..small()
                },
            ),
            (
                "radius",
                SyntheticParams {
                    radius: [0.0, 100.0],
                    ..small()
                },
            ),
            (
                "radius",
                SyntheticParams {
                    radius: [600.0, 150.0],
                    ..small()
                },
            ),
            (
                "radius",
                SyntheticParams {
                    radius: [100.0, f64::NAN],
                    ..small()
                },
            ),
            (
                "depth_range",
                SyntheticParams {
                    depth_range: [-50.0, -140.0],
                    ..small()
                },
            ),
            (
                "depth_range",
                SyntheticParams {
                    depth_range: [-140.0, 0.0],
                    ..small()
                },
            ),
            (
                "depth_range",
                SyntheticParams {
                    depth_range: [-140.0, 10.0],
                    ..small()
                },
            ),
            (
                "depth_range",
                SyntheticParams {
                    depth_range: [-1e6, -50.0],
                    ..small()
                },
            ),
            (
                "depth_range",
                SyntheticParams {
                    depth_range: [f64::NAN, -50.0],
                    ..small()
                },
            ),
            (
                "seamounts",
                SyntheticParams {
                    seamounts: 9_000,
                    valleys: 2_000,
                    ..small()
                },
            ),
            (
                "seamounts",
                SyntheticParams {
                    seamounts: usize::MAX,
                    valleys: 1,
                    ..small()
                },
            ),
        ];
        for (field, p) in cases {
            let err = Seafloor::synthetic(&p, 0).unwrap_err();
            match &err {
                SeafloorError::InvalidSynthetic { field: f, .. } => assert_eq!(*f, field, "{err}"),
                _ => panic!("{field}: {err:?}"),
            }
            assert!(err.to_string().contains(field), "{err}");
        }
    }
}
