//! Loading a scenario: TOML text (a file, or the embedded default of [`default_toml`]) plus
//! `--set key=value` overrides, deserialised and validated, with errors that name the source,
//! the line and the dotted key.
//!
//! How errors are located: the file is parsed with `toml_edit`, which keeps the byte span of
//! every key and value. Each override is parsed as a one-line document `key = value`, padded
//! with spaces so that its spans lie after the end of the file (override i occupies its own
//! byte range), and merged into the file's tree. Every span in the merged tree, and so in any
//! deserialisation error, therefore tells where the offending text came from: a file line, or
//! one override. Range errors found after deserialising are located by looking their key up in
//! the same tree.
//!
//! [`default_toml`]: super::default_toml

use super::schema::{self, Lookup, Schema};
use super::toml_path::{
    describe_found, node_at, path_at, position_of, render, strip_indices, Node, Seg,
};
use super::validate::{validate, Violation};
use super::Scenario;
use std::ops::Range;
use std::path::{Path, PathBuf};
use toml_edit::{DocumentMut, ImDocument, Item, Key, TableLike, Value};

/// Source name used for the embedded default scenario.
pub const EMBEDDED_DEFAULT: &str = "embedded default";

/// Why a scenario could not be loaded. Every message names where the problem is: the file (or
/// `--set k=v`, or `embedded default`), the line where there is one, the full dotted key, and
/// what is allowed.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read.
    #[error("{}: cannot read the scenario file: {source}", path.display())]
    Io {
        /// The file's path.
        path: PathBuf,
        /// The underlying I/O error.
        #[source]
        source: std::io::Error,
    },
    /// Not valid TOML (or not UTF-8).
    #[error("{source_name} line {line}, column {column}: {message}")]
    Syntax {
        /// The file's path, or `embedded default`.
        source_name: String,
        /// The line, 1-based.
        line: usize,
        /// The column, 1-based, in characters.
        column: usize,
        /// The TOML parser's message on one line, or that the file is not UTF-8.
        message: String,
    },
    /// A key that is not part of a scenario.
    #[error("{}: unknown key {key}; {allowed}", at(.source_name, .line))]
    UnknownKey {
        /// Where the problem is: the file's path, `--set k=v` or `embedded default`.
        source_name: String,
        /// The line in the file, 1-based; `None` for a `--set` override or when the problem has
        /// no position (a rule broken by defaults alone).
        line: Option<usize>,
        /// The unknown dotted key, up to its first unknown part.
        key: String,
        /// The keys allowed in that section, e.g. "allowed keys in \[usv\]: …".
        allowed: String,
    },
    /// A value of the wrong TOML type.
    #[error("{}: {key}: expected {expected}, found {found}", at(.source_name, .line))]
    WrongType {
        /// Where the problem is: the file's path, `--set k=v` or `embedded default`.
        source_name: String,
        /// The line in the file, 1-based; `None` for a `--set` override or when the problem has
        /// no position (a rule broken by defaults alone).
        line: Option<usize>,
        /// The full dotted key, array elements as `key[i]` (e.g. `initial.auvs[2]`).
        key: String,
        /// What the key takes, in words, e.g. "a number" or "an array of 2 numbers".
        expected: String,
        /// What was given, in words, e.g. "a string" or "an array of 3 elements".
        found: String,
    },
    /// A required key is missing (only inside `[initial]`, where `usv` and `auvs` go together).
    #[error("{}: {key} is missing: {allowed}", at(.source_name, .line))]
    MissingKey {
        /// Where the problem is: the file's path, `--set k=v` or `embedded default`.
        source_name: String,
        /// The line in the file, 1-based; `None` for a `--set` override or when the problem has
        /// no position (a rule broken by defaults alone).
        line: Option<usize>,
        /// The full dotted key, array elements as `key[i]` (e.g. `initial.auvs[2]`).
        key: String,
        /// How to give it ("give it as …"), or "it is required here".
        allowed: String,
    },
    /// A value of the right type outside its allowed range.
    #[error("{}: {key} = {value}: {allowed}", at(.source_name, .line))]
    OutOfRange {
        /// Where the problem is: the file's path, `--set k=v` or `embedded default`.
        source_name: String,
        /// The line in the file, 1-based; `None` for a `--set` override or when the problem has
        /// no position (a rule broken by defaults alone).
        line: Option<usize>,
        /// The full dotted key, array elements as `key[i]` (e.g. `initial.auvs[2]`).
        key: String,
        /// The value as written for a person ("(default)" appended when the key was not set).
        value: String,
        /// What is allowed, e.g. "must be a positive number …" or "must be one of …".
        allowed: String,
    },
    /// Any other deserialisation failure (kept with its message; not expected in practice).
    #[error("{}: {key}: {message}", at(.source_name, .line))]
    Invalid {
        /// Where the problem is: the file's path, `--set k=v` or `embedded default`.
        source_name: String,
        /// The line in the file, 1-based; `None` for a `--set` override or when the problem has
        /// no position (a rule broken by defaults alone).
        line: Option<usize>,
        /// The full dotted key, array elements as `key[i]` (e.g. `initial.auvs[2]`).
        key: String,
        /// The deserialiser's message, on one line.
        message: String,
    },
    /// A `--set` argument that is not `dotted.key=value`.
    #[error("--set {text}: {why}")]
    BadOverride {
        /// The argument as given, without `--set`.
        text: String,
        /// What is wrong with it.
        why: String,
    },
}

