//! What a plan tells its user beyond PASS: the warnings of `plan.json` and stderr. A plan can
//! pass every check and still be a poor mission; each warning says what happened, why, and
//! which setting to change.
//!
//! - A stage that did not converge: feasible, not the optimum of its window.
//! - A team that barely moves (issue 14): with OF1_8 ("away") the USV ends a window less than
//!   [`BARELY_MOVES`] of the way a formation could go, i.e. the team's terms outweigh the USV's.
//! - The grid's edge: a vehicle comes within one step's travel of the edge of the seafloor
//!   grid, which the plan cannot cross; a long mission then turns along it or stops.
//! - Implausible values: a setting far outside what a REMUS 100-class vehicle, its modem or the
//!   paper uses, most likely a unit slip ([`crate::scenario::plausible`]).
//! - More AUVs than lanes: every AUV stays within d_max of the USV (C1_5), so a window's
//!   swaths lie in a corridor 2·d_max wide; a team of more than 2·d_max / swath AUVs overlaps
//!   lanes already swept, and a window explores little more than a smaller team would.

use crate::plan::Window;
use crate::scenario::{Scenario, UsvObjective};
use crate::seafloor::Seafloor;

/// Share of the distance a formation could cover in a window (K·δ at the slower of the USV's
/// and the AUVs' speed limits) below which the team "barely moves".
pub const BARELY_MOVES: f64 = 0.1;

/// Every warning of a plan's windows, in window order.
pub fn warnings(windows: &[Window], s: &Scenario, floor: &Seafloor) -> Vec<String> {
    let mut out = crate::scenario::plausible::warnings(s);
    out.extend(more_auvs_than_lanes(s));
    out.extend(courses_unused(s));
    out.extend(unconverged(windows, s));
    out.extend(current_grids(s));
    for w in windows {
        let edge = grid_edge(w, s, floor);
        out.extend(barely_moves(w, s, edge.is_some()));
        out.extend(edge);
    }
    out
}

/// The planner plans in the current of `[current]`'s velocity and profile; grid files it does
/// not read (`sim::current::planned`): say that this plan is made in still water.
fn current_grids(s: &Scenario) -> Option<String> {
    (s.current.file_east.is_some() || s.current.file_north.is_some()).then(|| {
        "current.file_east/file_north: the planner does not read current grids; this plan is \
         made in still water, and `shoal simulate` flies it in the grids' current"
            .to_string()
    })
}

/// The number of swath-wide lanes in the corridor 2·d_max wide in which C1_5 keeps the team,
/// or None when the swath is not positive (no explored area is measured).
pub fn lanes(s: &Scenario) -> Option<usize> {
    let w = s.auv.swath_width;
    (w > 0.0 && w.is_finite()).then(|| (2.0 * s.acoustic.max_range / w).floor() as usize)
}

/// The warning for a team larger than the corridor's [`lanes`] (seed 4 of the default
/// scenario explores 1.666 km² with 20 AUVs and 1.640 km² with 30: BENCHMARKS.md).
fn more_auvs_than_lanes(s: &Scenario) -> Option<String> {
    let lanes = lanes(s)?;
    let n = s.team.auvs;
    (n > lanes).then(|| {
        format!(
            "{n} AUVs for {lanes} lanes: every AUV stays within acoustic.max_range = {} m of the \
             USV (C1_5), so a window's swaths (auv.swath_width = {} m) lie in a corridor {} m \
             wide, room for {lanes} side by side; the other AUVs sweep lanes already swept, and \
             a window explores little more than with {lanes} AUVs (raise acoustic.max_range, or \
             plan more windows)",
            s.acoustic.max_range,
            s.auv.swath_width,
            2.0 * s.acoustic.max_range,
        )
    })
}

/// The warning for `usv.courses` > 1 with a destination: the first guess heads for it, and no
/// course is tried.
fn courses_unused(s: &Scenario) -> Option<String> {
    (s.usv.courses > 1 && s.usv.objective == UsvObjective::Destination).then(|| {
        format!(
            "usv.courses = {} has no effect with usv.objective = \"destination\": the first \
             guess heads for usv.destination, and no other course is tried",
            s.usv.courses
        )
    })
}

