//! Issue 22's scaling and gap table: one window of the default scenario per team size and
//! seed, planned with the scenario's SCP settings and again run to convergence
//! (`scp.tolerance = 1e-7`, `scp.max_iterations = 300`), so that the gap of the default plan to
//! the converged optimum of the same window, (J − J_conv)/|J_conv|, can be read beside its time.
//!
//! Run:
//!   cargo run --release --example scaling                 # N = 3, 5, 10, 20; seeds 1-8
//!   cargo run --release --example scaling -- 1-3 N=5,20 c14=off fast
//!
//! Arguments: the seeds (`1-8` or a list), `N=` a list of team sizes, `c14=on|off|both` (C1_14
//! active, the default, or made inactive with `auv.max_heading_rate = 10` and
//! `auv.min_heading_speed = 1.999`, so that only the SCP's own progress differs), `fast` to skip
//! the converged runs (no gap), and any `key=value` with a dot in the key to override a
//! scenario key as `shoal plan --set` does (`scp.momentum=true`). Every plan is checked. One
//! CSV row per window on stdout; the medians per team size on stderr.

use shoal::plan::{Plan, Stage};
use shoal::seafloor::Seafloor;
use shoal::{mission, Planner, Scenario};

mod common;
use common::list;

/// What one run of a window measured.
struct Run {
    seconds: f64,
    step1_iterations: usize,
    step3_iterations: usize,
    /// Interior-point iterations of every convex solve of both stages.
    ipm: Vec<usize>,
    /// Milliseconds per interior-point iteration over the window's solves.
    ms_per_ipm: f64,
    objective: f64,
    explored_km2: f64,
    passed: bool,
    converged: bool,
}

fn measure(s: &Scenario, floor: &Seafloor) -> Result<Run, String> {
    let clock = std::time::Instant::now();
    let p: Plan = Planner::new(s, floor).run().map_err(|e| e.to_string())?;
    let seconds = clock.elapsed().as_secs_f64();
    let passed = shoal::check(&p, floor).passed();
    let w = &p.windows[0];
    let stages: [&Stage; 2] = [&w.step1, &w.final_];
    let ipm: Vec<usize> = stages
        .iter()
        .flat_map(|st| st.scp.iter().map(|i| i.solver_iterations as usize))
        .collect();
    let solver_s: f64 = stages
        .iter()
        .flat_map(|st| st.scp.iter().map(|i| i.solver_time_s))
        .sum();
    let total_ipm: usize = ipm.iter().sum();
    Ok(Run {
        seconds,
        step1_iterations: w.step1.iterations,
        step3_iterations: w.final_.iterations,
        ms_per_ipm: 1e3 * solver_s / total_ipm.max(1) as f64,
        ipm,
        objective: w.final_.objective.total,
        explored_km2: w.metrics.explored_area_km2,
        passed,
        converged: w.converged(),
    })
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let m = v.len() / 2;
    if v.len() % 2 == 1 {
        v[m]
    } else {
        0.5 * (v[m - 1] + v[m])
    }
}

fn main() {
    let mut seeds = list("1-8");
    let mut teams = vec![3, 5, 10, 20];
    let mut c14 = vec![true];
    let mut fast = false;
    let mut overrides = Vec::new();
    for a in std::env::args().skip(1) {
        if a.split_once('=').is_some_and(|(k, _)| k.contains('.')) {
            overrides.push(a);
        } else if let Some(v) = a.strip_prefix("N=") {
            teams = list(v);
        } else if let Some(v) = a.strip_prefix("c14=") {
            c14 = match v {
                "on" => vec![true],
                "off" => vec![false],
                "both" => vec![true, false],
                _ => panic!("c14=on|off|both"),
            };
        } else if a == "fast" {
            fast = true;
        } else {
            seeds = list(&a);
        }
    }
    println!(
        "auvs,c14,seed,seconds,step1_iterations,step3_iterations,ipm_median,ms_per_ipm,objective,\
         explored_km2,converged,passed,conv_seconds,conv_iterations,conv_objective,\
         conv_explored_km2,gap_percent"
    );
    for &active in &c14 {
        for &n in &teams {
            let (mut secs, mut gaps, mut ipms, mut mspi) = (vec![], vec![], vec![], vec![]);
            for &seed in &seeds {
                let mut s: Scenario =
                    shoal::scenario::default_with(&overrides).expect("valid overrides");
                s.seed = seed;
                s.team.auvs = n as usize;
                if !active {
                    s.auv.max_heading_rate = 10.0;
                    s.auv.min_heading_speed = 1.999;
                }
                // one floor for both runs of the window (the tolerance does not change it)
                let floor = match mission::scenario_floor(&s, std::path::Path::new(".")) {
                    Ok((f, _)) => f,
                    Err(e) => {
                        println!("{n},{active},{seed},error,\"floor: {e}\"");
                        continue;
                    }
                };
                let run = match measure(&s, &floor) {
                    Ok(r) => r,
                    Err(e) => {
                        println!("{n},{active},{seed},error,\"{e}\"");
                        continue;
                    }
                };
                let conv = if fast {
                    None
                } else {
                    s.scp.tolerance = 1e-7;
                    s.scp.max_iterations = 300;
                    // both stages, whatever Step 1's own settings were
                    s.scp.step1_tolerance = None;
                    s.scp.step1_max_iterations = None;
                    measure(&s, &floor).ok()
                };
                let mut ipm: Vec<f64> = run.ipm.iter().map(|&i| i as f64).collect();
                let ipm_median = median(&mut ipm);
                let gap = conv
                    .as_ref()
                    .map(|c| 100.0 * (run.objective - c.objective) / c.objective.abs());
                let opt = |f: &dyn Fn(&Run) -> String| conv.as_ref().map_or(String::new(), f);
                println!(
                    "{n},{active},{seed},{:.3},{},{},{ipm_median},{:.2},{:.3},{:.3},{},{},{},{},{},{},{}",
                    run.seconds,
                    run.step1_iterations,
                    run.step3_iterations,
                    run.ms_per_ipm,
                    run.objective,
                    run.explored_km2,
                    run.converged,
                    run.passed,
                    opt(&|c| format!("{:.3}", c.seconds)),
                    opt(&|c| format!("{}+{}", c.step1_iterations, c.step3_iterations)),
                    opt(&|c| format!("{:.3}", c.objective)),
                    opt(&|c| format!("{:.3}", c.explored_km2)),
                    gap.map_or(String::new(), |g| format!("{g:.2}")),
                );
                secs.push(run.seconds);
                ipms.push(ipm_median);
                mspi.push(run.ms_per_ipm);
                if let Some(g) = gap {
                    gaps.push(g);
                }
            }
            let worst = gaps.iter().copied().fold(f64::NAN, f64::max);
            eprintln!(
                "N = {n:>2}, C1_14 {}: window {:.3} s (median), interior-point iterations {:.0}, \
                 {:.2} ms each; gap median {:.2} %, worst {:.2} %",
                if active { "active" } else { "inactive" },
                median(&mut secs),
                median(&mut ipms),
                median(&mut mspi),
                median(&mut gaps),
                worst,
            );
        }
    }
}
