//! A study's `simulate = true`: each run's plan is also flown once (`shoal simulate`, its seed
//! the scenario's) and the row records what localization it gives: the flight's worst tracking,
//! whether it touched the floor, and the team's position error at the mission's end under dead
//! reckoning, the planned chain and every link (factor graph).

use super::columns::Kind;
use crate::plan::Plan;
use crate::seafloor::Seafloor;
use crate::sim::policy::Policy;
use crate::sim::record::SimRecord;

/// The columns a simulated run adds, after the row's.
pub const COLUMNS: [&str; 10] = [
    "sim_status",
    "sim_tracking_rms_m",
    "sim_below_floor",
    "sim_dead_reckoning_end_m",
    "sim_chain_end_m",
    "sim_all_links_end_m",
    "sim_planned_links_received",
    "sim_linked_fraction",
    "sim_min_separation_m",
    "sim_below_clearance",
];

/// The type of each of [`COLUMNS`].
pub const KINDS: [Kind; 10] = [
    Kind::Text,
    Kind::Real,
    Kind::Int,
    Kind::Real,
    Kind::Real,
    Kind::Real,
    Kind::Real,
    Kind::Real,
    Kind::Real,
    Kind::Int,
];

/// The simulation's fields of a run: its plan flown over its floor, or why not ("no plan",
/// or the simulation's error), NaN where there is no number.
pub fn fields(plan: Option<&Plan>, floor: Option<&Seafloor>) -> Vec<String> {
    let nan = || f64::NAN.to_string();
    let (Some(plan), Some(floor)) = (plan, floor) else {
        return std::iter::once("no plan".to_string())
            .chain((1..COLUMNS.len()).map(|_| nan()))
            .collect();
    };
    match crate::sim::simulate(plan, "sweep", floor, plan.scenario.seed) {
        Ok(r) => measured(&r),
        Err(e) => std::iter::once(format!("failed: {e}"))
            .chain((1..COLUMNS.len()).map(|_| nan()))
            .collect(),
    }
}

fn measured(r: &SimRecord) -> Vec<String> {
    let m = &r.flight.metrics;
    let tracking = m.tracking_rms_m.iter().copied().fold(f64::NAN, f64::max);
    let end = |p: Policy| {
        r.estimates
            .iter()
            .find(|e| e.flown == "final" && e.policy == p && e.estimator == "factor_graph")
            .and_then(|e| e.metrics.window_end_rmse_m.last().copied())
            .unwrap_or(f64::NAN)
    };
    vec![
        "flown".into(),
        tracking.to_string(),
        m.samples_below_floor.to_string(),
        end(Policy::DeadReckoning).to_string(),
        end(Policy::Chain).to_string(),
        end(Policy::AllLinks).to_string(),
        m.planned_links_received.to_string(),
        m.linked_fraction.to_string(),
        m.min_separation_m.to_string(),
        m.samples_below_clearance.to_string(),
    ]
}
