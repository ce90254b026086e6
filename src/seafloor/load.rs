//! Loading a grid file into the planner's metric frame: format by extension, the sign
//! convention, the mission window, and geographic grids resampled onto the local tangent plane.
//!
//! - **Formats**: `.asc` (ESRI ASCII grid: no CRS of its own; a `.prj` sidecar or a declared
//!   `seafloor.crs` gives it, otherwise coordinates are metres) and `.tif`/`.tiff` (GeoTIFF,
//!   with its CRS; see [`super::crs`]), read in pure Rust; with the `gdal` cargo feature,
//!   anything GDAL reads (NetCDF `.nc` as GEBCO's, GMT `.grd`, BAG, XYZ, ...; see
//!   `gdal_grid.rs`). Without the feature, those extensions give [`SeafloorError::NeedsGdal`].
//! - **Values**: [`Values::Elevation`] (negative below sea level, as GEBCO) or
//!   [`Values::Depth`] (positive down; negated on load). After loading, land is z ≥ 0.
//! - **Projected grids and grids without a CRS** keep their own coordinates (metres); the
//!   loaded floor is the nodes of the file inside the mission window ([`Region`]), exactly.
//! - **Geographic grids** (degrees) are resampled onto a metric lattice of the local tangent
//!   plane at the mission origin ([`super::geo::LocalFrame`]; default origin: the grid's
//!   centre): nodes at (i·dx, j·dy) with dx, dy the native spacing at the origin (rounded to
//!   1 mm). A metric node takes the bilinear value of the four native nodes around it; it is
//!   NODATA if any of them is, and land (z ≥ 0) if any of them is, so obstacles never shrink.
//!   Border rows and columns of the lattice that fall outside the native grid are dropped.
//! - **Only the window is read**: a GeoTIFF is decoded strip by strip or tile by tile, and only
//!   the chunks holding the mission window (plus one node) are decoded. An ESRI ASCII file is
//!   text and is parsed whole, then cut.

use super::crs::{resolve, CrsSource};
use super::esri_ascii;
use super::geo::{LocalFrame, MAX_FRAME_DISTANCE};
use super::geotiff::TiffGrid;
use super::{Lattice, Seafloor, SeafloorError, MAX_NODES_PER_AXIS};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// Largest number of nodes loaded at once (about 3.6 GB of values and mask): far beyond any
/// mission window, and a guard against a file whose header claims an absurd size.
pub const MAX_LOAD_NODES: usize = 400_000_000;

/// A block of nodes of a lattice: i0..i0+nx, j0..j0+ny.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NodeWindow {
    /// Column index (along x) of the block's first, south-west node.
    pub i0: usize,
    /// Row index (along y, j = 0 southernmost) of the block's first, south-west node.
    pub j0: usize,
    /// Number of node columns.
    pub nx: usize,
    /// Number of node rows.
    pub ny: usize,
}

/// The coordinate reference system of a grid file.
#[derive(Debug, Clone, PartialEq)]
pub enum Crs {
    /// Unknown (an ESRI ASCII grid, a GeoTIFF without GeoKeys): coordinates taken as metres.
    None,
    /// Projected, metres; the EPSG code unless user-defined.
    Projected {
        /// EPSG code of the projected CRS; None when user-defined.
        epsg: Option<u16>,
        /// The CRS's name as the file gives it (GeoTIFF's GTCitationGeoKey; through GDAL the
        /// name, with its PROJ string when there is no EPSG code), if any.
        citation: Option<String>,
    },
    /// Geographic, degrees (longitude, latitude); the EPSG code unless user-defined.
    Geographic {
        /// EPSG code of the geographic CRS; None when user-defined.
        epsg: Option<u16>,
    },
}

impl std::fmt::Display for Crs {
    /// "none", "EPSG:32631", "EPSG:4326", "projected (user-defined)", "geographic
    /// (user-defined)": what a plan records.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Crs::None => write!(f, "none"),
            Crs::Projected { epsg: Some(c), .. } | Crs::Geographic { epsg: Some(c) } => {
                write!(f, "EPSG:{c}")
            }
            Crs::Projected { epsg: None, .. } => write!(f, "projected (user-defined)"),
            Crs::Geographic { epsg: None } => write!(f, "geographic (user-defined)"),
        }
    }
}

