//! GeoTIFF grids: the writer, for `shoal seafloor export -o x.tif` and for test fixtures.
//!
//! One band, strips (compressed or not) or tiles (uncompressed), with ModelPixelScale,
//! ModelTiepoint, a GeoKeyDirectory for the CRS and GDAL_NODATA. The tiepoint is written at the
//! south-west node (PixelIsPoint) or at the south-west pixel's outer corner (PixelIsArea, when
//! that gives the node back bit-exactly), so that reading a written grid gives the same node
//! positions bit for bit.

use super::load::Crs;
use super::{Lattice, Seafloor, SeafloorError};
use std::io::{BufWriter, Seek, Write};
use std::path::Path;
use tiff::encoder::{
    colortype, Compression, DeflateLevel, DirectoryEncoder, TiffEncoder, TiffKindStandard,
};
use tiff::tags::{SampleFormat, Tag};

/// The sample type written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleType {
    /// 32-bit IEEE float (values rounded); NODATA −99999.
    Float32,
    /// 64-bit IEEE float; NODATA −99999.
    Float64,
    /// Signed 16-bit integer, values −32767 to 32767; NODATA −32768.
    Int16,
    /// Signed 32-bit integer; NODATA −99999.
    Int32,
    /// Unsigned 16-bit integer, values 0 to 65534; NODATA 65535.
    UInt16,
}

impl SampleType {
    /// The NODATA value written in GDAL_NODATA: outside every allowed elevation.
    fn nodata(self) -> f64 {
        match self {
            SampleType::Int16 => -32768.0,
            SampleType::UInt16 => 65535.0,
            _ => -99999.0,
        }
    }
}

/// How the raster is laid out and compressed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TiffLayout {
    /// Strips of `rows` rows (0: about 64 KiB each).
    Strips {
        /// Rows per strip; 0 picks about 64 KiB per strip.
        rows: u32,
        /// How each strip is compressed.
        compression: TiffCompression,
    },
    /// Square tiles of `size` pixels (a multiple of 16), uncompressed.
    Tiles {
        /// The tile's side, pixels (a multiple of 16; at least 16).
        size: u32,
    },
}

/// The compression of a strip layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TiffCompression {
    /// Uncompressed.
    None,
    /// Deflate (zlib), balanced level.
    Deflate,
    /// LZW.
    Lzw,
}

/// What [`write_geotiff`] writes, besides the nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct GeoTiffOptions {
    /// The sample type of the band.
    pub sample: SampleType,
    /// Strips or tiles, and the compression.
    pub layout: TiffLayout,
    /// Written as GTCitationGeoKey (e.g. what a user-defined CRS is).
    pub citation: Option<String>,
}

impl Default for GeoTiffOptions {
    fn default() -> Self {
        GeoTiffOptions {
            sample: SampleType::Float32,
            layout: TiffLayout::Strips {
                rows: 0,
                compression: TiffCompression::None,
            },
            citation: None,
        }
    }
}

