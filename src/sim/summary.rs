//! The tables `shoal simulate` prints: how the plan was kept, and each estimate's errors.

use super::record::{FlightRecord, SimRecord};
use std::fmt::Write;

fn flight_line(out: &mut String, name: &str, f: &FlightRecord, eps: f64) {
    let m = &f.metrics;
    let lo = m
        .tracking_rms_m
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    let hi = m.tracking_rms_m.iter().copied().fold(0.0, f64::max);
    let mx = m.tracking_max_m.iter().copied().fold(0.0, f64::max);
    let _ = writeln!(
        out,
        "{name}: tracking RMS {lo:.1}–{hi:.1} m (max {mx:.1} m); lowest altitude {:.1} m ({} \
         samples below ε = {eps} m, {} below the floor, {} off the grid); closest two AUVs \
         {:.1} m (planned {:.1} m); every AUV linked to the USV at {:.0} % of epochs (in \
         range and sight), through received pings at {:.0} %{}",
        m.min_altitude_m,
        m.samples_below_clearance,
        m.samples_below_floor,
        m.samples_off_grid,
        m.min_separation_m,
        m.min_separation_planned_m,
        100.0 * m.connected_fraction,
        100.0 * m.linked_fraction,
        if m.planned_links_up > 0.0 {
            format!(
                "; planned links in range and sight {:.0} %, received {:.0} %",
                100.0 * m.planned_links_up,
                100.0 * m.planned_links_received
            )
        } else {
            String::new()
        }
    );
}

/// The summary of a simulation: the flights, then one row per estimate (with the Monte Carlo
/// mean ± standard deviation when there were several runs).
pub fn table(r: &SimRecord) -> String {
    let mut out = String::new();
    if !r.check_failures.is_empty() {
        let _ = writeln!(
            out,
            "UNCHECKED: the plan fails its check ({}) and was flown all the same (--unchecked)",
            r.check_failures.join(", ")
        );
    }
    if let Some(i) = &r.incomplete {
        let _ = writeln!(
            out,
            "INCOMPLETE ({}): {} of {} runs finished; what follows is over those",
            i.reason, i.runs_finished, i.runs_asked
        );
    }
    flight_line(
        &mut out,
        "plan (Step 3) flown",
        &r.flight,
        r.floor_clearance,
    );
    flight_line(
        &mut out,
        "Step 1's paths flown",
        &r.step1_flight,
        r.floor_clearance,
    );
    let _ = writeln!(out);
    match &r.monte_carlo {
        None => {
            let _ = writeln!(
                out,
                "position error (3-D, m), seed {}: RMS and max over every AUV and epoch, RMS at \
                 each window's end",
                r.seed
            );
            let _ = writeln!(
                out,
                "{:<6} {:<15} {:<13} {:>7} {:>7} {:>7}  {:<24} {:>6} {:>6}",
                "flown",
                "policy",
                "estimator",
                "ranges",
                "RMSE",
                "max",
                "window ends",
                "%dist",
                "NEES"
            );
            for e in &r.estimates {
                let ends: Vec<String> = e
                    .metrics
                    .window_end_rmse_m
                    .iter()
                    .map(|x| format!("{x:.1}"))
                    .collect();
                let _ = writeln!(
                    out,
                    "{:<6} {:<15} {:<13} {:>7} {:>7.2} {:>7.2}  {:<24} {:>6.2} {:>6.1}",
                    e.flown,
                    e.policy.name(),
                    e.estimator,
                    e.ranges_used,
                    e.metrics.team_rmse_m,
                    e.metrics.team_max_m,
                    ends.join(" "),
                    e.metrics.end_percent_of_distance,
                    e.metrics.mean_nees
                );
            }
            for f in &r.failed_estimates {
                let _ = writeln!(
                    out,
                    "{:<6} {:<15} {:<13} {:>7}  {}: {}",
                    f.flown,
                    f.policy.name(),
                    f.estimator,
                    f.ranges_used,
                    f.policy.name(),
                    f.brief()
                );
            }
        }
        Some(mc) => {
            let _ = writeln!(
                out,
                "position error (3-D, m) over {} runs (seeds {}–{}): mean ± standard deviation",
                mc.runs,
                r.seed,
                r.seed.wrapping_add(mc.runs.saturating_sub(1) as u64)
            );
            let _ = writeln!(
                out,
                "{:<6} {:<15} {:<13} {:>14} {:>14} {:>14} {:>6}",
                "flown", "policy", "estimator", "RMSE", "max", "last window end", "NEES"
            );
            for s in &mc.summary {
                let pm = |x: &super::montecarlo::Stat| format!("{:.2} ± {:.2}", x.mean, x.std);
                let last = s
                    .window_end_rmse_m
                    .last()
                    .map(pm)
                    .unwrap_or_else(|| "-".into());
                if s.failed_runs >= mc.runs {
                    let _ = writeln!(
                        out,
                        "{:<6} {:<15} {:<13} {}: failed in every run",
                        s.flown,
                        s.policy.name(),
                        s.estimator,
                        s.policy.name()
                    );
                    continue;
                }
                let _ = writeln!(
                    out,
                    "{:<6} {:<15} {:<13} {:>14} {:>14} {:>14} {:>6.1}{}",
                    s.flown,
                    s.policy.name(),
                    s.estimator,
                    pm(&s.team_rmse_m),
                    pm(&s.team_max_m),
                    last,
                    s.mean_nees.mean,
                    match s.failed_runs {
                        0 => String::new(),
                        n => format!("  (failed in {n} of {} runs: over the others)", mc.runs),
                    }
                );
            }
        }
    }
    out
}

