//! Text reports of a plan for the terminal.

use crate::plan::{Course, Metrics, Plan};
use std::borrow::Cow;
use std::fmt::Write as _;

/// `text` made safe to print on a terminal, on one line: every control character (the C0 set
/// with ESC, CR, TAB and the newline; DEL; the C1 set) and every character that reorders text
/// (the bidirectional embeddings, overrides and isolates) is shown as a visible escape,
/// `\u{1b}`. For strings that come from files (a plan's warnings and names, a grid's CRS
/// citation, error messages that quote a file), which could otherwise move the cursor, recolour
/// or clear the terminal, or make a line read other than it is.
pub fn printable(text: &str) -> Cow<'_, str> {
    escape(text, false)
}

/// [`printable`] keeping the newlines: for a multi-line text (a table, a report) that holds
/// strings from files.
pub fn printable_lines(text: &str) -> Cow<'_, str> {
    escape(text, true)
}

fn escape(text: &str, keep_newlines: bool) -> Cow<'_, str> {
    let unsafe_char = |c: char| {
        (c.is_control() && !(keep_newlines && c == '\n'))
            || matches!(c, '\u{061C}' | '\u{200E}' | '\u{200F}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
    };
    if !text.chars().any(unsafe_char) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if unsafe_char(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// One row per window with the status and SCP iterations of Step 1 and Step 3, the final plan's
/// figures and its metrics, then a row for the whole mission.
pub fn summary_table(plan: &Plan) -> String {
    let mut t = String::new();
    let header = [
        "window",
        "step 1",
        "step 3",
        "energy",
        "height",
        "min h",
        "USV moved",
        "USV path",
        "explored",
        "connected",
        "chain",
        "off band",
        "max ψ̇",
        "time",
    ];
    let units = [
        "",
        "status/iter",
        "status/iter",
        "(m/s²)²",
        "m",
        "m",
        "m",
        "m",
        "km²",
        "%",
        "%",
        "links",
        "rad/s",
        "s",
    ];
    for row in [header, units] {
        let row: [&str; 14] = row;
        let _ = writeln!(t, "{}", line(&row.map(String::from)));
    }
    for w in &plan.windows {
        let st = &w.final_;
        let p0 = st.usv.position.first().copied().unwrap_or([0.0; 2]);
        let pk = st.usv.position.last().copied().unwrap_or([0.0; 2]);
        let moved = (pk[0] - p0[0]).hypot(pk[1] - p0[1]);
        let travelled = path_length(&st.usv.position);
        let _ = writeln!(
            t,
            "{}",
            line(&row(
                w.index.to_string(),
                format!("{}/{}", short(&w.step1.status), w.step1.iterations),
                format!("{}/{}", short(&st.status), st.iterations),
                [moved, travelled],
                w.links.out_of_band.len(),
                &w.metrics
            ))
        );
    }
    let first = plan
        .windows
        .first()
        .and_then(|w| w.final_.usv.position.first().copied());
    let last = plan
        .windows
        .last()
        .and_then(|w| w.final_.usv.position.last().copied());
    let moved = match (first, last) {
        (Some(a), Some(b)) => (b[0] - a[0]).hypot(b[1] - a[1]),
        _ => 0.0,
    };
    let off: usize = plan.windows.iter().map(|w| w.links.out_of_band.len()).sum();
    let travelled: f64 = plan
        .windows
        .iter()
        .map(|w| path_length(&w.final_.usv.position))
        .sum();
    let _ = writeln!(
        t,
        "{}",
        line(&row(
            "all".into(),
            String::new(),
            String::new(),
            [moved, travelled],
            off,
            &plan.metrics
        ))
    );
    if let Some(c) = plan.windows.first().and_then(|w| first_course(&w.courses)) {
        let _ = writeln!(t, "{c}");
    }
    if plan.windows.len() > 1 {
        // the mission's explored area is a union: say what the windows swept twice
        let m = &plan.metrics;
        let _ = writeln!(
            t,
            "explored over the mission: {} km² (each place once); {} km² more was swept \
             again in a later window",
            fixed(m.explored_area_km2, 3),
            fixed(m.revisited_area_km2, 3)
        );
    }
    // the statuses come from the plan file
    printable_lines(&t).into_owned()
}

/// The first window's course choice (`usv.courses` > 1): which course Step 1 started from,
/// of how many tried, and the merit each reached.
fn first_course(courses: &[Course]) -> Option<String> {
    let best = Course::best(courses)?;
    let tried: Vec<String> = courses
        .iter()
        .map(|c| match c.merit {
            Some(m) => format!("{:.0}° {m:.1}", c.heading.to_degrees()),
            None => format!("{:.0}° failed", c.heading.to_degrees()),
        })
        .collect();
    Some(format!(
        "first course: {:.0}° of {} tried (merit after one SCP iteration: {})",
        best.heading.to_degrees(),
        courses.len(),
        tried.join(", ")
    ))
}

/// Length of a polyline of USV positions, metres.
fn path_length(p: &[[f64; 2]]) -> f64 {
    p.windows(2)
        .map(|s| (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]))
        .sum()
}

fn short(status: &str) -> &str {
    match status {
        "converged" => "conv",
        "max_iterations" => "max",
        "stalled" => "stall",
        "solver_trouble" => "trbl",
        s => s,
    }
}

fn row(
    window: String,
    step1: String,
    step3: String,
    [moved, travelled]: [f64; 2],
    off_band: usize,
    m: &Metrics,
) -> [String; 14] {
    [
        window,
        step1,
        step3,
        fixed(m.input_energy, 3),
        fixed(m.mean_height, 1),
        fixed(m.min_height, 1),
        fixed(moved, 0),
        fixed(travelled, 0),
        fixed(m.explored_area_km2, 3),
        fixed(100.0 * m.connected_fraction, 1),
        fixed(100.0 * m.chain_fraction, 1),
        off_band.to_string(),
        format!("{:.2e}", m.max_heading_rate),
        fixed(m.step1_time_s + m.step2_time_s + m.step3_time_s, 3),
    ]
}

/// `v` with `decimals` decimals, and never "-0.000": a value that rounds to zero is written
/// without its sign.
pub fn fixed(v: f64, decimals: usize) -> String {
    no_negative_zero(format!("{v:.decimals$}"))
}

/// `text` (a formatted number) without the sign of a negative zero: "-0.000" becomes "0.000",
/// "-0" becomes "0"; any other text is returned as it is.
pub fn no_negative_zero(text: String) -> String {
    match text.strip_prefix('-') {
        Some(rest) if !rest.is_empty() && rest.chars().all(|c| c == '0' || c == '.') => {
            rest.to_string()
        }
        _ => text,
    }
}

fn line(cells: &[String; 14]) -> String {
    const WIDTH: [usize; 14] = [6, 11, 11, 9, 7, 7, 9, 8, 9, 9, 6, 8, 9, 7];
    cells
        .iter()
        .zip(WIDTH)
        .map(|(c, w)| format!("{c:>w$}"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_and_reordering_characters_are_shown_escaped() {
        assert_eq!(printable("plain — text, 5 m²"), "plain — text, 5 m²");
        assert!(matches!(printable("plain"), Cow::Borrowed(_)));
        assert_eq!(
            printable("\u{1b}[31mred\u{1b}[0m\r\n\t\u{7f}\u{9b}x"),
            "\\u{1b}[31mred\\u{1b}[0m\\u{d}\\u{a}\\u{9}\\u{7f}\\u{9b}x"
        );
        assert_eq!(printable("a\u{202e}b"), "a\\u{202e}b");
        assert_eq!(printable_lines("a\nb\u{1b}c"), "a\nb\\u{1b}c");
        assert!(!printable("\u{1b}]0;title\u{7}")
            .chars()
            .any(|c| c.is_control()));
    }

    #[test]
    fn regression_a_negative_zero_is_printed_as_zero() {
        assert_eq!(fixed(-0.0, 3), "0.000");
        assert_eq!(fixed(-1e-9, 3), "0.000");
        assert_eq!(fixed(-0.0004, 0), "0");
        assert_eq!(fixed(-0.0006, 3), "-0.001");
        assert_eq!(fixed(-2.5, 1), "-2.5");
        assert_eq!(no_negative_zero("-".into()), "-");
        assert_eq!(no_negative_zero("-inf".into()), "-inf");
        assert_eq!(no_negative_zero("-NaN".into()), "-NaN");
    }
}