fn at(source_name: &str, line: &Option<usize>) -> String {
    match line {
        Some(l) => format!("{source_name} line {l}"),
        None => source_name.to_string(),
    }
}

impl ScenarioError {
    /// The 1-based line in the file, when the error is in the file.
    pub fn line(&self) -> Option<usize> {
        match self {
            ScenarioError::Syntax { line, .. } => Some(*line),
            ScenarioError::UnknownKey { line, .. }
            | ScenarioError::WrongType { line, .. }
            | ScenarioError::MissingKey { line, .. }
            | ScenarioError::OutOfRange { line, .. }
            | ScenarioError::Invalid { line, .. } => *line,
            ScenarioError::Io { .. } | ScenarioError::BadOverride { .. } => None,
        }
    }

    /// The full dotted key at fault, when there is one.
    pub fn key(&self) -> Option<&str> {
        match self {
            ScenarioError::UnknownKey { key, .. }
            | ScenarioError::WrongType { key, .. }
            | ScenarioError::MissingKey { key, .. }
            | ScenarioError::OutOfRange { key, .. }
            | ScenarioError::Invalid { key, .. } => Some(key),
            _ => None,
        }
    }

    /// Where the error is: the file name, `--set k=v`, or `embedded default`.
    pub fn source_name(&self) -> String {
        match self {
            ScenarioError::Io { path, .. } => path.display().to_string(),
            ScenarioError::Syntax { source_name, .. }
            | ScenarioError::UnknownKey { source_name, .. }
            | ScenarioError::WrongType { source_name, .. }
            | ScenarioError::MissingKey { source_name, .. }
            | ScenarioError::OutOfRange { source_name, .. }
            | ScenarioError::Invalid { source_name, .. } => source_name.clone(),
            ScenarioError::BadOverride { text, .. } => format!("--set {text}"),
        }
    }

    /// The same error, its source named `name` when it is `--set {text}`: a command-line tool
    /// that turns its own flag into an override (`--seafloor X` into `--set seafloor.file=X`)
    /// names the flag the user gave.
    pub fn from_flag(mut self, text: &str, name: &str) -> ScenarioError {
        let set = format!("--set {text}");
        match &mut self {
            ScenarioError::Syntax { source_name, .. }
            | ScenarioError::UnknownKey { source_name, .. }
            | ScenarioError::WrongType { source_name, .. }
            | ScenarioError::MissingKey { source_name, .. }
            | ScenarioError::OutOfRange { source_name, .. }
            | ScenarioError::Invalid { source_name, .. }
                if *source_name == set =>
            {
                *source_name = name.to_string();
            }
            _ => {}
        }
        self
    }
}

// ---------------------------------------------------------------------------------------------
// Public entry points
// ---------------------------------------------------------------------------------------------

