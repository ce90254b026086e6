//! A geographic grid (degrees) resampled onto a metric lattice of the local tangent plane (see
//! [`super::load`] for the rules).

use super::geo::LocalFrame;
use super::load::{
    apply, count_signs, frame_for, GridFile, LoadOptions, NodeWindow, Region, MAX_LOAD_NODES,
    MAX_WINDOW_DISTANCE,
};
use super::{Lattice, Seafloor, SeafloorError, MAX_NODES_PER_AXIS};

/// Inclusive index ranges of the metric lattice (x = i·dx, y = j·dy).
#[derive(Debug, Clone, Copy)]
struct Target {
    i0: i64,
    i1: i64,
    j0: i64,
    j1: i64,
}

impl Target {
    fn nx(&self) -> usize {
        (self.i1 - self.i0 + 1).max(0) as usize
    }
    fn ny(&self) -> usize {
        (self.j1 - self.j0 + 1).max(0) as usize
    }
    /// The lattice nodes on the boundary, as (i, j).
    fn boundary(&self) -> Vec<(i64, i64)> {
        let mut b = Vec::new();
        for i in self.i0..=self.i1 {
            b.push((i, self.j0));
            b.push((i, self.j1));
        }
        for j in self.j0..=self.j1 {
            b.push((self.i0, j));
            b.push((self.i1, j));
        }
        b
    }
}

/// 1 mm resolution for the metric spacing, so that plans show round numbers.
fn round_mm(v: f64) -> f64 {
    ((v * 1000.0).round() / 1000.0).max(0.001)
}

/// The floor, the frame's origin [lat, lon], and the (positive, negative) counts of the raw
/// values read.
type Resampled = (Seafloor, [f64; 2], (usize, usize));

