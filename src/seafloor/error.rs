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
    OutsideGrid {
        /// The point's x, metres.
        x: f64,
        /// The point's y, metres.
        y: f64,
        /// The grid's node-centre extent.
        extent: Extent,
    },

    /// A query argument is NaN or infinite.
    #[error("{what} must be a finite number, got {value}")]
    NonFinite {
        /// The argument's name.
        what: &'static str,
        /// The value given.
        value: f64,
    },

    /// A query argument is finite but not allowed (e.g. a non-positive resolution).
    #[error("{what}: {reason}")]
    InvalidQuery {
        /// The argument's name, e.g. "resolution".
        what: &'static str,
        /// What is wrong and what is allowed.
        reason: String,
    },

    /// The node array handed to [`Seafloor::from_nodes`](super::Seafloor::from_nodes) is not a
    /// valid grid.
    #[error("invalid seafloor grid: {0}")]
    InvalidGrid(String),

    /// A parameter of the synthetic floor is out of range.
    #[error("invalid synthetic seafloor parameter {field}: {reason}")]
    InvalidSynthetic {
        /// The parameter's key in `seafloor.synthetic`, e.g. "cell".
        field: &'static str,
        /// What is wrong and what is allowed.
        reason: String,
    },

    /// An ESRI ASCII header line is malformed: unknown or repeated key, missing or bad value.
    #[error("{source_name} line {line}: {field}: {reason}")]
    Header {
        /// The grid's source name (usually the file's path).
        source_name: String,
        /// The line, 1-based.
        line: usize,
        /// The header key, e.g. "ncols" or "NODATA_value".
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },

    /// A required ESRI ASCII header key is absent; `line` is where the header ended.
    #[error("{source_name} line {line}: {field}: {reason}")]
    MissingKey {
        /// The grid's source name (usually the file's path).
        source_name: String,
        /// The line where the header ended, 1-based.
        line: usize,
        /// The missing header key.
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },

    /// A data value of an ESRI ASCII grid is not a number, not finite, or out of range.
    #[error("{source_name} line {line}: {field}: {reason}")]
    BadValue {
        /// The grid's source name (usually the file's path).
        source_name: String,
        /// The line, 1-based.
        line: usize,
        /// The value's place in the file, "row r, column c" (1-based, rows from the north).
        field: String,
        /// What is wrong and what is allowed.
        reason: String,
    },

    /// An ESRI ASCII grid holds fewer or more data values than ncols × nrows.
    #[error("{source_name} line {line}: data: {reason}")]
    DataCount {
        /// The grid's source name (usually the file's path).
        source_name: String,
        /// The line of the first extra value, or the last line of data when values are missing;
        /// 1-based.
        line: usize,
        /// ncols × nrows.
        expected: usize,
        /// The number of values found (expected + 1 when there are more).
        found: usize,
        /// What is wrong, with the counts.
        reason: String,
    },

    /// A GeoTIFF cannot be read or written: malformed, unsupported, or not georeferenced.
    #[error("{path}: {reason}")]
    GeoTiff {
        /// The file's path.
        path: String,
        /// What is wrong.
        reason: String,
    },

    /// A grid file's name has no known extension.
    #[error(
        "{path}: unknown grid format; expected an ESRI ASCII grid (.asc) or a GeoTIFF (.tif, .tiff)"
    )]
    Format {
        /// The file's path.
        path: String,
    },

    /// A grid file read through GDAL (the `gdal` cargo feature) cannot be opened or read, or
    /// holds something shoal cannot use.
    #[error("{path}: {reason}")]
    Gdal {
        /// The file's path.
        path: String,
        /// What is wrong (GDAL's message or what shoal cannot use).
        reason: String,
    },

    /// A format that only the GDAL reader opens (NetCDF, BAG, XYZ, ...), in a build without the
    /// `gdal` cargo feature.
    #[error(
        "{path}: a .{extension} grid is read through GDAL, which this build of shoal leaves out; \
         build shoal with `cargo build --release --features gdal` (needs libgdal-dev), or \
         convert the grid to a GeoTIFF first (gdal_translate -of GTiff {path} grid.tif)"
    )]
    NeedsGdal {
        /// The file's path.
        path: String,
        /// The file's extension, without the dot.
        extension: String,
    },

    /// The part of a grid that was asked for cannot be loaded: the mission area does not overlap
    /// the grid, is too large, or the grid does not hold the lattice a plan records.
    #[error("{path}: {reason}")]
    Region {
        /// The file's path.
        path: String,
        /// Why the region cannot be loaded.
        reason: String,
    },

    /// A declared CRS (`seafloor.crs`, `--crs`) disagrees with the one the file or its sidecar
    /// gives.
    #[error(
        "{path}: the declared CRS {declared} (seafloor.crs or --crs) conflicts with the grid's \
         own CRS {file_crs} ({file_source}); remove the declaration or correct the file"
    )]
    CrsConflict {
        /// The grid file's path.
        path: String,
        /// The declared CRS.
        declared: String,
        /// The CRS the file or its sidecar gives.
        file_crs: String,
        /// Where `file_crs` comes from (the file itself or its `.prj` sidecar).
        file_source: String,
    },

    /// A crop or resampling of a grid ([`super::export_grid`]) cannot be done as asked;
    /// `option` names the request (`region`, `region-latlon`, `cell`), as the CLI's options do.
    #[error("{path}: --{option}: {reason}")]
    Crop {
        /// The grid file's path.
        path: String,
        /// The request, as the CLI option without `--`: "region", "region-latlon" or "cell".
        option: &'static str,
        /// Why it cannot be done.
        reason: String,
    },

    /// Reading or writing a grid file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file's path.
        path: String,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
}
