//! ESRI ASCII grids (.asc): reading, with errors that name the file, line and field, and
//! atomic, exactly round-tripping writing.
//!
//! Header: `key value` lines, keys case-insensitive and in any order: `ncols`, `nrows`,
//! `xllcorner` or `xllcenter`, `yllcorner` or `yllcenter`, `cellsize` (or `dx` and `dy`, as
//! GDAL writes for non-square cells), optional `NODATA_value`. The header ends at the first
//! line that starts with a number. Data: nrows × ncols elevations in metres (negative below sea
//! level), rows north to south, read as one whitespace-separated stream (line breaks need not
//! match rows). A corner is the outer corner of the south-west cell, so the south-west node is at
//! corner + cellsize/2; a centre is the node itself.

use super::{Lattice, Seafloor, SeafloorError, MAX_ABS_ELEVATION, MAX_NODES_PER_AXIS};
use std::collections::HashMap;
use std::iter::Peekable;
use std::path::Path;

/// The NODATA marker written by [`Seafloor::to_esri_ascii`]; it lies outside the allowed
/// elevations, so it can never be confused with data.
const WRITTEN_NODATA: f64 = -99999.0;

/// Largest |coordinate| and spacing accepted in a header, metres: far beyond any projected
/// coordinate system, small enough that the grid's far corner is always finite.
const MAX_COORDINATE: f64 = 1e12;

/// Header keys, lower case.
const KEYS: [&str; 10] = [
    "ncols",
    "nrows",
    "xllcorner",
    "xllcenter",
    "yllcorner",
    "yllcenter",
    "cellsize",
    "dx",
    "dy",
    "nodata_value",
];

impl Seafloor {
    /// Reads an ESRI ASCII grid file. Errors name the file as given.
    pub fn read_esri_ascii(path: &Path) -> Result<Seafloor, SeafloorError> {
        let text = std::fs::read_to_string(path).map_err(|source| SeafloorError::Io {
            path: path.display().to_string(),
            source,
        })?;
        Seafloor::parse_esri_ascii(&text, &path.display().to_string())
    }

    /// Parses the text of an ESRI ASCII grid; `source_name` (usually the file path) starts every
    /// error message.
    pub fn parse_esri_ascii(text: &str, source_name: &str) -> Result<Seafloor, SeafloorError> {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text);
        let mut lines = text.lines().enumerate().map(|(k, l)| (k + 1, l)).peekable();
        let p = Parser { source_name };
        let h = p.header_of(&mut lines)?;
        let (z, nodata) = p.data(lines, &h)?;
        Seafloor::from_nodes(h.lattice, z, nodata)
    }

    /// The grid as ESRI ASCII text. Square cells are written with `cellsize`, others with `dx`
    /// and `dy`. The lower-left position is written as `xllcorner`/`yllcorner` when that gives
    /// back x0 and y0 bit-exactly on reading, else as `xllcenter`/`yllcenter`. NODATA nodes are
    /// written as -99999 (`NODATA_value -99999`); values use Rust's shortest round-trip
    /// formatting, so parse → write → parse is bit-exact.
    pub fn to_esri_ascii(&self) -> String {
        let corner = |c: f64, d: f64| {
            let corner = c - d / 2.0;
            (corner + d / 2.0 == c).then_some(corner)
        };
        let mut out = format!("ncols {}\nnrows {}\n", self.nx(), self.ny());
        match (corner(self.x0(), self.dx()), corner(self.y0(), self.dy())) {
            (Some(x), Some(y)) => out += &format!("xllcorner {x}\nyllcorner {y}\n"),
            _ => out += &format!("xllcenter {}\nyllcenter {}\n", self.x0(), self.y0()),
        }
        if self.dx() == self.dy() {
            out += &format!("cellsize {}\n", self.dx());
        } else {
            out += &format!("dx {}\ndy {}\n", self.dx(), self.dy());
        }
        out += &format!("NODATA_value {WRITTEN_NODATA}\n");
        for j in (0..self.ny()).rev() {
            let row: Vec<String> = (0..self.nx())
                .map(|i| {
                    let v = if self.is_nodata(i, j) {
                        WRITTEN_NODATA
                    } else {
                        self.node(i, j)
                    };
                    v.to_string()
                })
                .collect();
            out += &row.join(" ");
            out.push('\n');
        }
        out
    }

    /// Writes the grid atomically: a temporary file in the same directory, then a rename.
    pub fn write_esri_ascii(&self, path: &Path) -> Result<(), SeafloorError> {
        let io = |source: std::io::Error| SeafloorError::Io {
            path: path.display().to_string(),
            source,
        };
        crate::atomic_file::write(path, self.to_esri_ascii().as_bytes()).map_err(io)
    }
}