/// The file format, from the file name's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GridFormat {
    /// ESRI ASCII grid (`.asc`).
    EsriAscii,
    /// GeoTIFF (`.tif`, `.tiff`).
    GeoTiff,
    /// Read through GDAL (the `gdal` cargo feature).
    Gdal,
}

/// Extensions that go to GDAL whether or not the `gdal` feature is built (so that a build
/// without it says what is missing): NetCDF (GEBCO), GMT grids, BAG, gridded XYZ, HDF5 (S-102).
const GDAL_EXTENSIONS: [&str; 8] = ["nc", "nc4", "cdf", "grd", "bag", "xyz", "h5", "hdf5"];

impl GridFormat {
    /// `.asc` → ESRI ASCII, `.tif`/`.tiff` → GeoTIFF, the extensions GDAL reads (`.nc`,
    /// `.grd`, `.bag`, `.xyz`, `.h5`, ...) → GDAL (case-insensitive); with the `gdal` feature,
    /// any other name → GDAL too; None otherwise.
    pub fn from_path(path: &Path) -> Option<GridFormat> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("asc") => Some(GridFormat::EsriAscii),
            Some("tif" | "tiff") => Some(GridFormat::GeoTiff),
            Some(e) if GDAL_EXTENSIONS.contains(&e) => Some(GridFormat::Gdal),
            _ if cfg!(feature = "gdal") => Some(GridFormat::Gdal),
            _ => None,
        }
    }

    /// "esri-ascii", "geotiff" or "gdal", as a plan records it.
    pub fn name(self) -> &'static str {
        match self {
            GridFormat::EsriAscii => "esri-ascii",
            GridFormat::GeoTiff => "geotiff",
            GridFormat::Gdal => "gdal",
        }
    }
}

/// The sign convention of a grid file's values.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Values {
    /// Elevation, metres, negative below sea level (GEBCO, ETOPO).
    #[default]
    Elevation,
    /// Depth, metres, positive down (many survey grids); negated on load.
    Depth,
}

/// Which nodes to load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Region {
    /// The whole grid.
    All,
    /// The nodes covering this rectangle of the planner's frame (metres), plus one node each
    /// side, clipped to the grid.
    Area {
        /// Westernmost x of the rectangle, metres.
        x_min: f64,
        /// Easternmost x of the rectangle, metres.
        x_max: f64,
        /// Southernmost y of the rectangle, metres.
        y_min: f64,
        /// Northernmost y of the rectangle, metres.
        y_max: f64,
    },
    /// Exactly this lattice of the planner's frame (first node and counts, as a plan records
    /// them); its nodes must be nodes of the grid's frame lattice, otherwise
    /// [`SeafloorError::Region`].
    Nodes {
        /// x of the lattice's first (south-west) node, metres.
        x0: f64,
        /// y of the lattice's first (south-west) node, metres.
        y0: f64,
        /// Number of nodes along x.
        nx: usize,
        /// Number of nodes along y.
        ny: usize,
    },
}

/// How to load a grid file.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadOptions {
    /// Sign convention of the file's values (default: elevation).
    pub values: Values,
    /// Mission origin [latitude, longitude], degrees, for a geographic grid (default: its
    /// centre). Refused for other grids.
    pub origin: Option<[f64; 2]>,
    /// Which nodes to load (default: the whole grid).
    pub region: Region,
    /// The grid's CRS as declared by the user (`seafloor.crs`, e.g. "EPSG:4326"): the CRS of a
    /// file without one (ESRI ASCII), checked against a file's own (see `seafloor::crs`).
    pub crs: Option<String>,
}

impl Default for LoadOptions {
    fn default() -> Self {
        LoadOptions {
            values: Values::Elevation,
            origin: None,
            region: Region::All,
            crs: None,
        }
    }
}

