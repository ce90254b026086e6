//! A comparison's rows grouped by scenario, method and team size: how many runs planned and
//! passed their check, the wall time's median and range, and the measures' mean ± sd over the
//! runs that planned.

use super::Row;
use std::fmt::Write as _;

/// The runs of one (scenario, method, N).
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// The base scenario's name.
    pub scenario: String,
    /// The method.
    pub method: String,
    /// N.
    pub auvs: usize,
    /// Runs.
    pub runs: usize,
    /// Runs that made a plan.
    pub planned: usize,
    /// Runs whose plan passed `shoal check`.
    pub passed: usize,
    /// Wall time: median, least and most, s (over every run).
    pub wall_s: [f64; 3],
    /// Mean and sd of P2's objective at Step 1's paths.
    pub p2_objective: [f64; 2],
    /// Mean and sd of the energy Σ‖U‖² over the plans.
    pub energy: [f64; 2],
    /// Mean and sd of the mean height above the floor, m.
    pub mean_height_m: [f64; 2],
    /// Mean and sd of the explored area, km².
    pub explored_km2: [f64; 2],
    /// Mean and sd of the USV's distance moved, m.
    pub usv_moved_m: [f64; 2],
    /// Mean of the vehicle draws of a sampling planner.
    pub samples_drawn: f64,
}

/// Mean and sample standard deviation (NaN for none; sd 0 for one).
fn mean_sd(xs: &[f64]) -> [f64; 2] {
    let n = xs.len() as f64;
    if xs.is_empty() {
        return [f64::NAN; 2];
    }
    let mean = xs.iter().sum::<f64>() / n;
    let var = match xs.len() {
        1 => 0.0,
        _ => xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0),
    };
    [mean, var.sqrt()]
}

/// Median, least and most (NaN for none).
fn median_range(xs: &[f64]) -> [f64; 3] {
    let mut v: Vec<f64> = xs.iter().copied().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return [f64::NAN; 3];
    }
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    let median = if v.len() % 2 == 1 {
        v[m]
    } else {
        (v[m - 1] + v[m]) / 2.0
    };
    [median, v[0], v[v.len() - 1]]
}

/// The groups of `rows`, in the order their keys first appear.
pub fn summary(rows: &[Row]) -> Vec<Group> {
    let mut keys: Vec<(String, String, usize)> = Vec::new();
    for r in rows {
        let k = (r.scenario.clone(), r.method.clone(), r.auvs);
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    keys.into_iter()
        .map(|(scenario, method, auvs)| {
            let runs: Vec<&Row> = rows
                .iter()
                .filter(|r| r.scenario == scenario && r.method == method && r.auvs == auvs)
                .collect();
            let planned: Vec<&&Row> = runs.iter().filter(|r| r.planned()).collect();
            let of = |f: fn(&Row) -> f64| planned.iter().map(|r| f(r)).collect::<Vec<f64>>();
            Group {
                runs: runs.len(),
                planned: planned.len(),
                passed: runs.iter().filter(|r| r.status == "passed").count(),
                wall_s: median_range(&runs.iter().map(|r| r.wall_s).collect::<Vec<_>>()),
                p2_objective: mean_sd(&of(|r| r.p2_objective)),
                energy: mean_sd(&of(|r| r.energy)),
                mean_height_m: mean_sd(&of(|r| r.mean_height_m)),
                explored_km2: mean_sd(&of(|r| r.explored_km2)),
                usv_moved_m: mean_sd(&of(|r| r.usv_moved_m)),
                samples_drawn: mean_sd(&of(|r| r.samples_drawn as f64))[0],
                scenario,
                method,
                auvs,
            }
        })
        .collect()
}

/// The groups as a Markdown table (what BENCHMARKS.md shows).
pub fn markdown(groups: &[Group]) -> String {
    let mut out = String::from(
        "| scenario | method | N | planned / passed / runs | wall time s, median (range) | \
         P2 objective | energy Σ‖U‖² | mean height m | explored km² | USV moved m | draws |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    let pm = |v: [f64; 2], digits: usize| match v[0].is_finite() {
        true => format!("{:.*} ± {:.*}", digits, v[0], digits, v[1]),
        false => "-".into(),
    };
    for g in groups {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} / {} / {} | {:.2} ({:.2}–{:.2}) | {} | {} | {} | {} | {} | {} |",
            g.scenario,
            g.method,
            g.auvs,
            g.planned,
            g.passed,
            g.runs,
            g.wall_s[0],
            g.wall_s[1],
            g.wall_s[2],
            pm(g.p2_objective, 0),
            pm(g.energy, 3),
            pm(g.mean_height_m, 1),
            pm(g.explored_km2, 3),
            pm(g.usv_moved_m, 0),
            match g.samples_drawn {
                d if d > 0.0 => format!("{d:.0}"),
                _ => "-".into(),
            }
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_count_and_average_their_runs() {
        let mut rows = Vec::new();
        for (seed, wall, status) in [(1, 1.0, "passed"), (2, 3.0, "violated"), (3, 2.0, "failed")] {
            let mut r = Row::key("default", "mpc", 3, seed);
            r.status = status.into();
            r.wall_s = wall;
            if status != "failed" {
                r.energy = seed as f64;
            }
            rows.push(r);
        }
        rows.push(Row::key("default", "rrt-like", 3, 1));
        let g = summary(&rows);
        assert_eq!(g.len(), 2);
        assert_eq!((g[0].runs, g[0].planned, g[0].passed), (3, 2, 1));
        assert_eq!(g[0].wall_s, [2.0, 1.0, 3.0]);
        assert_eq!(g[0].energy[0], 1.5);
        assert!((g[0].energy[1] - 0.5f64.sqrt()).abs() < 1e-12);
        let md = markdown(&g);
        assert!(
            md.contains("| default | mpc | 3 | 2 / 1 / 3 | 2.00 (1.00–3.00) |"),
            "{md}"
        );
    }
}
