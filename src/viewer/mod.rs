//! `shoal view`: one self-contained HTML file showing a plan in 3D — the seafloor as a shaded
//! mesh, the final paths of every vehicle over all windows, the acoustic links of the current
//! step, a time slider with play, orbit and zoom, a legend and the metrics.
//!
//! The page works offline from `file://`: three.js (vendored under `assets/three/`, see its
//! README) and the viewer's own modules are embedded as text and loaded from blob URLs through
//! an import map; the plan data the page needs ([`data::ViewerData`]) is embedded as JSON.
//! With a simulation (`shoal view --sim sim.json`), the page also shows each AUV's executed
//! track and one estimate's, each a layer that can be hidden, and the markers follow the
//! executed track.

pub mod data;

use crate::plan::Plan;
use crate::seafloor::Seafloor;
use crate::sim::SimRecord;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// The three.js release vendored in `assets/three/` (`npm pack three@0.185.1`).
pub const THREE_VERSION: &str = "0.185.1";

const TEMPLATE: &str = include_str!("../../assets/viewer/index.html");
const CSS: &str = include_str!("../../assets/viewer/viewer.css");
const VIEWER_JS: &str = include_str!("../../assets/viewer/viewer.js");
const SCENE_JS: &str = include_str!("../../assets/viewer/scene.js");
const THREE_CORE: &str = include_str!("../../assets/three/three.core.min.js");
const THREE_MODULE: &str = include_str!("../../assets/three/three.module.min.js");
const ORBIT_CONTROLS: &str = include_str!("../../assets/three/OrbitControls.js");
const THREE_LICENSE: &str = include_str!("../../assets/three/LICENSE");

/// How `three.module.min.js` imports the core; rewritten to a bare specifier the import map
/// resolves (a module loaded from a blob URL cannot import relative paths).
const CORE_IMPORT: &str = "\"./three.core.min.js\"";

/// Errors of building and writing the viewer page.
#[derive(Debug, Error)]
pub enum ViewerError {
    /// The plan cannot be shown: no windows, or a window's final stage has missing, non-finite
    /// or inconsistent positions or links; holds what is wrong.
    #[error("cannot show the plan: {0}")]
    Plan(String),
    /// The simulation cannot be shown with the plan: another team, no such estimate, or arrays
    /// that do not fit its epochs; holds what is wrong.
    #[error("cannot show the simulation: {0}")]
    Sim(String),
    /// Writing the HTML file failed.
    #[error(transparent)]
    Write(#[from] crate::output::OutputError),
    /// Serialising the viewer data to JSON failed.
    #[error("cannot serialise the viewer data: {0}")]
    Json(#[from] serde_json::Error),
    /// The output path cannot be written to (it is a directory).
    #[error("cannot write {path}: {why}")]
    Path {
        /// The output path.
        path: PathBuf,
        /// Why it cannot be written to.
        why: String,
    },
}

/// Write the viewer of `plan` (on the floor it was planned on) to `out`, atomically.
pub fn write_html(plan: &Plan, floor: &Seafloor, out: &Path) -> Result<(), ViewerError> {
    write_html_with_sim(plan, floor, None, out)
}

/// [`write_html`], also showing the simulated flight `sim` of the plan when given: each AUV's
/// executed track and the estimate [`data::DEFAULT_ESTIMATE`]'s.
pub fn write_html_with_sim(
    plan: &Plan,
    floor: &Seafloor,
    sim: Option<&SimRecord>,
    out: &Path,
) -> Result<(), ViewerError> {
    if out.is_dir() {
        return Err(ViewerError::Path {
            path: out.to_path_buf(),
            why: "it is a directory; give a file name such as mission.html".into(),
        });
    }
    let html = render_html_with_sim(plan, floor, sim)?;
    crate::output::write_atomic(out, html.as_bytes())?;
    Ok(())
}

/// The viewer page of `plan` as one HTML document.
pub fn render_html(plan: &Plan, floor: &Seafloor) -> Result<String, ViewerError> {
    render_html_with_sim(plan, floor, None)
}

/// The viewer page of `plan` with the simulation `sim`, when given, as one HTML document.
pub fn render_html_with_sim(
    plan: &Plan,
    floor: &Seafloor,
    sim: Option<&SimRecord>,
) -> Result<String, ViewerError> {
    let data = data::build_with_sim(plan, floor, sim)?;
    let json = script_safe(&serde_json::to_string(&data)?);
    let modules = [
        ("three/core", THREE_CORE.to_string(), false),
        (
            "three",
            THREE_MODULE.replace(CORE_IMPORT, "\"three/core\""),
            false,
        ),
        (
            "three/addons/controls/OrbitControls.js",
            ORBIT_CONTROLS.to_string(),
            false,
        ),
        ("shoal/scene", SCENE_JS.to_string(), false),
        ("shoal/viewer", VIEWER_JS.to_string(), true),
    ];
    let mut blocks = String::new();
    for (name, source, entry) in &modules {
        debug_assert!(
            embeddable(source),
            "{name} cannot sit in a <script> element"
        );
        blocks.push_str(&format!(
            "<script type=\"text/plain\" data-module=\"{name}\"{}>\n{source}\n</script>\n",
            if *entry { " data-entry" } else { "" }
        ));
    }
    let title = html_escape(&data.title);
    Ok(fill(
        TEMPLATE,
        &[
            ("@THREE_VERSION@", THREE_VERSION),
            ("@LICENSE@", THREE_LICENSE.trim_end()),
            ("@TITLE@", &title),
            ("@CSS@", CSS),
            ("@TITLE@", &title),
            ("@DATA@", &json),
            ("@MODULES@", &blocks),
        ],
    ))
}

/// Replace each marker, in order of appearance in `template`, by its value. Values are not
/// searched, so they may contain anything.
fn fill(template: &str, parts: &[(&str, &str)]) -> String {
    let mut out =
        String::with_capacity(template.len() + parts.iter().map(|p| p.1.len()).sum::<usize>());
    let mut rest = template;
    for (marker, value) in parts {
        let at = rest
            .find(marker)
            .unwrap_or_else(|| panic!("viewer template lacks {marker} (in order)"));
        out.push_str(&rest[..at]);
        out.push_str(value);
        rest = &rest[at + marker.len()..];
    }
    out.push_str(rest);
    out
}

/// JSON that can sit inside a `<script>` element: `<` only occurs in strings there, where
/// `\u003c` means the same.
fn script_safe(json: &str) -> String {
    json.replace('<', "\\u003c")
}

/// Whether `source` can be the text of a `<script>` element unchanged.
fn embeddable(source: &str) -> bool {
    let lower = source.to_ascii_lowercase();
    !lower.contains("</script") && !lower.contains("<!--")
}

fn html_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests;
