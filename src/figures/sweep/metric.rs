//! The measures a sweep's figure can plot: the table's numeric columns and the fraction of runs
//! that passed the check; which of them are plotted by default; and how each is named.

use super::table::{Table, SEED};

/// The fraction of a point's runs whose plan passed the check (not a column: counted from
/// `status`, a run that made no plan counting as not passed).
pub(super) const PASSED_FRACTION: &str = "passed_fraction";

/// The measures plotted when none is named, those the table has, in this order.
pub(super) const DEFAULTS: [&str; 8] = [
    "wall_s",
    "p2_objective",
    "explored_km2",
    "mean_height_m",
    "chain_fraction",
    PASSED_FRACTION,
    "sim_chain_end_m",
    "sim_dead_reckoning_end_m",
];

/// Columns that are text or a run's key, never a measure.
const NOT_MEASURES: [&str; 8] = [
    "run",
    "scenario",
    "method",
    "auvs",
    SEED,
    "status",
    "error",
    "sim_status",
];

/// The measures of `table`: its columns but the run's key, the swept keys and text, then
/// [`PASSED_FRACTION`].
pub(super) fn allowed(table: &Table) -> Vec<String> {
    let first = table.column("scenario").unwrap_or(1);
    table.header[first..]
        .iter()
        .filter(|h| !NOT_MEASURES.contains(&h.as_str()) && !table.axes.contains(h))
        .cloned()
        .chain(std::iter::once(PASSED_FRACTION.to_string()))
        .collect()
}

/// A measure's panel title and y-axis label.
pub(super) fn describe(name: &str) -> (String, String) {
    let known = match name {
        "wall_s" => Some(("wall time per run", "s")),
        "p2_objective" => Some(("P2 objective (Step 1, summed)", "objective")),
        "energy" => Some(("input energy Σ‖U‖²", "(m/s²)²")),
        "explored_km2" => Some(("explored area", "km²")),
        "mean_height_m" => Some(("mean height above floor", "m")),
        "min_height_m" => Some(("least height above floor", "m")),
        "connected_fraction" => Some(("steps connected to the USV", "fraction of steps")),
        "chain_fraction" => Some(("steps with the chain whole", "fraction of steps")),
        PASSED_FRACTION => Some(("runs passing the check", "fraction of runs")),
        "sim_chain_end_m" => Some(("end error, chain (flown)", "m")),
        "sim_dead_reckoning_end_m" => Some(("end error, dead reckoning (flown)", "m")),
        "sim_all_links_end_m" => Some(("end error, all links (flown)", "m")),
        "sim_tracking_rms_m" => Some(("worst tracking RMS (flown)", "m")),
        "sim_below_floor" => Some(("flight samples under the floor", "samples")),
        "sim_below_clearance" => Some(("flight samples below the floor clearance", "samples")),
        "sim_planned_links_received" => {
            Some(("planned pings received (flown)", "fraction of pings"))
        }
        "sim_linked_fraction" => Some((
            "epochs every AUV reaches the USV by received pings",
            "fraction of epochs",
        )),
        "sim_min_separation_m" => Some(("closest two AUVs (flown)", "m")),
        _ => None,
    };
    let (what, unit) = known.unwrap_or_else(|| ("", unit_of(name)));
    let title = if what.is_empty() {
        name.to_string()
    } else {
        format!("{name}: {what}")
    };
    (title, unit.to_string())
}

/// A column's unit from its name's suffix.
fn unit_of(name: &str) -> &'static str {
    [
        ("_km2", "km²"),
        ("_mps", "m/s"),
        ("_radps", "rad/s"),
        ("_m", "m"),
        ("_s", "s"),
        ("_fraction", "fraction"),
    ]
    .iter()
    .find(|(s, _)| name.ends_with(s))
    .map_or("value", |(_, u)| u)
}
