//! The `shoal` command: a thin layer over the library.

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use shoal::planner::Progress;
use shoal::scenario::{self, Scenario};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "shoal",
    version,
    about = "Localization-aware path planning for a USV and a team of AUVs"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write the default scenario as a commented TOML file.
    Init {
        /// Where to write it.
        #[arg(default_value = "mission.toml")]
        path: PathBuf,
        /// Overwrite an existing file.
        #[arg(long)]
        force: bool,
    },
    /// Plan every window of a scenario, write plan.json and one CSV per vehicle, then check it.
    Plan {
        /// Scenario file (TOML); the embedded default when absent.
        scenario: Option<PathBuf>,
        /// Override one key, e.g. --set team.auvs=7 (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Seafloor grid (ESRI ASCII .asc or GeoTIFF .tif); same as --set seafloor.file=PATH.
        #[arg(long)]
        seafloor: Option<PathBuf>,
        /// Output directory.
        #[arg(short, long, default_value = "out")]
        out: PathBuf,
        /// Draw the figures into OUT/figures (the default).
        #[arg(long, overrides_with = "no_plot")]
        plot: bool,
        /// Do not draw the figures.
        #[arg(long, overrides_with = "plot")]
        no_plot: bool,
    },
    /// Verify every constraint of a plan from the plan file and the seafloor alone.
    Check {
        plan: PathBuf,
        /// Check against this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
    },
    /// Write one self-contained HTML file showing a plan in 3D (opens offline in a browser).
    View {
        plan: PathBuf,
        /// The HTML file to write.
        #[arg(short, long, default_value = "mission.html")]
        out: PathBuf,
        /// Show the plan on this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
    },
    /// Draw the figures of a plan (PNG and SVG): floor, paths, links, time series, metrics.
    Plot {
        plan: PathBuf,
        /// Output directory; default: `figures` beside the plan file.
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Draw over this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
    },
    /// Seafloor tools.
    Seafloor {
        #[command(subcommand)]
        command: SeafloorCommand,
    },
}

