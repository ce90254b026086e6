//! The table as Parquet (`runs.parquet`, beside `runs.csv`): the same rows and columns, each
//! column typed ([`Kind`]: INT64, DOUBLE, UTF8 string or BOOLEAN), every field OPTIONAL, an
//! empty cell or a NaN a null. One row group, snappy-compressed, written atomically, with the
//! shoal version (and the study file, when known) in the file's key-value metadata.

use super::columns::{self, Kind};
use super::SweepError;
use csv::StringRecord;
use parquet::basic::{Compression, LogicalType, Repetition, Type as Physical};
use parquet::column::writer::ColumnWriter;
use parquet::data_type::ByteArray;
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::Type;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// The Parquet table beside CSV table `csv` (`runs.csv` → `runs.parquet`).
pub fn beside(csv: &Path) -> PathBuf {
    csv.with_extension("parquet")
}

/// One column's values (the non-null ones) and its definition levels (1: a value, 0: null).
enum Values {
    Int(Vec<i64>),
    Real(Vec<f64>),
    Text(Vec<ByteArray>),
    Bool(Vec<bool>),
}

/// Write `records` under `header`, column `i` of type `kinds[i]`, to `path` atomically;
/// `study` (the study file's name) goes into the metadata when given.
pub fn write(
    path: &Path,
    header: &StringRecord,
    kinds: &[Kind],
    records: &[StringRecord],
    study: Option<&str>,
) -> Result<(), SweepError> {
    let bad = |why: String| SweepError::Table {
        path: path.to_path_buf(),
        why,
    };
    let pq = |e: parquet::errors::ParquetError| bad(format!("writing Parquet: {e}"));
    let fields = header
        .iter()
        .zip(kinds)
        .map(|(name, &kind)| field(name, kind).map(Arc::new))
        .collect::<Result<Vec<_>, _>>()
        .map_err(pq)?;
    let schema = Type::group_type_builder("runs")
        .with_fields(fields)
        .build()
        .map_err(pq)?;
    let mut meta = vec![KeyValue::new(
        "shoal.version".into(),
        env!("CARGO_PKG_VERSION").to_string(),
    )];
    if let Some(s) = study {
        meta.push(KeyValue::new("shoal.study".into(), s.to_string()));
    }
    meta.push(KeyValue::new(
        "shoal.columns".into(),
        "docs/sweep.md, The table".to_string(),
    ));
    let props = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_created_by(format!("shoal {}", env!("CARGO_PKG_VERSION")))
        .set_key_value_metadata(Some(meta))
        .build();
    let mut bytes = Vec::new();
    let mut writer =
        SerializedFileWriter::new(&mut bytes, Arc::new(schema), Arc::new(props)).map_err(pq)?;
    let mut group = writer.next_row_group().map_err(pq)?;
    let mut i = 0;
    while let Some(mut col) = group.next_column().map_err(pq)? {
        let (name, kind) = (&header[i], kinds[i]);
        let (values, levels) = column(records.iter().map(|r| r.get(i).unwrap_or("")), kind)
            .map_err(|cell| {
                bad(format!(
                    "column \"{name}\": \"{cell}\" is not {}",
                    match kind {
                        Kind::Int => "a whole number",
                        Kind::Real => "a number",
                        Kind::Bool => "true or false",
                        Kind::Text => "text",
                    }
                ))
            })?;
        let def = Some(levels.as_slice());
        match (col.untyped(), values) {
            (ColumnWriter::Int64ColumnWriter(w), Values::Int(v)) => w.write_batch(&v, def, None),
            (ColumnWriter::DoubleColumnWriter(w), Values::Real(v)) => w.write_batch(&v, def, None),
            (ColumnWriter::ByteArrayColumnWriter(w), Values::Text(v)) => {
                w.write_batch(&v, def, None)
            }
            (ColumnWriter::BoolColumnWriter(w), Values::Bool(v)) => w.write_batch(&v, def, None),
            _ => {
                return Err(bad(format!(
                    "column \"{name}\": its writer is not its type's"
                )))
            }
        }
        .map_err(pq)?;
        col.close().map_err(pq)?;
        i += 1;
    }
    group.close().map_err(pq)?;
    writer.close().map_err(pq)?;
    crate::output::write_atomic(path, &bytes).map_err(|e| bad(e.to_string()))
}

/// An OPTIONAL field of `kind` named `name`.
fn field(name: &str, kind: Kind) -> parquet::errors::Result<Type> {
    let (physical, logical) = match kind {
        Kind::Int => (Physical::INT64, None),
        Kind::Real => (Physical::DOUBLE, None),
        Kind::Text => (Physical::BYTE_ARRAY, Some(LogicalType::String)),
        Kind::Bool => (Physical::BOOLEAN, None),
    };
    Type::primitive_type_builder(name, physical)
        .with_repetition(Repetition::OPTIONAL)
        .with_logical_type(logical)
        .build()
}

/// A column's cells as values of `kind` and definition levels; Err(cell) names a cell that is
/// not of that kind. An empty cell is a null, and so is a NaN in a numeric column.
fn column<'a>(
    cells: impl Iterator<Item = &'a str>,
    kind: Kind,
) -> Result<(Values, Vec<i16>), String> {
    let mut levels = Vec::new();
    let mut values = match kind {
        Kind::Int => Values::Int(Vec::new()),
        Kind::Real => Values::Real(Vec::new()),
        Kind::Text => Values::Text(Vec::new()),
        Kind::Bool => Values::Bool(Vec::new()),
    };
    for cell in cells {
        let null = cell.is_empty() || (kind != Kind::Text && cell.eq_ignore_ascii_case("nan"));
        levels.push(i16::from(!null));
        if null {
            continue;
        }
        let wrong = || cell.to_string();
        match &mut values {
            Values::Int(v) => v.push(columns::int(cell).ok_or_else(wrong)?),
            Values::Real(v) => match columns::real(cell) {
                Some(x) if x.is_nan() => {
                    if let Some(l) = levels.last_mut() {
                        *l = 0;
                    }
                }
                Some(x) => v.push(x),
                None => return Err(wrong()),
            },
            Values::Text(v) => v.push(ByteArray::from(cell)),
            Values::Bool(v) => v.push(match cell {
                "true" => true,
                "false" => false,
                _ => return Err(wrong()),
            }),
        }
    }
    Ok((values, levels))
}
