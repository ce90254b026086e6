//! Locating keys and positions in a scenario's merged TOML tree (see `load`): the dotted path
//! at a byte position, the node at a path, and how a found value is described in errors.

use std::ops::Range;
use toml_edit::{Item, TableLike, Value};

#[derive(Clone, Debug, PartialEq)]
pub(super) enum Seg {
    Name(String),
    Index(usize),
}

pub(super) fn render(path: &[Seg]) -> String {
    let mut s = String::new();
    for seg in path {
        match seg {
            Seg::Name(n) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(n);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// The dotted key without array indices (for schema lookups).
pub(super) fn strip_indices(path: &[Seg]) -> String {
    let names: Vec<&str> = path
        .iter()
        .filter_map(|s| match s {
            Seg::Name(n) => Some(n.as_str()),
            Seg::Index(_) => None,
        })
        .collect();
    names.join(".")
}

fn contains(span: Option<Range<usize>>, pos: usize) -> bool {
    match span {
        Some(r) => r.start <= pos && (pos < r.end || r.start == r.end),
        None => false,
    }
}

/// The deepest key (or array element) whose key or value span contains `pos`.
pub(super) fn path_at(item: &Item, pos: usize) -> Option<Vec<Seg>> {
    match item {
        Item::None => None,
        Item::Value(v) => path_at_value(v, pos),
        Item::Table(t) => path_at_table(t, pos),
        Item::ArrayOfTables(a) => {
            for (i, t) in a.iter().enumerate() {
                if let Some(mut p) = path_at_table(t, pos) {
                    p.insert(0, Seg::Index(i));
                    return Some(p);
                }
                if contains(t.span(), pos) {
                    return Some(vec![Seg::Index(i)]);
                }
            }
            None
        }
    }
}

fn path_at_value(v: &Value, pos: usize) -> Option<Vec<Seg>> {
    match v {
        Value::InlineTable(t) => path_at_table(t, pos),
        Value::Array(a) => {
            for (i, e) in a.iter().enumerate() {
                if let Some(mut p) = path_at_value(e, pos) {
                    p.insert(0, Seg::Index(i));
                    return Some(p);
                }
                if contains(e.span(), pos) {
                    return Some(vec![Seg::Index(i)]);
                }
            }
            None
        }
        _ => None,
    }
}

fn path_at_table(t: &dyn TableLike, pos: usize) -> Option<Vec<Seg>> {
    let mut shallow = None;
    for (k, child) in t.iter() {
        if let Some(mut p) = path_at(child, pos) {
            p.insert(0, Seg::Name(k.to_string()));
            return Some(p);
        }
        if shallow.is_none() {
            let key_span = t.get_key_value(k).and_then(|(key, _)| key.span());
            if contains(key_span, pos) || contains(child.span(), pos) {
                shallow = Some(vec![Seg::Name(k.to_string())]);
            }
        }
    }
    shallow
}

fn parse_path(key: &str) -> Vec<Seg> {
    let mut out = Vec::new();
    for part in key.split('.') {
        let mut rest = part;
        if let Some(b) = rest.find('[') {
            out.push(Seg::Name(rest[..b].to_string()));
            rest = &rest[b..];
            while let Some(stripped) = rest.strip_prefix('[') {
                let Some(e) = stripped.find(']') else { break };
                if let Ok(i) = stripped[..e].parse() {
                    out.push(Seg::Index(i));
                }
                rest = &stripped[e + 1..];
            }
        } else {
            out.push(Seg::Name(rest.to_string()));
        }
    }
    out
}

/// What sits at a path of the merged tree: an item (table entry) or a value (array element).
#[derive(Clone, Copy)]
pub(super) enum Node<'a> {
    Item(&'a Item),
    Value(&'a Value),
}

/// The node at `path` and the span of the last key on the way (None inside arrays).
pub(super) fn node_at<'a>(
    root: &'a Item,
    path: &[Seg],
) -> Option<(Node<'a>, Option<Range<usize>>)> {
    let mut node = Node::Item(root);
    let mut key_span = None;
    for seg in path {
        match seg {
            Seg::Name(n) => {
                let t: &dyn TableLike = match node {
                    Node::Item(i) => i.as_table_like()?,
                    Node::Value(Value::InlineTable(t)) => t,
                    Node::Value(_) => return None,
                };
                let (k, child) = t.get_key_value(n)?;
                key_span = k.span();
                node = Node::Item(child);
            }
            Seg::Index(i) => {
                let arr = match node {
                    Node::Item(it) => it.as_array()?,
                    Node::Value(Value::Array(a)) => a,
                    Node::Value(_) => return None,
                };
                node = Node::Value(arr.get(*i)?);
                key_span = None;
            }
        }
    }
    Some((node, key_span))
}

/// Start of the span of the value (or, failing that, the key) at `key` in the merged tree.
pub(super) fn position_of(root: &Item, key: &str) -> Option<usize> {
    let (node, key_span) = node_at(root, &parse_path(key))?;
    let span = match node {
        Node::Item(i) => i.span(),
        Node::Value(v) => v.span(),
    };
    span.or(key_span).map(|s| s.start)
}

/// What a node holds, in words, for "found …" (never renders raw text: only parsed values).
pub(super) fn describe_found(node: Node) -> String {
    let v = match node {
        Node::Item(Item::Value(v)) | Node::Value(v) => v,
        Node::Item(Item::Table(_)) => return "a table".to_string(),
        Node::Item(Item::ArrayOfTables(a)) => {
            return format!("an array of {} tables ([[…]])", a.len())
        }
        Node::Item(Item::None) => return "nothing".to_string(),
    };
    match v {
        // a `--set` value that TOML could not read as a number stays a string: say so when it
        // is digits beyond TOML's integers (a u64 seed, say)
        Value::String(s)
            if !s.value().is_empty()
                && s.value()
                    .trim_start_matches('-')
                    .bytes()
                    .all(|b| b.is_ascii_digit()) =>
        {
            format!(
                "{}, beyond TOML's integers (at most {})",
                s.value(),
                i64::MAX
            )
        }
        Value::String(s) => format!("string {:?}", s.value()),
        Value::Integer(i) => format!("integer {}", i.value()),
        Value::Float(f) => format!("number {}", f.value()),
        Value::Boolean(b) => format!("boolean {}", b.value()),
        Value::Datetime(d) => format!("date-time {}", d.value()),
        Value::Array(a) => format!("an array of {} elements", a.len()),
        Value::InlineTable(_) => "a table".to_string(),
    }
}
