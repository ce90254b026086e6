//! `shoal seafloor info FILE`: what a grid file holds, read chunk by chunk without loading it.

use super::crs::CrsSource;
use super::geo::LocalFrame;
use super::load::{
    frame_for, sign_warning, Crs, GridFile, GridFormat, LoadOptions, NodeWindow, OpenedGrid,
    Region, Values,
};
use super::{Lattice, SeafloorError};
use std::fmt;
use std::path::Path;

/// What [`info`] finds in a grid file.
#[derive(Debug, Clone, PartialEq)]
pub struct GridInfo {
    /// The file's path.
    pub path: String,
    /// The file format, from the file name's extension.
    pub format: GridFormat,
    /// The GDAL driver that reads the file ("netCDF: Network Common Data Format"), for a file
    /// read through GDAL.
    pub driver: Option<String>,
    /// The grid's CRS: the file's own, or the declared one.
    pub crs: Crs,
    /// Where `crs` came from.
    pub crs_source: CrsSource,
    /// The file's nodes in its own units.
    pub native: Lattice,
    /// Node spacing in metres (at the suggested origin for a geographic grid).
    pub cell_m: [f64; 2],
    /// The node extent in the local tangent plane at the suggested origin [x_min, x_max, y_min,
    /// y_max], metres, for a geographic grid within the frame's range; the native extent for
    /// metric grids.
    pub metric_extent: Option<[f64; 4]>,
    /// The sign convention the values were read with.
    pub values: Values,
    /// Number of nodes holding a value.
    pub data_nodes: usize,
    /// Number of NODATA nodes.
    pub nodata_nodes: usize,
    /// Data nodes at or above sea level (after the sign convention).
    pub land_nodes: usize,
    /// (deepest, shallowest) elevation of the data nodes, metres (after the sign convention).
    pub z_range: Option<(f64, f64)>,
    /// The suggested mission origin: the grid's centre, [lat, lon] for a geographic grid,
    /// [x, y] in the grid's own metres otherwise.
    pub origin: [f64; 2],
    /// When `shoal plan` would refuse to start at the centre (it is land or NODATA, or in a
    /// cell that touches them: a coastal grid): the node nearest to it where a plan can start,
    /// in the same form as `origin` (rounded as printed), and its distance from the centre in
    /// metres. None when the centre will do, or no such node lies within 2048 nodes of it.
    pub water_origin: Option<([f64; 2], f64)>,
    /// Whether a plan can start at the centre (the default origin of a geographic grid).
    pub centre_clear: bool,
    /// Likely mistakes (the sign convention) and assumptions (a datum taken as WGS84); not
    /// part of the Display text.
    pub warnings: Vec<String>,
}

/// Reads a grid file's header and scans its values (one chunk at a time for a GeoTIFF).
pub fn info(path: &Path, values: Values) -> Result<GridInfo, SeafloorError> {
    info_with_crs(path, values, None)
}

/// [`info`] with a declared CRS (`"EPSG:<code>"`, as `seafloor.crs`; see `seafloor::crs`).
pub fn info_with_crs(
    path: &Path,
    values: Values,
    declared: Option<&str>,
) -> Result<GridInfo, SeafloorError> {
    let name = path.display().to_string();
    let OpenedGrid {
        mut file,
        format,
        native,
        crs,
        crs_source,
        mut warnings,
    } = OpenedGrid::open(path, declared)?;
    let driver = file.driver();
    let (mut data, mut nodata, mut land, mut pos, mut neg) = (0, 0, 0, 0, 0);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    let sign = if values == Values::Depth { -1.0 } else { 1.0 };
    file.scan(|v| match v {
        None => nodata += 1,
        Some(raw) => {
            data += 1;
            pos += usize::from(raw > 0.0);
            neg += usize::from(raw < 0.0);
            let z = sign * raw;
            land += usize::from(z >= 0.0);
            lo = lo.min(z);
            hi = hi.max(z);
        }
    })?;
    if let Some(w) = sign_warning(&name, values, (pos, neg)) {
        warnings.push(w);
    }
    let centre = [
        0.5 * (native.x0 + native.x_max()),
        0.5 * (native.y0 + native.y_max()),
    ];
    let (origin, cell_m, metric_extent) = match crs {
        Crs::Geographic { .. } => {
            let frame = frame_for(&native, None)?;
            let [me, mn] = frame.metres_per_degree();
            (
                frame.origin(),
                [me * native.dx, mn * native.dy],
                footprint(&frame, &native),
            )
        }
        _ => (
            centre,
            [native.dx, native.dy],
            Some([native.x0, native.x_max(), native.y0, native.y_max()]),
        ),
    };
    let start = StartTest {
        path,
        values,
        declared,
        geographic: matches!(crs, Crs::Geographic { .. }),
        reach: 4.0 * cell_m[0].max(cell_m[1]),
    };
    let centre_clear = land + nodata == 0 || start.accepts(None, centre);
    let water_origin = if centre_clear {
        None
    } else {
        nearest_start(&mut file, &native, sign, cell_m, &start)?
    };
    Ok(GridInfo {
        water_origin,
        centre_clear,
        path: name,
        format,
        driver,
        crs,
        crs_source,
        native,
        cell_m,
        metric_extent,
        values,
        data_nodes: data,
        nodata_nodes: nodata,
        land_nodes: land,
        z_range: (data > 0).then_some((lo, hi)),
        origin,
        warnings,
    })
}

