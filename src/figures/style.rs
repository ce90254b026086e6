//! What every figure shares: the embedded font, one colour and one name per vehicle, the link
//! colours, and the frame (title and legend strip) at the top of every figure.

use super::canvas::{Area, DrawResult};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// DejaVu Sans (Bitstream Vera licence, assets/fonts/DejaVuSans-LICENSE.txt).
pub(crate) static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// Font family name the font is registered under; SVG viewers use their own sans-serif.
pub(crate) const FAMILY: &str = "sans-serif";

/// Text sizes in pixels (plotters' size: the font's line height; the em is ≈ size / 1.24).
pub(crate) const TITLE: u32 = 30;
pub(crate) const LABEL: u32 = 24;
pub(crate) const TICK: u32 = 21;

pub(crate) fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // The font is a fixed, valid TTF; failure here would leave text undrawn, not crash.
        let _ = plotters::style::register_font(FAMILY, FontStyle::Normal, FONT);
    });
}

/// A tick label: no decimals on whole numbers, else up to three; a true minus sign.
pub(crate) fn tick(v: &f64) -> String {
    let s = if (v - v.round()).abs() < 1e-9 {
        format!("{:.0}", v.round() + 0.0)
    } else {
        let s = format!("{v:.3}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    };
    s.replace('-', "−")
}

pub(crate) fn text(size: u32) -> TextStyle<'static> {
    (FAMILY, size).into_font().color(&BLACK)
}

/// Colours of the series of a summary figure (a method, a line of a sweep), in order: the
/// first six of the vehicles' palette but an orange a shade darker, for thin lines on white.
pub(crate) const SERIES: [RGBColor; 6] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xf0, 0x7a, 0x0a),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
];

/// The neutral grey of a summary figure's legend keys (marker kinds, bands).
pub(crate) const KEY_GREY: RGBColor = RGBColor(0x5a, 0x5a, 0x5a);

/// Colours of AUV 0, 1, …: dark and saturated enough to read over the muted floor, none of them
/// black (the USV), light blue (A2U links) or yellow (A2A links). Beyond 20 AUVs they come
/// again in shades (`vehicle_colour`).
const PALETTE: [RGBColor; 20] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0x9a, 0x9b, 0x12),
    RGBColor(0x12, 0x9e, 0xad),
    RGBColor(0x39, 0x3b, 0x79),
    RGBColor(0xe6, 0x55, 0x0d),
    RGBColor(0x63, 0x79, 0x39),
    RGBColor(0xad, 0x49, 0x4a),
    RGBColor(0x7b, 0x41, 0x73),
    RGBColor(0x31, 0x82, 0xbd),
    RGBColor(0x8c, 0x6d, 0x31),
    RGBColor(0x31, 0xa3, 0x54),
    RGBColor(0x75, 0x6b, 0xb1),
    RGBColor(0x63, 0x63, 0x63),
];

/// The colour of a vehicle in every figure: `None` is the USV (black), `Some(n)` AUV n. AUVs
/// 0–19 take the palette; each later round of 20 (up to the 64 AUVs a scenario allows) takes
/// it again, darker (×0.7), then lighter (30 % of the way to white), then greyer (60 % of the
/// way to mid grey), so that no two AUVs share a colour (before, AUV 20 repeated AUV 0's).
pub fn vehicle_colour(vehicle: Option<usize>) -> RGBColor {
    let Some(n) = vehicle else { return BLACK };
    let RGBColor(r, g, b) = PALETTE[n % PALETTE.len()];
    let f = |c: u8| -> u8 {
        let c = f64::from(c);
        let v = match (n / PALETTE.len()) % 4 {
            0 => c,
            1 => 0.7 * c,
            2 => 0.7 * c + 0.3 * 255.0,
            _ => 0.4 * c + 0.6 * 128.0,
        };
        v.round() as u8
    };
    RGBColor(f(r), f(g), f(b))
}

/// The name of a vehicle in every figure: "USV", or "AUV n" (n from 0, as in `auvN.csv`).
pub fn vehicle_name(vehicle: Option<usize>) -> String {
    match vehicle {
        None => "USV".into(),
        Some(n) => format!("AUV {n}"),
    }
}

