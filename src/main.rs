//! The `shoal` command: a thin layer over the library.

use anyhow::{bail, Context, Result};
use clap::{Parser, Subcommand};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use shoal::report::{printable, printable_lines};
use shoal::scenario::{self, Scenario};
use shoal::Progress;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

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

/// The planners of `shoal plan --method`.
#[derive(Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Method {
    /// Algorithm 1: Steps 1–3 by sequential convex programming.
    Mpc,
    /// The paper's RRT-like sampling baseline (Section V).
    RrtLike,
}

impl Method {
    fn study(self) -> shoal::compare::Method {
        match self {
            Method::Mpc => shoal::compare::Method::Mpc,
            Method::RrtLike => shoal::compare::Method::RrtLike,
        }
    }
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
        /// Seafloor grid (ESRI ASCII .asc, GeoTIFF .tif; NetCDF .nc, BAG, XYZ... with the gdal
        /// feature); same as --set seafloor.file=PATH.
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
        /// Print no progress and no tables: only warnings and errors (on stderr).
        #[arg(short, long)]
        quiet: bool,
        /// Print a JSON summary on stdout instead of the tables (for scripts): the files, the
        /// check's verdict, the warnings, the mission's and each window's metrics.
        #[arg(long)]
        json: bool,
        /// The planner: "mpc", Algorithm 1 (Steps 1–3 by sequential convex programming), or
        /// "rrt-like", the paper's sampling baseline of Section V (settings in [sampling]).
        #[arg(long, value_enum, default_value_t = Method::Mpc)]
        method: Method,
        /// Make the plan from another planner's waypoints instead (a shoal-waypoints/1 file,
        /// e.g. from scripts/ompl_rrt_star.py), for the same scenario; checked like any plan.
        #[arg(long, value_name = "FILE", conflicts_with = "method")]
        waypoints: Option<PathBuf>,
        /// Also fly the plan once it passes its check (as `shoal simulate` does, at its
        /// default settings and the plan's seed): OUT/sim.json and the simulation's figures
        /// join the plan's outputs, and the flown figures are printed beside the planned ones.
        #[arg(long)]
        fly: bool,
    },
    /// Verify every constraint of a plan from the plan file and the seafloor alone.
    Check {
        /// The plan file (plan.json) to check.
        plan: PathBuf,
        /// Check against this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
        /// Hold the plan to the limits of this scenario file (speeds, turn rate, clearances,
        /// acoustic ranges) instead of those the plan records; its team size, steps, step length
        /// and windows must be the plan's.
        #[arg(long, value_name = "FILE")]
        scenario: Option<PathBuf>,
        /// Override one limit, e.g. --set auv.max_speed=1.5 (repeatable): over --scenario, or
        /// over the scenario the plan records.
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
    },
    /// Write one self-contained HTML file showing a plan in 3D (opens offline in a browser).
    View {
        /// The plan file (plan.json) to show.
        plan: PathBuf,
        /// The HTML file to write.
        #[arg(short, long, default_value = "mission.html")]
        out: PathBuf,
        /// Show the plan on this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
        /// Also show this simulation of the plan (sim.json of `shoal simulate`): each AUV's
        /// executed track and the chain's factor-graph estimate.
        #[arg(long)]
        sim: Option<PathBuf>,
    },
    /// Draw the figures of a plan (PNG and SVG): floor, paths, links, time series, metrics.
    Plot {
        /// The plan file (plan.json) to draw.
        plan: PathBuf,
        /// Output directory; default: `figures` beside the plan file.
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Draw over this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
    },
    /// Write a plan's positions as CSV, one row per vehicle and step of the final plan, in the
    /// planner's frame and, when the floor has a CRS, in latitude/longitude (geographic grid) or
    /// easting/northing (projected grid).
    Export {
        /// The plan file (plan.json).
        plan: PathBuf,
        /// The CSV file to write.
        #[arg(value_name = "OUT.csv", required_unless_present = "csv")]
        out: Option<PathBuf>,
        /// The CSV file to write (the same as OUT.csv, the older spelling).
        #[arg(long, value_name = "OUT.csv", conflicts_with = "out")]
        csv: Option<PathBuf>,
    },
    /// Fly a plan with 6-DoF REMUS 100 models in the scenario's current, measure what the
    /// vehicles would (DVL, compass, depth, GPS, acoustic ranges), and estimate every AUV's
    /// position with and without the acoustic chain; writes sim.json and prints the errors.
    Simulate {
        /// The plan file (plan.json) to fly.
        plan: PathBuf,
        /// Override a [current], [navigation] or [simulation] key, e.g. --set
        /// current.velocity=[0.3,0] (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Seed of the simulation's draws (sensor errors, noise, packets); default: the plan's
        /// seed.
        #[arg(long)]
        seed: Option<u64>,
        /// Monte Carlo: fly the plan RUNS times (seeds SEED, SEED+1, …) and print each metric's
        /// mean and spread; sim.json holds the first run and the runs' summary.
        #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=10000))]
        runs: u64,
        /// The file to write; default: sim.json beside the plan.
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// Fly over this seafloor grid instead of the one the plan names.
        #[arg(long)]
        seafloor: Option<PathBuf>,
        /// Do not draw the figures (sim-error, sim-tracks) into `figures` beside sim.json.
        #[arg(long)]
        no_plot: bool,
        /// Fly a plan that fails its check (`shoal check`) all the same, with a warning;
        /// sim.json then lists the failing families (check_failures). Without it such a plan
        /// is refused (exit 1).
        #[arg(long)]
        unchecked: bool,
    },
    /// Plan the same scenarios with the MPC and the paper's RRT-like baseline (team sizes ×
    /// seeds × scenarios), check every plan, and write runs.csv, summary.md and the figure
    /// compare.png/.svg: wall time, objective terms, constraint margins, explored area.
    Compare {
        /// Scenario files (TOML), one per floor; "default" is the embedded default. Default:
        /// the embedded default alone.
        scenarios: Vec<String>,
        /// Override one key of every scenario (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// Team sizes N.
        #[arg(long, value_delimiter = ',', default_value = "1,3,5")]
        auvs: Vec<usize>,
        /// Seeds: a list (1,4,7) or a range (1-10).
        #[arg(long, default_value = "1-10")]
        seeds: String,
        /// The planners compared.
        #[arg(
            long,
            value_enum,
            value_delimiter = ',',
            default_value = "mpc,rrt-like"
        )]
        methods: Vec<Method>,
        /// Output directory.
        #[arg(short, long, default_value = "compare")]
        out: PathBuf,
        /// Also write every run's plan.json into OUT/plans.
        #[arg(long)]
        keep_plans: bool,
        /// Also compare other planners' paths: waypoints files SCENARIO-nN-sSEED.json in this
        /// directory (e.g. from scripts/ompl_compare.sh), one more row for each that exists.
        #[arg(long, value_name = "DIR")]
        waypoints: Option<PathBuf>,
        /// Do not draw the figure.
        #[arg(long)]
        no_plot: bool,
    },
    /// Run a study: every combination of its axes (seeds, team sizes, any scenario key) on
    /// every core, or one shard of it (a Slurm job array's task); one row per run in
    /// OUT/runs.csv (or OUT/shard-I-of-N.csv). `shoal sweep collect OUT` merges the shards.
    #[command(args_conflicts_with_subcommands = true)]
    Sweep {
        #[command(subcommand)]
        command: Option<SweepCommand>,
        /// The study file (TOML: scenario, method, [set], [axes]; see docs/sweep.md).
        study: Option<PathBuf>,
        /// Output directory.
        #[arg(short, long, default_value = "sweep")]
        out: PathBuf,
        /// Make only the I-th (0-based) of N parts of the runs (dealt in a fixed pseudo-random
        /// order, sizes within one), into OUT/shard-I-of-N.csv.
        /// Default: SLURM_ARRAY_TASK_ID/SLURM_ARRAY_TASK_COUNT, or JOB_COMPLETION_INDEX/
        /// SHOAL_SHARDS, when set; otherwise every run.
        #[arg(long, value_name = "I/N")]
        shard: Option<String>,
        /// Skip the runs the table already has (after an interruption).
        #[arg(long)]
        resume: bool,
        /// Print no progress bar.
        #[arg(short, long)]
        quiet: bool,
    },
    /// Seafloor tools.
    Seafloor {
        #[command(subcommand)]
        command: SeafloorCommand,
    },
}

