//! Static figures of a plan, as PNG and SVG, drawn with `plotters`: the paper's Fig. 4 panels
//! (seafloor, Step 1 paths, Step 2 links, final paths; each path panel as a 3D perspective and a
//! top view), time series of the links, speeds, heading rates and depths against their limits,
//! and the metrics table; and the figures of a comparison ([`write_compare`]) and of a sweep's
//! table ([`write_sweep`]).
//!
//! Every figure covers every window of the plan (paths concatenated across windows, window
//! starts marked in the time series), names each vehicle the same way with one colour per
//! vehicle (USV black, AUV n from a fixed palette, see [`vehicle_colour`]), and has a title that
//! says which scenario and windows it shows. Text is drawn with DejaVu Sans, embedded in the
//! binary (assets/fonts), so no system font library is needed.
//!
//! Files are written atomically ([`crate::output::write_atomic`]).

mod canvas;
mod compare;
mod depth;
mod map;
mod overlay;
mod persp;
mod raster;
mod scene;
mod series;
mod sim;
mod sim_tracks;
mod style;
mod sweep;
mod table;
mod text;

use crate::plan::Plan;
use crate::seafloor::Seafloor;
use std::path::{Path, PathBuf};
use std::time::Instant;
use thiserror::Error;

pub use compare::{write_compare, COMPARE_FIGURE};
pub use sim::{write_sim, write_sim_with, SIM_FIGURES};
pub use style::{vehicle_colour, vehicle_name};
pub use sweep::{figure_stem as sweep_figure_stem, write_sweep};

/// The figures [`write_all`] writes, by file stem; each as `STEM.png` and `STEM.svg`.
pub const FIGURES: [&str; 11] = [
    "seafloor",
    "step1-3d",
    "step1-top",
    "links-3d",
    "links-top",
    "final-3d",
    "final-top",
    "link-lengths",
    "speed",
    "heading-rate",
    "depth",
];

/// The metrics table's file stem (written after [`FIGURES`]).
pub const TABLE: &str = "metrics";

/// Errors of drawing and writing the figures.
#[derive(Debug, Error)]
pub enum FigureError {
    /// Writing a figure's file (or creating its directory) failed.
    #[error(transparent)]
    Output(#[from] crate::output::OutputError),
    /// `plotters` failed to draw a figure.
    #[error("cannot draw figure {figure}: {why}")]
    Draw {
        /// The figure's file stem, e.g. "final-top".
        figure: &'static str,
        /// The drawing backend's error message.
        why: String,
    },
    /// The plan's arrays do not have the lengths the plan format promises (no windows, wrong
    /// number of AUVs, not K + 1 states, …); holds what is wrong.
    #[error("cannot plot the plan: {0}")]
    Plan(String),
    /// A simulation record that does not fit its plan or whose arrays do not have one entry
    /// per AUV and epoch; holds what is wrong.
    #[error("cannot plot the simulation: {0}")]
    Sim(String),
    /// Comparison rows that cannot be plotted: none, or none of the runs made a plan; holds
    /// what is wrong.
    #[error("cannot plot the comparison: {0}")]
    Compare(String),
    /// A sweep's table that cannot be plotted as asked (`shoal sweep plot`); holds the table
    /// file and what is wrong, naming the column and the columns allowed.
    #[error("{0}")]
    Sweep(String),
}

/// One figure written, for progress reports.
#[derive(Debug, Clone)]
pub struct FigureDone {
    /// File stem, e.g. "final-top".
    pub name: &'static str,
    /// The files written (PNG and SVG).
    pub files: Vec<PathBuf>,
    /// Wall-clock time to draw and write both files, seconds.
    pub seconds: f64,
}

/// Write every figure of `plan` (drawn over `floor`) into `dir`, creating it if needed.
/// Returns the paths written: `STEM.png` and `STEM.svg` for every stem of [`FIGURES`] and
/// [`TABLE`].
pub fn write_all(plan: &Plan, floor: &Seafloor, dir: &Path) -> Result<Vec<PathBuf>, FigureError> {
    write_all_with_progress(plan, floor, dir, |_| {})
}

/// [`write_all`], calling `progress` after each figure.
pub fn write_all_with_progress(
    plan: &Plan,
    floor: &Seafloor,
    dir: &Path,
    mut progress: impl FnMut(&FigureDone),
) -> Result<Vec<PathBuf>, FigureError> {
    let scene = scene::Scene::new(plan, floor)?;
    let mut written = Vec::new();
    let mut emit = |name: &'static str, files: Vec<PathBuf>, start: Instant| {
        let done = FigureDone {
            name,
            files,
            seconds: start.elapsed().as_secs_f64(),
        };
        progress(&done);
        written.extend(done.files);
    };
    macro_rules! figure {
        ($fig:expr) => {{
            let start = Instant::now();
            let fig = $fig;
            let files = canvas::write(&fig, dir)?;
            emit(canvas::Figure::name(&fig), files, start);
        }};
    }
    use scene::Stage::{Final, Step1};
    figure!(map::Map::floor(&scene));
    figure!(persp::Persp::new(&scene, Step1, false));
    figure!(map::Map::paths(&scene, Step1, false));
    figure!(persp::Persp::new(&scene, Step1, true));
    figure!(map::Map::paths(&scene, Step1, true));
    figure!(persp::Persp::new(&scene, Final, false));
    figure!(map::Map::paths(&scene, Final, false));
    figure!(series::links(&scene));
    figure!(series::speed(&scene));
    figure!(series::heading_rate(&scene));
    figure!(depth::Depth::new(&scene));
    figure!(table::Table::new(&scene));
    Ok(written)
}
