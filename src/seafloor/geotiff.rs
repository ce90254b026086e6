//! GeoTIFF grids (.tif, .tiff): the reader. A file is opened once ([`TiffGrid::open`]: the
//! header, the georeferencing and the CRS) and then read by windows of nodes
//! ([`TiffGrid::read_window`]), decoding only the strips or tiles that hold the window, or
//! scanned chunk by chunk ([`TiffGrid::scan`]) for statistics without holding the grid.
//!
//! Supported: one band of uint8/16/32, int8/16/32, float16/32/64 samples; strips or tiles;
//! uncompressed, PackBits, LZW or Deflate, with or without a predictor (as the `tiff` crate
//! decodes them); the georeferencing of ModelPixelScale (33550) + ModelTiepoint (33922), or a
//! ModelTransformation (34264) without rotation; GeoKeyDirectory (34735): GTModelTypeGeoKey,
//! GTRasterTypeGeoKey (PixelIsArea: the tiepoint is a pixel's corner; PixelIsPoint: its
//! centre), ProjectedCSTypeGeoKey / GeographicTypeGeoKey (EPSG codes), the linear and angular
//! units; GDAL_NODATA (42113). NaN samples are NODATA too. Not supported, with an error that
//! says so: several bands, rotated or sheared grids, grids georeferenced by control points,
//! geocentric CRSs, units other than metres and degrees.
//!
//! TIFF rows run north to south (when the pixel scale's y is positive, as GDAL writes it); the
//! windows returned here run south to north, as [`Seafloor::from_nodes`](super::Seafloor) takes
//! them.

use super::geokeys::{check_lattice, georeference, key, GeoKeys};
use super::load::{Crs, NodeWindow};
use super::{Lattice, SeafloorError};
use std::fs::File;
use std::io::BufReader;
use std::path::Path;
use tiff::decoder::{ChunkType, Decoder, DecodingResult, Limits};
use tiff::tags::Tag;

/// How the raster is cut into chunks.
#[derive(Debug, Clone, Copy)]
enum Chunks {
    Strips { rows: usize },
    Tiles { width: usize, height: usize },
}

/// An open GeoTIFF grid.
pub(crate) struct TiffGrid {
    name: String,
    decoder: Decoder<BufReader<File>>,
    width: usize,
    height: usize,
    /// Node positions in the CRS's units (south-west node, spacing).
    pub lattice: Lattice,
    pub crs: Crs,
    /// Whether TIFF row 0 is the northernmost (pixel scale y > 0).
    north_up: bool,
    nodata: Option<f64>,
    /// PhotometricInterpretation WhiteIsZero: the decoder inverts the samples (max − v for
    /// integers, 1 − v for floats), which [`to_values`] undoes. Elevations are data, not
    /// brightness: GDAL ignores the tag for data bands, and so do we.
    white_is_zero: bool,
    chunks: Chunks,
    /// Things worth telling the user (e.g. a datum treated as WGS84).
    pub warnings: Vec<String>,
}