pub(crate) fn geographic(
    file: &mut GridFile,
    native: &Lattice,
    opts: &LoadOptions,
    name: &str,
) -> Result<Resampled, SeafloorError> {
    let fail = |reason: String| SeafloorError::Region {
        path: name.to_string(),
        reason,
    };
    let frame =
        frame_for(native, opts.origin).map_err(|e| fail(format!("seafloor.origin: {e}")))?;
    let [me, mn] = frame.metres_per_degree();
    let (dx, dy) = (round_mm(me * native.dx), round_mm(mn * native.dy));
    let [lat0, lon0] = frame.origin();
    let too_far = |d: f64| {
        fail(format!(
            "{} reaches {:.0} km from the origin ({lat0}°, {lon0}°); the local tangent plane is \
             used within {:.0} km of it (set seafloor.origin nearer the mission)",
            match opts.region {
                Region::All => "the whole grid",
                _ => "the mission area",
            },
            d / 1e3,
            MAX_WINDOW_DISTANCE / 1e3
        ))
    };
    let exact = matches!(opts.region, Region::Nodes { .. });
    let mut t = match opts.region {
        Region::All => {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            let whole = Target {
                i0: 0,
                i1: native.nx as i64 - 1,
                j0: 0,
                j1: native.ny as i64 - 1,
            };
            for (i, j) in whole.boundary() {
                let (lon, lat) = (
                    native.x0 + i as f64 * native.dx,
                    native.y0 + j as f64 * native.dy,
                );
                let p = frame.to_local(lat, lon);
                if !frame.within_range(lat, lon) {
                    return Err(too_far(p[0].hypot(p[1])));
                }
                for d in 0..2 {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
            Target {
                i0: (lo[0] / dx).ceil() as i64,
                i1: (hi[0] / dx).floor() as i64,
                j0: (lo[1] / dy).ceil() as i64,
                j1: (hi[1] / dy).floor() as i64,
            }
        }
        Region::Area {
            x_min,
            x_max,
            y_min,
            y_max,
        } => {
            let far = [x_min.abs().max(x_max.abs()), y_min.abs().max(y_max.abs())];
            if !(far[0].is_finite() && far[1].is_finite())
                || far[0].hypot(far[1]) > MAX_WINDOW_DISTANCE
            {
                return Err(too_far(far[0].hypot(far[1])));
            }
            Target {
                i0: (x_min / dx).floor() as i64 - 1,
                i1: (x_max / dx).ceil() as i64 + 1,
                j0: (y_min / dy).floor() as i64 - 1,
                j1: (y_max / dy).ceil() as i64 + 1,
            }
        }
        Region::Nodes { x0, y0, nx, ny } => {
            let index = |v: f64, d: f64| {
                let k = (v / d).round();
                (k.abs() < 1e9 && (k * d - v).abs() <= 1e-6 * d).then_some(k as i64)
            };
            match (index(x0, dx), index(y0, dy)) {
                (Some(i0), Some(j0)) if nx >= 2 && ny >= 2 => Target {
                    i0,
                    i1: i0 + nx as i64 - 1,
                    j0,
                    j1: j0 + ny as i64 - 1,
                },
                _ => {
                    return Err(fail(format!(
                        "the local frame's lattice ({dx} × {dy} m cells at origin ({lat0}°, \
                         {lon0}°)) does not hold {nx} × {ny} nodes from ({x0}, {y0})"
                    )))
                }
            }
        }
    };
    let no_overlap = || {
        fail(
            "the mission area (around the start, in the local frame at the origin) does not \
             overlap the grid; the start must lie inside the grid"
                .to_string(),
        )
    };
    if t.nx() > MAX_NODES_PER_AXIS
        || t.ny() > MAX_NODES_PER_AXIS
        || t.nx() * t.ny() > MAX_LOAD_NODES
    {
        return Err(fail(format!(
            "the area needs {} × {} nodes of {dx} × {dy} m; at most {MAX_NODES_PER_AXIS} per axis \
             and {MAX_LOAD_NODES} in all",
            t.nx(),
            t.ny()
        )));
    }
    if t.nx() < 2 || t.ny() < 2 {
        return Err(no_overlap());
    }
    for (i, j) in [(t.i0, t.j0), (t.i1, t.j1), (t.i0, t.j1), (t.i1, t.j0)] {
        let d = (i as f64 * dx).hypot(j as f64 * dy);
        if d > MAX_WINDOW_DISTANCE {
            return Err(too_far(d));
        }
    }
    // The native nodes the lattice needs: the bounding box of its boundary's preimage, plus one.
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for (i, j) in t.boundary() {
        let [lat, lon] = frame
            .to_geographic(i as f64 * dx, j as f64 * dy)
            .ok_or_else(|| too_far((i as f64 * dx).hypot(j as f64 * dy)))?;
        let u = [(lon - native.x0) / native.dx, (lat - native.y0) / native.dy];
        for d in 0..2 {
            lo[d] = lo[d].min(u[d]);
            hi[d] = hi[d].max(u[d]);
        }
    }
    let range = |lo: f64, hi: f64, n: usize| {
        let (a, b) = (lo.floor() - 1.0, hi.ceil() + 1.0);
        (b >= 0.0 && a <= (n - 1) as f64).then(|| (a.max(0.0) as usize, (b as usize).min(n - 1)))
    };
    let (Some((ci0, ci1)), Some((cj0, cj1))) = (
        range(lo[0], hi[0], native.nx),
        range(lo[1], hi[1], native.ny),
    ) else {
        return Err(no_overlap());
    };
    if ci1 == ci0 || cj1 == cj0 {
        return Err(no_overlap());
    }
    let win = NodeWindow {
        i0: ci0,
        j0: cj0,
        nx: ci1 - ci0 + 1,
        ny: cj1 - cj0 + 1,
    };
    let (mut src, src_nd) = file.read(win)?;
    let signs = count_signs(&src, &src_nd);
    apply(opts.values, &mut src);
    let s = Source {
        native,
        win,
        z: &src,
        nodata: &src_nd,
    };

    // Resample every node of the lattice; then drop border lines that fall outside the grid.
    let (nx, ny) = (t.nx(), t.ny());
    // Node (i, j) of the lattice is at ((i0 + i)·dx, (j0 + j)·dy), computed from its global
    // index so that a node's value does not depend on the window it was loaded in.
    let mut z = vec![0.0; nx * ny];
    let mut nd = vec![false; nx * ny];
    let mut out = vec![false; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let k = j * nx + i;
            let (x, y) = ((t.i0 + i as i64) as f64 * dx, (t.j0 + j as i64) as f64 * dy);
            match s.sample(&frame, x, y) {
                Some(Some(v)) => z[k] = v,
                Some(None) => nd[k] = true,
                None => out[k] = true,
            }
        }
    }
    let (mut a, mut b, mut c, mut d) = (0, nx - 1, 0, ny - 1); // i range a..=b, j range c..=d
    if !exact {
        // The nodes inside the grid, then border lines with nodes outside it dropped, the line
        // with the largest share of such nodes first (the footprint's edges are slightly
        // curved in the frame).
        let inside: Vec<(usize, usize)> = (0..nx * ny)
            .filter(|&k| !out[k])
            .map(|k| (k % nx, k / nx))
            .collect();
        if inside.is_empty() {
            return Err(no_overlap());
        }
        a = inside.iter().map(|p| p.0).min().unwrap_or(0);
        b = inside.iter().map(|p| p.0).max().unwrap_or(0);
        c = inside.iter().map(|p| p.1).min().unwrap_or(0);
        d = inside.iter().map(|p| p.1).max().unwrap_or(0);
        loop {
            if b <= a || d <= c {
                return Err(no_overlap());
            }
            let col =
                |i: usize| (c..=d).filter(|&j| out[j * nx + i]).count() as f64 / (d - c + 1) as f64;
            let row =
                |j: usize| (a..=b).filter(|&i| out[j * nx + i]).count() as f64 / (b - a + 1) as f64;
            let shares = [col(a), col(b), row(c), row(d)];
            let (side, &worst) =
                shares
                    .iter()
                    .enumerate()
                    .fold((0, &0.0), |m, (k, v)| if *v > *m.1 { (k, v) } else { m });
            if worst == 0.0 {
                break;
            }
            match side {
                0 => a += 1,
                1 => b -= 1,
                2 => c += 1,
                _ => d -= 1,
            }
        }
        t.i0 += a as i64;
        t.j0 += c as i64;
    }
    let (mx, my) = (b - a + 1, d - c + 1);
    let mut zz = Vec::with_capacity(mx * my);
    let mut mm = Vec::with_capacity(mx * my);
    for j in c..=d {
        for i in a..=b {
            let k = j * nx + i;
            zz.push(z[k]);
            mm.push(nd[k] || out[k]);
        }
    }
    let floor = Seafloor::from_nodes(
        Lattice::new(mx, my, t.i0 as f64 * dx, t.j0 as f64 * dy, dx, dy),
        zz,
        mm,
    )
    .map_err(|e| fail(format!("the resampled grid: {e}")))?;
    Ok((floor, frame.origin(), signs))
}

/// The native window read, with the values already in elevations.
struct Source<'a> {
    native: &'a Lattice,
    win: NodeWindow,
    z: &'a [f64],
    nodata: &'a [bool],
}

