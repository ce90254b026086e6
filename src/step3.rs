//! Step 3 of Section IV-A: problem P5 and the line-of-sight loop (Algorithm 1, lines 17–22).
//!
//!   OF5:  min OF2 + Σ_k w5·OF1_5 (OF1_5 rewarded: non-adjacent AUVs spread out)
//!   s.t.  C5_1 = Step 1's constraints (dynamics, ranges, speeds, floor along segments, heading)
//!         C5_2, C5_3: every planned link's length in its band [d_s − d_t, d_s]
//!
//! P5 is the window problem of `team` with Step 2's links added (its link bands in
//! `team::links`, OF1_5 in `team::spread`, the links' keep-out rows in `team::keep_out`), solved
//! by the same SCvx loop, starting from Step 1's plan. What is Step 3's own is the loop round it:
//! - The bands are soft (`team::links`); every (step, link) left outside its band is reported in
//!   the plan (`links.out_of_band`). The hard requirement, that every AUV reaches the USV through
//!   links in range and in line of sight at every step, is verified after the loop (`planner`,
//!   with `metrics::first_cut_off`) and by `shoal check`.
//! - Line of sight (C1_13) is first a constraint of P5 itself, linearised rows over the
//!   keep-out field with a penalised slack (`team::keep_out`): lowering a band cannot clear a
//!   ridge between two AUVs. Then, as in the paper, after each P5 solve every planned link is tested with the seafloor's
//!   𝓛_r query over the keep-out field (`Seafloor::keep_out`), so a link over an obstacle cell
//!   (NODATA or land) is blocked as one under the floor is; a blocked link has its band's upper end lowered by `acoustic.los_shrink` (and
//!   the lower end with it when the band would close) and P5 is solved again from the last
//!   plan, at most `acoustic.los_rounds` times.

use crate::conic::SolveReport;
use crate::error::PlanError;
use crate::plan::{Band, OutOfBand};
use crate::scp::{Iteration, ScpOutcome};
use crate::seafloor::Seafloor;
use crate::team::{self, describe, LinkSet, TeamProblem};
use crate::trajectory::Trajectory;

/// What Step 3 returns for a window.
pub struct Step3 {
    /// The last round's SCP outcome.
    pub outcome: ScpOutcome<Trajectory>,
    /// The links with the bands of the last round.
    pub links: LinkSet,
    /// Rounds of the line-of-sight loop (P5 solves).
    pub los_rounds: usize,
    /// Every (step, link) left outside its band.
    pub out_of_band: Vec<OutOfBand>,
    /// SCP iterations summed over the rounds.
    pub iterations: usize,
}

/// Solve P5 for `problem` (built with links) from Step 1's plan, with the line-of-sight loop;
/// `observer` hears of every SCP iteration of every round.
pub fn solve(
    problem: &mut TeamProblem,
    step1: &Trajectory,
    observer: &mut dyn FnMut(&Iteration<SolveReport>),
) -> Result<Step3, PlanError> {
    let acoustic = &problem.scenario().acoustic;
    let (r, shrink, max_rounds) = (
        acoustic.resolution,
        acoustic.los_shrink,
        acoustic.los_rounds,
    );
    let mut reference = step1.clone();
    let mut iterations = 0;
    let mut round = 0;
    loop {
        round += 1;
        let out = problem.solve(reference, observer)?;
        iterations += out.iterations;
        let (floor, keep_out) = (problem.floor(), problem.keep_out());
        let blocked = match problem.links() {
            Some(set) => blocked_links(floor, keep_out, set, &out.iterate, r),
            None => Vec::new(),
        };
        let Some(set) = problem.links_mut() else {
            // without links this is P2: nothing to keep in sight
            return Ok(Step3 {
                links: LinkSet {
                    links: vec![],
                    bands: vec![],
                },
                los_rounds: round,
                out_of_band: vec![],
                iterations,
                outcome: out,
            });
        };
        if blocked.is_empty() {
            let links = set.clone();
            let out_of_band = out_of_band(&links, &out.iterate);
            return Ok(Step3 {
                outcome: out,
                links,
                los_rounds: round,
                out_of_band,
                iterations,
            });
        }
        if round >= max_rounds {
            let (k, li, why) = &blocked[0];
            return Err(PlanError::LineOfSight {
                link: describe(set.links[*k][*li]),
                k: *k,
                rounds: round,
                why: why.clone(),
            });
        }
        lower_bands(set, &blocked, shrink);
        reference = out.iterate;
    }
}

/// Algorithm 1, line 20: lower the upper end of every blocked link's band by `shrink` (the
/// lower end follows when the band would close), so the next P5 pulls its ends closer.
fn lower_bands(set: &mut LinkSet, blocked: &[(usize, usize, String)], shrink: f64) {
    for (k, li, _) in blocked {
        let band = &mut set.bands[*k][*li];
        band.hi = (band.hi - shrink).max(0.0);
        band.lo = band.lo.min(band.hi);
    }
}