/// A warning for every stage that did not converge: its plan is feasible, not the optimum.
fn unconverged(windows: &[Window], s: &Scenario) -> Vec<String> {
    let mut out = Vec::new();
    for w in windows {
        for (name, st, step1) in [
            ("step 1 (P2)", &w.step1, true),
            ("step 3 (P5)", &w.final_, false),
        ] {
            // the keys that set this stage's limit and tolerance (`Scp::step1`)
            let scp = &s.scp;
            let limit = match scp.step1_max_iterations.filter(|_| step1) {
                Some(n) => format!("scp.step1_max_iterations = {n}"),
                None => format!("scp.max_iterations = {}", scp.max_iterations),
            };
            let tolerance = match scp.step1_tolerance.filter(|_| step1) {
                Some(t) => format!("scp.step1_tolerance = {t}"),
                None => format!("scp.tolerance = {}", scp.tolerance),
            };
            let why = match st.status.as_str() {
                "converged" | crate::plan::SAMPLED => continue,
                "max_iterations" => format!(
                    "stopped at {limit} before its predicted decrease fell below {tolerance}"
                ),
                "stalled" => format!(
                    "stalled: its trust region shrank below scp.min_trust_region = {} m (or its \
                     penalty reached its limit) before its predicted decrease fell below \
                     {tolerance}",
                    s.scp.min_trust_region
                ),
                "solver_trouble" => "stopped: the convex solver (Clarabel) ended in numerical \
                                     trouble at every trust radius tried"
                    .to_string(),
                other => format!("ended with status {other}"),
            };
            out.push(format!(
                "window {}: {name} {why} after {} SCP iterations; the plan is feasible (it \
                 passes its check) but not the optimum of its window",
                w.index, st.iterations
            ));
        }
    }
    out
}

/// The warning for a window whose USV ends less than [`BARELY_MOVES`] of [`Scenario::reach`] from its
/// start although its objective asks it to move: away from its track, or towards a destination
/// it has not reached. `at_edge`: the grid's edge explains it (its own warning follows).
fn barely_moves(w: &Window, s: &Scenario, at_edge: bool) -> Option<String> {
    let usv = &w.final_.usv.position;
    let (first, last) = (usv.first()?, usv.last()?);
    let moved = (last[0] - first[0]).hypot(last[1] - first[1]);
    let reach = s.reach();
    let weights = &s.weights;
    let (wanted, term) = match s.usv.objective {
        UsvObjective::Away if s.w8() != weights.w8 => (
            reach,
            format!(
                "OF1_8 (move away, weights.w8 = {} × {:.3} for this window's K·δ², weights.w8_scaling)",
                weights.w8,
                s.w8() / weights.w8
            ),
        ),
        UsvObjective::Away => (
            reach,
            format!("OF1_8 (move away, weights.w8 = {})", weights.w8),
        ),
        UsvObjective::Destination => {
            let d = s.usv.destination;
            let to_go = (d[0] - first[0]).hypot(d[1] - first[1]);
            (
                reach.min(to_go),
                format!("OF1_8_2 (destination, weights.w8_2 = {})", weights.w8_2),
            )
        }
    };
    if moved >= BARELY_MOVES * wanted || !moved.is_finite() || at_edge {
        return None;
    }
    if !w.converged() {
        // the weights may not be to blame: the SCP stopped short of the window's optimum
        return Some(format!(
            "window {}: the team barely moves: the USV ends {moved:.0} m from where the window \
             started, {:.0} % of the {wanted:.0} m it could go, and the window's SCP did not \
             converge (see its warning): raise scp.max_iterations, or see the weights w1, w2 \
             and {term} if it still does not move",
            w.index,
            100.0 * moved / wanted,
        ));
    }
    let scaling = match s.weights.scaling {
        crate::scenario::WeightScaling::Sum => {
            "; with weights.scaling = \"sum\" the team's terms grow with N while the USV's \
             does not (\"per_auv\" weighs them per AUV)"
        }
        crate::scenario::WeightScaling::PerAuv => "",
    };
    let per_m2 = match (s.usv.objective, s.weights.w8_scaling) {
        (UsvObjective::Away, crate::scenario::W8Scaling::None) => {
            "; with weights.w8_scaling = \"none\" OF1_8 is per m², so a window of few or \
             short steps is paid little for the energy its way costs (\"energy\" pays it as \
             the paper's window)"
        }
        _ => "",
    };
    Some(format!(
        "window {}: the team barely moves: the USV ends {moved:.0} m from where the window \
         started, {:.0} % of the {wanted:.0} m it could go; the team's input energy \
         (weights.w1 = {}) and height above the floor (weights.w2 = {}) outweigh {term}: raise \
         the latter or lower the former{scaling}{per_m2}",
        w.index,
        100.0 * moved / wanted,
        weights.w1,
        weights.w2,
    ))
}

