//! Text reports of a plan for the terminal.

use crate::plan::{Metrics, Plan};
use std::fmt::Write as _;

/// One row per window with the status and SCP iterations of Step 1 and Step 3, the final plan's
/// figures and its metrics, then a row for the whole mission.
pub fn summary_table(plan: &Plan) -> String {
    let mut t = String::new();
    let header = [
        "window",
        "step 1",
        "step 3",
        "energy",
        "height",
        "min h",
        "USV moved",
        "explored",
        "connected",
        "chain",
        "off band",
        "max ψ̇",
        "time",
    ];
    let units = [
        "",
        "status/iter",
        "status/iter",
        "(m/s²)²",
        "m",
        "m",
        "m",
        "km²",
        "%",
        "%",
        "links",
        "rad/s",
        "s",
    ];
    for row in [header, units] {
        let _ = writeln!(t, "{}", line(&row.map(String::from)));
    }
    for w in &plan.windows {
        let st = &w.final_;
        let p0 = st.usv.position.first().copied().unwrap_or([0.0; 2]);
        let pk = st.usv.position.last().copied().unwrap_or([0.0; 2]);
        let moved = (pk[0] - p0[0]).hypot(pk[1] - p0[1]);
        let _ = writeln!(
            t,
            "{}",
            line(&row(
                w.index.to_string(),
                format!("{}/{}", short(&w.step1.status), w.step1.iterations),
                format!("{}/{}", short(&st.status), st.iterations),
                moved,
                w.links.out_of_band.len(),
                &w.metrics
            ))
        );
    }
    let first = plan
        .windows
        .first()
        .and_then(|w| w.final_.usv.position.first().copied());
    let last = plan
        .windows
        .last()
        .and_then(|w| w.final_.usv.position.last().copied());
    let moved = match (first, last) {
        (Some(a), Some(b)) => (b[0] - a[0]).hypot(b[1] - a[1]),
        _ => 0.0,
    };
    let off: usize = plan.windows.iter().map(|w| w.links.out_of_band.len()).sum();
    let _ = writeln!(
        t,
        "{}",
        line(&row(
            "all".into(),
            String::new(),
            String::new(),
            moved,
            off,
            &plan.metrics
        ))
    );
    t
}

fn short(status: &str) -> &str {
    match status {
        "converged" => "conv",
        "max_iterations" => "max",
        "stalled" => "stall",
        s => s,
    }
}

fn row(
    window: String,
    step1: String,
    step3: String,
    moved: f64,
    off_band: usize,
    m: &Metrics,
) -> [String; 13] {
    [
        window,
        step1,
        step3,
        format!("{:.3}", m.input_energy),
        format!("{:.1}", m.mean_height),
        format!("{:.1}", m.min_height),
        format!("{moved:.0}"),
        format!("{:.3}", m.explored_area_km2),
        format!("{:.1}", 100.0 * m.connected_fraction),
        format!("{:.1}", 100.0 * m.chain_fraction),
        off_band.to_string(),
        format!("{:.2e}", m.max_heading_rate),
        format!("{:.3}", m.step1_time_s + m.step2_time_s + m.step3_time_s),
    ]
}

fn line(cells: &[String; 13]) -> String {
    const WIDTH: [usize; 13] = [6, 11, 11, 9, 7, 7, 9, 9, 9, 6, 8, 9, 7];
    cells
        .iter()
        .zip(WIDTH)
        .map(|(c, w)| format!("{c:>w$}"))
        .collect::<Vec<_>>()
        .join(" ")
}
