//! The floor as pictures: elevations sampled over a view, a bathymetric colour map with hill
//! shading, and contour lines (marching squares, chained into polylines).

use super::canvas::Raster;
use crate::seafloor::Seafloor;
use plotters::style::RGBColor;
use std::collections::HashMap;

/// A view of the floor: [x_min, x_max, y_min, y_max], metres.
pub(crate) type View = [f64; 4];

/// Elevations at `nx × ny` points spanning `view` corner to corner, row 0 the southernmost; NaN
/// off the grid.
pub(crate) struct Grid {
    pub nx: usize,
    pub ny: usize,
    pub view: View,
    pub z: Vec<f64>,
}

impl Grid {
    pub fn sample(floor: &Seafloor, view: View, nx: usize, ny: usize) -> Grid {
        let (nx, ny) = (nx.max(2), ny.max(2));
        let mut z = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            let y = view[2] + (view[3] - view[2]) * j as f64 / (ny - 1) as f64;
            for i in 0..nx {
                let x = view[0] + (view[1] - view[0]) * i as f64 / (nx - 1) as f64;
                z.push(elevation(floor, x, y));
            }
        }
        Grid { nx, ny, view, z }
    }

    pub fn at(&self, i: usize, j: usize) -> f64 {
        self.z[j * self.nx + i]
    }

    /// Every cell (i, j) whose four corners are on the grid, with their elevations
    /// counter-clockwise from the south-west: (i, j), (i+1, j), (i+1, j+1), (i, j+1).
    pub fn cells(&self) -> impl Iterator<Item = (usize, usize, [f64; 4])> + '_ {
        (0..self.ny - 1)
            .flat_map(move |j| (0..self.nx - 1).map(move |i| (i, j)))
            .map(|(i, j)| {
                let z = [
                    self.at(i, j),
                    self.at(i + 1, j),
                    self.at(i + 1, j + 1),
                    self.at(i, j + 1),
                ];
                (i, j, z)
            })
            .filter(|(_, _, z)| !z.iter().any(|v| v.is_nan()))
    }

    pub fn point(&self, i: f64, j: f64) -> (f64, f64) {
        let v = self.view;
        (
            v[0] + (v[1] - v[0]) * i / (self.nx - 1) as f64,
            v[2] + (v[3] - v[2]) * j / (self.ny - 1) as f64,
        )
    }
}

/// Z(x, y), or NaN off the grid (checked first: an off-grid error formats a message).
pub(crate) fn elevation(floor: &Seafloor, x: f64, y: f64) -> f64 {
    if floor.contains(x, y) {
        floor.elevation(x, y).unwrap_or(f64::NAN)
    } else {
        f64::NAN
    }
}

/// Stops of the depth colour map, deep (t = 0) to shallow (t = 1).
const STOPS: [(f64, [f64; 3]); 5] = [
    (0.0, [0x25 as f64, 0x1a as f64, 0x52 as f64]),
    (0.3, [0x3b as f64, 0x5b as f64, 0xa0 as f64]),
    (0.55, [0x3f as f64, 0x96 as f64, 0xb0 as f64]),
    (0.8, [0x7c as f64, 0xcc as f64, 0xa4 as f64]),
    (1.0, [0xf4 as f64, 0xf6 as f64, 0xc2 as f64]),
];

/// Colour of an elevation within `range` (deepest, shallowest); land (z ≥ 0) is tan.
pub(crate) fn depth_colour(z: f64, range: (f64, f64)) -> [f64; 3] {
    if z >= 0.0 {
        return [0xd2 as f64, 0xb4 as f64, 0x8c as f64];
    }
    let t = if range.1 > range.0 {
        ((z - range.0) / (range.1 - range.0)).clamp(0.0, 1.0)
    } else {
        0.5
    };
    for w in STOPS.windows(2) {
        let ((t0, c0), (t1, c1)) = (w[0], w[1]);
        if t <= t1 {
            let s = (t - t0) / (t1 - t0);
            return [0, 1, 2].map(|i| c0[i] + s * (c1[i] - c0[i]));
        }
    }
    STOPS[STOPS.len() - 1].1
}

pub(crate) fn rgb(c: [f64; 3]) -> RGBColor {
    let b = |v: f64| v.round().clamp(0.0, 255.0) as u8;
    RGBColor(b(c[0]), b(c[1]), b(c[2]))
}

/// Mix towards white by `amount` in [0, 1].
pub(crate) fn whiten(c: [f64; 3], amount: f64) -> [f64; 3] {
    c.map(|v| v + (255.0 - v) * amount)
}