/// A loaded floor and where it came from.
#[derive(Debug, Clone)]
pub struct LoadedFloor {
    /// The floor in the planner's frame: elevations (z up, metres) on the region's nodes, or
    /// for a geographic grid on the metric lattice of the local tangent plane.
    pub floor: Seafloor,
    /// The file's format.
    pub format: GridFormat,
    /// The grid's CRS (for a geographic grid, the floor is in the local frame at `origin`).
    pub crs: Crs,
    /// Where `crs` came from: the file, a `.prj` sidecar, the declaration, or a guess.
    pub crs_source: CrsSource,
    /// The sign convention the values were read with (depths were negated).
    pub values: Values,
    /// [lat, lon] of the frame's origin when the grid is geographic.
    pub origin: Option<[f64; 2]>,
    /// The file's own node lattice (native units).
    pub native: Lattice,
    /// Things the user should hear about (likely sign-convention mistakes, datum
    /// assumptions); the CLI prints them on stderr.
    pub warnings: Vec<String>,
}

/// An open grid file of either format.
pub(crate) enum GridFile {
    Esri(Box<Seafloor>),
    Tiff(Box<TiffGrid>),
    #[cfg(feature = "gdal")]
    Gdal(Box<super::gdal_grid::GdalGrid>),
}

impl GridFile {
    /// Open a grid file; a grid that a killed `shoal seafloor export` left half moved into its
    /// folder is completed first ([`crate::output_set::settle`]).
    pub fn open(path: &Path) -> Result<(GridFile, GridFormat), SeafloorError> {
        crate::output_set::settle(crate::atomic_file::folder_of(path));
        let format = GridFormat::from_path(path).ok_or_else(|| SeafloorError::Format {
            path: path.display().to_string(),
        })?;
        Ok(match format {
            GridFormat::EsriAscii => (
                GridFile::Esri(Box::new(Seafloor::read_esri_ascii(path)?)),
                format,
            ),
            GridFormat::GeoTiff => (GridFile::Tiff(Box::new(TiffGrid::open(path)?)), format),
            GridFormat::Gdal => (open_gdal(path)?, format),
        })
    }

    /// The GDAL driver reading the file ("netCDF: Network Common Data Format"), if GDAL does.
    pub fn driver(&self) -> Option<String> {
        match self {
            #[cfg(feature = "gdal")]
            GridFile::Gdal(g) => Some(g.driver.clone()),
            _ => None,
        }
    }

    pub fn lattice(&self) -> Lattice {
        match self {
            GridFile::Esri(f) => f.lattice(),
            GridFile::Tiff(t) => t.lattice,
            #[cfg(feature = "gdal")]
            GridFile::Gdal(g) => g.lattice,
        }
    }

    pub fn crs(&self) -> Crs {
        match self {
            GridFile::Esri(_) => Crs::None,
            GridFile::Tiff(t) => t.crs.clone(),
            #[cfg(feature = "gdal")]
            GridFile::Gdal(g) => g.crs.clone(),
        }
    }

    pub fn warnings(&self) -> Vec<String> {
        match self {
            GridFile::Esri(_) => Vec::new(),
            GridFile::Tiff(t) => t.warnings.clone(),
            #[cfg(feature = "gdal")]
            GridFile::Gdal(g) => g.warnings.clone(),
        }
    }

    /// Raw values and NODATA flags of a block of nodes, south to north.
    pub fn read(&mut self, w: NodeWindow) -> Result<(Vec<f64>, Vec<bool>), SeafloorError> {
        match self {
            GridFile::Esri(f) => Ok(esri_ascii::window(f, w)),
            GridFile::Tiff(t) => t.read_window(w),
            #[cfg(feature = "gdal")]
            GridFile::Gdal(g) => g.read_window(w),
        }
    }

    /// Every node's raw value (None at NODATA), in any order.
    pub fn scan(&mut self, mut f: impl FnMut(Option<f64>)) -> Result<(), SeafloorError> {
        match self {
            GridFile::Esri(s) => {
                let (z, nd) = s.nodes();
                z.iter().zip(nd).for_each(|(&v, &m)| f((!m).then_some(v)));
                Ok(())
            }
            GridFile::Tiff(t) => t.scan(f),
            #[cfg(feature = "gdal")]
            GridFile::Gdal(g) => g.scan(f),
        }
    }
}

#[cfg(feature = "gdal")]
fn open_gdal(path: &Path) -> Result<GridFile, SeafloorError> {
    Ok(GridFile::Gdal(Box::new(super::gdal_grid::GdalGrid::open(
        path,
    )?)))
}

