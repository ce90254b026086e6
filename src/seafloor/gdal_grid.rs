//! Grid files read through GDAL (the optional `gdal` cargo feature, over the system's libgdal):
//! NetCDF (GEBCO, GMT `.grd`), BAG, gridded XYZ, and anything else GDAL opens as a raster.
//! Like the GeoTIFF reader, a file is opened once ([`GdalGrid::open`]: the georeferencing,
//! the CRS, band 1's NODATA value, scale and offset) and then read by windows of nodes
//! ([`GdalGrid::read_window`], one RasterIO call for the window only) or scanned a block of
//! rows at a time ([`GdalGrid::scan`]).
//!
//! - **Band**: band 1 holds the values (BAG: the elevation band; S-102, with GDAL 3.8 or later:
//!   depths, so `seafloor.values = "depth"`; their band 2, the uncertainty, is not read). A file with several bands elsewhere gets a warning; a file with no band but
//!   subdatasets (a NetCDF with several variables) an error listing them.
//! - **Georeferencing**: GDAL's geotransform places the corners of the pixels (PixelIsArea),
//!   row 0 at the north when the y step is negative; shoal's nodes are the pixel centres, row
//!   0 the southernmost. Rotated or sheared grids are refused.
//! - **CRS**: see `gdal_crs.rs` (projected or geographic, its EPSG code or its PROJ string). No
//!   CRS (an XYZ file): coordinates are metres, as for an ESRI ASCII grid.
//! - **Values**: raw × scale + offset when the band has them (NetCDF's scale_factor and
//!   add_offset); a raw value equal to the NODATA value (compared in float32 for a float32
//!   band, as GDAL does) or NaN is NODATA. A data value must be an elevation within
//!   ±[`MAX_ABS_ELEVATION`](super::MAX_ABS_ELEVATION) metres.
//!
//! GDAL's own messages are not printed: its errors come back in [`SeafloorError::Gdal`], and
//! its warnings while opening the file become the grid's warnings.

use super::geokeys::check_lattice;
use super::load::{Crs, NodeWindow, MAX_LOAD_NODES};
use super::{Lattice, SeafloorError};
use gdal::errors::{CplErrType, GdalError};
use gdal::raster::GdalDataType;
use gdal::{Dataset, DatasetOptions, GdalOpenFlags, Metadata};
use std::cell::RefCell;
use std::path::Path;

/// Values read per block when scanning the whole grid (about 8 MB of f64).
const SCAN_VALUES: usize = 1 << 20;

/// An open grid file read through GDAL.
pub(crate) struct GdalGrid {
    name: String,
    dataset: Dataset,
    width: usize,
    height: usize,
    /// Node positions in the CRS's units (south-west node, spacing).
    pub lattice: Lattice,
    pub crs: Crs,
    /// Whether raster row 0 is the northernmost (geotransform y step < 0).
    north_up: bool,
    /// Raw values taken as NODATA: band 1's NODATA value (and its float32 rounding).
    nodata: Vec<f64>,
    scale: f64,
    offset: f64,
    /// "netCDF: Network Common Data Format": the GDAL driver's short and long names.
    pub driver: String,
    short_driver: String,
    /// Things worth telling the user (GDAL's warnings, a datum treated as WGS84, ...).
    pub warnings: Vec<String>,
}

thread_local! {
    /// GDAL's warnings on this thread since the last [`take_gdal_warnings`].
    static GDAL_WARNINGS: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Routes GDAL's messages away from stderr: warnings are kept for the grid's warnings, errors
/// are dropped (GDAL also returns them to the caller, which reports them).
fn install_error_handler() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        gdal::config::set_error_handler(|class, _number, msg| {
            if class == CplErrType::Warning {
                GDAL_WARNINGS.with(|w| w.borrow_mut().push(msg.trim().to_string()));
            }
        });
    });
}

/// Turns off HDF5's automatic printing of its error stack. netCDF-C, under GDAL's netCDF
/// driver, probes optional attributes of a NetCDF-4 file through HDF5, and HDF5 printed every
/// failed probe (about 12 lines each, over 500 lines for the gdal tests) on stderr although
/// nothing was wrong (issue 13). GDAL's own HDF5 driver does the same thing,
/// H5Eset_auto2(H5E_DEFAULT, NULL, NULL). The function is looked up in the process (libgdal
/// loads libhdf5 through libnetcdf); where it is absent nothing is done. A thread-safe HDF5
/// (Debian's) keeps the setting per thread, so every open calls it.
#[cfg(unix)]
fn silence_hdf5() {
    // herr_t H5Eset_auto2(hid_t estack_id, H5E_auto2_t func, void *client_data);
    // hid_t is int64_t from HDF5 1.10 on; H5E_DEFAULT is 0
    type SetAuto = unsafe extern "C" fn(i64, *const libc::c_void, *const libc::c_void) -> i32;
    // SAFETY: dlsym with a NUL-terminated name; a non-null result is HDF5's H5Eset_auto2,
    // whose C signature SetAuto follows, called with the default stack and no handler.
    unsafe {
        let sym = libc::dlsym(libc::RTLD_DEFAULT, c"H5Eset_auto2".as_ptr());
        if !sym.is_null() {
            let set_auto: SetAuto = std::mem::transmute::<*mut libc::c_void, SetAuto>(sym);
            set_auto(0, std::ptr::null(), std::ptr::null());
        }
    }
}

