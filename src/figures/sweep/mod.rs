//! The figures of `shoal sweep plot`: a sweep's measures against a swept key, from its table
//! (`runs.csv`). One figure per key on x (`sweep-KEY.png` and `.svg`), one panel per measure:
//! at each value of the key, the median over the runs there (the seeds) as a line through
//! dots, the quartiles as a darker band and the extremes (min–max) as a lighter one; one line
//! per combination of the other swept keys but the seed (at most [`select::MAX_SERIES`], else
//! one line of every run, said in the caption). Runs that made no plan are left out of every
//! measure (but the fraction that passed the check, where they count as not passed) and
//! counted in the caption. A key whose values are not all numbers (floor files) is placed on a
//! categorical axis in the table's order. With the seed the only swept key, the measures are
//! plotted against it, one run per point.
//!
//! Split by job: [`table`] (reading the table), [`metric`] (the measures and their names),
//! [`select`] (the keys, measures and lines asked for, checked), [`stats`] (medians and
//! spreads) and [`panel`] (drawing one panel); this module lays the figure out.

mod metric;
mod panel;
mod select;
mod stats;
mod table;

use super::canvas::{self, Area, DrawResult, Figure, Images};
use super::style::{text, Entry, Frame, Swatch, TICK};
use super::FigureError;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use stats::{Series, XAxis};
use std::path::{Path, PathBuf};
use table::Table;

/// Draw the figures of the sweep table `table` (a `runs.csv`, or a sweep's directory) into
/// `dir` (default: the table's directory): against key `x` (default: every swept key but the
/// seed), measures `y` (default: the usual ones the table has). Returns the files written,
/// `sweep-KEY.png` and `sweep-KEY.svg` for each key, each written atomically. Errors name the
/// table and the column, and list the columns allowed.
pub fn write_sweep(
    table: &Path,
    dir: Option<&Path>,
    x: Option<&str>,
    y: &[String],
) -> Result<Vec<PathBuf>, FigureError> {
    let t = Table::read(table)?;
    let keys = select::x_keys(&t, x)?;
    let metrics = select::metrics(&t, y)?;
    if t.rows.is_empty() {
        return Err(err(&t.path, "no runs to plot".into()));
    }
    let dir = match dir {
        Some(d) => d.to_path_buf(),
        None => t.path.parent().unwrap_or(Path::new(".")).to_path_buf(),
    };
    let mut written = Vec::new();
    for key in keys {
        let fig = SweepFigure::new(&t, &key, metrics.clone());
        written.extend(canvas::write_as(&fig, &dir, &figure_stem(&key))?);
    }
    Ok(written)
}

/// The file stem of the figure against `key`: `sweep-KEY`, any character of the key but
/// letters, digits, `.`, `-` and `_` written as `_`.
pub fn figure_stem(key: &str) -> String {
    let key: String = key
        .chars()
        .map(|c| match c {
            'a'..='z' | 'A'..='Z' | '0'..='9' | '.' | '-' | '_' => c,
            _ => '_',
        })
        .collect();
    format!("sweep-{key}")
}

/// An error about table `path`.
fn err(path: &Path, why: String) -> FigureError {
    FigureError::Sweep(format!("{}: {why}", path.display()))
}

const PANEL_W: u32 = 620;
const PANEL_H: u32 = 440;
const CAPTION_LINE: u32 = 30;
/// One colour per line; a single line takes the first.
const LINES: [RGBColor; select::MAX_SERIES] = super::style::SERIES;
/// The legend's neutral colour.
const KEY: RGBColor = super::style::KEY_GREY;
/// The bands' opacities: min–max, quartiles.
const EXTREMES: f64 = 0.12;
const QUARTILES: f64 = 0.30;

/// A sweep's measures against one key.
struct SweepFigure<'a> {
    table: &'a Table,
    x: XAxis,
    metrics: Vec<String>,
    series: Vec<Series>,
    frame: Frame,
    caption: Vec<String>,
    cols: u32,
}