/// Without the `gdal` feature: an error that says how to build shoal with it.
#[cfg(not(feature = "gdal"))]
fn open_gdal(path: &Path) -> Result<GridFile, SeafloorError> {
    Err(SeafloorError::NeedsGdal {
        path: path.display().to_string(),
        extension: path
            .extension()
            .map_or_else(String::new, |e| e.to_string_lossy().to_ascii_lowercase()),
    })
}

/// A grid file opened, with its lattice, its warnings and its CRS resolved from the file, a
/// sidecar or the declaration (see [`super::crs`]): the common start of [`load`], `info` and
/// the export's crop.
pub(crate) struct OpenedGrid {
    pub file: GridFile,
    pub format: GridFormat,
    pub native: Lattice,
    pub crs: Crs,
    pub crs_source: CrsSource,
    pub warnings: Vec<String>,
}

impl OpenedGrid {
    pub(crate) fn open(path: &Path, declared: Option<&str>) -> Result<OpenedGrid, SeafloorError> {
        let (file, format) = GridFile::open(path)?;
        let native = file.lattice();
        let mut warnings = file.warnings();
        let (crs, crs_source) =
            resolve(path, format, file.crs(), &native, declared, &mut warnings)?;
        Ok(OpenedGrid {
            file,
            format,
            native,
            crs,
            crs_source,
            warnings,
        })
    }
}

/// Loads a grid file (see the module docs). Errors name the file.
pub fn load(path: &Path, opts: &LoadOptions) -> Result<LoadedFloor, SeafloorError> {
    let name = path.display().to_string();
    let OpenedGrid {
        mut file,
        format,
        native,
        crs,
        crs_source,
        mut warnings,
    } = OpenedGrid::open(path, opts.crs.as_deref())?;
    let region_error = |reason: String| SeafloorError::Region {
        path: name.clone(),
        reason,
    };
    let (floor, origin, raw_signs) = match crs {
        Crs::Geographic { .. } => {
            let g = super::resample::geographic(&mut file, &native, opts, &name)?;
            (g.0, Some(g.1), g.2)
        }
        _ => {
            if let Some(o) = opts.origin {
                return Err(region_error(format!(
                    "seafloor.origin = [{}, {}] is for geographic grids (degrees); this grid's \
                     CRS is {crs}, and its own coordinates (metres) are the planner's frame",
                    o[0], o[1]
                )));
            }
            let w = native_window(&native, opts.region).map_err(region_error)?;
            let (mut z, nodata) = file.read(w)?;
            let signs = count_signs(&z, &nodata);
            apply(opts.values, &mut z);
            let floor = Seafloor::from_nodes(native.block(w), z, nodata)
                .map_err(|e| region_error(format!("the nodes of the mission window: {e}")))?;
            (floor, None, signs)
        }
    };
    if let Some(w) = sign_warning(&name, opts.values, raw_signs) {
        warnings.push(w);
    }
    Ok(LoadedFloor {
        floor,
        format,
        crs,
        crs_source,
        values: opts.values,
        origin,
        native,
        warnings,
    })
}

/// Negates depths into elevations.
pub(crate) fn apply(values: Values, z: &mut [f64]) {
    if values == Values::Depth {
        z.iter_mut().for_each(|v| *v = -*v);
    }
}

/// (positive, negative) counts of raw data values.
pub(crate) fn count_signs(z: &[f64], nodata: &[bool]) -> (usize, usize) {
    z.iter()
        .zip(nodata)
        .filter(|(_, &m)| !m)
        .fold((0, 0), |(p, n), (&v, _)| {
            (p + usize::from(v > 0.0), n + usize::from(v < 0.0))
        })
}

/// The warning for a grid whose values are mostly of the sign the convention does not expect.
pub(crate) fn sign_warning(
    name: &str,
    values: Values,
    (pos, neg): (usize, usize),
) -> Option<String> {
    let total = pos + neg;
    let pct = |n: usize| 100.0 * n as f64 / total.max(1) as f64;
    match values {
        Values::Elevation if pos * 2 > total => Some(format!(
            "{name}: {:.0} % of the data values are positive (above sea level) while \
             seafloor.values = \"elevation\"; if the grid holds depths (positive down), set \
             seafloor.values = \"depth\"; if it is a coastal grid that is mostly land, the \
             positive nodes are land, which the planner keeps every vehicle out of",
            pct(pos)
        )),
        Values::Depth if neg * 2 > total => Some(format!(
            "{name}: {:.0} % of the data values are negative while seafloor.values = \"depth\" \
             (positive down); if the grid holds elevations (negative below sea level, as GEBCO), \
             set seafloor.values = \"elevation\"",
            pct(neg)
        )),
        _ => None,
    }
}