#[cfg(not(unix))]
fn silence_hdf5() {}

fn take_gdal_warnings() -> Vec<String> {
    GDAL_WARNINGS.with(|w| std::mem::take(&mut *w.borrow_mut()))
}

/// GDAL's own message in an error of the `gdal` crate.
pub(crate) fn message(e: &GdalError) -> String {
    match e {
        GdalError::CplError { msg, .. } | GdalError::NullPointer { msg, .. } if !msg.is_empty() => {
            msg.clone()
        }
        other => other.to_string(),
    }
}

impl GdalGrid {
    /// Opens a grid file with GDAL and reads its georeferencing. Errors name the file.
    pub fn open(path: &Path) -> Result<GdalGrid, SeafloorError> {
        let name = path.display().to_string();
        let fail = |reason: String| SeafloorError::Gdal {
            path: name.clone(),
            reason,
        };
        install_error_handler();
        silence_hdf5(); // per thread: a thread-safe HDF5 keeps the setting per thread
        take_gdal_warnings();
        let options = DatasetOptions {
            open_flags: GdalOpenFlags::GDAL_OF_RASTER | GdalOpenFlags::GDAL_OF_VERBOSE_ERROR,
            ..DatasetOptions::default()
        };
        let dataset = match Dataset::open_ex(path, options) {
            Ok(d) => d,
            Err(e) => {
                // a missing file is an I/O error, as for the other formats (GDAL's virtual
                // file systems, /vsizip/... and the like, are not on disk)
                if !name.starts_with("/vsi") {
                    if let Err(source) = std::fs::metadata(path) {
                        return Err(SeafloorError::Io { path: name, source });
                    }
                }
                return Err(fail(format!("GDAL cannot open it: {}", message(&e))));
            }
        };
        let driver = dataset.driver();
        let short_driver = driver.short_name();
        let driver = format!("{short_driver}: {}", driver.long_name());
        let bands = dataset.raster_count();
        if bands == 0 {
            let subs: Vec<String> = dataset
                .metadata_domain("SUBDATASETS")
                .unwrap_or_default()
                .into_iter()
                .filter_map(|kv| {
                    let (k, v) = kv.split_once('=')?;
                    k.ends_with("_NAME").then(|| v.to_string())
                })
                .collect();
            return Err(fail(if subs.is_empty() {
                format!("GDAL ({driver}) finds no raster band in it: expected a grid")
            } else {
                format!(
                    "it holds {} subdatasets and no single grid: {}; extract the one of \
                     elevations or depths, e.g. gdal_translate -of netCDF '{}' elevation.nc",
                    subs.len(),
                    subs.join(", "),
                    subs[0]
                )
            }));
        }
        let (width, height) = dataset.raster_size();
        if width < 2 || height < 2 {
            return Err(fail(format!(
                "{width} × {height} pixels: a grid needs at least 2 × 2"
            )));
        }
        let mut warnings = Vec::new();
        // BAG and S-102 hold the values in band 1 and the uncertainty in band 2
        if bands > 1 && !["BAG", "S102"].contains(&short_driver.as_str()) {
            warnings.push(format!(
                "{name}: {bands} bands; band 1 is read as the grid's values"
            ));
        }
        let band = dataset
            .rasterband(1)
            .map_err(|e| fail(format!("band 1: {}", message(&e))))?;
        let band_type = band.band_type();
        if band_type == GdalDataType::Unknown {
            return Err(fail(
                "band 1 holds complex or unknown samples: expected real numbers".into(),
            ));
        }
        let nodata = match band.no_data_value() {
            None => Vec::new(),
            Some(nd) if band_type == GdalDataType::Float32 => vec![nd, f64::from(nd as f32)],
            Some(nd) => vec![nd],
        };
        let scale = band.scale().unwrap_or(1.0);
        let offset = band.offset().unwrap_or(0.0);
        if !(scale.is_finite() && scale != 0.0 && offset.is_finite()) {
            return Err(fail(format!(
                "band 1 has scale {scale} and offset {offset}: expected a finite non-zero scale \
                 and a finite offset"
            )));
        }
        unit_check(&band.unit(), &name, &mut warnings).map_err(fail)?;
        let gt = dataset.geo_transform().map_err(|e| {
            fail(format!(
                "no georeferencing (GDAL: {}): shoal needs the grid's position and cell size",
                message(&e)
            ))
        })?;
        let (lattice, north_up) = lattice_of(&gt, width, height).map_err(fail)?;
        let crs = super::gdal_crs::crs_of(&dataset, &name, &mut warnings).map_err(fail)?;
        check_lattice(&lattice, &crs).map_err(fail)?;
        warnings.extend(
            take_gdal_warnings()
                .into_iter()
                .map(|w| format!("{name}: GDAL: {w}")),
        );
        Ok(GdalGrid {
            name,
            dataset,
            width,
            height,
            lattice,
            crs,
            north_up,
            nodata,
            scale,
            offset,
            driver,
            short_driver,
            warnings,
        })
    }