#[derive(Subcommand)]
enum SeafloorCommand {
    /// Write the scenario's seafloor as the planner uses it (default: the synthetic one; a grid
    /// file cut to the mission window, in metres) as an ESRI ASCII grid (.asc) or a GeoTIFF
    /// (.tif, .tiff).
    Export {
        /// Scenario file; the embedded default when absent.
        scenario: Option<PathBuf>,
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        #[arg(short, long, default_value = "seafloor.asc")]
        out: PathBuf,
    },
    /// Describe a grid file: size, extent, CRS and where it comes from, depth range, NODATA and
    /// land, suggested origin.
    Info {
        /// Grid file (.asc, .tif, .tiff).
        file: PathBuf,
        /// Sign convention of the values: elevation (negative below sea level) or depth.
        #[arg(long, default_value = "elevation", value_parser = ["elevation", "depth"])]
        values: String,
        /// The file's CRS, "EPSG:<code>" (as seafloor.crs): for a grid without one, or to check
        /// a file's own.
        #[arg(long)]
        crs: Option<String>,
    },
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

fn run(cli: Cli) -> Result<ExitCode> {
    match cli.command {
        Command::Init { path, force } => {
            if path.exists() && !force {
                bail!("{} exists; use --force to overwrite it", path.display());
            }
            shoal::output::write_atomic(&path, scenario::default_toml().as_bytes())?;
            println!("wrote {}", path.display());
            Ok(ExitCode::SUCCESS)
        }
        Command::Plan {
            scenario,
            mut set,
            seafloor,
            out,
            plot: _,
            no_plot,
        } => {
            if let Some(f) = seafloor {
                set.push(format!("seafloor.file={}", toml_string(&f)));
            }
            let (s, source) = load_scenario(scenario.as_deref(), &set)?;
            plan(&s, source, set, scenario.as_deref(), &out, !no_plot)
        }
        Command::Plot {
            plan,
            out,
            seafloor,
        } => {
            let p = shoal::output::read_plan(&plan)?;
            let floor = shoal::check::load_floor(&p, seafloor.as_deref())
                .with_context(|| format!("loading the seafloor of {}", plan.display()))?;
            let dir = out.unwrap_or_else(|| base_dir(Some(&plan)).join("figures"));
            plot(&p, &floor, &dir, true).with_context(|| format!("plotting {}", plan.display()))?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Check { plan, seafloor } => {
            let p = shoal::output::read_plan(&plan)?;
            let floor = shoal::check::load_floor(&p, seafloor.as_deref())
                .with_context(|| format!("loading the seafloor of {}", plan.display()))?;
            let report = shoal::check::check_plan(&p, &floor);
            print!("{}", report.table());
            if report.passed() {
                println!("{}: every constraint holds", plan.display());
                Ok(ExitCode::SUCCESS)
            } else {
                println!("{}: VIOLATED (see FAIL rows)", plan.display());
                Ok(ExitCode::from(1))
            }
        }
        Command::View {
            plan,
            out,
            seafloor,
        } => view(&plan, seafloor.as_deref(), &out),
        Command::Seafloor {
            command: SeafloorCommand::Export { scenario, set, out },
        } => {
            let (s, _) = load_scenario(scenario.as_deref(), &set)?;
            let (floor, source) =
                shoal::planner::scenario_floor(&s, base_dir(scenario.as_deref()))?;
            source
                .warnings
                .iter()
                .for_each(|w| eprintln!("warning: {w}"));
            shoal::output::write_floor(&floor, &source, &out)?;
            let (lo, hi) = floor.z_range();
            println!(
                "wrote {} ({} × {} nodes, {} m cells, z from {lo:.1} to {hi:.1} m)",
                out.display(),
                floor.nx(),
                floor.ny(),
                floor.dx()
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Seafloor {
            command: SeafloorCommand::Info { file, values, crs },
        } => {
            let values = match values.as_str() {
                "depth" => shoal::seafloor::Values::Depth,
                _ => shoal::seafloor::Values::Elevation,
            };
            let info = shoal::seafloor::info_with_crs(&file, values, crs.as_deref())?;
            print!("{info}");
            info.warnings.iter().for_each(|w| eprintln!("warning: {w}"));
            Ok(ExitCode::SUCCESS)
        }
    }
}

fn view(plan: &Path, seafloor: Option<&Path>, out: &Path) -> Result<ExitCode> {
    let p = shoal::output::read_plan(plan)?;
    let floor = shoal::check::load_floor(&p, seafloor)
        .with_context(|| format!("loading the seafloor of {}", plan.display()))?;
    shoal::viewer::write_html(&p, &floor, out)?;
    let size = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
    println!(
        "wrote {} ({:.1} MB): open it in a browser",
        out.display(),
        size as f64 / 1e6
    );
    Ok(ExitCode::SUCCESS)
}

/// Draw every figure of `plan` into `dir`; one line per figure when `each`, else one in all.
fn plot(
    plan: &shoal::plan::Plan,
    floor: &shoal::seafloor::Seafloor,
    dir: &Path,
    each: bool,
) -> Result<()> {
    let start = std::time::Instant::now();
    let files = shoal::figures::write_all_with_progress(plan, floor, dir, |done| {
        if each {
            println!("  {:<13} {:>6.3} s", done.name, done.seconds);
        }
    })?;
    println!(
        "wrote {} figure files (PNG and SVG) in {} in {:.2} s",
        files.len(),
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}

fn toml_string(p: &Path) -> String {
    format!("{:?}", p.to_string_lossy())
}

fn base_dir(scenario: Option<&Path>) -> &Path {
    scenario.and_then(|p| p.parent()).unwrap_or(Path::new(""))
}

fn load_scenario(path: Option<&Path>, set: &[String]) -> Result<(Scenario, String)> {
    Ok(match path {
        Some(p) => (scenario::load(p, set)?, p.display().to_string()),
        None => (scenario::default_with(set)?, "embedded default".to_string()),
    })
}

fn plan(
    s: &Scenario,
    source: String,
    overrides: Vec<String>,
    scenario_path: Option<&Path>,
    out: &Path,
    figures: bool,
) -> Result<ExitCode> {
    let (floor, floor_source) = shoal::planner::scenario_floor(s, base_dir(scenario_path))?;
    floor_source
        .warnings
        .iter()
        .for_each(|w| eprintln!("warning: {w}"));
    let input = shoal::planner::PlanInput {
        scenario: s,
        floor: &floor,
        scenario_source: source,
        overrides,
        seafloor_source: floor_source,
    };
    eprintln!(
        "planning {} window(s): N = {} AUVs, K = {} steps of δ = {} s, seed {}",
        s.windows, s.team.auvs, s.horizon.steps, s.horizon.dt, s.seed
    );
    let plan = shoal::planner::plan_with_progress(&input, |event| match event {
        Progress::Step1 { window, stage } => eprintln!(
            "  window {window}: step 1 (P2) {} after {} SCP iterations in {:.3} s",
            stage.status, stage.iterations, stage.solve_time_s
        ),
        Progress::Step2 { window, graph } => eprintln!(
            "  window {window}: step 2 (P3 + P4) {} graph in {:.4} s",
            if graph.exact { "exact" } else { "heuristic" },
            graph.solve_time_s
        ),
        Progress::Step3 {
            window,
            stage,
            los_rounds,
            out_of_band,
        } => eprintln!(
            "  window {window}: step 3 (P5) {} after {} SCP iterations, {los_rounds} line-of-sight \
             round(s), {out_of_band} link-step(s) outside their band, in {:.3} s",
            stage.status, stage.iterations, stage.solve_time_s
        ),
    })?;
    let plan_path = out.join("plan.json");
    shoal::output::write_plan(&plan, &plan_path)?;
    let csvs = shoal::output::write_csvs(&plan, out)?;
    println!("{}", shoal::report::summary_table(&plan));
    println!(
        "wrote {} and {} CSV files in {}",
        plan_path.display(),
        csvs.len(),
        out.display()
    );
    if figures {
        self::plot(&plan, &floor, &out.join("figures"), false)?;
    }
    let report = shoal::check::check_plan(&plan, &floor);
    print!("{}", report.table());
    if report.passed() {
        println!("check: every constraint holds");
        Ok(ExitCode::SUCCESS)
    } else {
        println!("check: VIOLATED (see FAIL rows)");
        Ok(ExitCode::from(1))
    }
}
