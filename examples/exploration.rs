//! Issue 14's figures: explored area against team size and against mission length, on the
//! default scenario (synthetic floor) over seeds.
//!
//! Run:
//!   cargo run --release --example exploration -- team      # N = 3, 5, 7, 10, 15, 20, 30; 1 window
//!   cargo run --release --example exploration -- windows   # 1, 2, 5, 10 windows; N = 5 and 20
//!
//! Optional after the mode: the seeds (default `1-5`, or a list `1,3`), `N=...` and `W=...`
//! lists that replace the mode's defaults (`N=5,20 W=1,2`), and `away=window` for the paper's
//! OF1_8 (measured from each window's start) instead of the default `away=track`, and any
//! `key=value` with a dot in the key to override a scenario key
//! (`acoustic.graph=per_step`). One CSV row
//! per run on stdout (every plan is checked); the mean and range over seeds per setting on
//! stderr.

use shoal::{mission, Planner, Scenario};
use std::collections::BTreeMap;

mod common;
use common::list;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mode = args.first().map(String::as_str).unwrap_or("team");
    let (mut teams, mut windows) = match mode {
        "team" => (vec![3, 5, 7, 10, 15, 20, 30], vec![1]),
        "windows" => (vec![5, 20], vec![1, 2, 5, 10]),
        _ => panic!("the mode is `team` or `windows`"),
    };
    let mut seeds = list("1-5");
    let mut away = None;
    let mut overrides = Vec::new();
    for a in args.iter().skip(1) {
        if a.split_once('=').is_some_and(|(k, _)| k.contains('.')) {
            overrides.push(a.clone());
        } else if let Some(v) = a.strip_prefix("N=") {
            teams = list(v);
        } else if let Some(v) = a.strip_prefix("W=") {
            windows = list(v);
        } else if a == "away=window" {
            away = Some(shoal::scenario::AwayFrom::Window);
        } else {
            seeds = list(a);
        }
    }
    println!(
        "auvs,windows,seed,explored_km2,revisited_km2,mean_height_m,usv_away_m,usv_path_m,\
         chain_percent,off_band_link_steps,passed,seconds,warnings"
    );
    let mut summary: BTreeMap<(u64, u64), Vec<[f64; 3]>> = BTreeMap::new();
    for &n in &teams {
        for &w in &windows {
            for &seed in &seeds {
                let mut s: Scenario =
                    shoal::scenario::default_with(&overrides).expect("valid overrides");
                s.seed = seed;
                s.windows = w as usize;
                s.team.auvs = n as usize;
                if let Some(a) = away {
                    s.usv.away_from = a;
                }
                let clock = std::time::Instant::now();
                let (floor, _) = mission::scenario_floor(&s, std::path::Path::new("."))
                    .expect("the default floor builds");
                let p = match Planner::new(&s, &floor).run() {
                    Ok(p) => p,
                    Err(e) => {
                        println!("{n},{w},{seed},,,,,,,error,,\"{e}\"");
                        continue;
                    }
                };
                let secs = clock.elapsed().as_secs_f64();
                let passed = shoal::check(&p, &floor).passed();
                let m = &p.metrics;
                let usv: Vec<[f64; 2]> = p
                    .windows
                    .iter()
                    .flat_map(|w| w.final_.usv.position.iter().copied())
                    .collect();
                let (first, last) = (usv[0], usv[usv.len() - 1]);
                let away_m = (last[0] - first[0]).hypot(last[1] - first[1]);
                let path: f64 = usv
                    .windows(2)
                    .map(|s| (s[1][0] - s[0][0]).hypot(s[1][1] - s[0][1]))
                    .sum();
                let off_band: usize = p.windows.iter().map(|w| w.links.out_of_band.len()).sum();
                println!(
                    "{n},{w},{seed},{:.4},{:.4},{:.2},{away_m:.0},{path:.0},{:.1},{off_band},\
                     {passed},{secs:.1},\"{}\"",
                    m.explored_area_km2,
                    m.revisited_area_km2,
                    m.mean_height,
                    100.0 * m.chain_fraction,
                    p.warnings.join(" | ").replace('"', "'")
                );
                summary.entry((n, w)).or_default().push([
                    m.explored_area_km2,
                    away_m,
                    m.mean_height,
                ]);
            }
        }
    }
    eprintln!(
        "auvs windows  explored km² mean [min, max]   USV away m mean [min, max]   \
         mean height m"
    );
    for ((n, w), v) in summary {
        let stats = |i: usize| {
            let xs: Vec<f64> = v.iter().map(|r| r[i]).collect();
            let mean = xs.iter().sum::<f64>() / xs.len() as f64;
            let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
            let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            (mean, lo, hi)
        };
        let (a, a0, a1) = stats(0);
        let (d, d0, d1) = stats(1);
        let (h, _, _) = stats(2);
        eprintln!(
            "{n:>4} {w:>7}  {a:>6.3} [{a0:.3}, {a1:.3}]        {d:>6.0} [{d0:.0}, {d1:.0}]  \
             {h:>6.1}"
        );
    }
}