/// The block of a metric lattice's nodes that a region selects (the grid's own frame).
fn native_window(l: &Lattice, region: Region) -> Result<NodeWindow, String> {
    let (i0, i1, j0, j1) = match region {
        Region::All => (0, l.nx - 1, 0, l.ny - 1),
        Region::Area {
            x_min,
            x_max,
            y_min,
            y_max,
        } => {
            let axis = |lo: f64, hi: f64, o: f64, d: f64, n: usize| {
                let a = ((lo - o) / d).floor() - 1.0;
                let b = ((hi - o) / d).ceil() + 1.0;
                if !(a.is_finite() && b.is_finite()) || b < 0.0 || a > (n - 1) as f64 {
                    return None;
                }
                Some((a.max(0.0) as usize, (b as usize).min(n - 1)))
            };
            match (
                axis(x_min, x_max, l.x0, l.dx, l.nx),
                axis(y_min, y_max, l.y0, l.dy, l.ny),
            ) {
                (Some((i0, i1)), Some((j0, j1))) if i1 > i0 && j1 > j0 => (i0, i1, j0, j1),
                _ => {
                    return Err(format!(
                        "the mission area (x from {x_min:.1} to {x_max:.1} m, y from {y_min:.1} \
                         to {y_max:.1} m, around the start) does not overlap the grid, which \
                         covers x from {} to {} and y from {} to {}; the start must lie inside \
                         the grid (with a projected grid the frame is the grid's own \
                         coordinates: give [initial] positions there)",
                        l.x0,
                        l.x_max(),
                        l.y0,
                        l.y_max()
                    ))
                }
            }
        }
        Region::Nodes { x0, y0, nx, ny } => {
            let index = |v: f64, o: f64, d: f64| {
                let k = ((v - o) / d).round();
                (k >= 0.0 && ((o + k * d) - v).abs() <= 1e-6 * d).then_some(k as usize)
            };
            match (index(x0, l.x0, l.dx), index(y0, l.y0, l.dy)) {
                (Some(i0), Some(j0))
                    if nx >= 2 && ny >= 2 && i0 + nx <= l.nx && j0 + ny <= l.ny =>
                {
                    (i0, i0 + nx - 1, j0, j0 + ny - 1)
                }
                _ => {
                    return Err(format!(
                        "the grid does not hold the lattice of {nx} × {ny} nodes from ({x0}, \
                         {y0})"
                    ))
                }
            }
        }
    };
    let (nx, ny) = (i1 - i0 + 1, j1 - j0 + 1);
    if nx > MAX_NODES_PER_AXIS || ny > MAX_NODES_PER_AXIS || nx * ny > MAX_LOAD_NODES {
        return Err(format!(
            "the mission area needs {nx} × {ny} nodes of this grid; at most \
             {MAX_NODES_PER_AXIS} per axis and {MAX_LOAD_NODES} in all (fewer windows or steps, \
             or a coarser grid)"
        ));
    }
    Ok(NodeWindow { i0, j0, nx, ny })
}

/// The frame's origin: the given one (its longitude moved by whole turns next to the grid's),
/// or the grid's centre.
pub(crate) fn frame_for(
    native: &Lattice,
    origin: Option<[f64; 2]>,
) -> Result<LocalFrame, SeafloorError> {
    let centre_lon = 0.5 * (native.x0 + native.x_max());
    let [lat, lon] = origin.unwrap_or([0.5 * (native.y0 + native.y_max()), centre_lon]);
    let lon = lon + 360.0 * ((centre_lon - lon) / 360.0).round();
    LocalFrame::new(lat, lon)
}

/// Largest distance from the frame's origin that a loaded geographic window may reach.
pub(crate) const MAX_WINDOW_DISTANCE: f64 = MAX_FRAME_DISTANCE;