impl<'a> SweepFigure<'a> {
    fn new(table: &'a Table, key: &str, metrics: Vec<String>) -> SweepFigure<'a> {
        let x = XAxis::new(table, key, table.column(key).unwrap_or(0));
        let (series, pooled) = select::series(table, key);
        let cols = match metrics.len() {
            0 | 1 => 1,
            2..=4 => 2,
            _ => 3,
        };
        let width = cols * PANEL_W;
        let mut entries = Vec::new();
        for (i, s) in series.iter().enumerate() {
            if !s.label.is_empty() {
                let label = format!("{} ({} runs)", s.label, s.rows.len());
                entries.push(Entry::new(label, Swatch::Line(LINES[i], 4)));
            }
        }
        let over = if key == table::SEED {
            "median of the runs at each seed"
        } else {
            "median over the seeds"
        };
        entries.push(Entry::new(over, Swatch::Line(KEY, 3)));
        entries.push(Entry::new(
            "quartiles (25–75 %)",
            Swatch::Area(tint(QUARTILES)),
        ));
        entries.push(Entry::new("min–max", Swatch::Area(tint(EXTREMES))));
        let scenario = table
            .column("scenario")
            .and_then(|c| table.rows.first().map(|r| r[c].clone()))
            .unwrap_or_default();
        let title = format!("{scenario}: measures against {key}");
        let frame = Frame::new(title, entries, width);
        let count = |s: &str| {
            (0..table.rows.len())
                .filter(|&r| table.status(r) == s)
                .count()
        };
        let mut caption = vec![format!(
            "{} runs in {}: {} made no plan (left out; they count as not passed in \
             passed_fraction), {} violated the check (kept).",
            table.rows.len(),
            table.name(),
            count("failed"),
            count("violated"),
        )];
        caption.push(
            "Line: median over the runs at each value (the seeds); dark band: quartiles \
             (25–75 %); light band: min–max."
                .into(),
        );
        caption.extend(pooled);
        let caption = caption
            .iter()
            .flat_map(|line| wrap(line, width - 40))
            .collect();
        SweepFigure {
            table,
            x,
            metrics,
            series,
            frame,
            caption,
            cols,
        }
    }

    fn rows(&self) -> u32 {
        (self.metrics.len() as u32).div_ceil(self.cols).max(1)
    }
}

/// `line` cut at spaces into lines at most `width` pixels wide (at the caption's size).
fn wrap(line: &str, width: u32) -> Vec<String> {
    let font = text(TICK);
    let fits = |s: &str| font.font.box_size(s).map_or(true, |b| b.0 <= width);
    let mut lines: Vec<String> = Vec::new();
    let mut current = String::new();
    for word in line.split(' ') {
        let longer = match current.is_empty() {
            true => word.to_string(),
            false => format!("{current} {word}"),
        };
        if fits(&longer) || current.is_empty() {
            current = longer;
        } else {
            lines.push(std::mem::replace(&mut current, word.to_string()));
        }
    }
    lines.push(current);
    lines
}

/// Grey at `opacity` over white, for the legend's band swatches.
fn tint(opacity: f64) -> RGBColor {
    let c = |v: u8| (255.0 - opacity * (255.0 - f64::from(v))).round() as u8;
    RGBColor(c(KEY.0), c(KEY.1), c(KEY.2))
}

impl Figure for SweepFigure<'_> {
    fn name(&self) -> &'static str {
        "sweep"
    }

    fn size(&self) -> (u32, u32) {
        let caption = self.caption.len() as u32 * CAPTION_LINE + 16;
        (
            self.cols * PANEL_W,
            self.frame.height() + self.rows() * PANEL_H + caption,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, _: &mut Images) -> DrawResult<DB> {
        let body = self.frame.draw(root)?;
        let (grid, foot) = body.split_vertically(self.rows() * PANEL_H);
        let panels = grid.split_evenly((self.rows() as usize, self.cols as usize));
        for (area, metric) in panels.iter().zip(&self.metrics) {
            self.panel(area, metric)?;
        }
        let style = text(TICK).pos(Pos::new(HPos::Left, VPos::Top));
        for (i, line) in self.caption.iter().enumerate() {
            let y = 8 + (i as u32 * CAPTION_LINE) as i32;
            foot.draw_text(line, &style, (20, y))?;
        }
        Ok(())
    }
}