/// The values and NODATA flags of a block of a grid's nodes (south to north), for
/// [`super::load`]. The block must lie inside the grid.
pub(crate) fn window(f: &Seafloor, w: super::NodeWindow) -> (Vec<f64>, Vec<bool>) {
    let (z, m) = f.nodes();
    let mut values = Vec::with_capacity(w.nx * w.ny);
    let mut nodata = Vec::with_capacity(w.nx * w.ny);
    for j in w.j0..w.j0 + w.ny {
        let row = j * f.nx() + w.i0;
        values.extend_from_slice(&z[row..row + w.nx]);
        nodata.extend_from_slice(&m[row..row + w.nx]);
    }
    (values, nodata)
}

/// What the header says.
struct Header {
    /// ncols, nrows, the south-west node and the cell size.
    lattice: Lattice,
    /// NODATA_value and its line.
    nodata: Option<(f64, usize)>,
    /// The first line after the header.
    end: usize,
}

/// Reads one source, and builds its located errors.
struct Parser<'a> {
    source_name: &'a str,
}

impl Parser<'_> {
    /// Reads the header lines; leaves `lines` at the first data line.
    fn header_of<'t>(
        &self,
        lines: &mut Peekable<impl Iterator<Item = (usize, &'t str)>>,
    ) -> Result<Header, SeafloorError> {
        // key → (value, line). The header ends at the first line starting with a number.
        let mut keys: HashMap<&'static str, (&'t str, usize)> = HashMap::new();
        let mut next_line = 1;
        while let Some(&(line, text)) = lines.peek() {
            let mut tokens = text.split_whitespace();
            if let Some(key) = tokens.next() {
                if key.parse::<f64>().is_ok() {
                    break;
                }
                let lower = key.to_ascii_lowercase();
                let Some(&canonical) = KEYS.iter().find(|&&k| k == lower) else {
                    let keys = KEYS.join(", ").replace("nodata_value", "NODATA_value");
                    let reason = format!("unknown header key; expected one of {keys}, or data");
                    return Err(self.header(line, key, reason));
                };
                let value = match (tokens.next(), tokens.next()) {
                    (Some(v), None) => v,
                    (None, _) => {
                        return Err(self.header(line, key, "expected a value after the key"))
                    }
                    (Some(_), Some(_)) => {
                        let reason = "expected one value after the key, found more";
                        return Err(self.header(line, key, reason));
                    }
                };
                if let Some((_, first)) = keys.insert(canonical, (value, line)) {
                    let reason = format!("given twice (first on line {first})");
                    return Err(self.header(line, key, reason));
                }
            }
            lines.next();
            next_line = line + 1;
        }
        let end = lines.peek().map_or(next_line, |&(line, _)| line);
        let get = |key: &str| keys.get(key).copied();

        let nx = self.count(get("ncols"), "ncols", end)?;
        let ny = self.count(get("nrows"), "nrows", end)?;
        let (dx, dy) = match (get("cellsize"), get("dx"), get("dy")) {
            (Some(c), None, None) => {
                let c = self.spacing(c, "cellsize")?;
                (c, c)
            }
            (None, Some(dx), Some(dy)) => (self.spacing(dx, "dx")?, self.spacing(dy, "dy")?),
            (Some(_), Some((_, line)), _) | (Some(_), None, Some((_, line))) => {
                let reason = "give either cellsize or dx and dy, not both";
                return Err(self.header(line, "cellsize", reason));
            }
            (None, dx, _) => {
                let key = if dx.is_some() { "dy" } else { "cellsize" };
                let reason = "the header must give cellsize, or dx and dy";
                return Err(self.missing(end, key, reason));
            }
        };
        let x0 = self.origin(get("xllcorner"), get("xllcenter"), "xll", dx, end)?;
        let y0 = self.origin(get("yllcorner"), get("yllcenter"), "yll", dy, end)?;
        let nodata = match get("nodata_value") {
            None => None,
            Some((v, line)) => match v.parse::<f64>() {
                Ok(nd) => Some((nd, line)),
                Err(_) => {
                    let reason = format!("expected a number, got {v:?}");
                    return Err(self.header(line, "NODATA_value", reason));
                }
            },
        };
        Ok(Header {
            lattice: Lattice::new(nx, ny, x0, y0, dx, dy),
            nodata,
            end,
        })
    }

    /// Reads the data values, north to south in the file, and returns them south to north as
    /// [`Seafloor::from_nodes`] takes them. Vectors grow as values are read, so memory follows
    /// the file's size rather than the header's claim.
    fn data<'t>(
        &self,
        lines: impl Iterator<Item = (usize, &'t str)>,
        h: &Header,
    ) -> Result<(Vec<f64>, Vec<bool>), SeafloorError> {
        let (nx, ny) = (h.lattice.nx, h.lattice.ny);
        let expected = nx * ny; // ≤ 2.5e9 by the count bounds
        let count_error = |line: usize, found: usize, reason: String| SeafloorError::DataCount {
            source_name: self.source_name.to_string(),
            line,
            expected,
            found,
            reason: format!("expected {expected} values ({ny} rows × {nx} columns), {reason}"),
        };
        let mut values: Vec<f64> = Vec::new();
        let mut missing: Vec<bool> = Vec::new();
        let mut last_line = h.end.saturating_sub(1).max(1);
        for (line, text) in lines {
            for token in text.split_whitespace() {
                let found = values.len();
                if found == expected {
                    let reason = format!("found more: value {} is on line {line}", found + 1);
                    return Err(count_error(line, found + 1, reason));
                }
                let field = || format!("row {}, column {}", found / nx + 1, found % nx + 1);
                let bad = |reason: String| SeafloorError::BadValue {
                    source_name: self.source_name.to_string(),
                    line,
                    field: field(),
                    reason,
                };
                let v: f64 = token
                    .parse()
                    .map_err(|_| bad(format!("expected a number, got {token:?}")))?;
                let is_nodata = h
                    .nodata
                    .is_some_and(|(nd, _)| v == nd || (nd.is_nan() && v.is_nan()));
                if !is_nodata && !v.is_finite() {
                    let hint = match h.nodata {
                        Some(_) => "",
                        None => " (the header gives no NODATA_value)",
                    };
                    return Err(bad(format!(
                        "expected a finite number, got {token:?}{hint}"
                    )));
                }
                if !is_nodata && v.abs() > MAX_ABS_ELEVATION {
                    return Err(bad(format!(
                        "expected an elevation in metres within ±{MAX_ABS_ELEVATION} \
                         or NODATA_value, got {token:?}"
                    )));
                }
                values.push(if is_nodata { 0.0 } else { v });
                missing.push(is_nodata);
                last_line = line;
            }
        }
        if values.len() < expected {
            let found = values.len();
            let reason = format!("found {found}; the data ended on line {last_line}");
            return Err(count_error(last_line, found, reason));
        }
        if missing.iter().all(|&m| m) {
            let line = h.nodata.map_or(h.end, |(_, line)| line);
            let reason = "every data value is NODATA; the grid has no data";
            return Err(self.header(line, "NODATA_value", reason));
        }
        // Rows run north to south in the file, south to north in the grid.
        let z = values.chunks(nx).rev().flatten().copied().collect();
        let nodata = missing.chunks(nx).rev().flatten().copied().collect();
        Ok((z, nodata))
    }

    fn header(&self, line: usize, field: &str, reason: impl Into<String>) -> SeafloorError {
        SeafloorError::Header {
            source_name: self.source_name.to_string(),
            line,
            field: field.to_string(),
            reason: reason.into(),
        }
    }

    fn missing(&self, line: usize, field: &str, reason: &str) -> SeafloorError {
        SeafloorError::MissingKey {
            source_name: self.source_name.to_string(),
            line,
            field: field.to_string(),
            reason: format!("missing; {reason} (the header ended here)"),
        }
    }

    /// ncols or nrows: a whole number of nodes, 2 to MAX_NODES_PER_AXIS.
    fn count(
        &self,
        entry: Option<(&str, usize)>,
        key: &str,
        header_end: usize,
    ) -> Result<usize, SeafloorError> {
        let Some((v, line)) = entry else {
            return Err(self.missing(header_end, key, &format!("the header must give {key}")));
        };
        match v.parse::<usize>() {
            Ok(n) if (2..=MAX_NODES_PER_AXIS).contains(&n) => Ok(n),
            _ => Err(self.header(
                line,
                key,
                format!("expected a whole number from 2 to {MAX_NODES_PER_AXIS}, got {v:?}"),
            )),
        }
    }

    /// cellsize, dx or dy: positive, at most MAX_COORDINATE.
    fn spacing(&self, (v, line): (&str, usize), key: &str) -> Result<f64, SeafloorError> {
        match v.parse::<f64>() {
            Ok(d) if d > 0.0 && d <= MAX_COORDINATE => Ok(d),
            _ => Err(self.header(
                line,
                key,
                format!("expected a positive number (at most {MAX_COORDINATE:e} m), got {v:?}"),
            )),
        }
    }

    /// The first node's coordinate from `<axis>corner` or `<axis>center` (exactly one given).
    fn origin(
        &self,
        corner: Option<(&str, usize)>,
        center: Option<(&str, usize)>,
        axis: &str,
        spacing: f64,
        header_end: usize,
    ) -> Result<f64, SeafloorError> {
        let finite = |(v, line): (&str, usize), key: &str| match v.parse::<f64>() {
            Ok(c) if c.abs() <= MAX_COORDINATE => Ok(c),
            _ => Err(self.header(
                line,
                key,
                format!("expected a coordinate in metres within ±{MAX_COORDINATE:e}, got {v:?}"),
            )),
        };
        match (corner, center) {
            (Some(c), None) => Ok(finite(c, &format!("{axis}corner"))? + spacing / 2.0),
            (None, Some(c)) => finite(c, &format!("{axis}center")),
            (Some(_), Some((_, line))) => Err(self.header(
                line,
                &format!("{axis}center"),
                format!("give either {axis}corner or {axis}center, not both"),
            )),
            (None, None) => Err(self.missing(
                header_end,
                &format!("{axis}corner"),
                &format!("the header must give {axis}corner or {axis}center"),
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SURVEY: &str =
        "ncols 4\nnrows 3\nxllcorner 1000\nyllcorner 2000\ncellsize 10\nNODATA_value -9999\n\
        -10 -11 -12 -13\n-20 -21 -9999 -23\n-30 -31.5 -32 5\n";

    fn parse(text: &str) -> Result<Seafloor, SeafloorError> {
        Seafloor::parse_esri_ascii(text, "survey.asc")
    }

    #[test]
    fn reads_rows_north_to_south_with_corner_offset() {
        let f = parse(SURVEY).unwrap();
        assert_eq!(
            (f.nx(), f.ny(), f.x0(), f.y0(), f.dx(), f.dy()),
            (4, 3, 1005.0, 2005.0, 10.0, 10.0)
        );
        assert_eq!(f.node(0, 0), -30.0); // last file row is the south row
        assert_eq!(f.node(1, 0), -31.5);
        assert_eq!(f.node(3, 2), -13.0);
        assert!(f.is_nodata(2, 1) && f.node(2, 1) == 0.0);
        assert_eq!(f.z_range(), (-32.0, 5.0));
    }

    #[test]
    fn corner_and_center_headers_give_the_same_grid() {
        let center = SURVEY
            .replace("xllcorner 1000", "XLLCENTER 1005")
            .replace("yllcorner 2000", "yllcenter 2005");
        assert_eq!(parse(&center).unwrap(), parse(SURVEY).unwrap());
        assert_eq!(
            parse(&center).unwrap().fingerprint(),
            parse(SURVEY).unwrap().fingerprint()
        );
    }

    #[test]
    fn header_keys_are_case_insensitive_in_any_order_and_data_may_wrap() {
        let text = "\u{feff}CellSize 10\r\nYLLCORNER 2000\r\n\r\nnodata_value -9999\r\nNROWS 3\r\nxllcorner 1000\r\nNCols 4\r\n\
            -10 -11 -12\r\n-13 -20 -21 -9999 -23 -30\r\n-31.5\r\n-32 5";
        assert_eq!(parse(text).unwrap(), parse(SURVEY).unwrap());
    }

    #[test]
    fn gdal_dx_dy_headers_for_non_square_cells() {
        let text = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ndx 4\ndy 2\n-1 -2\n-3 -4\n";
        let f = parse(text).unwrap();
        assert_eq!((f.x0(), f.y0(), f.dx(), f.dy()), (2.0, 1.0, 4.0, 2.0));
        let written = f.to_esri_ascii();
        assert!(
            written.contains("\ndx 4\ndy 2\n") && !written.contains("cellsize"),
            "{written}"
        );
        assert_eq!(parse(&written).unwrap(), f);
    }

    #[test]
    fn parse_write_parse_is_bit_exact() {
        let awkward =
            "ncols 3\nnrows 2\nxllcorner 0.1\nyllcorner -7.3\ncellsize 0.3\nNODATA_value nan\n\
            -0.1 -1e-7 -12345.678901234567\nnan -0.30000000000000004 -0\n";
        for text in [SURVEY, awkward] {
            let f = parse(text).unwrap();
            let written = f.to_esri_ascii();
            let g = parse(&written).unwrap();
            assert_eq!(g.fingerprint(), f.fingerprint(), "{written}");
            assert_eq!(g.to_esri_ascii(), written);
            for j in 0..f.ny() {
                for i in 0..f.nx() {
                    assert_eq!(g.node(i, j).to_bits(), f.node(i, j).to_bits());
                }
            }
        }
        // Corner form whenever it reads back exactly, centre form otherwise.
        assert!(parse(SURVEY)
            .unwrap()
            .to_esri_ascii()
            .contains("xllcorner 1000\nyllcorner 2000\n"));
        let f = Seafloor::from_nodes(
            Lattice::new(2, 2, 0.1, 0.7, 0.3, 0.3),
            vec![-1.0; 4],
            vec![false; 4],
        )
        .unwrap();
        let written = f.to_esri_ascii();
        let g = parse(&written).unwrap();
        assert_eq!(
            (g.x0().to_bits(), g.y0().to_bits()),
            (0.1f64.to_bits(), 0.7f64.to_bits()),
            "{written}"
        );
    }

    #[test]
    fn write_is_atomic_and_reads_back() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("floor.asc");
        std::fs::write(&path, "old contents").unwrap();
        let f = parse(SURVEY).unwrap();
        f.write_esri_ascii(&path).unwrap();
        assert_eq!(Seafloor::read_esri_ascii(&path).unwrap(), f);
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            1,
            "no temporary file left behind"
        );
        let missing = dir.path().join("nope.asc");
        let err = Seafloor::read_esri_ascii(&missing).unwrap_err();
        assert!(
            matches!(err, SeafloorError::Io { .. }) && err.to_string().contains("nope.asc"),
            "{err}"
        );
        let err = f
            .write_esri_ascii(&dir.path().join("no/such/dir/x.asc"))
            .unwrap_err();
        assert!(matches!(err, SeafloorError::Io { .. }), "{err}");
    }

    #[test]
    fn read_errors_name_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("survey.asc");
        std::fs::write(&path, SURVEY.replace("cellsize 10", "cellsize -5")).unwrap();
        let msg = Seafloor::read_esri_ascii(&path).unwrap_err().to_string();
        assert_eq!(
            msg,
            format!(
                "{} line 5: cellsize: expected a positive number (at most 1e12 m), got \"-5\"",
                path.display()
            )
        );
    }

    #[test]
    fn nodata_and_land_from_a_file_are_obstacles() {
        let f = parse(SURVEY).unwrap();
        assert!(f.is_obstacle(1020.0, 2010.0).unwrap()); // cell (1, 0) touches NODATA (2, 1)
        assert!(f.is_obstacle(1034.0, 2006.0).unwrap()); // cell (2, 0) touches land (3, 0) = +5
        assert!(!f.is_obstacle(1010.0, 2020.0).unwrap()); // cell (0, 1)
    }

    /// Every malformed input: (what, text, expected variant, line, field).
    #[test]
    fn malformed_input_gives_located_errors() {
        type Check = fn(&SeafloorError) -> bool;
        let header: Check = |e| matches!(e, SeafloorError::Header { .. });
        let missing: Check = |e| matches!(e, SeafloorError::MissingKey { .. });
        let value: Check = |e| matches!(e, SeafloorError::BadValue { .. });
        let count: Check = |e| matches!(e, SeafloorError::DataCount { .. });
        let body = "-1 -2\n-3 -4\n";
        let hdr = |h: &str| format!("{h}\n{body}");
        let cases: Vec<(&str, String, Check, usize, &str)> = vec![
            ("negative cellsize", SURVEY.replace("cellsize 10", "cellsize -5"), header, 5, "cellsize: expected a positive number"),
            ("zero cellsize", SURVEY.replace("cellsize 10", "cellsize 0"), header, 5, "cellsize: expected a positive number"),
            ("text cellsize", SURVEY.replace("cellsize 10", "cellsize ten"), header, 5, "got \"ten\""),
            ("nan cellsize", SURVEY.replace("cellsize 10", "cellsize NaN"), header, 5, "cellsize"),
            ("ncols 0", SURVEY.replace("ncols 4", "ncols 0"), header, 1, "ncols: expected a whole number from 2 to 50000"),
            ("ncols 1", SURVEY.replace("ncols 4", "ncols 1"), header, 1, "ncols: expected a whole number from 2 to 50000"),
            ("nrows 1 (1 × n grid)", SURVEY.replace("nrows 3", "nrows 1"), header, 2, "nrows: expected a whole number from 2"),
            ("nrows absurd", SURVEY.replace("nrows 3", "nrows 50001"), header, 2, "nrows"),
            ("nrows negative", SURVEY.replace("nrows 3", "nrows -3"), header, 2, "got \"-3\""),
            ("nrows fractional", SURVEY.replace("nrows 3", "nrows 3.5"), header, 2, "nrows"),
            ("xllcorner inf", SURVEY.replace("xllcorner 1000", "xllcorner inf"), header, 3, "xllcorner: expected a coordinate"),
            ("yllcorner text", SURVEY.replace("yllcorner 2000", "yllcorner north"), header, 4, "yllcorner"),
            ("NODATA text", SURVEY.replace("NODATA_value -9999", "NODATA_value none"), header, 6, "NODATA_value: expected a number"),
            ("unknown key", SURVEY.replace("cellsize 10", "cellsize 10\nbyteorder LSBFIRST"), header, 6, "byteorder: unknown header key"),
            ("duplicate key", SURVEY.replace("cellsize 10", "cellsize 10\nCELLSIZE 10"), header, 6, "CELLSIZE: given twice (first on line 5)"),
            ("key without value", SURVEY.replace("cellsize 10", "cellsize"), header, 5, "cellsize: expected a value"),
            ("key with two values", SURVEY.replace("cellsize 10", "cellsize 10 10"), header, 5, "cellsize: expected one value"),
            ("corner and centre", SURVEY.replace("cellsize 10", "cellsize 10\nxllcenter 1005"), header, 6, "xllcenter: give either"),
            ("cellsize and dx", SURVEY.replace("cellsize 10", "cellsize 10\ndx 10"), header, 6, "cellsize: give either cellsize or dx and dy"),
            ("missing ncols", SURVEY.replace("ncols 4\n", ""), missing, 6, "ncols: missing"),
            ("missing nrows", SURVEY.replace("nrows 3\n", ""), missing, 6, "nrows: missing"),
            ("missing cellsize", SURVEY.replace("cellsize 10\n", ""), missing, 6, "cellsize: missing"),
            ("dx without dy", SURVEY.replace("cellsize 10", "dx 10"), missing, 7, "dy: missing"),
            ("missing xll", SURVEY.replace("xllcorner 1000\n", ""), missing, 6, "xllcorner: missing; the header must give xllcorner or xllcenter"),
            ("missing yll", SURVEY.replace("yllcorner 2000\n", ""), missing, 6, "yllcorner: missing"),
            ("empty file", String::new(), missing, 1, "ncols: missing"),
            ("header only", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\n".to_string(), missing, 5, "cellsize: missing"),
            ("short data", SURVEY.replace("-30 -31.5 -32 5\n", "-30 -31.5\n"), count, 9, "data: expected 12 values (3 rows × 4 columns), found 10; the data ended on line 9"),
            ("no data", "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n\n".to_string(), count, 6, "found 0"),
            ("long data", format!("{SURVEY}\n7\n"), count, 11, "found more: value 13 is on line 11"),
            ("text value", SURVEY.replace("-31.5", "-31,5"), value, 9, "row 3, column 2: expected a number, got \"-31,5\""),
            ("word value", hdr("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1").replace("-4", "deep"), value, 7, "row 2, column 2"),
            ("infinite value", SURVEY.replace("-23", "inf"), value, 8, "row 2, column 4: expected a finite number, got \"inf\""),
            ("nan value, no NODATA", hdr("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1").replace("-2", "NaN"), value, 6, "row 1, column 2: expected a finite number, got \"NaN\" (the header gives no NODATA_value)"),
            ("absurd value", SURVEY.replace("-12 ", "-1e6 "), value, 7, "row 1, column 3: expected an elevation in metres within ±50000"),
            ("all NODATA", hdr("ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -1").replace("-2", "-1").replace("-3", "-1").replace("-4", "-1"), header, 6, "NODATA_value: every data value is NODATA"),
        ];
        for (what, text, check, line, needle) in cases {
            let err = parse(&text).expect_err(what);
            assert!(check(&err), "{what}: wrong variant {err:?}");
            let msg = err.to_string();
            assert!(
                msg.starts_with(&format!("survey.asc line {line}: ")),
                "{what}: {msg}"
            );
            assert!(msg.contains(needle), "{what}: {msg}");
        }
    }

    proptest::proptest! {
        /// Arbitrary bytes and arbitrary edits of a valid file give a grid or an error, never a
        /// panic.
        #[test]
        fn never_panics(
            junk in "\\PC{0,200}",
            at in 0usize..200,
            insert in "[-+.0-9eEaInf \n]{0,12}",
        ) {
            let _ = parse(&junk);
            let cut = SURVEY.char_indices().map(|(i, _)| i).nth(at % SURVEY.len()).unwrap_or(0);
            let edited = format!("{}{insert}{}", &SURVEY[..cut], &SURVEY[cut..]);
            let _ = parse(&edited);
        }
    }
}
