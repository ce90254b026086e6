//! A sub-grid of a grid file or of a floor, cropped to a region and optionally resampled
//! (`shoal seafloor export --from FILE --region … --cell …`).
//!
//! - **Region**: a rectangle in the grid's own units (`xmin, ymin, xmax, ymax`: metres, or
//!   longitude and latitude in degrees), or for a geographic grid a latitude/longitude box
//!   (south, west, north, east). It must lie inside the grid's node extent.
//! - **Crop** (no cell size): the grid's own nodes inside the region, values unchanged.
//! - **Resample** (a cell size, metres): nodes at the multiples of the cell inside the region;
//!   for a geographic grid the cell is turned into degrees at the region's centre latitude
//!   (metres per degree east and north on WGS84 there), so the cells are about `cell` metres
//!   square. A node's value is the bilinear value of the source there.
//! - **Obstacles never shrink**: with s the source spacing and c the target's, a target node is
//!   NODATA if a source NODATA node lies closer than max(s, c) on both axes, and land
//!   (raised to z = 0 if below) if a source land node (z ≥ 0) does. Then every point of a source
//!   cell that touches NODATA or land lies in a target cell that does too; with c = s and
//!   aligned nodes nothing changes.
//! - Values are elevations after the sign convention (depths are negated), as the planner reads
//!   them.

use super::crs::CrsSource;
use super::geo::LocalFrame;
use super::load::{apply, Crs, NodeWindow, OpenedGrid, Values, MAX_LOAD_NODES};
use super::{Lattice, Seafloor, SeafloorError, MAX_NODES_PER_AXIS};
use std::path::Path;

/// Which part of a grid to export.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum CropRegion {
    /// The whole grid.
    All,
    /// [xmin, ymin, xmax, ymax] in the grid's own units.
    Native([f64; 4]),
    /// [south, west, north, east], degrees: a geographic grid only.
    LatLon([f64; 4]),
}

/// How to export a grid file.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportOptions {
    /// The sign convention of the file's values (depths are negated).
    pub values: Values,
    /// A declared CRS, as `seafloor.crs` (`"EPSG:<code>"`).
    pub crs: Option<String>,
    /// The part of the grid to export.
    pub region: CropRegion,
    /// Resample onto cells of this size, metres (see the module docs); None: crop only.
    pub cell: Option<f64>,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            values: Values::Elevation,
            crs: None,
            region: CropRegion::All,
            cell: None,
        }
    }
}

/// A cropped (and maybe resampled) grid in its file's CRS and units.
#[derive(Debug, Clone)]
pub struct ExportedGrid {
    /// Node coordinates in the CRS's units (degrees for a geographic grid), elevations.
    pub floor: Seafloor,
    /// The grid's CRS: the file's own, or the declared one.
    pub crs: Crs,
    /// Where `crs` came from.
    pub crs_source: CrsSource,
    /// Likely mistakes and assumptions found while reading the file (e.g. a datum taken as
    /// WGS84).
    pub warnings: Vec<String>,
}

