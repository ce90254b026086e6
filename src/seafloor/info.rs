//! `shoal seafloor info FILE`: what a grid file holds, read chunk by chunk without loading it.

use super::crs::CrsSource;
use super::geo::LocalFrame;
use super::load::{
    frame_for, sign_warning, Crs, GridFile, GridFormat, NodeWindow, OpenedGrid, Values,
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
    /// When the centre node is land or NODATA (a coastal grid): the water node (data below sea
    /// level) nearest to it, in the same form as `origin`, and its distance from the centre in
    /// metres. None when the centre is water, or no water node lies within 2048 nodes of it.
    pub water_origin: Option<([f64; 2], f64)>,
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
    let water_origin = if land + nodata == 0 {
        None
    } else {
        nearest_water(&mut file, &native, sign, cell_m)?.map(|([x, y], d)| {
            let at = match crs {
                Crs::Geographic { .. } => [y, x], // [lat, lon]
                _ => [x, y],
            };
            (at, d)
        })
    };
    Ok(GridInfo {
        water_origin,
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

/// Half-sizes (nodes) of the windows about the centre node that `nearest_water` reads in
/// turn: at most 4097 × 4097 nodes are held at once.
const WATER_SEARCH: [usize; 4] = [16, 128, 512, 2048];

/// The water node (data, below sea level after `sign`) nearest the grid's centre node, as
/// native (x, y), and its distance in metres (`cell_m`: metres per node step); None when the
/// centre node is water or none lies within the largest window of `WATER_SEARCH`.
fn nearest_water(
    file: &mut GridFile,
    n: &Lattice,
    sign: f64,
    cell_m: [f64; 2],
) -> Result<Option<([f64; 2], f64)>, SeafloorError> {
    let (ic, jc) = ((n.nx - 1) / 2, (n.ny - 1) / 2);
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
        let mut best: Option<(f64, usize, usize)> = None;
        for (k, (&raw, &m)) in z.iter().zip(&missing).enumerate() {
            let water = sign * raw < 0.0; // false for NaN
            if m || !water {
                continue;
            }
            let (i, j) = (i0 + k % w.nx, j0 + k / w.nx);
            let d = ((i as f64 - ic as f64) * cell_m[0]).hypot((j as f64 - jc as f64) * cell_m[1]);
            if best.map_or(true, |b| d < b.0) {
                best = Some((d, i, j));
            }
        }
        let whole = w.nx == n.nx && w.ny == n.ny;
        if let Some((d, i, j)) = best {
            if d == 0.0 {
                return Ok(None); // the centre is water
            }
            // nearer than any node outside this window, or nothing left outside it
            if d <= h as f64 * cell_m[0].min(cell_m[1]) || whole || h == WATER_SEARCH[3] {
                let x = n.x0 + i as f64 * n.dx;
                let y = n.y0 + j as f64 * n.dy;
                return Ok(Some(([x, y], d)));
            }
        } else if whole {
            return Ok(None);
        }
    }
    Ok(None)
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
                "origin      the grid centre is on land or NODATA; the nearest water node is \
                 {what}, {dist:.0} m from it: start there ({set})"
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
