//! The field queries of a [`Seafloor`]: bilinear elevation and gradient, the obstacle test, and
//! the segment query 𝓛_r (see the parent module's docs for the rules they follow).

use super::{Obstacle, Seafloor, SeafloorError, SegmentClearance, MAX_SEGMENT_SAMPLES};

/// A coordinate this close to a node line (in cells) is snapped onto it.
const SNAP: f64 = 1e-9;

impl Seafloor {
    /// The cell holding (x, y) and the local coordinates (t, s) ∈ [0, 1]² in it.
    fn locate(&self, x: f64, y: f64) -> Result<Cell, SeafloorError> {
        finite("x", x)?;
        finite("y", y)?;
        if !self.contains(x, y) {
            return Err(SeafloorError::OutsideGrid {
                x,
                y,
                extent: self.extent(),
            });
        }
        let l = &self.lattice;
        let (i, t) = axis((x - l.x0) / l.dx, l.nx);
        let (j, s) = axis((y - l.y0) / l.dy, l.ny);
        let k = l.index(i, j);
        Ok(Cell {
            k,
            t,
            s,
            z00: self.z[k],
            z10: self.z[k + 1],
            z01: self.z[k + l.nx],
            z11: self.z[k + l.nx + 1],
        })
    }

    /// Bilinear elevation Z(x, y), metres.
    pub fn elevation(&self, x: f64, y: f64) -> Result<f64, SeafloorError> {
        Ok(self.locate(x, y)?.value())
    }

    /// Bilinear elevation and its gradient [∂Z/∂x, ∂Z/∂y] (dimensionless). The gradient is that
    /// of the bilinear patch of the cell holding (x, y) (see the module docs for which cell a
    /// point on a cell edge belongs to).
    pub fn elevation_and_gradient(&self, x: f64, y: f64) -> Result<(f64, [f64; 2]), SeafloorError> {
        let c = self.locate(x, y)?;
        let gx = ((1.0 - c.s) * (c.z10 - c.z00) + c.s * (c.z11 - c.z01)) / self.lattice.dx;
        let gy = ((1.0 - c.t) * (c.z01 - c.z00) + c.t * (c.z11 - c.z10)) / self.lattice.dy;
        Ok((c.value(), [gx, gy]))
    }

    /// Whether (x, y) is over an obstacle: any of the four nodes of its cell is NODATA or land
    /// (z ≥ 0).
    pub fn is_obstacle(&self, x: f64, y: f64) -> Result<bool, SeafloorError> {
        let c = self.locate(x, y)?;
        let nx = self.lattice.nx;
        Ok([c.k, c.k + 1, c.k + nx, c.k + nx + 1]
            .iter()
            .any(|&k| self.nodata[k] || self.z[k] >= 0.0))
    }

    /// Why the cell holding (x, y) is an obstacle, if it is: a NODATA node, else the highest
    /// land node (z ≥ 0); `at_point` is the floor's elevation at (x, y) itself.
    pub fn obstacle(&self, x: f64, y: f64) -> Result<Option<Obstacle>, SeafloorError> {
        let c = self.locate(x, y)?;
        let nx = self.lattice.nx;
        let ks = [c.k, c.k + 1, c.k + nx, c.k + nx + 1];
        if ks.iter().any(|&k| self.nodata[k]) {
            return Ok(Some(Obstacle::Nodata));
        }
        let highest = ks
            .iter()
            .map(|&k| self.z[k])
            .fold(f64::NEG_INFINITY, f64::max);
        Ok((highest >= 0.0).then(|| Obstacle::Land {
            highest,
            at_point: c.value(),
        }))
    }

    /// The paper's 𝓛_r: samples the straight segment a → b at n + 1 evenly spaced points
    /// (endpoints included), n = max(1, ⌈horizontal length / resolution⌉), and returns the
    /// smallest clearance z − Z(x, y) and where it occurs. Both endpoints must be inside the
    /// grid (then so is every sample); `resolution` must be positive and finite, and n at most
    /// [`MAX_SEGMENT_SAMPLES`].
    pub fn segment_clearance(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
    ) -> Result<SegmentClearance, SeafloorError> {
        self.clearance_from(a, b, resolution, 0)
    }

