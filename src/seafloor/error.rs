//! The one error type of the seafloor module.

use super::Extent;

/// Everything that can go wrong when building, reading, writing or querying a seafloor.
///
/// The grid-file variants (`Header`, `MissingKey`, `BadValue`, `DataCount`) all print as
/// `<source> line <n>: <field>: <what is wrong and what is allowed>`.
#[derive(Debug, thiserror::Error)]
pub enum SeafloorError {
    /// A query point lies outside the node-centre extent of the grid.
    #[error("point ({x}, {y}) is outside the seafloor grid, which covers {extent}")]
    OutsideGrid { x: f64, y: f64, extent: Extent },

    /// A query argument is NaN or infinite.
    #[error("{what} must be a finite number, got {value}")]
    NonFinite { what: &'static str, value: f64 },

    /// A query argument is finite but not allowed (e.g. a non-positive resolution).
    #[error("{what}: {reason}")]
    InvalidQuery { what: &'static str, reason: String },

    /// The node array handed to [`Seafloor::from_nodes`](super::Seafloor::from_nodes) is not a
    /// valid grid.
    #[error("invalid seafloor grid: {0}")]
    InvalidGrid(String),

    /// A parameter of the synthetic floor is out of range.
    #[error("invalid synthetic seafloor parameter {field}: {reason}")]
    InvalidSynthetic { field: &'static str, reason: String },

    /// An ESRI ASCII header line is malformed: unknown or repeated key, missing or bad value.
    #[error("{source_name} line {line}: {field}: {reason}")]
    Header {
        source_name: String,
        line: usize,
        field: String,
        reason: String,
    },

    /// A required ESRI ASCII header key is absent; `line` is where the header ended.
    #[error("{source_name} line {line}: {field}: {reason}")]
    MissingKey {
        source_name: String,
        line: usize,
        field: String,
        reason: String,
    },

    /// A data value of an ESRI ASCII grid is not a number, not finite, or out of range.
    #[error("{source_name} line {line}: {field}: {reason}")]
    BadValue {
        source_name: String,
        line: usize,
        field: String,
        reason: String,
    },

    /// An ESRI ASCII grid holds fewer or more data values than ncols × nrows.
    #[error("{source_name} line {line}: data: {reason}")]
    DataCount {
        source_name: String,
        line: usize,
        expected: usize,
        found: usize,
        reason: String,
    },

    /// A GeoTIFF cannot be read or written: malformed, unsupported, or not georeferenced.
    #[error("{path}: {reason}")]
    GeoTiff { path: String, reason: String },

    /// A grid file's name has no known extension.
    #[error(
        "{path}: unknown grid format; expected an ESRI ASCII grid (.asc) or a GeoTIFF (.tif, .tiff)"
    )]
    Format { path: String },

    /// A grid file read through GDAL (the `gdal` cargo feature) cannot be opened or read, or
    /// holds something shoal cannot use.
    #[error("{path}: {reason}")]
    Gdal { path: String, reason: String },

    /// A format that only the GDAL reader opens (NetCDF, BAG, XYZ, ...), in a build without the
    /// `gdal` cargo feature.
    #[error(
        "{path}: a .{extension} grid is read through GDAL, which this build of shoal leaves out; \
         build shoal with `cargo build --release --features gdal` (needs libgdal-dev), or \
         convert the grid to a GeoTIFF first (gdal_translate -of GTiff {path} grid.tif)"
    )]
    NeedsGdal { path: String, extension: String },

    /// The part of a grid that was asked for cannot be loaded: the mission area does not overlap
    /// the grid, is too large, or the grid does not hold the lattice a plan records.
    #[error("{path}: {reason}")]
    Region { path: String, reason: String },

    /// A declared CRS (`seafloor.crs`, `--crs`) disagrees with the one the file or its sidecar
    /// gives.
    #[error(
        "{path}: the declared CRS {declared} (seafloor.crs or --crs) conflicts with the grid's \
         own CRS {file_crs} ({file_source}); remove the declaration or correct the file"
    )]
    CrsConflict {
        path: String,
        declared: String,
        file_crs: String,
        file_source: String,
    },

    /// A crop or resampling of a grid ([`super::export_grid`]) cannot be done as asked;
    /// `option` names the request (`region`, `region-latlon`, `cell`), as the CLI's options do.
    #[error("{path}: --{option}: {reason}")]
    Crop {
        path: String,
        option: &'static str,
        reason: String,
    },

    /// Reading or writing a grid file failed.
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
}