/// Crops (and resamples) a grid file in its own CRS; see the module docs. Errors name the file
/// and the option at fault.
pub fn export_grid(path: &Path, opts: &ExportOptions) -> Result<ExportedGrid, SeafloorError> {
    let name = path.display().to_string();
    let OpenedGrid {
        mut file,
        native,
        crs,
        crs_source,
        warnings,
        ..
    } = OpenedGrid::open(path, opts.crs.as_deref())?;
    let geographic = matches!(crs, Crs::Geographic { .. });
    let fail = |option: &'static str, reason: String| SeafloorError::Crop {
        path: name.clone(),
        option,
        reason,
    };
    let (region, option) = match opts.region {
        CropRegion::All => (None, "region"),
        CropRegion::Native(r) => (Some(r), "region"),
        CropRegion::LatLon([s, w, n, e]) => {
            if !geographic {
                return Err(fail(
                    "region-latlon",
                    format!(
                        "the grid's CRS is {crs} ({crs_source}), not geographic; give the region \
                         in its own coordinates with --region xmin,ymin,xmax,ymax"
                    ),
                ));
            }
            // longitudes moved by whole turns next to the grid's
            let centre = 0.5 * (native.x0 + native.x_max());
            let turn = 360.0 * ((centre - 0.5 * (w + e)) / 360.0).round();
            (Some([w + turn, s, e + turn, n]), "region-latlon")
        }
    };
    let bounds = check_region(&native, region).map_err(|r| fail(option, r))?;
    let spacing = match opts.cell {
        None => None,
        Some(c) if !(c.is_finite() && c > 0.0) => {
            return Err(fail(
                "cell",
                format!("{c}: expected a positive number of metres"),
            ))
        }
        Some(c) if geographic => {
            let lat = 0.5 * (bounds[1] + bounds[3]);
            let frame = LocalFrame::new(lat, 0.5 * (bounds[0] + bounds[2]))
                .map_err(|e| fail(option, format!("the region's centre: {e}")))?;
            let [me, mn] = frame.metres_per_degree();
            Some([c / me, c / mn])
        }
        Some(c) => Some([c, c]),
    };
    let target = target_lattice(&native, bounds, spacing)
        .map_err(|(o, r)| fail(if o == "region" { option } else { o }, r))?;
    // The source nodes the target needs: its extent grown by the obstacle radius and a node.
    let (sx, sy) = (native.dx, native.dy);
    let grow = [target.dx.max(sx) + sx, target.dy.max(sy) + sy];
    let index = |v: f64, o: f64, d: f64, n: usize| ((v - o) / d).clamp(0.0, (n - 1) as f64);
    let i0 = index(target.x0 - grow[0], native.x0, sx, native.nx).floor() as usize;
    let i1 = index(target.x_max() + grow[0], native.x0, sx, native.nx).ceil() as usize;
    let j0 = index(target.y0 - grow[1], native.y0, sy, native.ny).floor() as usize;
    let j1 = index(target.y_max() + grow[1], native.y0, sy, native.ny).ceil() as usize;
    let w = NodeWindow {
        i0,
        j0,
        nx: i1 - i0 + 1,
        ny: j1 - j0 + 1,
    };
    if w.nx * w.ny > MAX_LOAD_NODES {
        return Err(fail(
            option,
            format!(
                "needs {} × {} nodes of the grid; at most {MAX_LOAD_NODES} in all",
                w.nx, w.ny
            ),
        ));
    }
    let (mut z, nodata) = file.read(w)?;
    apply(opts.values, &mut z);
    let all_nodata = || fail(option, "every node of the region is NODATA".to_string());
    let source = Seafloor::from_nodes(native.block(w), z, nodata)
        .map_err(|e| nodata_error(e, all_nodata))?;
    let floor = match spacing {
        None => cut(&source, &target),
        Some(_) => resample_onto(&source, &target),
    }
    .map_err(|e| nodata_error(e, all_nodata))?;
    Ok(ExportedGrid {
        floor,
        crs,
        crs_source,
        warnings,
    })
}

/// Crops (and resamples, with `cell` in metres) a floor in a metric frame, such as the planner's
/// (see the module docs); `region` is [xmin, ymin, xmax, ymax] in metres. Errors name `name`
/// (what the floor is) and the option at fault.
pub fn crop_floor(
    floor: &Seafloor,
    region: Option<[f64; 4]>,
    cell: Option<f64>,
    name: &str,
) -> Result<Seafloor, SeafloorError> {
    let fail = |option: &'static str, reason: String| SeafloorError::Crop {
        path: name.to_string(),
        option,
        reason,
    };
    let l = floor.lattice();
    let bounds = check_region(&l, region).map_err(|r| fail("region", r))?;
    let spacing = match cell {
        Some(c) if !(c.is_finite() && c > 0.0) => {
            return Err(fail(
                "cell",
                format!("{c}: expected a positive number of metres"),
            ))
        }
        c => c.map(|c| [c, c]),
    };
    let target = target_lattice(&l, bounds, spacing).map_err(|(o, r)| fail(o, r))?;
    match spacing {
        None => cut(floor, &target),
        Some(_) => resample_onto(floor, &target),
    }
    .map_err(|e| {
        nodata_error(e, || {
            fail("region", "every node of the region is NODATA".to_string())
        })
    })
}