/// A2U links: light blue, as in the paper's Fig. 4(c).
pub(crate) const A2U: RGBColor = RGBColor(0x4f, 0xb8, 0xf0);
/// A2A links: yellow (a deep one, to read on white), as in Fig. 4(c).
pub(crate) const A2A: RGBColor = RGBColor(0xf2, 0xc2, 0x00);
/// Limits and bands.
pub(crate) const LIMIT: RGBColor = RGBColor(0xc0, 0x00, 0x00);
pub(crate) const BAND: RGBColor = RGBColor(0x9c, 0xd8, 0x9c);
/// Window boundaries in time series.
pub(crate) const WINDOW: RGBColor = RGBColor(0x60, 0x60, 0x60);

/// How a legend entry is drawn.
#[derive(Clone, Copy)]
pub(crate) enum Swatch {
    Line(RGBColor, u32),
    Dashed(RGBColor, u32),
    Dot(RGBColor),
    Ring(RGBColor),
    Square(RGBColor),
    Area(RGBColor),
    /// A link: the colour over a dark outline.
    Link(RGBColor),
}

/// The dark outline a link colour is drawn over, so yellow reads on a pale floor.
pub(crate) fn outline(c: RGBColor) -> RGBColor {
    RGBColor(c.0 / 2, c.1 / 2, c.2 / 2)
}

pub(crate) struct Entry {
    pub label: String,
    pub swatch: Swatch,
}

impl Entry {
    pub fn new(label: impl Into<String>, swatch: Swatch) -> Entry {
        Entry {
            label: label.into(),
            swatch,
        }
    }
}

/// One line entry per vehicle: the USV first when `usv`, then AUV 0..n.
pub(crate) fn vehicles(n: usize, usv: bool) -> Vec<Entry> {
    let usv = usv.then_some(None);
    usv.into_iter()
        .chain((0..n).map(Some))
        .map(|v| Entry::new(vehicle_name(v), Swatch::Line(vehicle_colour(v), 4)))
        .collect()
}

const SWATCH_W: i32 = 34;
const ROW_H: u32 = 32;
const TITLE_H: u32 = 50;
const SIDE: u32 = 20;

/// Title and legend at the top of a figure; the rest of the canvas is the body.
pub(crate) struct Frame {
    title: String,
    entries: Vec<Entry>,
    /// Legend rows: ranges into `entries`, with each entry's x offset.
    rows: Vec<Vec<(usize, i32)>>,
    width: u32,
}

impl Frame {
    /// Lays the legend out in rows that fit `width` pixels.
    pub fn new(title: String, entries: Vec<Entry>, width: u32) -> Frame {
        register_font();
        let font = text(TICK);
        let mut rows: Vec<Vec<(usize, i32)>> = vec![Vec::new()];
        let mut x = SIDE as i32;
        for (i, e) in entries.iter().enumerate() {
            let w = font.font.box_size(&e.label).map_or(80, |b| b.0 as i32);
            let w = SWATCH_W + 8 + w + 26;
            if x + w > width as i32 - SIDE as i32 && !rows.last().is_some_and(|r| r.is_empty()) {
                rows.push(Vec::new());
                x = SIDE as i32;
            }
            if let Some(r) = rows.last_mut() {
                r.push((i, x));
            }
            x += w;
        }
        rows.retain(|r| !r.is_empty());
        Frame {
            title,
            entries,
            rows,
            width,
        }
    }

    /// Height of title and legend, pixels.
    pub fn height(&self) -> u32 {
        TITLE_H + self.rows.len() as u32 * ROW_H + 8
    }

    /// Fill the canvas white, draw title and legend; returns the body below them.
    pub fn draw<DB: DrawingBackend>(&self, root: &Area<DB>) -> Result<Area<DB>, DrawErr<DB>> {
        root.fill(&WHITE)?;
        let centre = Pos::new(HPos::Center, VPos::Center);
        root.draw_text(
            &self.title,
            &text(TITLE).pos(centre),
            (self.width as i32 / 2, TITLE_H as i32 / 2 + 4),
        )?;
        let left = Pos::new(HPos::Left, VPos::Center);
        for (r, row) in self.rows.iter().enumerate() {
            let y = (TITLE_H + r as u32 * ROW_H + ROW_H / 2) as i32;
            // Centre the row.
            let used = self.row_width(row);
            let shift = (self.width as i32 - used) / 2 - SIDE as i32;
            for &(i, x) in row {
                let x = x + shift.max(0);
                let e = &self.entries[i];
                swatch(root, e.swatch, x, y)?;
                root.draw_text(&e.label, &text(TICK).pos(left), (x + SWATCH_W + 8, y))?;
            }
        }
        let (_, body) = root.split_vertically(self.height());
        Ok(body)
    }