/// Writes nodes on `lattice` (south-west node and spacing, in the CRS's units) as a GeoTIFF,
/// atomically (a temporary file, then a rename). `values[j * nx + i]` is node (i, j), j = 0 the
/// southernmost; `nodata[k]` marks a NODATA node. Integer sample types need integral values in
/// range; float32 rounds.
pub fn write_geotiff(
    path: &Path,
    lattice: &Lattice,
    values: &[f64],
    nodata: &[bool],
    crs: &Crs,
    opts: &GeoTiffOptions,
) -> Result<(), SeafloorError> {
    let name = path.display().to_string();
    let fail = |reason: String| SeafloorError::GeoTiff {
        path: name.clone(),
        reason,
    };
    let (nx, ny) = (lattice.nx, lattice.ny);
    if values.len() != nx * ny || nodata.len() != nx * ny {
        return Err(fail(format!(
            "{nx} × {ny} nodes but {} values and {} NODATA flags",
            values.len(),
            nodata.len()
        )));
    }
    let (w, h) = match (u32::try_from(nx), u32::try_from(ny)) {
        (Ok(w), Ok(h)) => (w, h),
        _ => return Err(fail(format!("{nx} × {ny} nodes: too large for a TIFF"))),
    };
    // North to south, NODATA as the sample type's marker.
    let nd = opts.sample.nodata();
    let mut rows = Vec::with_capacity(nx * ny);
    for j in (0..ny).rev() {
        for i in 0..nx {
            let k = j * nx + i;
            rows.push(if nodata[k] { nd } else { values[k] });
        }
    }
    let io = |source: std::io::Error| SeafloorError::Io {
        path: name.clone(),
        source,
    };
    let mut tmp = crate::atomic_file::temp_for(path).map_err(io)?;
    {
        let mut out = BufWriter::new(tmp.as_file_mut());
        let t = |e: tiff::TiffError| fail(format!("cannot encode: {e}"));
        let check_int = |lo: f64, hi: f64, what: &str| -> Result<(), SeafloorError> {
            for (k, &v) in values.iter().enumerate() {
                let fits = v.fract() == 0.0 && (lo..=hi).contains(&v) && v != nd;
                if !nodata[k] && !fits {
                    return Err(fail(format!(
                        "node (i = {}, j = {}) = {v} cannot be stored as {what}",
                        k % nx,
                        k / nx
                    )));
                }
            }
            Ok(())
        };
        macro_rules! image {
            ($ct:ty, $conv:expr) => {{
                let data: Vec<_> = rows.iter().map($conv).collect();
                write_image::<_, $ct>(&mut out, w, h, &data, opts, lattice, crs, nd).map_err(t)?
            }};
        }
        match opts.sample {
            SampleType::Float32 => image!(colortype::Gray32Float, |&v| v as f32),
            SampleType::Float64 => image!(colortype::Gray64Float, |&v| v),
            SampleType::Int16 => {
                check_int(-32767.0, 32767.0, "int16")?;
                image!(colortype::GrayI16, |&v| v as i16)
            }
            SampleType::Int32 => {
                check_int(-2147483648.0, 2147483647.0, "int32")?;
                image!(colortype::GrayI32, |&v| v as i32)
            }
            SampleType::UInt16 => {
                check_int(0.0, 65534.0, "uint16")?;
                image!(colortype::Gray16, |&v| v as u16)
            }
        }
        out.flush().map_err(io)?;
    }
    crate::atomic_file::persist(tmp, path).map_err(io)?;
    Ok(())
}