/// Read a scenario file and apply `overrides` (`dotted.key=value`, in order; a later one wins).
pub fn load(path: &Path, overrides: &[String]) -> Result<Scenario, ScenarioError> {
    let bytes = std::fs::read(path).map_err(|source| ScenarioError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let source_name = path.display().to_string();
    let text = match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let good = e.utf8_error().valid_up_to();
            let bytes = e.as_bytes();
            let (line, column) = line_col_bytes(bytes, good);
            return Err(ScenarioError::Syntax {
                source_name,
                line,
                column,
                message: "the file is not valid UTF-8 text".to_string(),
            });
        }
    };
    from_toml_str(&text, &source_name, overrides)
}

/// The embedded default scenario (the text of [`super::default_toml`]) plus `overrides`.
pub fn default_with(overrides: &[String]) -> Result<Scenario, ScenarioError> {
    from_toml_str(&super::default_toml(), EMBEDDED_DEFAULT, overrides)
}

/// Parse scenario TOML `text` (named `source` in errors: a path or `embedded default`), apply
/// `overrides`, deserialise and validate. Never panics.
pub fn from_toml_str(
    text: &str,
    source: &str,
    overrides: &[String],
) -> Result<Scenario, ScenarioError> {
    let doc = ImDocument::parse(text).map_err(|e| {
        let pos = e.span().map(|s| s.start).unwrap_or(0);
        let (line, column) = line_col_bytes(text.as_bytes(), pos);
        ScenarioError::Syntax {
            source_name: source.to_string(),
            line,
            column,
            message: one_line(e.message()),
        }
    })?;
    let schema = Schema::new();
    let mut origins = Origins {
        source,
        text,
        overrides: Vec::new(),
    };
    let mut root = Item::Table(doc.into_table());

    let mut offset = text.len() + 1;
    for o in overrides {
        let ov = parse_override(o, &schema, offset)?;
        origins.overrides.push((offset..ov.end, o.as_str()));
        offset = ov.end + 1;
        let segs: Vec<&str> = ov.segs.iter().map(String::as_str).collect();
        merge(&mut root, &ov.root, &segs);
    }

    check_shape(&root, schema.root(), &mut Vec::new(), &schema, &origins)?;

    let table = match root.as_table() {
        Some(t) => t.clone(),
        None => toml_edit::Table::new(),
    };
    let scenario: Scenario = toml_edit::de::from_document(DocumentMut::from(table))
        .map_err(|e| de_error(&e, &root, &schema, &origins))?;

    if let Err(violations) = validate(&scenario) {
        if let Some(v) = violations.first() {
            return Err(range_error(v, &root, &origins));
        }
    }
    Ok(scenario)
}

// ---------------------------------------------------------------------------------------------
// Where a byte position came from
// ---------------------------------------------------------------------------------------------

struct Origins<'a> {
    source: &'a str,
    text: &'a str,
    /// Byte range in the merged address space and the override's text.
    overrides: Vec<(Range<usize>, &'a str)>,
}

impl Origins<'_> {
    /// (source name, line) of a byte position in the merged address space.
    fn locate(&self, pos: usize) -> (String, Option<usize>) {
        if pos <= self.text.len() {
            let (line, _) = line_col_bytes(self.text.as_bytes(), pos);
            return (self.source.to_string(), Some(line));
        }
        for (range, text) in &self.overrides {
            if pos < range.end + 1 {
                return (format!("--set {text}"), None);
            }
        }
        (self.source.to_string(), None)
    }

    fn unknown_position(&self) -> (String, Option<usize>) {
        (self.source.to_string(), None)
    }
}

/// 1-based line and column (in characters) of byte `pos` of `bytes`.
fn line_col_bytes(bytes: &[u8], pos: usize) -> (usize, usize) {
    let pos = pos.min(bytes.len());
    let before = &bytes[..pos];
    let line = before.iter().filter(|b| **b == b'\n').count() + 1;
    let start = before
        .iter()
        .rposition(|b| *b == b'\n')
        .map(|i| i + 1)
        .unwrap_or(0);
    let seg = &bytes[start..pos];
    let column = match std::str::from_utf8(seg) {
        Ok(s) => s.chars().count(),
        Err(_) => seg.len(),
    } + 1;
    (line, column)
}

fn one_line(msg: &str) -> String {
    let parts: Vec<&str> = msg
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    parts.join("; ")
}