/// Light factor of a surface with gradient (gx, gy) lit from the north-west, 45° up: 1 on flat
/// ground, darker on slopes facing away.
pub(crate) fn hillshade(gx: f64, gy: f64) -> f64 {
    let n = [-gx, -gy, 1.0];
    let len = (n[0] * n[0] + n[1] * n[1] + 1.0).sqrt();
    let l = [-0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2];
    let dot = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len;
    (1.0 + 0.9 * (dot - l[2])).clamp(0.55, 1.15)
}

/// Vertical exaggeration that makes the mean slope of `g` about 0.5 for the shading.
fn exaggeration(g: &Grid) -> f64 {
    let (dx, dy) = (
        (g.view[1] - g.view[0]) / (g.nx - 1) as f64,
        (g.view[3] - g.view[2]) / (g.ny - 1) as f64,
    );
    let (mut sum, mut count) = (0.0, 0usize);
    for j in 0..g.ny - 1 {
        for i in 0..g.nx - 1 {
            let s = ((g.at(i + 1, j) - g.at(i, j)) / dx).hypot((g.at(i, j + 1) - g.at(i, j)) / dy);
            if s.is_finite() {
                (sum, count) = (sum + s, count + 1);
            }
        }
    }
    if count == 0 || sum <= 0.0 {
        return 1.0;
    }
    (0.5 / (sum / count as f64)).clamp(1.0, 100.0)
}

/// The floor over `view` as a `w × h` shaded depth raster (top row north); off the grid light
/// grey. `muted` mixes it half-way to white, for drawing paths over it.
pub(crate) fn depth_raster(
    floor: &Seafloor,
    view: View,
    (w, h): (u32, u32),
    muted: bool,
) -> Raster {
    let (w, h) = (w.max(2), h.max(2));
    // Pixel centres: sample the grid one pixel beyond so gradients exist at the border.
    let (px, py) = (
        (view[1] - view[0]) / w as f64,
        (view[3] - view[2]) / h as f64,
    );
    let g = Grid::sample(
        floor,
        [
            view[0] + 0.5 * px,
            view[1] - 0.5 * px,
            view[2] + 0.5 * py,
            view[3] - 0.5 * py,
        ],
        w as usize,
        h as usize,
    );
    let ex = exaggeration(&g);
    let range = floor.z_range();
    let mut out = Vec::with_capacity(w as usize * h as usize * 3);
    for row in 0..h as usize {
        let j = h as usize - 1 - row;
        for i in 0..w as usize {
            let z = g.at(i, j);
            let c = if z.is_nan() {
                [0xee as f64; 3]
            } else {
                let d = |a: f64, b: f64, s: f64| {
                    if (a - b).is_finite() {
                        (a - b) / s
                    } else {
                        0.0
                    }
                };
                let (i0, i1) = (i.saturating_sub(1), (i + 1).min(w as usize - 1));
                let (j0, j1) = (j.saturating_sub(1), (j + 1).min(h as usize - 1));
                let gx = d(g.at(i1, j), g.at(i0, j), (i1 - i0) as f64 * px);
                let gy = d(g.at(i, j1), g.at(i, j0), (j1 - j0) as f64 * py);
                let shade = hillshade(ex * gx, ex * gy);
                if muted {
                    // Half the relief and half-way to white, for drawing paths over it.
                    let shade = 1.0 + 0.5 * (shade - 1.0);
                    whiten(depth_colour(z, range).map(|v| v * shade), 0.5)
                } else {
                    depth_colour(z, range).map(|v| v * shade)
                }
            };
            let RGBColor(r, gr, b) = rgb(c);
            out.extend([r, gr, b]);
        }
    }
    Raster {
        width: w,
        height: h,
        rgb: out,
    }
}

/// A round contour interval giving about `target` levels over `range`.
pub(crate) fn nice_step(range: f64, target: f64) -> f64 {
    if !(range.is_finite() && range > 0.0) {
        return 1.0;
    }
    let raw = range / target;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    let nice = if f < 1.5 {
        1.0
    } else if f < 3.5 {
        2.0
    } else if f < 7.5 {
        5.0
    } else {
        10.0
    };
    nice * mag
}

/// A grid edge: (0, i, j) joins nodes (i, j)–(i+1, j); (1, i, j) joins (i, j)–(i, j+1).
type Key = (u8, usize, usize);