/// Half-sizes (nodes) of the windows about the centre node that `nearest_start` reads in
/// turn: at most 4097 × 4097 nodes are held at once.
const WATER_SEARCH: [usize; 4] = [16, 128, 512, 2048];

/// A node suggested as a start has only water (data below sea level) within this many nodes
/// of it, along each axis: its own cell, the cells around an obstacle cell that the planner's
/// keep-out field rises over, and for a geographic grid the native cells that the metric
/// resampling blends into the start's cell.
const CLEAR_NODES: usize = 3;

/// Most candidate nodes [`nearest_start`] loads the floor around before it gives up.
const MAX_TRIES: usize = 32;

/// Whether `shoal plan` starts at a point, decided as it decides it: the floor loaded around
/// the point as the planner loads it (the same origin, CRS and sign convention), the point
/// inside the grid, its cell free of NODATA and land, and the keep-out field there the floor
/// itself, below sea level.
struct StartTest<'a> {
    path: &'a Path,
    values: Values,
    declared: Option<&'a str>,
    geographic: bool,
    /// Half-size of the area loaded around the point, metres.
    reach: f64,
}

impl StartTest<'_> {
    /// Whether a plan starts at `origin` ([lat, lon] of a geographic grid's frame, the USV at
    /// its origin; None: the grid's centre) or, for another grid, at `at` ([x, y]).
    fn accepts(&self, origin: Option<[f64; 2]>, at: [f64; 2]) -> bool {
        let (origin, [x, y]) = match self.geographic {
            true => (origin, [0.0, 0.0]),
            false => (None, origin.unwrap_or(at)),
        };
        let r = self.reach;
        let opts = LoadOptions {
            values: self.values,
            origin,
            crs: self.declared.map(str::to_string),
            region: Region::Area {
                x_min: x - r,
                x_max: x + r,
                y_min: y - r,
                y_max: y + r,
            },
        };
        let Ok(loaded) = super::load(self.path, &opts) else {
            return false;
        };
        let floor = loaded.floor;
        let (Ok(z), Ok(field)) = (floor.elevation(x, y), floor.keep_out().elevation(x, y)) else {
            return false;
        };
        floor.contains(x, y) && matches!(floor.obstacle(x, y), Ok(None)) && field == z && z < 0.0
    }
}