    fn row_width(&self, row: &[(usize, i32)]) -> i32 {
        let font = text(TICK);
        row.last().map_or(0, |&(i, x)| {
            let w = font
                .font
                .box_size(&self.entries[i].label)
                .map_or(80, |b| b.0 as i32);
            x + SWATCH_W + 8 + w - SIDE as i32
        })
    }
}

pub(crate) type DrawErr<DB> = DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>;

fn swatch<DB: DrawingBackend>(root: &Area<DB>, s: Swatch, x: i32, y: i32) -> DrawResult<DB> {
    let (a, b) = ((x, y), (x + SWATCH_W, y));
    match s {
        Swatch::Line(c, w) => root.draw(&PathElement::new(vec![a, b], c.stroke_width(w))),
        Swatch::Dashed(c, w) => root.draw(&plotters::element::DashedPathElement::new(
            vec![a, b],
            8,
            5,
            c.stroke_width(w),
        )),
        Swatch::Dot(c) => root.draw(&Circle::new((x + SWATCH_W / 2, y), 7, c.filled())),
        Swatch::Ring(c) => root.draw(&Circle::new((x + SWATCH_W / 2, y), 7, c.stroke_width(3))),
        Swatch::Link(c) => {
            root.draw(&PathElement::new(vec![a, b], outline(c).stroke_width(5)))?;
            root.draw(&PathElement::new(vec![a, b], c.stroke_width(3)))
        }
        Swatch::Square(c) => root.draw(&Rectangle::new(
            [(x + SWATCH_W / 2 - 7, y - 7), (x + SWATCH_W / 2 + 7, y + 7)],
            c.filled(),
        )),
        Swatch::Area(c) => root.draw(&Rectangle::new(
            [(x, y - 9), (x + SWATCH_W, y + 9)],
            c.filled(),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks_drop_needless_decimals_and_use_a_true_minus() {
        assert_eq!(tick(&-100.0), "−100");
        assert_eq!(tick(&-0.0), "0");
        assert_eq!(tick(&0.5), "0.5");
        assert_eq!(tick(&2.25), "2.25");
        assert_eq!(vehicle_name(None), "USV");
        assert_eq!(vehicle_name(Some(3)), "AUV 3");
        // AUV 21 is AUV 1's colour, darker (see palette_tests): no longer a repeat
        assert_ne!(vehicle_colour(Some(21)), vehicle_colour(Some(1)));
    }
}

#[cfg(test)]
mod palette_tests {
    use super::*;

    /// Regression (issue 13): colours repeated beyond 20 AUVs. Every one of the 64 AUVs a
    /// scenario allows has its own colour, none within 15 (RGB distance) of another or within
    /// 60 of the USV's black.
    #[test]
    fn regression_colours_repeated_beyond_20_auvs() {
        let dist = |a: RGBColor, b: RGBColor| {
            let d = |x: u8, y: u8| (f64::from(x) - f64::from(y)).powi(2);
            (d(a.0, b.0) + d(a.1, b.1) + d(a.2, b.2)).sqrt()
        };
        let colours: Vec<RGBColor> = (0..64).map(|n| vehicle_colour(Some(n))).collect();
        for (i, &a) in colours.iter().enumerate() {
            assert!(
                dist(a, BLACK) >= 60.0,
                "AUV {i} {a:?} is near the USV's black"
            );
            for (j, &b) in colours.iter().enumerate().skip(i + 1) {
                assert!(dist(a, b) >= 15.0, "AUV {i} {a:?} and AUV {j} {b:?}");
            }
        }
        assert_eq!(colours[..20], PALETTE[..], "the first 20 are the palette");
    }
}