/// The contour lines of `g` at `level`, as polylines of (x, y) in metres.
pub(crate) fn contours(g: &Grid, level: f64) -> Vec<Vec<(f64, f64)>> {
    let mut segs: Vec<[Key; 2]> = Vec::new();
    for (i, j, z) in g.cells() {
        let above = |c: usize| usize::from(z[c] >= level) << c;
        let case = above(0) | above(1) | above(2) | above(3);
        let (b, r, t, l) = ((0, i, j), (1, i + 1, j), (0, i, j + 1), (1, i, j));
        let centre_above = z.iter().sum::<f64>() / 4.0 >= level;
        let pairs: &[[Key; 2]] = match case {
            1 | 14 => &[[l, b]],
            2 | 13 => &[[b, r]],
            3 | 12 => &[[l, r]],
            4 | 11 => &[[r, t]],
            6 | 9 => &[[b, t]],
            7 | 8 => &[[l, t]],
            5 if centre_above => &[[l, t], [b, r]],
            5 => &[[l, b], [r, t]],
            10 if centre_above => &[[l, b], [r, t]],
            10 => &[[b, r], [l, t]],
            _ => &[],
        };
        segs.extend_from_slice(pairs);
    }
    let mut at: HashMap<Key, Vec<usize>> = HashMap::new();
    for (s, ends) in segs.iter().enumerate() {
        for &k in ends {
            at.entry(k).or_default().push(s);
        }
    }
    let mut used = vec![false; segs.len()];
    let mut lines = Vec::new();
    for s0 in 0..segs.len() {
        if used[s0] {
            continue;
        }
        used[s0] = true;
        let mut halves = [vec![segs[s0][1]], vec![segs[s0][0]]];
        for half in &mut halves {
            // Walk from the last key through the unused segment sharing it.
            while let Some(&s) = at[half.last().unwrap()].iter().find(|&&s| !used[s]) {
                used[s] = true;
                let last = *half.last().unwrap();
                half.push(if segs[s][0] == last {
                    segs[s][1]
                } else {
                    segs[s][0]
                });
            }
        }
        let [fwd, back] = halves;
        let keys = back.into_iter().rev().chain(fwd);
        lines.push(keys.map(|k| crossing(g, k, level)).collect());
    }
    lines
}

/// Where the contour at `level` crosses edge `k`.
fn crossing(g: &Grid, (dir, i, j): Key, level: f64) -> (f64, f64) {
    let (i1, j1) = if dir == 0 { (i + 1, j) } else { (i, j + 1) };
    let (a, b) = (g.at(i, j), g.at(i1, j1));
    let s = if b != a {
        ((level - a) / (b - a)).clamp(0.0, 1.0)
    } else {
        0.5
    };
    g.point(
        i as f64 + s * (i1 - i) as f64,
        j as f64 + s * (j1 - j) as f64,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cone() -> Grid {
        // z = −distance from the centre of [−1, 1]², 41 × 41 samples.
        let n = 41;
        let mut z = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (-1.0 + 2.0 * i as f64 / 40.0, -1.0 + 2.0 * j as f64 / 40.0);
                z.push(-(x * x + y * y).sqrt());
            }
        }
        Grid {
            nx: n,
            ny: n,
            view: [-1.0, 1.0, -1.0, 1.0],
            z,
        }
    }

    #[test]
    fn a_cone_has_one_closed_circular_contour_per_level() {
        let g = cone();
        let lines = contours(&g, -0.5);
        assert_eq!(lines.len(), 1, "one chained line");
        let line = &lines[0];
        assert!(line.len() > 20);
        assert_eq!(line.first(), line.last(), "closed");
        for &(x, y) in line {
            assert!(((x * x + y * y).sqrt() - 0.5).abs() < 0.02, "({x}, {y})");
        }
    }

    #[test]
    fn nice_steps_are_round() {
        assert_eq!(nice_step(90.0, 10.0), 10.0);
        assert_eq!(nice_step(12.0, 10.0), 1.0);
        assert_eq!(nice_step(400.0, 10.0), 50.0);
        assert_eq!(nice_step(0.0, 10.0), 1.0);
    }

    #[test]
    fn colours_run_dark_deep_to_light_shallow() {
        let lum = |c: [f64; 3]| c.iter().sum::<f64>();
        let r = (-140.0, -50.0);
        assert!(lum(depth_colour(-140.0, r)) < lum(depth_colour(-95.0, r)));
        assert!(lum(depth_colour(-95.0, r)) < lum(depth_colour(-50.0, r)));
        assert_eq!(hillshade(0.0, 0.0), 1.0);
    }
}