/// The node nearest the grid's centre node where a plan can start ([`StartTest`]), as it is
/// printed ([lat, lon] to 1e-6° for a geographic grid, [x, y] to 0.1 m otherwise), and its
/// distance from the centre in metres (`cell_m`: metres per node step). Only nodes with
/// nothing but water within [`CLEAR_NODES`] are tried, nearest first, at most [`MAX_TRIES`].
/// None when no node within the largest window of `WATER_SEARCH` will do.
fn nearest_start(
    file: &mut GridFile,
    n: &Lattice,
    sign: f64,
    cell_m: [f64; 2],
    start: &StartTest,
) -> Result<Option<([f64; 2], f64)>, SeafloorError> {
    let (ic, jc) = ((n.nx - 1) / 2, (n.ny - 1) / 2);
    let c = CLEAR_NODES;
    let mut tried = std::collections::HashSet::new();
    for h in WATER_SEARCH {
        let (i0, j0) = (ic.saturating_sub(h), jc.saturating_sub(h));
        let (i1, j1) = ((ic + h).min(n.nx - 1), (jc + h).min(n.ny - 1));
        let w = NodeWindow {
            i0,
            j0,
            nx: i1 - i0 + 1,
            ny: j1 - j0 + 1,
        };
        let (z, missing) = file.read(w)?;
        // prefix sums of the nodes that are not water: a box is clear when its sum is 0
        let (wx, wy) = (w.nx, w.ny);
        let mut dry = vec![0u32; (wx + 1) * (wy + 1)];
        for j in 0..wy {
            for i in 0..wx {
                let k = j * wx + i;
                let water = !missing[k] && sign * z[k] < 0.0; // false for NaN
                dry[(j + 1) * (wx + 1) + i + 1] =
                    u32::from(!water) + dry[j * (wx + 1) + i + 1] + dry[(j + 1) * (wx + 1) + i]
                        - dry[j * (wx + 1) + i];
            }
        }
        let clear = |i: usize, j: usize| {
            // the box [i − c, i + c] × [j − c, j + c] in window coordinates, inside the window
            if i < c || j < c || i + c >= wx || j + c >= wy {
                return false;
            }
            let (a, b, p, q) = (i - c, j - c, i + c + 1, j + c + 1);
            let at = |x: usize, y: usize| dry[y * (wx + 1) + x];
            at(p, q) + at(a, b) == at(a, q) + at(p, b)
        };
        let mut candidates: Vec<(f64, usize, usize)> = Vec::new();
        for j in 0..wy {
            for i in 0..wx {
                if clear(i, j) {
                    let (gi, gj) = (i0 + i, j0 + j);
                    let d = ((gi as f64 - ic as f64) * cell_m[0])
                        .hypot((gj as f64 - jc as f64) * cell_m[1]);
                    candidates.push((d, gi, gj));
                }
            }
        }
        candidates.sort_by(|a, b| a.0.total_cmp(&b.0).then((a.2, a.1).cmp(&(b.2, b.1))));
        let whole = w.nx == n.nx && w.ny == n.ny;
        // nearer than any clear node this window cannot see (outside it, or within c of its
        // edge), unless it sees everything there is to see
        let bound = match whole || h == WATER_SEARCH[3] {
            true => f64::INFINITY,
            false => h.saturating_sub(c) as f64 * cell_m[0].min(cell_m[1]),
        };
        for (d, i, j) in candidates {
            if d > bound || tried.len() >= MAX_TRIES {
                break;
            }
            if !tried.insert((i, j)) {
                continue;
            }
            let (x, y) = (n.x0 + i as f64 * n.dx, n.y0 + j as f64 * n.dy);
            let at = match start.geographic {
                true => [round_to(y, 1e6), round_to(x, 1e6)], // [lat, lon]
                false => [round_to(x, 10.0), round_to(y, 10.0)],
            };
            if start.accepts(Some(at), at) {
                return Ok(Some((at, d)));
            }
        }
        if whole || tried.len() >= MAX_TRIES {
            return Ok(None);
        }
    }
    Ok(None)
}

/// `v` rounded to 1/`per` (as printed with log10(per) decimals).
fn round_to(v: f64, per: f64) -> f64 {
    (v * per).round() / per
}

/// The bounding box of the grid's boundary nodes in the frame; None if any lies beyond the
/// frame's range.
fn footprint(frame: &LocalFrame, n: &Lattice) -> Option<[f64; 4]> {
    let mut e = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let mut visit = |i: usize, j: usize| {
        let (lon, lat) = (n.x(i), n.y(j));
        if !frame.within_range(lat, lon) {
            return false;
        }
        let [x, y] = frame.to_local(lat, lon);
        e = [e[0].min(x), e[1].max(x), e[2].min(y), e[3].max(y)];
        true
    };
    for i in 0..n.nx {
        if !(visit(i, 0) && visit(i, n.ny - 1)) {
            return None;
        }
    }
    for j in 0..n.ny {
        if !(visit(0, j) && visit(n.nx - 1, j)) {
            return None;
        }
    }
    Some(e)
}

impl fmt::Display for GridInfo {
    /// The description, its names from the file (path, driver, CRS citation) made printable
    /// ([`crate::report::printable_lines`]).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut text = String::new();
        self.describe(&mut text)?;
        f.write_str(&crate::report::printable_lines(&text))
    }
}