    /// [`Seafloor::segment_clearance`] over the half-open segment (a, b]: the samples of 𝓛_r
    /// but the first. Along a polyline each waypoint is then measured once, as the end of the
    /// segment it closes; the SCP's merit sums the violations of a vehicle's segments, and
    /// with both ends it counted a waypoint below the floor twice while the model's rows
    /// (one per waypoint) priced it once (issue 22).
    pub fn open_segment_clearance(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
    ) -> Result<SegmentClearance, SeafloorError> {
        self.clearance_from(a, b, resolution, 1)
    }

    /// The least clearance over the samples j = first..=n of 𝓛_r on a → b.
    fn clearance_from(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
        first: usize,
    ) -> Result<SegmentClearance, SeafloorError> {
        let n = self.segment_intervals(a, b, resolution)?;
        let sample = |k: usize| -> Result<SegmentClearance, SeafloorError> {
            let fraction = k as f64 / n as f64;
            let at = segment_point(a, b, fraction);
            Ok(SegmentClearance {
                min_clearance: at[2] - self.elevation(at[0], at[1])?,
                at,
                fraction,
            })
        };
        let mut best = sample(first)?;
        for k in first + 1..=n {
            let c = sample(k)?;
            if c.min_clearance < best.min_clearance {
                best = c;
            }
        }
        Ok(best)
    }

    /// n of 𝓛_r for the segment a → b, after checking its arguments (finite, both ends inside
    /// the grid, a positive resolution, n at most [`MAX_SEGMENT_SAMPLES`]).
    pub(super) fn segment_intervals(
        &self,
        a: [f64; 3],
        b: [f64; 3],
        resolution: f64,
    ) -> Result<usize, SeafloorError> {
        for (what, p) in [("segment start", a), ("segment end", b)] {
            for v in p {
                finite(what, v)?;
            }
            if !self.contains(p[0], p[1]) {
                return Err(SeafloorError::OutsideGrid {
                    x: p[0],
                    y: p[1],
                    extent: self.extent(),
                });
            }
        }
        finite("resolution", resolution)?;
        if resolution <= 0.0 {
            return Err(SeafloorError::InvalidQuery {
                what: "resolution",
                reason: format!("expected a positive length in metres, got {resolution}"),
            });
        }
        segment_samples(a, b, resolution)
    }
}

/// The four nodes of a cell and a point's local coordinates in it.
struct Cell {
    /// Storage index of the south-west node.
    k: usize,
    t: f64,
    s: f64,
    z00: f64,
    z10: f64,
    z01: f64,
    z11: f64,
}

impl Cell {
    /// Bilinear value; the (1 − t)·a + t·b form is exact at t = 0 and t = 1.
    fn value(&self) -> f64 {
        let south = (1.0 - self.t) * self.z00 + self.t * self.z10;
        let north = (1.0 - self.t) * self.z01 + self.t * self.z11;
        (1.0 - self.s) * south + self.s * north
    }
}

/// Cell index and local coordinate along one axis, for u = (coordinate − origin) / spacing in
/// [0, n − 1] (up to rounding).
fn axis(u: f64, n: usize) -> (usize, f64) {
    let r = u.round();
    let u = if (u - r).abs() <= SNAP { r } else { u };
    let i = (u.max(0.0).floor() as usize).min(n - 2);
    (i, (u - i as f64).clamp(0.0, 1.0))
}

fn finite(what: &'static str, value: f64) -> Result<(), SeafloorError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(SeafloorError::NonFinite { what, value })
    }
}

/// n of 𝓛_r: max(1, ⌈horizontal length / resolution⌉), bounded by [`MAX_SEGMENT_SAMPLES`].
fn segment_samples(a: [f64; 3], b: [f64; 3], resolution: f64) -> Result<usize, SeafloorError> {
    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = (length / resolution).ceil().max(1.0);
    if n > MAX_SEGMENT_SAMPLES as f64 {
        return Err(SeafloorError::InvalidQuery {
            what: "resolution",
            reason: format!(
                "{resolution} m would need {n} samples on a {length} m segment \
                 (at most {MAX_SEGMENT_SAMPLES})"
            ),
        });
    }
    Ok(n as usize)
}

/// a + fraction·(b − a), kept inside the segment's bounding box despite rounding so that a
/// sample of a segment inside the grid is inside the grid.
pub(super) fn segment_point(a: [f64; 3], b: [f64; 3], fraction: f64) -> [f64; 3] {
    std::array::from_fn(|d| (a[d] + fraction * (b[d] - a[d])).clamp(a[d].min(b[d]), a[d].max(b[d])))
}