/// A grid of NODATA only as the caller's error; other errors as they are.
fn nodata_error(e: SeafloorError, all_nodata: impl Fn() -> SeafloorError) -> SeafloorError {
    match e {
        SeafloorError::InvalidGrid(r) if r.contains("every node is NODATA") => all_nodata(),
        e => e,
    }
}

/// The smallest rectangle of a local frame (metres) holding a latitude/longitude box [south,
/// west, north, east] (its edges sampled every 1/64 of their length); None if part of the box is
/// beyond the frame's range.
pub fn latlon_box_in_frame(frame: &LocalFrame, [s, w, n, e]: [f64; 4]) -> Option<[f64; 4]> {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for k in 0..=64 {
        let t = k as f64 / 64.0;
        let (lat, lon) = (s + t * (n - s), w + t * (e - w));
        for (la, lo) in [(lat, w), (lat, e), (s, lon), (n, lon)] {
            if !frame.within_range(la, lo) {
                return None;
            }
            let [x, y] = frame.to_local(la, lo);
            b = [b[0].min(x), b[1].min(y), b[2].max(x), b[3].max(y)];
        }
    }
    Some(b)
}

/// The region, checked: finite, ordered, inside the lattice's node extent (to 1e-9 of a cell).
fn check_region(l: &Lattice, region: Option<[f64; 4]>) -> Result<[f64; 4], String> {
    let [x0, y0, x1, y1] = region.unwrap_or([l.x0, l.y0, l.x_max(), l.y_max()]);
    if !([x0, y0, x1, y1].iter().all(|v| v.is_finite()) && x0 < x1 && y0 < y1) {
        return Err(format!(
            "{x0},{y0},{x1},{y1}: expected four finite numbers xmin,ymin,xmax,ymax with xmin < \
             xmax and ymin < ymax"
        ));
    }
    let (tx, ty) = (1e-9 * l.dx, 1e-9 * l.dy);
    if x0 < l.x0 - tx || x1 > l.x_max() + tx || y0 < l.y0 - ty || y1 > l.y_max() + ty {
        return Err(format!(
            "x from {x0} to {x1} and y from {y0} to {y1} is not inside the grid, which covers x \
             from {} to {} and y from {} to {} (node centres, in the grid's own units)",
            l.x0,
            l.x_max(),
            l.y0,
            l.y_max()
        ));
    }
    Ok([x0, y0, x1, y1])
}