/// The flown figures beside the planned ones (`shoal plan --fly`): what the plan promised, on
/// its own positions in time, and what its flight gave. Planned: the references' samples below
/// the floor and below ε, the closest two references, the mean p(d) of the planned links, and
/// the share of epochs with every AUV in range and sight of the USV through links; a tracking
/// error and an estimate have no planned value.
pub fn beside_plan(r: &SimRecord) -> String {
    let m = &r.flight.metrics;
    let worst = m.tracking_rms_m.iter().copied().fold(0.0, f64::max);
    let chain = r
        .estimates
        .iter()
        .find(|e| {
            e.flown == "final"
                && e.policy == super::policy::Policy::Chain
                && e.estimator == "factor_graph"
        })
        .and_then(|e| e.metrics.window_end_rmse_m.last())
        .map_or("-".to_string(), |x| format!("{x:.1}"));
    let pct = |x: f64| format!("{:.0} %", 100.0 * x);
    let rows: [(String, String, String); 8] = [
        (
            "samples below the floor".into(),
            m.planned_samples_below_floor.to_string(),
            m.samples_below_floor.to_string(),
        ),
        (
            format!("samples below ε = {} m", r.floor_clearance),
            m.planned_samples_below_clearance.to_string(),
            m.samples_below_clearance.to_string(),
        ),
        (
            "lowest altitude, m".into(),
            format!("{:.1}", m.planned_min_altitude_m),
            format!("{:.1}", m.min_altitude_m),
        ),
        (
            "tracking RMS, worst AUV, m".into(),
            "-".into(),
            format!("{worst:.1}"),
        ),
        (
            "closest two AUVs, m".into(),
            format!("{:.1}", m.min_separation_planned_m),
            format!("{:.1}", m.min_separation_m),
        ),
        (
            "planned-link pings received".into(),
            pct(m.planned_links_expected),
            pct(m.planned_links_received),
        ),
        (
            "epochs every AUV linked to the USV".into(),
            pct(m.planned_connected_fraction),
            pct(m.linked_fraction),
        ),
        (
            "chain error at the last window's end, m".into(),
            "-".into(),
            chain,
        ),
    ];
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{:<40} {:>9} {:>9}",
        "flown beside planned", "planned", "flown"
    );
    for (name, planned, flown) in rows {
        let _ = writeln!(out, "{name:<40} {planned:>9} {flown:>9}");
    }
    let _ = writeln!(
        out,
        "(planned: the plan's own positions in time, sampled as the flight is; pings: the mean \
         p(d) of its links; linked: in range and sight. Flown: the pings received, and links \
         whose pings were received)"
    );
    out
}