#[derive(Subcommand)]
enum SweepCommand {
    /// Merge the shard tables of a sweep's directory into DIR/runs.csv, sorted by run.
    Collect {
        /// The sweep's output directory.
        dir: PathBuf,
    },
    /// Plot a sweep's table: each measure against a swept key, the median over the seeds as a
    /// line and their spread as bands (quartiles, min–max), one line per value of the other
    /// swept keys; OUT/sweep-KEY.png and .svg per key (see docs/sweep.md).
    Plot {
        /// The table (runs.csv) or the sweep's directory.
        table: PathBuf,
        /// Output directory (default: the table's).
        #[arg(short, long)]
        out: Option<PathBuf>,
        /// The swept key on x (default: every swept key but seed, one figure each).
        #[arg(long, value_name = "KEY")]
        x: Option<String>,
        /// The measures, one panel each (default: wall_s, p2_objective, explored_km2,
        /// mean_height_m, chain_fraction, passed_fraction and, when flown, sim_chain_end_m and
        /// sim_dead_reckoning_end_m).
        #[arg(long, value_name = "METRIC", num_args = 1..)]
        y: Vec<String>,
    },
}

#[derive(Subcommand)]
enum SeafloorCommand {
    /// Write the scenario's seafloor as the planner uses it (default: the synthetic one; a grid
    /// file cut to the mission window, in metres), or a grid file in its own CRS (--from), as an
    /// ESRI ASCII grid (.asc, with a .prj sidecar when the CRS is known) or a GeoTIFF (.tif,
    /// .tiff); optionally cropped to a region and resampled (bilinear; NODATA and land never
    /// shrink). Values are written as elevations.
    Export {
        /// Scenario file; the embedded default when absent.
        scenario: Option<PathBuf>,
        /// Override one scenario key, e.g. --set seed=3 (repeatable).
        #[arg(long = "set", value_name = "KEY=VALUE")]
        set: Vec<String>,
        /// The grid file to write: .asc (ESRI ASCII) or .tif/.tiff (GeoTIFF).
        #[arg(short, long, default_value = "seafloor.asc")]
        out: PathBuf,
        /// Export this grid file (in its own CRS) instead of the scenario's floor.
        #[arg(long, value_name = "FILE", conflicts_with_all = ["scenario", "set"])]
        from: Option<PathBuf>,
        /// With --from: sign convention of the file's values.
        #[arg(long, requires = "from", value_parser = ["elevation", "depth"])]
        values: Option<String>,
        /// With --from: the file's CRS, "EPSG:<code>" (as seafloor.crs).
        #[arg(long, requires = "from")]
        crs: Option<String>,
        /// Crop to this rectangle, in the grid's own units (with --from: metres, or degrees of
        /// longitude and latitude; else the planner's frame, metres).
        #[arg(long, value_name = "XMIN,YMIN,XMAX,YMAX", value_parser = four_numbers,
              allow_hyphen_values = true)]
        region: Option<[f64; 4]>,
        /// Crop to this latitude/longitude box (degrees; a geographic grid, or a scenario floor
        /// from one).
        #[arg(long, value_name = "SOUTH,WEST,NORTH,EAST", value_parser = four_numbers,
              conflicts_with = "region", allow_hyphen_values = true)]
        region_latlon: Option<[f64; 4]>,
        /// Resample onto cells of this size, metres (for a geographic grid, turned into degrees
        /// at the region's centre latitude).
        #[arg(long, value_name = "METRES")]
        cell: Option<f64>,
    },
    /// Describe a grid file: size, extent, CRS and where it comes from, depth range, NODATA and
    /// land, suggested origin.
    Info {
        /// Grid file (.asc, .tif, .tiff; with the gdal feature .nc, .grd, .bag, .xyz, ...).
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
    // SAFETY: setting a signal's disposition to the default before any thread starts.
    #[cfg(unix)]
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    match run(Cli::parse()) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {}", printable_lines(&error_chain(&e)));
            ExitCode::from(2)
        }
    }
}