    fn fail(&self, reason: String) -> SeafloorError {
        SeafloorError::Gdal {
            path: self.name.clone(),
            reason,
        }
    }

    /// Raster rows r0..r0 + rows, columns c0..c0 + cols, as stored (row 0 the top of the
    /// raster), NaN at NODATA, after scale and offset.
    fn rows(
        &self,
        r0: usize,
        rows: usize,
        c0: usize,
        cols: usize,
    ) -> Result<Vec<f64>, SeafloorError> {
        let band = self
            .dataset
            .rasterband(1)
            .map_err(|e| self.fail(format!("band 1: {}", message(&e))))?;
        let buf = band
            .read_as::<f64>((c0 as isize, r0 as isize), (cols, rows), (cols, rows), None)
            .map_err(|e| {
                self.fail(format!(
                    "cannot read rows {} to {} (from the top): {}",
                    r0 + 1,
                    r0 + rows,
                    message(&e)
                ))
            })?;
        let (_, mut v) = buf.into_shape_and_vec();
        for (k, x) in v.iter_mut().enumerate() {
            if x.is_nan() || self.nodata.contains(x) {
                *x = f64::NAN;
            } else {
                *x = self.checked(*x * self.scale + self.offset, r0 + k / cols, c0 + k % cols)?;
            }
        }
        Ok(v)
    }

    /// The raw values (before any sign convention) and NODATA flags of a window of lattice
    /// nodes, south to north: entry `j * nx + i` is node (i0 + i, j0 + j).
    pub fn read_window(&mut self, win: NodeWindow) -> Result<(Vec<f64>, Vec<bool>), SeafloorError> {
        let NodeWindow { i0, j0, nx, ny } = win;
        if nx == 0 || ny == 0 || i0 + nx > self.width || j0 + ny > self.height {
            return Err(self.fail(format!("window {win:?} is not inside the grid")));
        }
        if nx * ny > MAX_LOAD_NODES {
            return Err(self.fail(format!(
                "a window of {nx} × {ny} nodes: at most {MAX_LOAD_NODES} are loaded at once"
            )));
        }
        // raster rows of lattice rows j0 ..= j0 + ny - 1
        let r0 = if self.north_up {
            self.height - (j0 + ny)
        } else {
            j0
        };
        let v = self.rows(r0, ny, i0, nx)?;
        let mut z = vec![0.0; nx * ny];
        let mut missing = vec![false; nx * ny];
        for r in 0..ny {
            let j = if self.north_up { ny - 1 - r } else { r };
            for i in 0..nx {
                let x = v[r * nx + i];
                if x.is_nan() {
                    missing[j * nx + i] = true;
                } else {
                    z[j * nx + i] = x;
                }
            }
        }
        Ok((z, missing))
    }

    /// Calls `f` with every value of the grid (None at NODATA), reading a block of rows at a
    /// time.
    pub fn scan(&mut self, mut f: impl FnMut(Option<f64>)) -> Result<(), SeafloorError> {
        let (w, h) = (self.width, self.height);
        let block = self
            .dataset
            .rasterband(1)
            .map(|b| b.block_size().1.max(1))
            .unwrap_or(1);
        let rows = (SCAN_VALUES / w).max(1).div_ceil(block) * block;
        let mut r0 = 0;
        while r0 < h {
            let n = rows.min(h - r0);
            for x in self.rows(r0, n, 0, w)? {
                f((!x.is_nan()).then_some(x));
            }
            r0 += n;
        }
        Ok(())
    }