/// The GeoTIFF tags of `lattice` and `crs` (see the module docs for the tiepoint).
#[allow(clippy::too_many_arguments)]
fn geo_tags<W: Write + Seek>(
    enc: &mut DirectoryEncoder<'_, W, TiffKindStandard>,
    lattice: &Lattice,
    crs: &Crs,
    citation: Option<&str>,
    nodata: f64,
) -> tiff::TiffResult<()> {
    let l = lattice;
    let corner = |c: f64, d: f64| {
        let corner = c - d / 2.0;
        (corner + 0.5 * d == c).then_some(corner)
    };
    let (area, tie) = match (corner(l.x0, l.dx), corner(l.y0, l.dy)) {
        (Some(x), Some(y)) => (true, [0.0, l.ny as f64, 0.0, x, y, 0.0]),
        _ => (false, [0.0, (l.ny - 1) as f64, 0.0, l.x0, l.y0, 0.0]),
    };
    enc.write_tag(Tag::ModelPixelScaleTag, &[l.dx, l.dy, 0.0][..])?;
    enc.write_tag(Tag::ModelTiepointTag, &tie[..])?;
    let mut keys: Vec<[u16; 4]> = Vec::new();
    let mut ascii = String::new();
    let (model, code_key) = match crs {
        Crs::None => (None, None),
        Crs::Projected { epsg, .. } => (Some(1), Some((3072, epsg.unwrap_or(32767)))),
        Crs::Geographic { epsg } => (Some(2), Some((2048, epsg.unwrap_or(32767)))),
    };
    if let Some(m) = model {
        keys.push([1024, 0, 1, m]);
    }
    keys.push([1025, 0, 1, if area { 1 } else { 2 }]);
    let cite = citation.map(str::to_string).or(match crs {
        Crs::Projected { citation, .. } => citation.clone(),
        _ => None,
    });
    if let Some(c) = cite {
        ascii = format!("{c}|");
        keys.push([1026, 34737, ascii.len() as u16, 0]);
    }
    if let Some((k, code)) = code_key {
        keys.push([k, 0, 1, code]);
        keys.push(match crs {
            Crs::Geographic { .. } => [2054, 0, 1, 9102],
            _ => [3076, 0, 1, 9001],
        });
    }
    keys.sort();
    let mut dir: Vec<u16> = vec![1, 1, 0, keys.len() as u16];
    dir.extend(keys.iter().flatten());
    enc.write_tag(Tag::GeoKeyDirectoryTag, &dir[..])?;
    if !ascii.is_empty() {
        enc.write_tag(Tag::GeoAsciiParamsTag, ascii.as_str())?;
    }
    enc.write_tag(Tag::GdalNodata, format!("{nodata}").as_str())?;
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn write_image<W: Write + Seek, C: colortype::ColorType>(
    out: W,
    w: u32,
    h: u32,
    data: &[C::Inner],
    opts: &GeoTiffOptions,
    lattice: &Lattice,
    crs: &Crs,
    nd: f64,
) -> tiff::TiffResult<()>
where
    [C::Inner]: tiff::encoder::TiffValue,
    C::Inner: Copy + Default,
{
    let citation = opts.citation.as_deref();
    match opts.layout {
        TiffLayout::Strips { rows, compression } => {
            let compression = match compression {
                TiffCompression::None => Compression::Uncompressed,
                TiffCompression::Deflate => Compression::Deflate(DeflateLevel::Balanced),
                TiffCompression::Lzw => Compression::Lzw,
            };
            let mut enc = TiffEncoder::new(out)?.with_compression(compression);
            let mut image = enc.new_image::<C>(w, h)?;
            let row_bytes = (w as usize * std::mem::size_of::<C::Inner>()).max(1);
            let rows = if rows == 0 {
                (65536 / row_bytes).max(1) as u32
            } else {
                rows
            };
            image.rows_per_strip(rows.min(h))?;
            geo_tags(image.encoder(), lattice, crs, citation, nd)?;
            image.write_data(data)
        }
        TiffLayout::Tiles { size } => {
            let t = size.max(16) as usize;
            let (wu, hu) = (w as usize, h as usize);
            let mut enc = TiffEncoder::new(out)?;
            let mut d = enc.image_directory()?;
            let (mut offsets, mut counts) = (Vec::new(), Vec::new());
            for ty in 0..hu.div_ceil(t) {
                for tx in 0..wu.div_ceil(t) {
                    let mut tile = vec![C::Inner::default(); t * t];
                    for r in 0..t.min(hu - ty * t) {
                        for c in 0..t.min(wu - tx * t) {
                            tile[r * t + c] = data[(ty * t + r) * wu + tx * t + c];
                        }
                    }
                    offsets.push(u32::try_from(d.write_data(&tile[..])?)?);
                    counts.push(u32::try_from(t * t * std::mem::size_of::<C::Inner>())?);
                }
            }
            d.write_tag(Tag::ImageWidth, w)?;
            d.write_tag(Tag::ImageLength, h)?;
            d.write_tag(Tag::BitsPerSample, C::BITS_PER_SAMPLE[0])?;
            d.write_tag(Tag::Compression, 1u16)?;
            d.write_tag(Tag::PhotometricInterpretation, 1u16)?;
            d.write_tag(Tag::SamplesPerPixel, 1u16)?;
            d.write_tag(Tag::TileWidth, t as u32)?;
            d.write_tag(Tag::TileLength, t as u32)?;
            d.write_tag(Tag::TileOffsets, &offsets[..])?;
            d.write_tag(Tag::TileByteCounts, &counts[..])?;
            let format: &[SampleFormat] = C::SAMPLE_FORMAT;
            d.write_tag(Tag::SampleFormat, format[0].to_u16())?;
            geo_tags(&mut d, lattice, crs, citation, nd)?;
            d.finish()
        }
    }
}

impl Seafloor {
    /// Writes the grid as a GeoTIFF with the given CRS (and citation, e.g. for a local frame),
    /// losslessly: float32 when every node value is exactly a float32, float64 otherwise;
    /// strips of about 64 KiB, uncompressed.
    pub fn write_geotiff(
        &self,
        path: &Path,
        crs: &Crs,
        citation: Option<&str>,
    ) -> Result<(), SeafloorError> {
        let (values, nodata) = self.nodes();
        let exact32 = values.iter().all(|&v| f64::from(v as f32) == v);
        let opts = GeoTiffOptions {
            sample: if exact32 {
                SampleType::Float32
            } else {
                SampleType::Float64
            },
            citation: citation.map(str::to_string),
            ..GeoTiffOptions::default()
        };
        write_geotiff(path, &self.lattice(), values, nodata, crs, &opts)
    }
}