/// The warning for a window in which a vehicle comes within one step's travel (δ at its speed
/// limit) of the grid's edge, which no plan can cross: the nearest such waypoint and the edge.
fn grid_edge(w: &Window, s: &Scenario, floor: &Seafloor) -> Option<String> {
    let e = floor.extent();
    let step = s.horizon.dt * s.usv.max_speed.max(s.auv.max_speed);
    // every horizontal waypoint with its vehicle: None the USV, Some(n) AUV n
    let usv = w.final_.usv.position.iter().map(|p| (None, *p));
    let auvs = (w.final_.auvs.iter().enumerate())
        .flat_map(|(n, a)| a.position.iter().map(move |p| (Some(n), [p[0], p[1]])));
    let mut nearest: Option<(f64, Option<usize>, &str, &str, f64)> = None;
    for (who, p) in usv.chain(auvs) {
        for (gap, side, axis, at) in [
            (p[0] - e.x_min, "west", "x", e.x_min),
            (e.x_max - p[0], "east", "x", e.x_max),
            (p[1] - e.y_min, "south", "y", e.y_min),
            (e.y_max - p[1], "north", "y", e.y_max),
        ] {
            if gap < step && nearest.map_or(true, |n| gap < n.0) {
                nearest = Some((gap, who, side, axis, at));
            }
        }
    }
    let (gap, who, side, axis, at) = nearest?;
    let who = who.map_or("the USV".to_string(), |n| format!("AUV {n}"));
    Some(format!(
        "window {}: the grid's edge stops the team: {who} comes within {gap:.0} m of the \
         grid's {side} edge ({axis} = {at:.0} m), closer than one step's travel ({step:.0} m), \
         and no plan leaves the grid; the mission turns along the edge or stops. Load a larger \
         grid (seafloor.file, seafloor.synthetic.size) or give the USV a destination inside \
         it (usv.objective = \"destination\")",
        w.index
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_team_larger_than_the_corridors_lanes_is_told_so() {
        let mut s = Scenario::default();
        // d_max = 400 m, swath 50 m: 16 lanes
        assert_eq!(lanes(&s), Some(16));
        s.team.auvs = 16;
        assert_eq!(more_auvs_than_lanes(&s), None);
        s.team.auvs = 17;
        let w = more_auvs_than_lanes(&s).expect("a warning");
        assert!(w.starts_with("17 AUVs for 16 lanes"), "{w}");
        assert!(w.contains("acoustic.max_range = 400"), "{w}");
        s.auv.swath_width = 0.0;
        assert_eq!(more_auvs_than_lanes(&s), None);
    }

    #[test]
    fn courses_with_a_destination_are_told_they_do_nothing() {
        let mut s = Scenario::default();
        s.usv.courses = 8;
        assert_eq!(courses_unused(&s), None);
        s.usv.objective = UsvObjective::Destination;
        let w = courses_unused(&s).expect("a warning");
        assert!(w.starts_with("usv.courses = 8 has no effect"), "{w}");
        s.usv.courses = 1;
        assert_eq!(courses_unused(&s), None);
    }
}