    /// A data value must be a finite elevation within ±MAX_ABS_ELEVATION.
    fn checked(&self, v: f64, row: usize, col: usize) -> Result<f64, SeafloorError> {
        if let Ok(v) = super::raster_elevation(v, row, col, "") {
            return Ok(v);
        }
        let hint = match self.nodata.first() {
            Some(nd) => format!("band 1's NODATA value is {nd}"),
            None if self.short_driver == "XYZ" => "an XYZ file has no NODATA value: leave the \
                                                   lines without data out, and GDAL reads their \
                                                   nodes as NODATA"
                .to_string(),
            None => "band 1 has no NODATA value".to_string(),
        };
        super::raster_elevation(v, row, col, &hint).map_err(|m| self.fail(m))
    }
}

/// The node lattice of a GDAL geotransform (pixel corners, row 0 at the top) and whether the
/// raster's row 0 is the northernmost.
fn lattice_of(gt: &[f64; 6], width: usize, height: usize) -> Result<(Lattice, bool), String> {
    if !gt.iter().all(|v| v.is_finite()) {
        return Err(format!("the geotransform {gt:?} is not finite"));
    }
    if gt[2] != 0.0 || gt[4] != 0.0 {
        return Err(format!(
            "the grid is rotated or sheared (geotransform terms {} and {}): not supported; \
             warp it onto a north-up grid first (e.g. gdalwarp)",
            gt[2], gt[4]
        ));
    }
    if gt[1] <= 0.0 || gt[5] == 0.0 {
        return Err(format!(
            "the geotransform gives cells of {} × {}: expected a positive x step (columns \
             running east) and a non-zero y step",
            gt[1], gt[5]
        ));
    }
    let north_up = gt[5] < 0.0;
    let (dx, dy) = (gt[1], gt[5].abs());
    let x0 = gt[0] + 0.5 * dx;
    let y0 = if north_up {
        gt[3] - (height as f64 - 0.5) * dy
    } else {
        gt[3] + 0.5 * dy
    };
    Ok((
        Lattice {
            nx: width,
            ny: height,
            x0,
            y0,
            dx,
            dy,
        },
        north_up,
    ))
}

/// Band 1's unit must be metres if it is given: feet are refused, other units warned about.
fn unit_check(unit: &str, name: &str, warnings: &mut Vec<String>) -> Result<(), String> {
    let u = unit.trim().to_ascii_lowercase();
    if u.is_empty() || ["m", "metre", "metres", "meter", "meters"].contains(&u.as_str()) {
        return Ok(());
    }
    if u.contains("ft") || u.contains("feet") || u.contains("foot") {
        return Err(format!(
            "band 1's unit is {unit:?}: elevations must be in metres (convert them first, e.g. \
             gdal_calc.py)"
        ));
    }
    warnings.push(format!(
        "{name}: band 1's unit is {unit:?}; shoal reads the values as metres"
    ));
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lattice_from_north_up_and_south_up_geotransforms() {
        // 4 × 3 pixels of 10 × 5 m, top-left corner at (100, 215)
        let (l, north_up) = lattice_of(&[100.0, 10.0, 0.0, 215.0, 0.0, -5.0], 4, 3).unwrap();
        assert!(north_up);
        assert_eq!((l.x0, l.y0, l.dx, l.dy), (105.0, 202.5, 10.0, 5.0));
        assert_eq!(l.y_max(), 212.5);
        // the same grid stored south first (a NetCDF read bottom-up)
        let (l2, north_up) = lattice_of(&[100.0, 10.0, 0.0, 200.0, 0.0, 5.0], 4, 3).unwrap();
        assert!(!north_up);
        assert_eq!(l2, l);
        let rotated = lattice_of(&[0.0, 1.0, 0.2, 0.0, 0.0, -1.0], 4, 3).unwrap_err();
        assert!(
            rotated.contains("rotated") && rotated.contains("gdalwarp"),
            "{rotated}"
        );
        assert!(lattice_of(&[0.0, -1.0, 0.0, 0.0, 0.0, -1.0], 4, 3).is_err());
        assert!(lattice_of(&[f64::NAN, 1.0, 0.0, 0.0, 0.0, -1.0], 4, 3).is_err());
    }

    #[test]
    fn band_units_other_than_metres() {
        let mut w = Vec::new();
        for ok in ["", "m", "metres", "Meters"] {
            unit_check(ok, "f", &mut w).unwrap();
        }
        assert!(w.is_empty());
        assert!(unit_check("ft", "f", &mut w)
            .unwrap_err()
            .contains("metres"));
        unit_check("fathoms", "f", &mut w).unwrap();
        assert!(w[0].contains("\"fathoms\""), "{w:?}");
    }
}