// ---------------------------------------------------------------------------------------------
// Overrides
// ---------------------------------------------------------------------------------------------

struct Override {
    segs: Vec<String>,
    /// The override parsed as the document `key = value`, with spans in the merged address
    /// space.
    root: Item,
    /// End of its byte range.
    end: usize,
}

fn bad(text: &str, why: impl Into<String>) -> ScenarioError {
    ScenarioError::BadOverride {
        text: text.to_string(),
        why: why.into(),
    }
}

fn parse_override(text: &str, schema: &Schema, offset: usize) -> Result<Override, ScenarioError> {
    let Some((key, value)) = text.split_once('=') else {
        return Err(bad(
            text,
            "expected key=value with a dotted key, e.g. acoustic.sonar_range=120",
        ));
    };
    let key = key.trim();
    let value = value.trim();
    if key.is_empty() {
        return Err(bad(
            text,
            "no key before '='; e.g. acoustic.sonar_range=120",
        ));
    }
    let segs: Vec<&str> = key.split('.').map(str::trim).collect();
    let bare = |s: &str| {
        !s.is_empty()
            && s.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
    };
    if !segs.iter().all(|s| bare(s)) {
        return Err(bad(
            text,
            format!(
                "`{key}` is not a dotted key of plain names (letters, digits, _ and -), \
                 e.g. acoustic.sonar_range; arrays are set whole, e.g. usv.destination=[100, 2]"
            ),
        ));
    }
    let dotted = segs.join(".");
    match schema.lookup(&segs) {
        Lookup::Leaf(_) | Lookup::Section(_) => {}
        Lookup::Unknown {
            index,
            prefix,
            allowed,
        } => {
            return Err(ScenarioError::UnknownKey {
                source_name: format!("--set {text}"),
                line: None,
                key: segs[..=index].join("."),
                allowed: schema::allowed_list(&prefix, &allowed),
            })
        }
        Lookup::BelowLeaf { prefix } => {
            return Err(bad(
                text,
                format!("{prefix} is a single value, not a section: set it whole"),
            ))
        }
    }
    if value.is_empty() {
        return Err(bad(
            text,
            format!("no value after '='; write {dotted}=\"\" for an empty string"),
        ));
    }
    // A TOML value if it parses as one, otherwise the text taken as a string.
    let repr = match value.parse::<Value>() {
        Ok(_) => value.to_string(),
        Err(_) => Value::from(value).to_string().trim().to_string(),
    };
    let line = format!("{dotted} = {repr}");
    let mut padded = " ".repeat(offset);
    padded.push_str(&line);
    let end = padded.len();
    let doc = ImDocument::parse(padded).map_err(|e| {
        bad(
            text,
            format!("cannot read the value: {}", one_line(e.message())),
        )
    })?;
    Ok(Override {
        segs: segs.iter().map(|s| s.to_string()).collect(),
        root: Item::Table(doc.into_table()),
        end,
    })
}

/// Merge the override tree `src` (a table holding only the path `segs`) into `dst`, replacing
/// whatever `dst` holds at `segs`. Keys and values keep the override's spans.
fn merge(dst: &mut Item, src: &Item, segs: &[&str]) {
    let Some((seg, rest)) = segs.split_first() else {
        return;
    };
    let Some((skey, sitem)) = src.as_table_like().and_then(|t| t.get_key_value(seg)) else {
        return;
    };
    if !rest.is_empty() {
        if let Some(child) = dst.get_mut(*seg) {
            if child.is_table_like() {
                merge(child, sitem, rest);
                return;
            }
        }
    }
    put(dst, skey, sitem.clone());
}

fn put(dst: &mut Item, key: &Key, item: Item) {
    match dst {
        Item::Table(t) => {
            t.remove(key.get());
            t.insert_formatted(key, item);
        }
        Item::Value(Value::InlineTable(t)) => {
            if let Ok(v) = item.into_value() {
                t.remove(key.get());
                t.insert_formatted(key, v);
            }
        }
        _ => {}
    }
}

// ---------------------------------------------------------------------------------------------
// Errors
// ---------------------------------------------------------------------------------------------