/// The error and its causes joined by ": ", leaving out a cause whose text the message already
/// ends with (the library's messages quote their source, e.g. "x.asc: No such file or
/// directory", and also name it as the source).
fn error_chain(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if out.ends_with(&text) {
            continue;
        }
        if !out.is_empty() {
            out.push_str(": ");
        }
        out.push_str(&text);
    }
    out
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
            quiet,
            json,
            method,
            waypoints,
            fly,
        } => {
            let flag = seafloor.map(|f| {
                let text = format!("seafloor.file={}", toml_string(&f));
                set.push(text.clone());
                (text, format!("--seafloor {}", f.display()))
            });
            let (s, source) = match load_scenario(scenario.as_deref(), &set) {
                Ok(loaded) => loaded,
                Err(e) => match (e.downcast::<scenario::ScenarioError>(), &flag) {
                    // an error in the override made of --seafloor names the flag given
                    (Ok(e), Some((text, name))) => return Err(e.from_flag(text, name).into()),
                    (Ok(e), None) => return Err(e.into()),
                    (Err(e), _) => return Err(e),
                },
            };
            let how = How {
                figures: !no_plot,
                quiet,
                json,
                method,
                waypoints,
                fly,
            };
            plan(&s, source, set, scenario.as_deref(), &out, how)
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
            plot(&p, &floor, &dir, &dir, true, false)
                .with_context(|| format!("plotting {}", plan.display()))?;
            Ok(ExitCode::SUCCESS)
        }
        Command::Check {
            plan,
            seafloor,
            scenario,
            set,
        } => check(&plan, seafloor.as_deref(), scenario.as_deref(), &set),
        Command::View {
            plan,
            out,
            seafloor,
            sim,
        } => view(&plan, seafloor.as_deref(), sim.as_deref(), &out),
        Command::Simulate {
            plan,
            set,
            seed,
            runs,
            out,
            seafloor,
            no_plot,
            unchecked,
        } => simulate(
            &plan,
            &set,
            seed,
            runs as usize,
            out,
            seafloor.as_deref(),
            !no_plot,
            unchecked,
        ),
        Command::Compare {
            scenarios,
            set,
            auvs,
            seeds,
            methods,
            out,
            keep_plans,
            waypoints,
            no_plot,
        } => {
            let seeds = shoal::compare::parse_seeds(&seeds)?;
            let study = shoal::compare::Study {
                bases: compare_bases(&scenarios, &set)?,
                methods: methods.iter().map(|m| m.study()).collect(),
                auvs,
                seeds,
                waypoints,
            };
            compare(&study, &out, keep_plans, !no_plot)
        }
        Command::Sweep {
            command: Some(SweepCommand::Collect { dir }),
            ..
        } => {
            let (table, rows) = shoal::sweep::collect(&dir)?;
            println!(
                "wrote {} ({rows} runs) and {}",
                table.display(),
                shoal::sweep::parquet_path(&dir).display()
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Sweep {
            command: Some(SweepCommand::Plot { table, out, x, y }),
            ..
        } => {
            let files = shoal::figures::write_sweep(&table, out.as_deref(), x.as_deref(), &y)?;
            for f in &files {
                println!("wrote {}", f.display());
            }
            Ok(ExitCode::SUCCESS)
        }
        Command::Sweep {
            command: None,
            study,
            out,
            shard,
            resume,
            quiet,
        } => {
            let study = study.context("give a study file (or `shoal sweep collect DIR`)")?;
            sweep(&study, out, shard.as_deref(), resume, quiet)
        }
        Command::Export { plan, out, csv } => {
            let csv = out.or(csv).expect("clap requires OUT.csv or --csv");
            let p = shoal::output::read_plan(&plan)?;
            let (rows, georef) = shoal::positions::write_csv(&p, &csv)
                .with_context(|| format!("exporting the positions of {}", plan.display()))?;
            println!(
                "wrote {} ({rows} rows: positions in the planner's frame and {})",
                csv.display(),
                georef.describe()
            );
            Ok(ExitCode::SUCCESS)
        }
        Command::Seafloor {
            command:
                SeafloorCommand::Export {
                    scenario,
                    set,
                    out,
                    from,
                    values,
                    crs,
                    region,
                    region_latlon,
                    cell,
                },
        } => {
            let notes = match from {
                Some(file) => {
                    use shoal::seafloor::{CropRegion, ExportOptions};
                    let region = match (region, region_latlon) {
                        (Some(r), _) => CropRegion::Native(r),
                        (_, Some(r)) => CropRegion::LatLon(r),
                        _ => CropRegion::All,
                    };
                    let opts = ExportOptions {
                        values: values_of(values.as_deref()),
                        crs,
                        region,
                        cell,
                    };
                    let g = shoal::seafloor::export_grid(&file, &opts)?;
                    g.warnings
                        .iter()
                        .for_each(|w| eprintln!("warning: {}", printable(w)));
                    let notes = shoal::output::write_grid(&g.floor, &g.crs, None, &out)?;
                    let (lo, hi) = g.floor.z_range();
                    println!(
                        "wrote {} ({} × {} nodes from ({}, {}), cells of {} × {}, CRS {} ({}), z \
                         from {lo:.1} to {hi:.1} m)",
                        out.display(),
                        g.floor.nx(),
                        g.floor.ny(),
                        g.floor.x0(),
                        g.floor.y0(),
                        g.floor.dx(),
                        g.floor.dy(),
                        printable(&g.crs.to_string()),
                        printable(&g.crs_source.to_string())
                    );
                    notes
                }
                None => {
                    let (s, _) = load_scenario(scenario.as_deref(), &set)?;
                    let (mut floor, source) =
                        shoal::mission::scenario_floor(&s, base_dir(scenario.as_deref()))?;
                    source
                        .warnings
                        .iter()
                        .for_each(|w| eprintln!("warning: {}", printable(w)));
                    let region = match (region, region_latlon, source.origin) {
                        (Some(r), _, _) => Some(r),
                        (_, Some(b), Some([lat, lon])) => {
                            let frame = shoal::seafloor::geo::LocalFrame::new(lat, lon)?;
                            Some(
                                shoal::seafloor::latlon_box_in_frame(&frame, b).with_context(
                                    || "--region-latlon: the box reaches beyond the local frame",
                                )?,
                            )
                        }
                        (_, Some(_), None) => bail!(
                            "--region-latlon: the scenario's floor is not from a geographic grid \
                             (its CRS is {}); give --region in its own coordinates, metres",
                            source.crs
                        ),
                        _ => None,
                    };
                    if region.is_some() || cell.is_some() {
                        floor = shoal::seafloor::crop_floor(
                            &floor,
                            region,
                            cell,
                            "the scenario's floor (planner's frame, metres)",
                        )?;
                    }
                    let notes = shoal::output::write_floor(&floor, &source, &out)?;
                    let (lo, hi) = floor.z_range();
                    println!(
                        "wrote {} ({} × {} nodes, {} m cells, z from {lo:.1} to {hi:.1} m)",
                        out.display(),
                        floor.nx(),
                        floor.ny(),
                        floor.dx()
                    );
                    notes
                }
            };
            notes.iter().for_each(|n| println!("{n}"));
            Ok(ExitCode::SUCCESS)
        }
        Command::Seafloor {
            command: SeafloorCommand::Info { file, values, crs },
        } => {
            let info =
                shoal::seafloor::info_with_crs(&file, values_of(Some(&values)), crs.as_deref())?;
            print!("{info}");
            info.warnings
                .iter()
                .for_each(|w| eprintln!("warning: {}", printable(w)));
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// `shoal check`: the plan against its floor, with the limits it records or those the user
/// states (`--scenario`, `--set`).
fn check(
    plan: &Path,
    seafloor: Option<&Path>,
    scenario: Option<&Path>,
    set: &[String],
) -> Result<ExitCode> {
    let p = shoal::output::read_plan(plan)?;
    let floor = shoal::check::load_floor(&p, seafloor)
        .with_context(|| format!("loading the seafloor of {}", plan.display()))?;
    let report = if scenario.is_none() && set.is_empty() {
        shoal::check::check_plan(&p, &floor)
    } else {
        let stated = match scenario {
            Some(file) => scenario::load(file, set)?,
            None => scenario::with_overrides(&p.scenario, &plan.display().to_string(), set)?,
        };
        let file = scenario.map(|f| f.display().to_string());
        let source = shoal::check::limits_source(file.as_deref(), set);
        shoal::check::check_plan_against(&p, &floor, &stated, &source)?
    };
    let name = plan.display().to_string();
    let name = printable(&name);
    for line in report.limits.lines() {
        println!("{}", printable(&line));
    }
    print!("{}", report.table());
    for w in &p.warnings {
        eprintln!("warning: {}", printable(w));
    }
    if report.passed() {
        let unconverged = p.unconverged_stages();
        if unconverged == 0 {
            println!("{name}: every constraint holds");
        } else {
            println!(
                "{name}: every constraint holds, but {unconverged} stage(s) did not converge: \
                 feasible, not optimal"
            );
        }
        Ok(ExitCode::SUCCESS)
    } else {
        println!("{name}: VIOLATED (see FAIL rows)");
        Ok(ExitCode::from(1))
    }
}

fn values_of(v: Option<&str>) -> shoal::seafloor::Values {
    match v {
        Some("depth") => shoal::seafloor::Values::Depth,
        _ => shoal::seafloor::Values::Elevation,
    }
}

/// "a,b,c,d": four numbers.
fn four_numbers(text: &str) -> Result<[f64; 4], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let nums: Vec<f64> = parts.iter().filter_map(|p| p.parse().ok()).collect();
    match <[f64; 4]>::try_from(nums) {
        Ok(v) if parts.len() == 4 && v.iter().all(|x| x.is_finite()) => Ok(v),
        _ => Err(format!(
            "{text:?}: expected four finite numbers separated by commas"
        )),
    }
}

/// Raised by Ctrl-C during `shoal simulate`: the library stops between samples and estimates.
static SIM_CANCEL: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Whether `shoal simulate`'s outputs have begun to move into place.
static SIM_GATE: shoal::output_set::CommitGate = shoal::output_set::CommitGate::new();

/// Write sim.json (as `file`) and, for a finished record, its figures into `set`, and move
/// the set into place: a new sim.json never stands beside an earlier flight's figures (an
/// interrupted record has none, and the earlier ones go).
fn write_sim_set(
    p: &shoal::Plan,
    floor: &shoal::Seafloor,
    record: &shoal::sim::SimRecord,
    set: shoal::output_set::OutputSet,
    file: &str,
    figures: bool,
) -> Result<()> {
    shoal::sim::write(record, &set.dir().join(file))?;
    if figures && record.incomplete.is_none() {
        let dir = set.dir().join("figures");
        shoal::figures::write_sim(p, floor, record, &dir)
            .with_context(|| format!("drawing the figures of {file}"))?;
    }
    if !SIM_GATE.enter() {
        loop {
            std::thread::park();
        }
    }
    set.commit(None)?;
    Ok(())
}

#[allow(clippy::too_many_arguments)]
fn simulate(
    plan: &Path,
    set: &[String],
    seed: Option<u64>,
    runs: usize,
    out: Option<PathBuf>,
    seafloor: Option<&Path>,
    figures: bool,
    unchecked: bool,
) -> Result<ExitCode> {
    use shoal::sim::{Gate, Progress, SimError};
    use std::sync::atomic::Ordering;
    let p = shoal::output::read_plan(plan)?;
    let floor = shoal::check::load_floor(&p, seafloor)
        .with_context(|| format!("loading the seafloor of {}", plan.display()))?;
    let name = plan.display().to_string();
    let p = shoal::sim::run::with_settings(&p, &name, set)?;
    let seed = seed.unwrap_or(p.scenario.seed);
    let out = out.unwrap_or_else(|| base_dir(Some(plan)).join("sim.json"));
    // sim.json and its figures are one output set: staged beside sim.json, moved in whole
    let file = out
        .file_name()
        .and_then(|f| f.to_str())
        .with_context(|| format!("{}: not a file name", out.display()))?
        .to_string();
    let set = shoal::output_set::OutputSet::begin_kind(
        base_dir(Some(&out)),
        shoal::output_set::Kind::Simulation(file.clone()),
    )?;
    let staging = set.dir().to_path_buf();
    ctrlc::set_handler(move || {
        if SIM_CANCEL.swap(true, Ordering::SeqCst) {
            if SIM_GATE.interrupt() {
                let _ = std::fs::remove_dir_all(&staging);
                eprintln!("interrupted again: stopping now, writing nothing");
                std::process::exit(130);
            }
            eprintln!("interrupt: the outputs are being moved into place; that ends first");
            return;
        }
        eprintln!(
            "interrupted: stopping after the runs that have finished (Ctrl-C again to stop at \
             once, writing nothing)"
        );
    })
    .context("installing the Ctrl-C handler")?;
    // on a terminal: a bar of the runs with their ETA (a spinner for one run); hidden otherwise
    let bar = ProgressBar::with_draw_target(Some(runs as u64), ProgressDrawTarget::stderr());
    let template = match runs {
        1 => "{spinner} [{elapsed_precise}] {msg}",
        _ => "{bar:30} {pos}/{len} runs, {elapsed_precise} elapsed, ETA {eta} {msg}",
    };
    bar.set_style(ProgressStyle::with_template(template).expect("a valid template"));
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    let say = |text: String| match bar.is_hidden() {
        true => eprintln!("{text}"),
        false => bar.println(text),
    };
    let options = shoal::sim::Options {
        seed,
        runs,
        gate: if unchecked {
            Gate::Unchecked
        } else {
            Gate::Check
        },
        cancel: Some(&SIM_CANCEL),
        max_iterations: shoal::sim::run::FACTOR_GRAPH_ITERATIONS,
    };
    let start = std::time::Instant::now();
    let flown = shoal::sim::fly_plan(&p, &name, &floor, &options, &mut |event| match event {
        Progress::Unchecked { failing } => say(format!(
            "WARNING: {name} fails its check ({}): flying it anyway (--unchecked); what it \
             shows is of a plan the team cannot fly as planned, and sim.json says so \
             (check_failures)",
            failing.join(", ")
        )),
        Progress::Counted(c) => say(format!(
            "simulating {name}: {} AUV(s) over {} s, {} samples of {} RK4 steps each per AUV \
             and flight, {} acoustic epochs; {} run(s)",
            c.auvs, c.duration, c.samples, c.substeps, c.epochs, c.runs
        )),
        Progress::Flying(what) => bar.set_message(format!("flying {what}")),
        Progress::Estimating { run } => bar.set_message(match runs {
            1 => "estimating".to_string(),
            _ => format!("estimating run {}", run + 1),
        }),
        Progress::RunDone { finished, .. } => bar.set_position(finished as u64),
    });
    bar.finish_and_clear();
    let record = match flown {
        Ok(record) => record,
        Err(SimError::Interrupted) => {
            eprintln!(
                "interrupted before the first run finished: nothing was written (any earlier {} \
                 is left as it was)",
                out.display()
            );
            return Ok(ExitCode::from(130));
        }
        Err(e @ (SimError::FailsCheck { .. } | SimError::Malformed { .. })) => {
            eprintln!("error: {e}");
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(e.into()),
    };
    match write_sim_set(&p, &floor, &record, set, &file, figures) {
        Err(_) if SIM_GATE.interrupted() => loop {
            std::thread::park();
        },
        written => written?,
    }
    print!("{}", printable_lines(&shoal::sim::summary::table(&record)));
    if !record.failed_estimates.is_empty() {
        let each: Vec<String> = record
            .failed_estimates
            .iter()
            .map(|f| {
                format!(
                    "{} {} {}: {}",
                    f.flown,
                    f.policy.name(),
                    f.estimator,
                    f.brief()
                )
            })
            .collect();
        eprintln!(
            "warning: {} estimate(s) failed ({}); the flight and the other estimates are in {}",
            each.len(),
            each.join("; "),
            out.display()
        );
    }
    if figures && record.incomplete.is_none() {
        println!(
            "drew {} figure files in {}",
            2 * shoal::figures::SIM_FIGURES.len(),
            base_dir(Some(&out)).join("figures").display()
        );
    }
    let finished = record.incomplete.as_ref().map_or(runs, |i| i.runs_finished);
    println!(
        "wrote {} ({} run{}{}, seed {seed}, {:.1} s)",
        out.display(),
        finished,
        if finished == 1 { "" } else { "s" },
        match finished < runs {
            true => format!(" of {runs}: interrupted, marked incomplete"),
            false => String::new(),
        },
        start.elapsed().as_secs_f64()
    );
    Ok(match record.incomplete {
        Some(_) => ExitCode::from(130),
        None => ExitCode::SUCCESS,
    })
}

fn view(plan: &Path, seafloor: Option<&Path>, sim: Option<&Path>, out: &Path) -> Result<ExitCode> {
    let p = shoal::output::read_plan(plan)?;
    let floor = shoal::check::load_floor(&p, seafloor)
        .with_context(|| format!("loading the seafloor of {}", plan.display()))?;
    let record = sim.map(shoal::sim::read).transpose()?;
    shoal::viewer::write_html_with_sim(&p, &floor, record.as_ref(), out).map_err(|e| {
        match (&e, sim) {
            (shoal::viewer::ViewerError::Sim(_), Some(path)) => anyhow::Error::new(e).context(
                format!("{} does not fit {}", path.display(), plan.display()),
            ),
            _ => e.into(),
        }
    })?;
    let size = std::fs::metadata(out).map(|m| m.len()).unwrap_or(0);
    println!(
        "wrote {} ({:.1} MB): open it in a browser",
        out.display(),
        size as f64 / 1e6
    );
    Ok(ExitCode::SUCCESS)
}

/// Draw every figure of `plan` into `dir`, which is `shown` once in place (the staging
/// directory of `shoal plan`); on stderr, one line per figure with its time when `each`, else
/// one in all.
fn plot(
    plan: &shoal::plan::Plan,
    floor: &shoal::seafloor::Seafloor,
    dir: &Path,
    shown: &Path,
    each: bool,
    quiet: bool,
) -> Result<()> {
    let start = std::time::Instant::now();
    let files = shoal::figures::write_all_with_progress(plan, floor, dir, |done| {
        if each && !quiet {
            eprintln!("  {:<13} {:>6.3} s", done.name, done.seconds);
        }
    })?;
    if quiet {
        return Ok(());
    }
    eprintln!(
        "drew {} figure files (PNG and SVG) for {} in {:.2} s",
        files.len(),
        shown.display(),
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

/// How `shoal plan` reports.
struct How {
    /// Draw the figures.
    figures: bool,
    /// No progress, no tables.
    quiet: bool,
    /// A JSON summary on stdout instead of the tables.
    json: bool,
    /// The planner.
    method: Method,
    /// Another planner's waypoints file, instead of planning.
    waypoints: Option<PathBuf>,
    /// Fly the plan once checked (`--fly`).
    fly: bool,
}

/// Progress on stderr: a line per step, and on a terminal a spinner with the SCP iteration,
/// its merit and trust radius (indicatif); nothing when quiet.
struct Report {
    bar: Option<ProgressBar>,
}

impl Report {
    fn new(quiet: bool) -> Report {
        let bar = (!quiet).then(|| {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            bar.set_style(
                ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
                    .expect("a valid template"),
            );
            bar.enable_steady_tick(std::time::Duration::from_millis(120));
            bar
        });
        Report { bar }
    }

    /// A line above the spinner (or on stderr when it is hidden: not a terminal).
    fn line(&self, text: String) {
        match &self.bar {
            Some(b) if !b.is_hidden() => b.println(text),
            Some(_) => eprintln!("{text}"),
            None => {}
        }
    }

    fn event(&self, event: Progress) {
        match event {
            Progress::Iteration {
                window,
                step,
                iteration: it,
            } => {
                if let Some(b) = &self.bar {
                    b.set_message(format!(
                        "window {window}, step {step}: SCP merit {:.6e}, trust radius {:.3} m, \
                         solver {} ({} IPM iterations)",
                        it.merit_after, it.trust_region, it.solver_status, it.solver_iterations
                    ));
                }
            }
            Progress::Step1 {
                window,
                stage,
                courses,
            } => self.line(format!(
                "  window {window}: step 1 (P2) {} after {} SCP iterations{} in {:.3} s",
                stage.status,
                stage.iterations,
                match courses.len() {
                    0 => String::new(),
                    m => format!(" from the best of {m} first courses (one iteration each)"),
                },
                stage.solve_time_s
            )),
            Progress::Retry { window, turn, why } => self.line(format!(
                "  window {window}: {why}; planned again from a first guess turned {:+.0}°",
                turn.to_degrees()
            )),
            Progress::Step2 { window, graph } => self.line(format!(
                "  window {window}: step 2 (P3 + P4) {} graph in {:.4} s",
                if graph.exact { "exact" } else { "heuristic" },
                graph.solve_time_s
            )),
            Progress::Step3 {
                window,
                stage,
                los_rounds,
                out_of_band,
                bridges,
            } => self.line(format!(
                "  window {window}: step 3 (P5) {} after {} SCP iterations, {los_rounds} \
                 line-of-sight round(s), {out_of_band} link-step(s) outside their band{}, in \
                 {:.3} s",
                stage.status,
                stage.iterations,
                if bridges > 0 {
                    format!(", {bridges} bridge(s)")
                } else {
                    String::new()
                },
                stage.solve_time_s
            )),
        }
    }

    /// A step of the RRT-like tree has ended.
    fn sampled(&self, done: shoal::sampling::StepDone) {
        let st = done.step;
        self.line(format!(
            "  window {}: step k = {}: {} draws, {} valid team samples, {} nodes kept, {:.3} s",
            done.window, done.k, st.drawn, st.valid, st.kept, st.time_s
        ));
    }

    fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

fn plan(
    s: &Scenario,
    source: String,
    overrides: Vec<String>,
    scenario_path: Option<&Path>,
    out: &Path,
    how: How,
) -> Result<ExitCode> {
    // the output set is staged inside `out` and moved into place after its check; `-o` naming
    // a file, or a folder whose manifest cannot be trusted, is refused before any planning
    let set = shoal::output_set::OutputSet::begin(out)?;
    let stop = interrupt_plan(set.dir().to_path_buf(), s.windows)?;
    match plan_into(s, source, overrides, scenario_path, out, how, set, stop) {
        // a write into the staging directory that Ctrl-C's handler is removing: let the
        // handler end the process with its own message
        Err(_) if stop.gate.interrupted() => loop {
            std::thread::park();
        },
        done => done,
    }
}

/// [`plan`] once its output set has begun.
#[allow(clippy::too_many_arguments)]
fn plan_into(
    s: &Scenario,
    source: String,
    overrides: Vec<String>,
    scenario_path: Option<&Path>,
    out: &Path,
    how: How,
    set: shoal::output_set::OutputSet,
    stop: &PlanStop,
) -> Result<ExitCode> {
    let (floor, floor_source) = shoal::mission::scenario_floor(s, base_dir(scenario_path))?;
    floor_source
        .warnings
        .iter()
        .for_each(|w| eprintln!("warning: {}", printable(w)));
    let provenance = shoal::Provenance {
        scenario_source: source,
        overrides,
        seafloor: floor_source,
    };
    let report = Report::new(how.quiet);
    report.line(format!(
        "planning {} window(s): N = {} AUVs, K = {} steps of δ = {} s, seed {}",
        s.windows, s.team.auvs, s.horizon.steps, s.horizon.dt, s.seed
    ));
    let planned = match (&how.waypoints, how.method) {
        (Some(path), _) => shoal::sampling::waypoints::read(path).and_then(|file| {
            let name = path.display().to_string();
            shoal::sampling::waypoints::plan(s, &floor, &provenance, &file, &name)
        }),
        (None, Method::RrtLike) => {
            shoal::sampling::plan(s, &floor, &provenance, &mut |done| report.sampled(done))
        }
        (None, Method::Mpc) => shoal::Planner::new(s, &floor)
            .provenance(provenance)
            .on_progress(|event| {
                if let Progress::Step3 { .. } = event {
                    stop.windows_done.fetch_add(1, Ordering::SeqCst);
                }
                report.event(event)
            })
            .stop_when(&stop.requested)
            .run(),
    };
    stop.planning_over();
    report.finish();
    let plan = planned?;
    let tables = !how.quiet && !how.json;
    let plan_path = set.dir().join("plan.json");
    shoal::output::write_plan(&plan, &plan_path)?;
    let csvs = shoal::output::write_csvs(&plan, set.dir())?;
    if tables {
        println!("{}", shoal::report::summary_table(&plan));
    }
    if how.figures {
        let dir = set.dir().join("figures");
        self::plot(&plan, &floor, &dir, &out.join("figures"), false, how.quiet)?;
    }
    // the check verifies what was written: the file read back, not the plan in memory
    let written = shoal::output::read_plan(&plan_path).map_err(|e| {
        anyhow::anyhow!(
            "the plan does not read back as written, so nothing was written to {}: {}",
            out.display(),
            e.to_string()
                .replace(&plan_path.display().to_string(), "plan.json")
        )
    })?;
    let check = shoal::check::check_plan(&written, &floor);
    // --fly: the plan that passed its check is flown as `shoal simulate` would fly it, and its
    // record and figures join the plan's set, moved into place with it
    // a plan that cannot be flown (a current it cannot stem) is still written, and said so
    let (flown, fly_error) = match how.fly && check.passed() {
        true => match fly_written(&written, &floor, out, set.dir(), how.figures, how.quiet) {
            Ok(record) => (Some(record), None),
            Err(e) => {
                // what the flight had written goes: the set holds the plan alone
                let _ = std::fs::remove_file(set.dir().join(shoal::output_set::PLAN_FLIGHT));
                for stem in shoal::figures::SIM_FIGURES {
                    for ext in ["png", "svg"] {
                        let _ = std::fs::remove_file(
                            set.dir().join("figures").join(format!("{stem}.{ext}")),
                        );
                    }
                }
                (None, Some(error_chain(&e)))
            }
        },
        false => (None, None),
    };
    if !stop.gate.enter() {
        // Ctrl-C came first: its handler is ending the process
        loop {
            std::thread::park();
        }
    }
    let files = set.commit(Some(check.passed()))?;
    let cut_short = written.windows.len() < s.windows;
    for w in &written.warnings {
        eprintln!("warning: {}", printable(w));
    }
    if how.json {
        let mut summary = json_summary(&written, out, &files, &check);
        if let (Some(record), Some(map)) = (&flown, summary.as_object_mut()) {
            // --fly: where the flight is, and its metrics (flown and planned)
            map.insert(
                "flight".into(),
                serde_json::json!({
                    "sim": out.join(shoal::output_set::PLAN_FLIGHT),
                    "metrics": record.flight.metrics,
                }),
            );
        }
        println!(
            "{}",
            serde_json::to_string_pretty(&summary).expect("a summary serialises")
        );
    }
    if tables {
        println!(
            "wrote {} with {} CSV files{} in {} ({} files)",
            out.join("plan.json").display(),
            csvs.len(),
            if how.figures { " and the figures" } else { "" },
            out.display(),
            files.len()
        );
        print!("{}", check.table());
        if let Some(record) = &flown {
            println!();
            print!("{}", printable_lines(&shoal::sim::summary::table(record)));
            println!();
            print!(
                "{}",
                printable_lines(&shoal::sim::summary::beside_plan(record))
            );
            println!(
                "flew the plan: wrote {}",
                out.join(shoal::output_set::PLAN_FLIGHT).display()
            );
        }
        let unconverged = written.unconverged_stages();
        if !check.passed() {
            println!("check: VIOLATED (see FAIL rows)");
        } else if unconverged > 0 {
            println!(
                "check: every constraint holds, but the plan is unconverged in {unconverged} \
                 stage(s) (see the warnings): feasible, not optimal"
            );
        } else if !written.warnings.is_empty() {
            println!(
                "check: every constraint holds (see the {} warning(s) above)",
                written.warnings.len()
            );
        } else {
            println!("check: every constraint holds");
        }
    } else if !check.passed() {
        eprintln!("check: VIOLATED (run `shoal check` on the plan for the table)");
    }
    if let Some(e) = &fly_error {
        eprintln!(
            "error: the plan is written, not flown: {}",
            printable_lines(e)
        );
    }
    if how.fly && !check.passed() {
        eprintln!(
            "not flown (--fly): the plan fails its check, and shoal simulate flies only plans \
             that pass (shoal simulate --unchecked flies it anyway)"
        );
    }
    if cut_short {
        eprintln!(
            "interrupted: wrote the {} of {} windows planned before Ctrl-C to {} (the plan records \
             windows = {} and says so in its warnings)",
            written.windows.len(),
            s.windows,
            out.display(),
            written.windows.len()
        );
        return Ok(ExitCode::from(130));
    }
    Ok(if check.passed() && fly_error.is_none() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// `shoal plan --fly`: fly `plan` (already checked) as `shoal simulate OUT/plan.json` would at
/// its default settings (one run, the plan's seed), and write its record (and, with `figures`,
/// the simulation's figures) into the plan's staging directory `staging`.
fn fly_written(
    plan: &shoal::Plan,
    floor: &shoal::Seafloor,
    out: &Path,
    staging: &Path,
    figures: bool,
    quiet: bool,
) -> Result<shoal::sim::SimRecord> {
    let name = out.join("plan.json").display().to_string();
    if !quiet {
        eprintln!("flying {name} (--fly)");
    }
    let options = shoal::sim::Options::new(plan.scenario.seed, 1);
    let record = shoal::sim::fly_plan(plan, &name, floor, &options, &mut |_| {})
        .with_context(|| format!("flying {name} (--fly)"))?;
    shoal::sim::write(&record, &staging.join(shoal::output_set::PLAN_FLIGHT))?;
    if figures {
        shoal::figures::write_sim(plan, floor, &record, &staging.join("figures"))
            .context("drawing the figures of the flight (--fly)")?;
    }
    for f in &record.failed_estimates {
        eprintln!(
            "warning: {} {} {} failed: {}",
            f.flown,
            f.policy.name(),
            f.estimator,
            f.brief()
        );
    }
    Ok(record)
}

/// What `shoal plan` and its Ctrl-C handler share.
struct PlanStop {
    /// Set by a first Ctrl-C once a window is done: stop after the window being planned.
    requested: AtomicBool,
    /// Windows planned so far.
    windows_done: AtomicUsize,
    /// Set when planning has ended (the plan is being written, checked and moved into place).
    over: AtomicBool,
    /// Whether the output set has begun to move into place.
    gate: shoal::output_set::CommitGate,
}

impl PlanStop {
    fn planning_over(&self) {
        self.over.store(true, Ordering::SeqCst);
    }
}

/// Install `shoal plan`'s Ctrl-C handler. A first Ctrl-C while a window of a multi-window plan
/// is being planned, with a window already done, lets that window end and writes the windows
/// done (a whole, checked plan of fewer windows, exit 130). Otherwise, or at a second Ctrl-C,
/// the run ends at once and writes nothing: the staging directory is removed and the earlier
/// outputs stay as they were. While the set moves into place, Ctrl-C waits for it.
fn interrupt_plan(staging: PathBuf, windows: usize) -> Result<&'static PlanStop> {
    let stop: &'static PlanStop = Box::leak(Box::new(PlanStop {
        requested: AtomicBool::new(false),
        windows_done: AtomicUsize::new(0),
        over: AtomicBool::new(false),
        gate: shoal::output_set::CommitGate::new(),
    }));
    ctrlc::set_handler(move || {
        let done = stop.windows_done.load(Ordering::SeqCst);
        let first = !stop.requested.swap(true, Ordering::SeqCst);
        if first && done >= 1 && done < windows && !stop.over.load(Ordering::SeqCst) {
            match done + 1 == windows {
                true => eprintln!(
                    "interrupt: {done} of {windows} windows are planned and the last is under \
                     way; the whole plan is written when it ends (Ctrl-C again to stop at once, \
                     writing nothing)"
                ),
                false => eprintln!(
                    "interrupt: {done} of {windows} windows are planned; stopping when window {} \
                     ends and writing the windows planned by then (Ctrl-C again to stop at \
                     once, writing nothing)",
                    done + 1
                ),
            }
            return;
        }
        if stop.gate.interrupt() {
            let _ = std::fs::remove_dir_all(&staging);
            eprintln!(
                "interrupted: nothing was written (the earlier outputs, if any, are unchanged)"
            );
            std::process::exit(130);
        }
        eprintln!("interrupt: the outputs are being moved into place; that ends first");
    })
    .context("installing the Ctrl-C handler")?;
    Ok(stop)
}

/// The `--json` summary of a plan written in `out`.
fn json_summary(
    p: &shoal::Plan,
    out: &Path,
    files: &[String],
    check: &shoal::check::CheckReport,
) -> serde_json::Value {
    let windows: Vec<serde_json::Value> = p
        .windows
        .iter()
        .map(|w| {
            serde_json::json!({
                "index": w.index,
                "step1": { "status": w.step1.status, "iterations": w.step1.iterations },
                "step3": { "status": w.final_.status, "iterations": w.final_.iterations },
                "out_of_band": w.links.out_of_band.len(),
                "metrics": w.metrics,
            })
        })
        .collect();
    let failing: Vec<&str> = check.failures().iter().map(|f| f.name).collect();
    serde_json::json!({
        "plan": out.join("plan.json"),
        "files": files,
        "seed": p.scenario.seed,
        "check": { "passed": check.passed(), "failing": failing },
        "warnings": p.warnings,
        "metrics": p.metrics,
        "windows": windows,
    })
}

/// The study's bases: each scenario file (or "default") with `set` applied.
fn compare_bases(scenarios: &[String], set: &[String]) -> Result<Vec<shoal::compare::Base>> {
    let names: Vec<String> = match scenarios.is_empty() {
        true => vec!["default".into()],
        false => scenarios.to_vec(),
    };
    names
        .iter()
        .map(|name| {
            let path = (name != "default").then(|| Path::new(name));
            let (scenario, _) = load_scenario(path, set)?;
            let stem = path
                .and_then(|p| p.file_stem())
                .map_or("default".into(), |s| s.to_string_lossy().into_owned());
            Ok(shoal::compare::Base {
                name: stem,
                scenario,
                dir: base_dir(path).to_path_buf(),
            })
        })
        .collect()
}

/// `shoal compare`: run the study with a progress bar on a terminal (a line per run otherwise),
/// write the outputs and print the summary. Ctrl-C stops it after the run under way (a second
/// Ctrl-C at once) and writes the finished runs, marked incomplete; exit code 130.
fn compare(
    study: &shoal::compare::Study,
    out: &Path,
    keep_plans: bool,
    figure: bool,
) -> Result<ExitCode> {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, Mutex};
    study.validate()?;
    std::fs::create_dir_all(out).with_context(|| format!("creating {}", out.display()))?;
    let total = study.runs();
    let bar = runs_bar(total, false);
    let cancel = Arc::new(AtomicBool::new(false));
    let finished: Arc<Mutex<Vec<shoal::compare::Row>>> = Arc::default();
    {
        let (cancel, finished, out) = (cancel.clone(), finished.clone(), out.to_path_buf());
        ctrlc::set_handler(move || {
            if !cancel.swap(true, Ordering::SeqCst) {
                eprintln!(
                    "stopping after the run under way (Ctrl-C again to stop at once); the \
                     finished runs will be written"
                );
                return;
            }
            let rows = finished.lock().map(|r| r.clone()).unwrap_or_default();
            match write_compare_set(&out, &rows, total, false) {
                Ok(_) => eprintln!("{}", interrupted(rows.len(), total, &out.join("runs.csv"))),
                Err(e) => eprintln!("interrupted: {e}"),
            }
            std::process::exit(130);
        })
        .context("installing the Ctrl-C handler")?;
    }
    let mut plan_error = None;
    let rows = shoal::compare::run_until(study, &cancel, &mut |i, planned| {
        let r = &planned.row;
        let line = format!(
            "[{}/{total}] {} {} N = {} seed {}: {} in {:.2} s{}",
            i + 1,
            r.scenario,
            r.method,
            r.auvs,
            r.seed,
            r.status,
            r.wall_s,
            match r.error.is_empty() {
                true => String::new(),
                false => format!(" ({})", printable(&r.error)),
            }
        );
        match bar.is_hidden() {
            true => eprintln!("{line}"),
            false => bar.println(line),
        }
        bar.inc(1);
        if let (true, Some(plan)) = (keep_plans, &planned.plan) {
            let name = format!("{}-{}-n{}-s{}.json", r.scenario, r.method, r.auvs, r.seed);
            if let Err(e) = shoal::output::write_plan(plan, &out.join("plans").join(name)) {
                plan_error.get_or_insert(e);
            }
        }
        if let Ok(mut f) = finished.lock() {
            f.push(r.clone());
        }
    });
    bar.finish_and_clear();
    let rows = rows?;
    if let Some(e) = plan_error {
        return Err(e.into());
    }
    let table = write_compare_set(out, &rows, total, figure)?;
    let (csv_path, md_path) = (out.join("runs.csv"), out.join("summary.md"));
    println!("{table}");
    if rows.len() < total {
        eprintln!("{}", interrupted(rows.len(), total, &csv_path));
        return Ok(ExitCode::from(130));
    }
    println!(
        "wrote {} and {}{}",
        csv_path.display(),
        md_path.display(),
        if figure { " and compare.png/.svg" } else { "" }
    );
    Ok(ExitCode::SUCCESS)
}

/// Write compare's runs.csv, summary.md and (for a finished comparison, when `figure`) its
/// figure into `out` as one output set; returns the summary's text.
fn write_compare_set(
    out: &Path,
    rows: &[shoal::compare::Row],
    total: usize,
    figure: bool,
) -> Result<String> {
    let set = shoal::output_set::OutputSet::begin_kind(out, shoal::output_set::Kind::Compare)?;
    let (_, _, table) = shoal::compare::write_tables(set.dir(), rows, total)?;
    if figure && rows.len() == total {
        let mut methods: Vec<&str> = Vec::new();
        for r in rows {
            if !methods.contains(&r.method.as_str()) {
                methods.push(&r.method);
            }
        }
        let title = format!("{}, {} runs", methods.join(" vs "), rows.len());
        shoal::figures::write_compare(rows, &title, set.dir())?;
    }
    set.commit(None)?;
    Ok(table)
}

/// What an interrupted comparison says it kept.
fn interrupted(done: usize, total: usize, csv: &Path) -> String {
    format!(
        "interrupted after {done} of {total} runs: wrote {} with the {done} finished runs \
         (incomplete)",
        csv.display()
    )
}

/// A progress bar of `total` runs on stderr with the elapsed time and the ETA, hidden when
/// `quiet` or when stderr is not a terminal.
fn runs_bar(total: usize, quiet: bool) -> ProgressBar {
    let bar = match quiet {
        true => ProgressBar::hidden(),
        false => ProgressBar::with_draw_target(Some(total as u64), ProgressDrawTarget::stderr()),
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{bar:30} {pos}/{len} runs, {elapsed_precise} elapsed, ETA {eta} {msg}",
        )
        .expect("a valid template"),
    );
    bar
}

/// `shoal sweep STUDY`: run it (or its shard) with a progress bar; print the totals. Exit
/// code 0 when the table holds its runs and not every one failed, 1 when every run of the
/// table failed, 130 when interrupted (Ctrl-C: the runs under way finish and keep their rows;
/// a second Ctrl-C stops at once, every finished row already in the table).
fn sweep(
    path: &Path,
    out: PathBuf,
    shard: Option<&str>,
    resume: bool,
    quiet: bool,
) -> Result<ExitCode> {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    let study = shoal::sweep::Study::load(path)?;
    let shard = match shard {
        Some(text) => {
            Some(shoal::sweep::Shard::parse(text).map_err(|e| anyhow::anyhow!("--shard {e}"))?)
        }
        None => shoal::sweep::Shard::from_env(|k| std::env::var(k).ok())
            .map_err(|e| anyhow::anyhow!(e))?,
    };
    let opts = shoal::sweep::Options { out, shard, resume };
    let total = study
        .total()
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    let mine = shard.map_or(total, |s| s.runs(total).len());
    let table = match shard {
        Some(s) => s.table(&opts.out),
        None => shoal::sweep::table_path(&opts.out),
    };
    let cancel = Arc::new(AtomicBool::new(false));
    {
        let (cancel, table) = (cancel.clone(), table.clone());
        let again = format!(
            "shoal sweep {} -o {} --resume",
            path.display(),
            opts.out.display()
        );
        ctrlc::set_handler(move || {
            if !cancel.swap(true, Ordering::SeqCst) {
                eprintln!(
                    "stopping: no new run starts, the runs under way finish and keep their rows \
                     (Ctrl-C again to stop at once)"
                );
                return;
            }
            eprintln!(
                "interrupted: {} keeps every run that finished (each row is written as its run \
                 ends); `{again}` makes the rest",
                table.display()
            );
            std::process::exit(130);
        })
        .context("installing the Ctrl-C handler")?;
    }
    let bar = runs_bar(mine, quiet);
    let counts = std::sync::Mutex::new([0usize; 3]);
    let outcome = shoal::sweep::run_until(
        &study,
        &opts,
        &|done| {
            let mut c = counts.lock().unwrap_or_else(|p| p.into_inner());
            match done.status.as_str() {
                "passed" => c[0] += 1,
                "violated" => c[1] += 1,
                _ => c[2] += 1,
            }
            bar.set_message(format!(
                "(passed {}, violated {}, failed {})",
                c[0], c[1], c[2]
            ));
            bar.inc(1);
        },
        &cancel,
    );
    bar.finish_and_clear();
    let o = outcome?;
    for note in &o.notes {
        eprintln!("warning: {note}");
    }
    let made = o.passed + o.violated + o.failed;
    if o.interrupted {
        eprintln!(
            "interrupted after {made} of {} runs: wrote {} with the {} finished runs of its {} \
             (incomplete; `shoal sweep {} -o {} --resume` makes the rest)",
            o.mine - o.skipped,
            o.table.display(),
            o.rows,
            o.mine,
            path.display(),
            opts.out.display()
        );
        return Ok(ExitCode::from(130));
    }
    if !o.complete {
        eprintln!(
            "error: {} holds {} of its {} runs (see the warnings above); `--resume` makes the \
             rest",
            o.table.display(),
            o.rows,
            o.mine
        );
        return Ok(ExitCode::from(1));
    }
    println!(
        "{} of {} runs{}: {} passed, {} violated, {} failed{} in {:.1} s (the runs' own times sum to \
         {:.1} s: {:.2}× in parallel); wrote {}",
        o.mine - o.skipped,
        o.total,
        match opts.shard {
            Some(s) => format!(" (shard {}/{}: {} runs)", s.index, s.count, o.mine),
            None => String::new(),
        },
        o.passed,
        o.violated,
        o.failed,
        if o.skipped > 0 { format!(", {} already in the table", o.skipped) } else { String::new() },
        o.wall_s,
        o.runs_s,
        o.runs_s / o.wall_s.max(1e-9),
        match &o.parquet {
            Some(p) => format!("{} and {}", o.table.display(), p.display()),
            None => o.table.display().to_string(),
        }
    );
    if o.rows > 0 && o.rows_failed == o.rows {
        eprintln!(
            "error: every run of {} failed (no plan), e.g. {}",
            o.table.display(),
            o.first_failure.as_deref().unwrap_or("?")
        );
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}
