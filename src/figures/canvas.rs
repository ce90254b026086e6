//! Rendering a figure to PNG and SVG and writing both files atomically. A figure is drawn once
//! per backend by the same code ([`Figure::draw`]); depth rasters go through [`Images`], which
//! blits them into the PNG and embeds them as `<image>` PNG data in the SVG.

use super::FigureError;
use crate::output::write_atomic;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};

pub(crate) type Area<DB> = DrawingArea<DB, Shift>;
pub(crate) type DrawResult<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure that can draw itself on any plotters backend.
pub(crate) trait Figure {
    /// File stem, e.g. "final-top".
    fn name(&self) -> &'static str;
    /// Canvas size in pixels.
    fn size(&self) -> (u32, u32);
    fn draw<DB: DrawingBackend>(&self, root: &Area<DB>, images: &mut Images) -> DrawResult<DB>;
}

/// An RGB raster (row-major, top row first).
pub(crate) struct Raster {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

/// Where rasters go: blitted pixel for pixel (PNG), or kept aside and embedded afterwards as
/// PNG data in place of a placeholder rectangle (SVG).
pub(crate) struct Images {
    svg: bool,
    pending: Vec<(i32, i32, u32, u32, Vec<u8>)>,
}

/// Fill colour of the SVG placeholder rectangles (replaced by `<image>` elements).
const PLACEHOLDER: RGBColor = RGBColor(1, 2, 3);
const PLACEHOLDER_FILL: &str = "fill=\"#010203\"";

impl Images {
    /// The largest raster side worth computing: the PNG takes the raster at screen size, the
    /// SVG a smaller one that the viewer scales.
    pub fn max_side(&self) -> Option<u32> {
        self.svg.then_some(480)
    }

    /// Draw `raster` into the pixel rectangle at `pos` of size `size` (the raster must have
    /// that size for PNG; the SVG scales it).
    pub fn draw<DB: DrawingBackend>(
        &mut self,
        root: &Area<DB>,
        pos: (i32, i32),
        size: (u32, u32),
        raster: Raster,
    ) -> DrawResult<DB> {
        if self.svg {
            let png = encode_png(raster.width, raster.height, &raster.rgb);
            root.draw(&Rectangle::new(
                [pos, (pos.0 + size.0 as i32, pos.1 + size.1 as i32)],
                PLACEHOLDER.filled(),
            ))?;
            self.pending.push((pos.0, pos.1, size.0, size.1, png));
            Ok(())
        } else {
            let el =
                BitMapElement::with_owned_buffer(pos, (raster.width, raster.height), raster.rgb);
            match el {
                Some(el) => root.draw(&el),
                None => Ok(()),
            }
        }
    }

    /// Replace each placeholder rectangle of `svg`, in order, by its image.
    fn splice(self, svg: &str) -> String {
        let mut out = String::with_capacity(svg.len());
        let mut rest = svg;
        for (x, y, w, h, png) in self.pending {
            let Some(at) = rest.find(PLACEHOLDER_FILL) else {
                break;
            };
            let start = rest[..at].rfind("<rect").unwrap_or(at);
            let end = rest[at..].find("/>").map_or(rest.len(), |e| at + e + 2);
            out.push_str(&rest[..start]);
            out.push_str(&format!(
                "<image x=\"{x}\" y=\"{y}\" width=\"{w}\" height=\"{h}\" \
                 preserveAspectRatio=\"none\" href=\"data:image/png;base64,{}\"/>",
                base64(&png)
            ));
            rest = &rest[end..];
        }
        out.push_str(rest);
        out
    }
}

/// Draw `fig` as `dir/NAME.png` and `dir/NAME.svg`; returns both paths.
pub(crate) fn write<F: Figure>(fig: &F, dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    write_as(fig, dir, fig.name())
}

/// Draw `fig` as `dir/STEM.png` and `dir/STEM.svg` (a stem made at run time, e.g. from a
/// swept key); returns both paths.
pub(crate) fn write_as<F: Figure>(
    fig: &F,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, FigureError> {
    super::style::register_font();
    let name = stem;
    let failed = |why: String| FigureError::Draw {
        figure: fig.name(),
        why,
    };
    let (w, h) = fig.size();

    let mut rgb = vec![255u8; w as usize * h as usize * 3];
    {
        let bitmap = BitMapBackend::with_buffer(&mut rgb, (w, h));
        let root = super::text::Crisp(bitmap).into_drawing_area();
        let mut images = Images {
            svg: false,
            pending: Vec::new(),
        };
        fig.draw(&root, &mut images)
            .and_then(|_| root.present())
            .map_err(|e| failed(e.to_string()))?;
    }
    let png_path = dir.join(format!("{name}.png"));
    write_atomic(&png_path, &encode_png(w, h, &rgb))?;

    let mut svg = String::new();
    let mut images = Images {
        svg: true,
        pending: Vec::new(),
    };
    {
        let root = SVGBackend::with_string(&mut svg, (w, h)).into_drawing_area();
        fig.draw(&root, &mut images)
            .and_then(|_| root.present())
            .map_err(|e| failed(e.to_string()))?;
    }
    let svg = images.splice(&svg);
    let svg_path = dir.join(format!("{name}.svg"));
    write_atomic(&svg_path, svg.as_bytes())?;
    Ok(vec![png_path, svg_path])
}

/// PNG bytes of an RGB image (8 bits per channel).
pub(crate) fn encode_png(w: u32, h: u32, rgb: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    let mut enc = png::Encoder::new(&mut out, w, h);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.set_compression(png::Compression::Balanced);
    // Writing to a Vec fails only on a size mismatch, which the callers rule out.
    if let Ok(mut writer) = enc.write_header() {
        let _ = writer.write_image_data(rgb);
        let _ = writer.finish();
    }
    out
}

/// Standard base64 with padding (RFC 4648 §4).
pub(crate) fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let b = [c[0], *c.get(1).unwrap_or(&0), *c.get(2).unwrap_or(&0)];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for i in 0..4 {
            if i <= c.len() {
                s.push(A[(n >> (18 - 6 * i) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn base64_matches_rfc_4648_test_vectors() {
        let cases = [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ];
        for (plain, enc) in cases {
            assert_eq!(base64(plain.as_bytes()), enc);
        }
    }

    #[test]
    fn splice_replaces_placeholders_in_order() {
        let svg = "<svg><rect x=\"1\" fill=\"#010203\" stroke=\"none\"/><line/>\
                   <rect x=\"2\" fill=\"#010203\"/></svg>";
        let images = Images {
            svg: true,
            pending: vec![(1, 2, 3, 4, b"a".to_vec()), (5, 6, 7, 8, b"b".to_vec())],
        };
        let out = images.splice(svg);
        assert!(!out.contains("#010203"), "{out}");
        let a = out.find("base64,YQ==").unwrap();
        let b = out.find("base64,Yg==").unwrap();
        assert!(a < out.find("<line/>").unwrap() && out.find("<line/>").unwrap() < b);
        assert!(out.starts_with("<svg><image x=\"1\" y=\"2\" width=\"3\" height=\"4\""));
    }
}