/// Check the merged tree against the schema, in document order: every key must be a scenario
/// key, and fixed-size arrays must have their exact length (the deserialiser would silently drop
/// extra elements).
fn check_shape(
    item: &Item,
    schema: &dyn TableLike,
    path: &mut Vec<String>,
    sch: &Schema,
    origins: &Origins,
) -> Result<(), ScenarioError> {
    let Some(t) = item.as_table_like() else {
        return Ok(());
    };
    for (k, child) in t.iter() {
        let key_span = t.get_key_value(k).and_then(|(key, _)| key.span());
        let place = |span: Option<Range<usize>>| match span {
            Some(s) => origins.locate(s.start),
            None => origins.unknown_position(),
        };
        let prefix = path.join(".");
        let key = if prefix.is_empty() {
            k.to_string()
        } else {
            format!("{prefix}.{k}")
        };
        let Some(s) = schema.get(k) else {
            let (source_name, line) = place(key_span.or_else(|| child.span()));
            return Err(ScenarioError::UnknownKey {
                source_name,
                line,
                key,
                allowed: sch.allowed_text(&prefix),
            });
        };
        if let Some(st) = s.as_table_like() {
            if !child.is_table_like() {
                let (source_name, line) = place(child.span().or(key_span));
                return Err(ScenarioError::WrongType {
                    source_name,
                    line,
                    key,
                    expected: "a table (section) of keys".to_string(),
                    found: describe_found(Node::Item(child)),
                });
            }
            path.push(k.to_string());
            let r = check_shape(child, st, path, sch, origins);
            path.pop();
            r?;
            continue;
        }
        let Some(arr) = child.as_array() else {
            continue;
        };
        let wrong_len = |key: String, n: usize, want: usize, span: Option<Range<usize>>| {
            let (source_name, line) = place(span);
            ScenarioError::WrongType {
                source_name,
                line,
                key,
                expected: format!("an array of {want} numbers"),
                found: format!("an array of {n} elements"),
            }
        };
        if let Some(want) = sch.fixed_len(&key) {
            if arr.len() != want {
                return Err(wrong_len(key, arr.len(), want, child.span().or(key_span)));
            }
        }
        if let Some(want) = sch.fixed_len(&format!("{key}[]")) {
            for (i, e) in arr.iter().enumerate() {
                if let Value::Array(inner) = e {
                    if inner.len() != want {
                        return Err(wrong_len(
                            format!("{key}[{i}]"),
                            inner.len(),
                            want,
                            e.span().or(key_span.clone()),
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Text between the first pair of backticks after `prefix`.
fn backticked_after<'m>(msg: &'m str, prefix: &str) -> Option<&'m str> {
    let rest = msg.strip_prefix(prefix)?;
    let rest = rest.strip_prefix('`')?;
    let end = rest.find('`')?;
    Some(&rest[..end])
}

/// serde's names for what it expected, in words.
fn humanise_expected(exp: &str) -> String {
    match exp {
        "f64" | "f32" => "a number".to_string(),
        "u64" | "usize" | "u32" | "u16" | "u8" => "a non-negative integer".to_string(),
        "i64" | "i32" => "an integer".to_string(),
        "a string" | "string" => "a string".to_string(),
        e if e.starts_with("struct ") => "a table (section) of keys".to_string(),
        e => e.to_string(),
    }
}

fn de_error(
    e: &toml_edit::de::Error,
    root: &Item,
    schema: &Schema,
    origins: &Origins,
) -> ScenarioError {
    let msg = one_line(e.message());
    let pos = e.span().map(|s| s.start);
    let mut path = pos.and_then(|p| path_at(root, p)).unwrap_or_default();
    let (source_name, line) = match pos {
        Some(p) => origins.locate(p),
        None => origins.unknown_position(),
    };

    if let Some(field) = backticked_after(&msg, "missing field ") {
        path.push(Seg::Name(field.to_string()));
        let key = render(&path);
        let allowed = match schema.expected(&strip_indices(&path)) {
            Some(exp) => format!("give it as {exp}"),
            None => "it is required here".to_string(),
        };
        return ScenarioError::MissingKey {
            source_name,
            line,
            key,
            allowed,
        };
    }
    if let Some(field) = backticked_after(&msg, "unknown field ") {
        if path.last() != Some(&Seg::Name(field.to_string())) {
            path.push(Seg::Name(field.to_string()));
        }
        let parent = strip_indices(&path[..path.len() - 1]);
        return ScenarioError::UnknownKey {
            source_name,
            line,
            key: render(&path),
            allowed: schema.allowed_text(&parent),
        };
    }
    let key = render(&path);
    let found_here = node_at(root, &path).map(|(n, _)| describe_found(n));
    let has_index = path.iter().any(|s| matches!(s, Seg::Index(_)));
    let schema_expected = if has_index {
        None
    } else {
        schema.expected(&key)
    };
    if let Some(rest) = msg.strip_prefix("invalid type: ") {
        let (found, exp) = rest.split_once(", expected ").unwrap_or((rest, ""));
        return ScenarioError::WrongType {
            source_name,
            line,
            key,
            expected: schema_expected.unwrap_or_else(|| humanise_expected(exp)),
            found: found_here.unwrap_or_else(|| found.to_string()),
        };
    }
    let is_enum = schema::enum_values(&strip_indices(&path)).is_some();
    if is_enum && !msg.starts_with("unknown variant ") {
        // An enum given as something other than a string.
        return ScenarioError::WrongType {
            source_name,
            line,
            key,
            expected: schema_expected.unwrap_or_else(|| "a string".to_string()),
            found: found_here.unwrap_or(msg),
        };
    }
    if let Some(rest) = msg.strip_prefix("invalid length ") {
        let (n, exp) = rest.split_once(", expected ").unwrap_or((rest, ""));
        return ScenarioError::WrongType {
            source_name,
            line,
            key,
            expected: schema_expected.unwrap_or_else(|| humanise_expected(exp)),
            found: format!("an array of {n} elements"),
        };
    }
    if let Some(rest) = msg.strip_prefix("invalid value: ") {
        let (found, exp) = rest.split_once(", expected ").unwrap_or((rest, ""));
        let value = found
            .split_once('`')
            .and_then(|(_, r)| r.split_once('`'))
            .map(|(v, _)| v.to_string())
            .unwrap_or_else(|| found.to_string());
        return ScenarioError::OutOfRange {
            source_name,
            line,
            key,
            value,
            allowed: format!(
                "must be {}",
                schema_expected.unwrap_or_else(|| humanise_expected(exp))
            ),
        };
    }
    if let Some(variant) = backticked_after(&msg, "unknown variant ") {
        let allowed = match schema::enum_values(&strip_indices(&path)) {
            Some(vals) => {
                let q: Vec<String> = vals.iter().map(|v| format!("\"{v}\"")).collect();
                format!("must be one of {}", q.join(", "))
            }
            None => msg.clone(),
        };
        return ScenarioError::OutOfRange {
            source_name,
            line,
            key,
            value: format!("\"{variant}\""),
            allowed,
        };
    }
    ScenarioError::Invalid {
        source_name,
        line,
        key,
        message: msg,
    }
}

fn range_error(v: &Violation, root: &Item, origins: &Origins) -> ScenarioError {
    // Point at whichever of the involved keys was set last (largest position: the file comes
    // first, then the overrides in order); a rule broken by defaults alone has no position.
    let pos = std::iter::once(&v.key)
        .chain(v.related.iter())
        .filter_map(|k| position_of(root, k))
        .max();
    let (source_name, line) = match pos {
        Some(p) => origins.locate(p),
        None => origins.unknown_position(),
    };
    let value = if position_of(root, &v.key).is_some() {
        v.value.clone()
    } else {
        format!("{} (default)", v.value)
    };
    ScenarioError::OutOfRange {
        source_name,
        line,
        key: v.key.clone(),
        value,
        allowed: v.allowed.clone(),
    }
}

/// `s` with `overrides` applied (`dotted.key=value`, as `--set` takes them), validated again;
/// errors name `source` (e.g. the plan file whose scenario it is) or the override.
pub fn with_overrides(
    s: &Scenario,
    source: &str,
    overrides: &[String],
) -> Result<Scenario, ScenarioError> {
    if overrides.is_empty() {
        return Ok(s.clone());
    }
    let text = super::schema::to_document(s).to_string();
    from_toml_str(&text, source, overrides)
}