impl TiffGrid {
    /// Opens a GeoTIFF and reads its georeferencing. Errors name the file.
    pub fn open(path: &Path) -> Result<TiffGrid, SeafloorError> {
        let name = path.display().to_string();
        let file = File::open(path).map_err(|source| SeafloorError::Io {
            path: name.clone(),
            source,
        })?;
        let fail = |reason: String| SeafloorError::GeoTiff {
            path: name.clone(),
            reason,
        };
        let tiff = |e: tiff::TiffError| fail(format!("not a readable TIFF: {e}"));
        let mut limits = Limits::default();
        limits.decoding_buffer_size = 1 << 30;
        limits.ifd_value_size = 16 << 20;
        let mut decoder = Decoder::new(BufReader::new(file))
            .map_err(tiff)?
            .with_limits(limits);
        let (w, h) = decoder.dimensions().map_err(tiff)?;
        let (width, height) = (w as usize, h as usize);
        if width < 2 || height < 2 {
            return Err(fail(format!(
                "{width} × {height} pixels: a grid needs at least 2 × 2"
            )));
        }
        match decoder.colortype().map_err(tiff)? {
            tiff::ColorType::Gray(_) => {}
            other => {
                return Err(fail(format!(
                    "the image is {other:?}: expected a single band of elevations"
                )))
            }
        }
        let format = decoder
            .find_tag_unsigned::<u16>(Tag::SampleFormat)
            .map_err(tiff)?
            .unwrap_or(1);
        if !(1..=3).contains(&format) {
            return Err(fail(format!(
                "SampleFormat {format} is not supported: expected unsigned or signed integers \
                 or IEEE floating point"
            )));
        }
        let white_is_zero = decoder
            .find_tag_unsigned::<u16>(Tag::PhotometricInterpretation)
            .map_err(tiff)?
            == Some(0);
        if white_is_zero && format == 2 {
            return Err(fail(
                "PhotometricInterpretation is WhiteIsZero with signed integers, which the TIFF \
                 reader cannot decode; rewrite the file as BlackIsZero (gdal_translate -co \
                 PHOTOMETRIC=MINISBLACK), the values are read as they are either way"
                    .into(),
            ));
        }
        let chunks = match decoder.get_chunk_type() {
            ChunkType::Strip => {
                let rows = decoder
                    .find_tag_unsigned::<u32>(Tag::RowsPerStrip)
                    .map_err(tiff)?
                    .unwrap_or(h)
                    .clamp(1, h) as usize;
                Chunks::Strips { rows }
            }
            ChunkType::Tile => {
                let tw = decoder
                    .find_tag_unsigned::<u32>(Tag::TileWidth)
                    .map_err(tiff)?;
                let th = decoder
                    .find_tag_unsigned::<u32>(Tag::TileLength)
                    .map_err(tiff)?;
                match (tw, th) {
                    (Some(tw), Some(th)) if tw > 0 && th > 0 => Chunks::Tiles {
                        width: tw as usize,
                        height: th as usize,
                    },
                    _ => return Err(fail("a tiled TIFF without TileWidth / TileLength".into())),
                }
            }
        };
        let keys = match decoder.find_tag(Tag::GeoKeyDirectoryTag).map_err(tiff)? {
            Some(v) => v.into_u16_vec().map_err(tiff)?,
            None => Vec::new(),
        };
        let doubles = decoder
            .find_tag(Tag::GeoDoubleParamsTag)
            .map_err(tiff)?
            .map(|v| v.into_f64_vec())
            .transpose()
            .map_err(tiff)?
            .unwrap_or_default();
        let ascii = decoder
            .find_tag(Tag::GeoAsciiParamsTag)
            .map_err(tiff)?
            .map(|v| v.into_string())
            .transpose()
            .map_err(tiff)?
            .unwrap_or_default();
        let geo = GeoKeys::parse(&keys, &doubles, &ascii).map_err(fail)?;
        let mut warnings = Vec::new();
        let crs = geo.crs(&name, &mut warnings).map_err(fail)?;
        let point = match geo.short(key::RASTER_TYPE) {
            None | Some(1) => false,
            Some(2) => true,
            Some(v) => {
                return Err(fail(format!(
                    "GTRasterTypeGeoKey = {v}: expected 1 (PixelIsArea) or 2 (PixelIsPoint)"
                )))
            }
        };
        let scale = find_f64s(&mut decoder, Tag::ModelPixelScaleTag).map_err(tiff)?;
        let ties = find_f64s(&mut decoder, Tag::ModelTiepointTag).map_err(tiff)?;
        let transform = find_f64s(&mut decoder, Tag::ModelTransformationTag).map_err(tiff)?;
        let (tie, sx, sy) = georeference(scale, ties, transform).map_err(fail)?;
        let off = if point { 0.0 } else { 0.5 };
        let north_up = sy > 0.0;
        let (dx, dy) = (sx, sy.abs());
        let x0 = tie[2] + (off - tie[0]) * dx;
        let y0 = if north_up {
            tie[3] - ((height - 1) as f64 + off - tie[1]) * dy
        } else {
            tie[3] + (off - tie[1]) * dy
        };
        let lattice = Lattice {
            nx: width,
            ny: height,
            x0,
            y0,
            dx,
            dy,
        };
        check_lattice(&lattice, &crs).map_err(fail)?;
        let nodata = match decoder.find_tag(Tag::GdalNodata).map_err(tiff)? {
            None => None,
            Some(v) => {
                let text = v.into_string().map_err(tiff)?;
                let t = text.trim_matches(|c: char| c == '\0' || c.is_whitespace());
                match t.parse::<f64>() {
                    Ok(nd) => Some(nd),
                    Err(_) => {
                        return Err(fail(format!(
                            "GDAL_NODATA (42113) = {t:?}: expected a number"
                        )))
                    }
                }
            }
        };
        Ok(TiffGrid {
            name,
            decoder,
            width,
            height,
            lattice,
            crs,
            north_up,
            nodata,
            white_is_zero,
            chunks,
            warnings,
        })
    }