impl GridInfo {
    fn describe(&self, f: &mut String) -> fmt::Result {
        use fmt::Write as _;
        let n = &self.native;
        let format = match (self.format, &self.driver) {
            (GridFormat::EsriAscii, _) => "ESRI ASCII grid".to_string(),
            (GridFormat::GeoTiff, _) => "GeoTIFF".to_string(),
            (GridFormat::Gdal, Some(d)) => format!("{d}, read with GDAL"),
            (GridFormat::Gdal, None) => "read with GDAL".to_string(),
        };
        writeln!(f, "file        {} ({format})", self.path)?;
        writeln!(
            f,
            "size        {} × {} nodes ({} nodes)",
            n.nx,
            n.ny,
            n.node_count()
        )?;
        let geographic = matches!(self.crs, Crs::Geographic { .. });
        let kind = match self.crs {
            Crs::None => "no CRS: coordinates are read as metres",
            Crs::Projected { .. } => {
                "projected, metres: the planner's frame is the grid's own coordinates"
            }
            Crs::Geographic { .. } => {
                "geographic, degrees: the planner works in a local tangent plane"
            }
        };
        writeln!(f, "CRS         {} ({kind})", self.crs)?;
        writeln!(f, "CRS source  {}", self.crs_source)?;
        if let Crs::Projected {
            citation: Some(c), ..
        } = &self.crs
        {
            writeln!(f, "            {c}")?;
        }
        if geographic {
            writeln!(
                f,
                "extent      longitude {} to {}°, latitude {} to {}° (node centres); cells of \
                 {}° × {}°",
                n.x0,
                n.x_max(),
                n.y0,
                n.y_max(),
                n.dx,
                n.dy
            )?;
            let [lat, lon] = self.origin;
            match self.metric_extent {
                Some([x0, x1, y0, y1]) => writeln!(
                    f,
                    "metric      x {x0:.1} to {x1:.1} m, y {y0:.1} to {y1:.1} m in the local \
                     tangent plane at ({lat}°, {lon}°); cells ≈ {:.2} × {:.2} m",
                    self.cell_m[0], self.cell_m[1]
                )?,
                None => writeln!(
                    f,
                    "metric      ≈ {:.0} × {:.0} km at the centre's scale; cells ≈ {:.2} × \
                     {:.2} m (the grid reaches beyond the local frame's range: the planner \
                     loads only the mission window)",
                    self.cell_m[0] * (n.nx - 1) as f64 / 1e3,
                    self.cell_m[1] * (n.ny - 1) as f64 / 1e3,
                    self.cell_m[0],
                    self.cell_m[1]
                )?,
            }
        } else {
            writeln!(
                f,
                "extent      x {} to {} m, y {} to {} m (node centres); cells of {} × {} m",
                n.x0,
                n.x_max(),
                n.y0,
                n.y_max(),
                n.dx,
                n.dy
            )?;
        }
        let convention = match self.values {
            Values::Elevation => "elevation (negative below sea level)",
            Values::Depth => "depth (positive down; negated on load)",
        };
        writeln!(f, "values      {convention}")?;
        match self.z_range {
            Some((lo, hi)) => writeln!(
                f,
                "elevation   {lo:.2} to {hi:.2} m (depth {:.2} to {:.2} m)",
                -hi, -lo
            )?,
            None => writeln!(f, "elevation   no data")?,
        }
        let pct = |k: usize| 100.0 * k as f64 / n.node_count().max(1) as f64;
        writeln!(
            f,
            "nodes       {} with data, {} NODATA ({:.2} %), {} land (z ≥ 0, {:.2} %)",
            self.data_nodes,
            self.nodata_nodes,
            pct(self.nodata_nodes),
            self.land_nodes,
            pct(self.land_nodes)
        )?;
        let [a, b] = self.origin;
        if let Some(([c, d], dist)) = self.water_origin {
            let (what, set) = if geographic {
                (
                    format!("({c:.6}°, {d:.6}°)"),
                    format!("seafloor.origin = [{c:.6}, {d:.6}]"),
                )
            } else {
                (
                    format!("x = {c:.1}, y = {d:.1} m"),
                    format!("[initial] usv = [{c:.1}, {d:.1}]"),
                )
            };
            return writeln!(
                f,
                "origin      the grid centre is on land or NODATA, or next to it; the nearest \
                 node a plan can start from is {what}, {dist:.0} m from it: start there ({set})"
            );
        }
        if !self.centre_clear {
            let set = match geographic {
                true => "seafloor.origin",
                false => "[initial] usv",
            };
            return writeln!(
                f,
                "origin      the grid centre is on land or NODATA, or next to it, and no node \
                 a plan can start from was found near it: set {set} to a point over open water"
            );
        }
        if geographic {
            writeln!(
                f,
                "origin      seafloor.origin = [{a:.6}, {b:.6}] (lat, lon of the grid centre, \
                 the default)"
            )?;
        } else {
            writeln!(
                f,
                "origin      the grid centre is x = {a:.1}, y = {b:.1} m: start the USV near it \
                 ([initial] usv = [{a:.1}, {b:.1}])"
            )?;
        }
        Ok(())
    }
}
