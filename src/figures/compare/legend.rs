//! The legend's entries: one per method with its run count (and how many violated the check
//! or made no plan), then the marker kinds (passed, violated, no plan), the median bar and the
//! paper's reference line.

use super::runs::{Method, Run, Status};
use super::{KEY, PAPER_LABEL};
use crate::figures::style::{self, Entry, Swatch};

/// The legend of `methods`' `runs`.
pub(super) fn entries(methods: &[Method], runs: &[Run]) -> Vec<Entry> {
    let mut entries = Vec::new();
    for (i, m) in methods.iter().enumerate() {
        let of = runs.iter().filter(|r| r.method == i);
        let count = |s: Status| of.clone().filter(|r| r.status == s).count();
        let mut label = format!("{}: {} runs", m.name, of.clone().count());
        let (violated, failed) = (count(Status::Violated), count(Status::Failed));
        if violated > 0 {
            label.push_str(&format!(", {violated} violated"));
        }
        if failed > 0 {
            label.push_str(&format!(", {failed} made no plan"));
        }
        entries.push(Entry::new(label, Swatch::Dot(m.colour)));
    }
    entries.push(Entry::new("check passed", Swatch::Dot(KEY)));
    if runs.iter().any(|r| r.status == Status::Violated) {
        entries.push(Entry::new("check violated", Swatch::Ring(KEY)));
    }
    if runs.iter().any(|r| r.status == Status::Failed) {
        entries.push(Entry::new(
            "no plan: time to give up (a), count at its foot",
            Swatch::Square(KEY),
        ));
    }
    entries.push(Entry::new("median over seeds", Swatch::Line(KEY, 4)));
    entries.push(Entry::new(PAPER_LABEL, Swatch::Dashed(style::LIMIT, 3)));
    entries
}