impl Source<'_> {
    /// The bilinear value at frame point (x, y): None outside the grid, Some(None) at NODATA
    /// (any of the four native nodes), land (≥ 0) if any of the four is land.
    fn sample(&self, frame: &LocalFrame, x: f64, y: f64) -> Option<Option<f64>> {
        let [lat, lon] = frame.to_geographic(x, y)?;
        let n = self.native;
        let w = self.win;
        let local = |g: f64, k0: usize, len: usize| -> Option<(usize, f64)> {
            let u = g - k0 as f64;
            let last = (len - 1) as f64;
            if !(-1e-9..=last + 1e-9).contains(&u) {
                return None;
            }
            let u = u.clamp(0.0, last);
            let c = (u.floor() as usize).min(len - 2);
            Some((c, u - c as f64))
        };
        let (i, t) = local((lon - n.x0) / n.dx, w.i0, w.nx)?;
        let (j, s) = local((lat - n.y0) / n.dy, w.j0, w.ny)?;
        let k = j * w.nx + i;
        let ks = [k, k + 1, k + w.nx, k + w.nx + 1];
        if ks.iter().any(|&k| self.nodata[k]) {
            return Some(None);
        }
        let [z00, z10, z01, z11] = ks.map(|k| self.z[k]);
        let south = (1.0 - t) * z00 + t * z10;
        let north = (1.0 - t) * z01 + t * z11;
        let v = (1.0 - s) * south + s * north;
        let land = [z00, z10, z01, z11].iter().any(|&z| z >= 0.0);
        Some(Some(if land { v.max(0.0) } else { v }))
    }
}