    fn fail(&self, reason: String) -> SeafloorError {
        SeafloorError::GeoTiff {
            path: self.name.clone(),
            reason,
        }
    }

    /// The TIFF row of lattice row j (j = 0 the southernmost).
    fn tiff_row(&self, j: usize) -> usize {
        if self.north_up {
            self.height - 1 - j
        } else {
            j
        }
    }

    /// Chunk `index` as values: NaN where the sample is NODATA (GDAL_NODATA or NaN). Also
    /// returns the chunk's data width (its height is len / width).
    fn chunk(
        &mut self,
        index: usize,
        data_width: usize,
        data_height: usize,
    ) -> Result<Vec<f64>, SeafloorError> {
        let res = u32::try_from(index)
            .map_err(|_| self.fail(format!("chunk {index} is beyond the TIFF's range")))
            .and_then(|i| {
                self.decoder
                    .read_chunk(i)
                    .map_err(|e| self.fail(format!("cannot decode chunk {index}: {e}")))
            })?;
        let v = to_values(res, self.nodata, self.white_is_zero);
        if v.len() < data_width * data_height {
            return Err(self.fail(format!(
                "chunk {index} holds {} samples, expected {data_width} × {data_height}",
                v.len()
            )));
        }
        Ok(v)
    }

    /// (chunk index, first TIFF row, first column, data width, data height) of every chunk that
    /// intersects TIFF rows r0..=r1 and columns c0..=c1.
    fn chunks_over(&self, r0: usize, r1: usize, c0: usize, c1: usize) -> Vec<[usize; 5]> {
        let (w, h) = (self.width, self.height);
        match self.chunks {
            Chunks::Strips { rows } => (r0 / rows..=r1 / rows)
                .map(|s| [s, s * rows, 0, w, rows.min(h - s * rows)])
                .collect(),
            Chunks::Tiles { width, height } => {
                let across = w.div_ceil(width);
                let mut out = Vec::new();
                for ty in r0 / height..=r1 / height {
                    for tx in c0 / width..=c1 / width {
                        out.push([
                            ty * across + tx,
                            ty * height,
                            tx * width,
                            width.min(w - tx * width),
                            height.min(h - ty * height),
                        ]);
                    }
                }
                out
            }
        }
    }

    /// The raw values (as stored, before any sign convention) and NODATA flags of a window of
    /// lattice nodes, south to north: entry `j * nx + i` is node (i0 + i, j0 + j).
    pub fn read_window(&mut self, win: NodeWindow) -> Result<(Vec<f64>, Vec<bool>), SeafloorError> {
        let NodeWindow { i0, j0, nx, ny } = win;
        if nx == 0 || ny == 0 || i0 + nx > self.width || j0 + ny > self.height {
            return Err(self.fail(format!("window {win:?} is not inside the grid")));
        }
        if nx * ny > super::load::MAX_LOAD_NODES {
            return Err(self.fail(format!(
                "a window of {nx} × {ny} nodes: at most {} are loaded at once",
                super::load::MAX_LOAD_NODES
            )));
        }
        let (ra, rb) = (self.tiff_row(j0), self.tiff_row(j0 + ny - 1));
        let (r0, r1) = (ra.min(rb), ra.max(rb));
        let (c0, c1) = (i0, i0 + nx - 1);
        let mut z = vec![0.0; nx * ny];
        let mut missing = vec![false; nx * ny];
        for [index, row0, col0, cw, ch] in self.chunks_over(r0, r1, c0, c1) {
            let data = self.chunk(index, cw, ch)?;
            for r in row0.max(r0)..(row0 + ch).min(r1 + 1) {
                let j = if self.north_up {
                    self.height - 1 - r
                } else {
                    r
                } - j0;
                for c in col0.max(c0)..(col0 + cw).min(c1 + 1) {
                    let v = data[(r - row0) * cw + (c - col0)];
                    let k = j * nx + (c - i0);
                    if v.is_nan() {
                        missing[k] = true;
                    } else {
                        z[k] = self.checked(v, r, c)?;
                    }
                }
            }
        }
        Ok((z, missing))
    }