/// (k, link index, why) of every planned link at k = 1..=K without line of sight over the
/// keep-out field `keep_out` of `floor` (`floor` names the obstacle in the reason).
fn blocked_links(
    floor: &Seafloor,
    keep_out: &Seafloor,
    set: &LinkSet,
    t: &Trajectory,
    resolution: f64,
) -> Vec<(usize, usize, String)> {
    let mut out = Vec::new();
    for k in 1..set.links.len() {
        for (li, &link) in set.links[k].iter().enumerate() {
            let (a, b) = team::ends(t, k, link);
            match keep_out.segment_clearance(a, b, resolution) {
                Ok(c) if c.min_clearance >= 0.0 => {}
                Ok(c) => {
                    let why = match floor.segment_obstacle(a, b, resolution) {
                        Ok(Some(o)) => format!(
                            "the line crosses ({:.1}, {:.1}, {:.1}), which is {}",
                            o.at[0], o.at[1], o.at[2], o.obstacle
                        ),
                        _ => {
                            let raised = keep_out.elevation(c.at[0], c.at[1]).ok()
                                > floor.elevation(c.at[0], c.at[1]).ok();
                            format!(
                                "the floor{} rises {:.1} m above the line at ({:.1}, {:.1}, {:.1})",
                                if raised {
                                    " (raised next to an obstacle cell)"
                                } else {
                                    ""
                                },
                                -c.min_clearance,
                                c.at[0],
                                c.at[1],
                                c.at[2]
                            )
                        }
                    };
                    out.push((k, li, why));
                }
                Err(e) => out.push((k, li, e.to_string())),
            }
        }
    }
    out
}