/// The target nodes: the lattice's own inside the region, or the multiples of `spacing` there.
/// The error names the option at fault ("region" or "cell").
fn target_lattice(
    l: &Lattice,
    [x0, y0, x1, y1]: [f64; 4],
    spacing: Option<[f64; 2]>,
) -> Result<Lattice, (&'static str, String)> {
    let (ox, oy, dx, dy) = match spacing {
        None => (l.x0, l.y0, l.dx, l.dy),
        Some([cx, cy]) => (0.0, 0.0, cx, cy),
    };
    let range = |lo: f64, hi: f64, o: f64, d: f64| {
        let a = ((lo - o) / d - 1e-9).ceil();
        let b = ((hi - o) / d + 1e-9).floor();
        (a, b - a + 1.0)
    };
    let (i0, nx) = range(x0, x1, ox, dx);
    let (j0, ny) = range(y0, y1, oy, dy);
    let option = if spacing.is_some() { "cell" } else { "region" };
    if nx < 2.0 || ny < 2.0 {
        return Err((
            option,
            format!(
                "the region holds {} × {} nodes of {dx} × {dy} (the grid's units): at least 2 × \
                 2 are needed; widen the region{}",
                nx.max(0.0),
                ny.max(0.0),
                if spacing.is_some() {
                    " or use a smaller cell"
                } else {
                    ""
                }
            ),
        ));
    }
    let max = MAX_NODES_PER_AXIS as f64;
    if nx > max || ny > max || nx * ny > MAX_LOAD_NODES as f64 {
        return Err((
            option,
            format!(
                "the region needs {nx} × {ny} nodes; at most {MAX_NODES_PER_AXIS} per axis and \
                 {MAX_LOAD_NODES} in all{}",
                if spacing.is_some() {
                    ": use a larger cell"
                } else {
                    ": give a smaller region or a cell size"
                }
            ),
        ));
    }
    Ok(Lattice {
        nx: nx as usize,
        ny: ny as usize,
        x0: ox + i0 * dx,
        y0: oy + j0 * dy,
        dx,
        dy,
    })
}

/// The source's own nodes on `target` (a block of its lattice), values unchanged.
fn cut(src: &Seafloor, target: &Lattice) -> Result<Seafloor, SeafloorError> {
    let i0 = ((target.x0 - src.x0()) / src.dx()).round() as usize;
    let j0 = ((target.y0 - src.y0()) / src.dy()).round() as usize;
    let (z, nd) = super::esri_ascii::window(
        src,
        NodeWindow {
            i0,
            j0,
            nx: target.nx,
            ny: target.ny,
        },
    );
    Seafloor::from_nodes(*target, z, nd)
}

/// The source resampled onto `target` (inside the source's extent): bilinear values, and the
/// obstacle rule of the module docs.
fn resample_onto(src: &Seafloor, target: &Lattice) -> Result<Seafloor, SeafloorError> {
    let (nx, ny) = (target.nx, target.ny);
    let s = src.lattice();
    let rx = src.dx().max(target.dx) * (1.0 - 1e-9);
    let ry = src.dy().max(target.dy) * (1.0 - 1e-9);
    let mut nodata = vec![false; nx * ny];
    let mut land = vec![false; nx * ny];
    // Target indices strictly within r of q along one axis.
    let near = |q: f64, r: f64, o: f64, d: f64, n: usize| {
        let lo = (((q - r - o) / d).floor().max(0.0)) as usize;
        let hi = (((q + r - o) / d).ceil().max(0.0) as usize).min(n - 1);
        (lo..=hi).filter(move |&k| (o + k as f64 * d - q).abs() < r)
    };
    let (values, mask) = src.nodes();
    for (k, (&v, &m)) in values.iter().zip(mask).enumerate() {
        if !(m || v >= 0.0) {
            continue;
        }
        let (qx, qy) = (s.x(k % s.nx), s.y(k / s.nx));
        for j in near(qy, ry, target.y0, target.dy, ny) {
            for i in near(qx, rx, target.x0, target.dx, nx) {
                let t = j * nx + i;
                if m {
                    nodata[t] = true;
                } else {
                    land[t] = true;
                }
            }
        }
    }
    let mut z = vec![0.0; nx * ny];
    let e = src.extent();
    for j in 0..ny {
        for i in 0..nx {
            let t = j * nx + i;
            if nodata[t] {
                continue;
            }
            // inside the source's extent by construction; clamp the last ulp
            let (x, y) = (target.x(i), target.y(j));
            let v = src.elevation(x.clamp(e.x_min, e.x_max), y.clamp(e.y_min, e.y_max))?;
            z[t] = if land[t] { v.max(0.0) } else { v };
        }
    }
    Seafloor::from_nodes(*target, z, nodata)
}

#[cfg(test)]
mod tests;