    /// Calls `f` with every sample of the grid, chunk by chunk (None at NODATA), holding one
    /// chunk at a time.
    pub fn scan(&mut self, mut f: impl FnMut(Option<f64>)) -> Result<(), SeafloorError> {
        let (h, w) = (self.height, self.width);
        for [index, row0, col0, cw, ch] in self.chunks_over(0, h - 1, 0, w - 1) {
            let data = self.chunk(index, cw, ch)?;
            for r in 0..ch {
                for c in 0..cw {
                    let v = data[r * cw + c];
                    if v.is_nan() {
                        f(None);
                    } else {
                        f(Some(self.checked(v, row0 + r, col0 + c)?));
                    }
                }
            }
        }
        Ok(())
    }

    /// A data value must be a finite elevation within ±MAX_ABS_ELEVATION.
    fn checked(&self, v: f64, row: usize, col: usize) -> Result<f64, SeafloorError> {
        let hint = || match self.nodata {
            Some(nd) => format!("GDAL_NODATA is {nd}"),
            None => "the file has no GDAL_NODATA tag".to_string(),
        };
        super::raster_elevation(v, row, col, &hint()).map_err(|m| self.fail(m))
    }
}

fn find_f64s(
    d: &mut Decoder<BufReader<File>>,
    tag: Tag,
) -> Result<Option<Vec<f64>>, tiff::TiffError> {
    d.find_tag(tag)?.map(|v| v.into_f64_vec()).transpose()
}

/// The samples of a chunk as f64, NaN at NODATA. A float32 sample is compared with the NODATA
/// value rounded to float32, as GDAL does. With `white_is_zero` the decoder's inversion is
/// undone first, in the sample's own type (exact for integers; for floats 1 − (1 − v), within
/// an ulp of v).
fn to_values(res: DecodingResult, nodata: Option<f64>, white_is_zero: bool) -> Vec<f64> {
    fn conv<T: Copy>(v: Vec<T>, f: impl Fn(T) -> f64, nd: Option<f64>) -> Vec<f64> {
        v.into_iter()
            .map(|s| {
                let x = f(s);
                if nd == Some(x) {
                    f64::NAN
                } else {
                    x
                }
            })
            .collect()
    }
    let nd32 = nodata.map(|n| f64::from(n as f32));
    let res = if white_is_zero {
        undo_inversion(res)
    } else {
        res
    };
    match res {
        DecodingResult::U8(v) => conv(v, f64::from, nodata),
        DecodingResult::I8(v) => conv(v, f64::from, nodata),
        DecodingResult::U16(v) => conv(v, f64::from, nodata),
        DecodingResult::I16(v) => conv(v, f64::from, nodata),
        DecodingResult::U32(v) => conv(v, f64::from, nodata),
        DecodingResult::I32(v) => conv(v, f64::from, nodata),
        DecodingResult::U64(v) => conv(v, |s| s as f64, nodata),
        DecodingResult::I64(v) => conv(v, |s| s as f64, nodata),
        DecodingResult::F16(v) => conv(v, |s| s.to_f64(), nodata),
        DecodingResult::F32(v) => conv(v, f64::from, nd32),
        DecodingResult::F64(v) => conv(v, |s| s, nodata),
    }
}

/// The decoder's WhiteIsZero inversion undone (it inverts unsigned integers as max − v and
/// floats as 1 − v; signed integers it refuses, see `open`).
fn undo_inversion(res: DecodingResult) -> DecodingResult {
    match res {
        DecodingResult::U8(v) => DecodingResult::U8(v.into_iter().map(|s| u8::MAX - s).collect()),
        DecodingResult::U16(v) => {
            DecodingResult::U16(v.into_iter().map(|s| u16::MAX - s).collect())
        }
        DecodingResult::U32(v) => {
            DecodingResult::U32(v.into_iter().map(|s| u32::MAX - s).collect())
        }
        DecodingResult::U64(v) => {
            DecodingResult::U64(v.into_iter().map(|s| u64::MAX - s).collect())
        }
        DecodingResult::F32(v) => DecodingResult::F32(v.into_iter().map(|s| 1.0 - s).collect()),
        DecodingResult::F64(v) => DecodingResult::F64(v.into_iter().map(|s| 1.0 - s).collect()),
        other => other,
    }
}