/// Every (step, link) of k = 1..=K whose length is outside its band by more than 1 mm.
pub(crate) fn out_of_band(set: &LinkSet, t: &Trajectory) -> Vec<OutOfBand> {
    let mut out = Vec::new();
    for k in 1..set.links.len() {
        for (&link, &band) in set.links[k].iter().zip(&set.bands[k]) {
            let length = team::length(t, k, link);
            if team::outside(length, band) > 1e-3 {
                out.push(OutOfBand {
                    k,
                    link,
                    length,
                    band: Band { ..band },
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::{Graph, Link};

    /// A floor at −100 m with a ridge rising to −20 m along x = 0.
    fn ridge() -> Seafloor {
        let (n, c, x0) = (41usize, 25.0, -500.0);
        let z = (0..n * n)
            .map(|i| {
                let x = x0 + (i % n) as f64 * c;
                if x.abs() < 30.0 {
                    -20.0
                } else {
                    -100.0
                }
            })
            .collect();
        let lattice = crate::seafloor::Lattice::new(n, n, x0, x0, c, c);
        Seafloor::from_nodes(lattice, z, vec![false; n * n]).unwrap()
    }

    /// Two AUVs at −60 m on either side of the ridge, the USV above AUV 0; one step.
    fn team() -> (Trajectory, LinkSet) {
        let t = Trajectory {
            usv_p: vec![[-100.0, 0.0]; 2],
            usv_u: vec![[0.0; 2]],
            auv_p: vec![vec![[-70.0, 0.0, -60.0]; 2], vec![[70.0, 0.0, -60.0]; 2]],
            auv_v: vec![vec![[0.0; 3]; 2]; 2],
            auv_u: vec![vec![[0.0; 3]]; 2],
        };
        let g = Graph {
            a2u: vec![0, 0],
            a2a: vec![vec![[0, 1]]; 2],
            exact: true,
            solve_time_s: 0.0,
        };
        (t, LinkSet::from_graph(&g, 150.0, 30.0))
    }

    #[test]
    fn the_ridge_blocks_the_a2a_edge_and_only_it() {
        let (t, set) = team();
        let floor = ridge();
        let blocked = blocked_links(&floor, &floor.keep_out(), &set, &t, 5.0);
        assert_eq!(blocked.len(), 1, "{blocked:?}");
        let (k, li, why) = &blocked[0];
        assert_eq!((*k, set.links[*k][*li]), (1, Link { a: 0, b: Some(1) }));
        assert!(why.contains("the floor rises"), "{why}");
        assert_eq!(describe(set.links[1][1]), "A2A edge AUV 0–AUV 1");
    }

    /// A NODATA node at (0, 25) on a flat floor at −100 m: the A2A edge along y = 0 has 40 m
    /// of clearance over the floor but crosses the obstacle cells beside the node, so it is
    /// blocked, and the reason names the obstacle.
    #[test]
    fn an_obstacle_cell_blocks_a_link_with_clearance() {
        let (n, c, x0) = (41usize, 25.0, -500.0);
        let mut nodata = vec![false; n * n];
        nodata[21 * n + 20] = true;
        let lattice = crate::seafloor::Lattice::new(n, n, x0, x0, c, c);
        let floor = Seafloor::from_nodes(lattice, vec![-100.0; n * n], nodata).unwrap();
        let (t, set) = team();
        let blocked = blocked_links(&floor, &floor.keep_out(), &set, &t, 5.0);
        assert_eq!(blocked.len(), 1, "{blocked:?}");
        let (k, li, why) = &blocked[0];
        assert_eq!((*k, set.links[*k][*li]), (1, Link { a: 0, b: Some(1) }));
        assert!(
            why.starts_with("the line crosses (-25.0, 0.0, -60.0), which is over a NODATA cell"),
            "{why}"
        );
        // over the floor alone the same edge would have been clear
        assert!(blocked_links(&floor, &floor, &set, &t, 5.0).is_empty());
    }

    /// Regression (issue 13, sweep draws 18 and 27: "no line of sight … after 5 rounds of
    /// lowering its range"): over a grid without obstacles P5 had no line-of-sight rows, and
    /// lowering a band cannot clear a ridge between two AUVs. With the rows of
    /// `team::keep_out` on every grid, one round is enough: P5 moves the AUVs into sight.
    #[test]
    fn links_regain_sight_over_a_ridge_in_one_round() {
        let mut s = crate::scenario::Scenario::default();
        s.team.auvs = 2;
        s.horizon.steps = 4;
        s.horizon.dt = 60.0;
        s.acoustic.los_rounds = 1;
        // the paper's vehicle in still water: four steps of 60 s leave a REMUS at 1.25 m/s no
        // room to turn back over the ridge (the rounds of line of sight are this test's subject)
        s.auv.min_speed = 0.0;
        s.auv.max_flight_path_angle = crate::scenario::NO_ANGLE_LIMIT;
        s.auv.min_separation = 0.0;
        s.current.velocity = [0.0; 2];
        let floor = ridge();
        let field = floor.keep_out();
        let auv = crate::vehicle::AuvModel::new(&s.auv, s.horizon.dt).unwrap();
        let usv = crate::vehicle::UsvModel {
            dt: s.horizon.dt,
            max_speed: s.usv.max_speed,
        };
        let (one, _) = team();
        let kk = s.horizon.steps;
        let still = Trajectory {
            usv_p: vec![one.usv_p[0]; kk + 1],
            usv_u: vec![[0.0; 2]; kk],
            auv_p: one.auv_p.iter().map(|p| vec![p[0]; kk + 1]).collect(),
            auv_v: vec![vec![[0.0; 3]; kk + 1]; 2],
            auv_u: vec![vec![[0.0; 3]; kk]; 2],
        };
        let start = crate::trajectory::Start {
            usv: still.usv_p[0],
            auvs: still
                .auv_p
                .iter()
                .map(|p| crate::plan::AuvState {
                    position: p[0],
                    velocity: [0.0; 3],
                })
                .collect(),
        };
        let graph = Graph {
            a2u: vec![0; kk + 1],
            a2a: vec![vec![[0, 1]]; kk + 1],
            exact: true,
            solve_time_s: 0.0,
        };
        // the reference's A2A edge is blocked at every step
        let set = LinkSet::from_graph(&graph, 150.0, 30.0);
        assert_eq!(blocked_links(&floor, &field, &set, &still, 5.0).len(), kk);
        let mut problem = TeamProblem::new(&s, &floor, &field, auv, usv, start).with_links(set);
        let out = solve(&mut problem, &still, &mut |_| {}).expect("P5 keeps the edge in sight");
        assert_eq!(out.los_rounds, 1);
        let clear = blocked_links(&floor, &field, &out.links, &out.outcome.iterate, 5.0);
        assert!(clear.is_empty(), "{clear:?}");
    }

    #[test]
    fn a_blocked_links_band_is_lowered_and_stays_a_band() {
        let (t, mut set) = team();
        let floor = ridge();
        let blocked = blocked_links(&floor, &floor, &set, &t, 5.0);
        lower_bands(&mut set, &blocked, 15.0);
        assert_eq!(
            set.bands[1][1],
            Band {
                lo: 120.0,
                hi: 135.0
            }
        );
        assert_eq!(
            set.bands[1][0],
            Band {
                lo: 120.0,
                hi: 150.0
            }
        ); // the A2U link is clear
        for _ in 0..3 {
            lower_bands(&mut set, &blocked, 15.0);
        }
        assert_eq!(set.bands[1][1], Band { lo: 90.0, hi: 90.0 });
    }
}
