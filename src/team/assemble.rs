//! The convex model of the window problem about a reference trajectory, as Clarabel data: the
//! one place that puts the constraint families together, in cone order. The sequence of
//! (row, column) entries never depends on values, so the pattern built at the first iteration
//! serves every later one (only values change), except the separation rows' (`separation`):
//! their set of pairs grows when a reference brings more pairs near, and the solver is then
//! built again.
//!
//! - objective: OF2's model (`objective`), the slacks' prices (`floor`, `heading`, `keep_out`,
//!   `links`), the linearised OF1_5 (`spread`) and the lanes term (`lanes`), the last three
//!   P5's only;
//! - zero cone: the dynamics C1_1 (`dynamics`);
//! - nonnegative cone: C1_4 and the grid bounds (`bounds`), the linearised floor clearance C2_2
//!   (`floor`), the USV's and the links' keep-out rows (`keep_out`, over a grid with obstacles),
//!   C1_14's Turn rows (`heading`), the bands' lower ends (`links`), the bridges' line of sight
//!   (`bridges`), the lanes' shortfalls (`lanes`), the vehicle's envelope (`depth`, `climb`,
//!   `cruise`), the AUVs' separation half-spaces (`separation`), slacks ν ≥ 0;
//! - second-order cones: the speed limits (`speed`), C1_5/C1_6 (`ranges`), the trust region
//!   and the AUVs' squared steps τ (`trust`), C1_14's slow alternatives (`heading`), the bands' upper ends (`links`), the
//!   bridges' ranges (`bridges`).

use super::model::Assembly;
use super::{bounds, bridges, dynamics, floor, heading, keep_out, links, objective, ranges};
use super::{climb, cruise, depth, lanes, separation, speed, spread, trust, TeamProblem};
use crate::error::PlanError;
use crate::trajectory::Trajectory;
use clarabel::solver::SupportedConeT::NonnegativeConeT;

/// The model of `p` about the reference `r` with trust radius `radius` and slack price
/// `penalty`.
pub(super) fn assemble(
    p: &TeamProblem,
    r: &Trajectory,
    radius: f64,
    penalty: f64,
) -> Result<Assembly, PlanError> {
    let l = p.layout;
    let (kk, nn) = (l.k, l.n);
    let mut m = Assembly::new(l.variables());

    // ---- objective ----
    objective::model(p, r, &mut m);
    floor::objective(p, &mut m, penalty);
    trust::objective(p, &mut m);
    heading::objective(p, &mut m, penalty);
    keep_out::objective(p, &mut m, penalty);
    links::objective(p, &mut m); // Step 3 only
    bridges::objective(p, &mut m, penalty); // Step 3 only
    spread::objective(p, r, &mut m); // Step 3 only
    depth::objective(p, &mut m, penalty);
    climb::objective(p, &mut m, penalty);
    cruise::objective(p, &mut m, penalty);
    separation::objective(p, &mut m, penalty);

    // ---- zero cone ----
    dynamics::rows(p, r, &mut m);

    // ---- nonnegative cone ----
    let first = m.b.len();
    let ext = p.floor.extent();
    for n in 0..nn {
        for k in 1..=kk {
            bounds::underwater(p, &mut m, n, k);
            // the trust region keeps an AUV within Δ of the reference, horizontally
            let a = r.auv_p[n][k];
            bounds::grid(&mut m, l.auv_p(n, k), &ext, [a[0], a[1]], radius);
        }
    }
    // the speed limit keeps the USV within k·δ·v_max of the window's start
    let usv_reach = p.scenario.horizon.dt * p.scenario.usv.max_speed;
    for k in 1..=kk {
        let reach = k as f64 * usv_reach;
        bounds::grid(&mut m, l.usv_p(k), &ext, p.start.usv, reach);
    }
    let bent = floor::rows(p, r, &mut m, radius)?;
    trust::proximal(p, &mut m, r, &bent);
    keep_out::usv_rows(p, r, &mut m)?; // over a grid with obstacles
    keep_out::los_rows(p, r, &mut m)?; // Step 3, over every grid
    let pieces = heading::pieces(p, r);
    heading::rows(p, r, &pieces, &mut m);
    heading::shared_rows(p, &pieces, &mut m);
    for n in 0..nn {
        bounds::terminal(p, &mut m, n, &ext);
    }
    links::lower_rows(p, r, &mut m); // Step 3 only
    bridges::rows(p, r, &mut m)?; // Step 3 only
    lanes::rows(p, r, &mut m); // Step 3 only, with its lanes
    depth::rows(p, &mut m);
    climb::rows(p, r, &mut m);
    cruise::rows(p, r, &mut m);
    separation::rows(p, r, &mut m); // the pairs near enough to matter, and the slacks
    for n in 0..nn {
        for k in 1..=kk {
            m.nonnegative(l.floor_slack(n, k));
            m.nonnegative(l.heading_slack(n, k));
        }
    }
    for k in 1..=kk {
        if l.obstacles {
            m.nonnegative(l.usv_slack(k));
        }
        for li in 0..l.links {
            m.nonnegative(l.los_slack(li, k));
        }
    }
    m.cones.push(NonnegativeConeT(m.b.len() - first));

    // ---- second-order cones ----
    for k in 0..kk {
        speed::usv(p, &mut m, k);
    }
    for n in 0..nn {
        for k in 1..=kk {
            speed::auv(p, &mut m, n, k);
            ranges::auv(p, &mut m, n, k);
            trust::auv(p, &mut m, r, radius, n, k);
            trust::squared_steps(p, &mut m, r, &bent, n, k);
        }
    }
    if l.obstacles {
        // the USV's keep-out rows are linearised too: trust region on its positions
        for k in 1..=kk {
            trust::usv(p, &mut m, r, radius, k);
        }
    } else if p.away_from_a_track() {
        // OF1_8 measured from a track of several points is not concave (a minimum over its
        // segments), so its linearisation is no majorant: near a turn of the track it promises
        // a decrease at any distance. Trust it only within Δ of the reference's P_USV[K].
        trust::usv(p, &mut m, r, radius, kk);
    }
    heading::cones(p, &pieces, &mut m);
    links::upper_cones(p, &mut m); // Step 3 only
    bridges::cones(p, &mut m); // Step 3 only
    Ok(m)
}
