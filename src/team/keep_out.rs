//! Keep-out rows of the team problem: the USV's over a grid with obstacles (NODATA or land
//! cells; see `Seafloor::keep_out` for the keep-out field, in which every obstacle cell lies
//! at least `KEEP_OUT_LIFT` above the surface, and which is the floor itself over a grid
//! without them), and P5's line of sight over every grid:
//!
//! - the USV keeps the field `KEEP_OUT_MARGIN` below the surface along its segments
//!   (`usv_rows`, over a grid with obstacles);
//! - in P5 (Step 3), every planned link keeps line of sight over the field, C1_13 as
//!   linearised rows (`los_rows`), `KEEP_OUT_MARGIN` above it at its interior samples. A link
//!   with a ridge or an obstacle between its ends cannot regain its line of sight by being
//!   shortened, which is all the loop of Algorithm 1 (lines 17–22) does: the two AUVs must
//!   rise over it or move round it, and only a constraint in P5 makes them. (Over a grid
//!   without obstacles these rows were once left out, and the sweep of issue 13 found
//!   feasible missions refused after five rounds of lowering bands.)
//!
//! Both are linearised about the reference at the samples of 𝓛_r, the `USV_ROWS` (USV) or
//! `LOS_ROWS` (link) samples with the largest g getting a row sharing one slack per segment,
//! like the AUVs' floor rows; the SCP measures the true violation at every sample
//! (`violations`). Step 1 (P2, no links) over a grid without obstacles has none of this.

use super::floor::{apart, pick_samples};
use super::links::{describe, end_columns, ends};
use super::model::{Assembly, INACTIVE};
use super::{TeamProblem, OBSTACLE};
use crate::error::PlanError;
use crate::linearise::{floor_sample, lerp, segment_intervals};
use crate::plan::Link;
use crate::trajectory::Trajectory;

/// Margin (metres) by which the USV keeps the keep-out field below the surface, and a link
/// above it. Unlike the AUVs' `FLOOR_MARGIN`, which only the convex model asks for, it is part
/// of the constraint the SCP measures too: the model then agrees with the measure at the
/// reference, as SCvx needs. With the margin in the model only, a violated reference looks
/// `margin` × penalty worse to the model than to the measure, and once the penalty grows the
/// model can predict no decrease at all: the USV was seen stuck in a hole so.
const KEEP_OUT_MARGIN: f64 = 0.25;

/// Keep-out rows per USV segment (over a grid with obstacles): 12, as the AUVs' floor rows
/// had before `floor::FLOOR_ROWS` became 6 (the USV's rows have no curvature term and no
/// rows for the samples a rejected candidate broke).
const USV_ROWS: usize = 12;

/// Line-of-sight rows per planned link and step (fewer than `USV_ROWS`: links are at most d_s
/// long, and there are N of them per step).
const LOS_ROWS: usize = 6;

/// A keep-out violation: which segment.
#[derive(Debug, Clone, Copy)]
pub(super) enum KeepOut {
    /// The USV between steps k − 1 and k, at the point.
    Usv { k: usize, at: [f64; 3] },
    /// Planned link `li` at step k, at the point.
    Link { k: usize, li: usize, at: [f64; 3] },
}

/// The keep-out slacks' price (over a grid with obstacles): the SCP's penalty λ per metre.
pub(super) fn objective(p: &TeamProblem, m: &mut Assembly, penalty: f64) {
    let l = p.layout;
    for k in 1..=l.k {
        if l.obstacles {
            m.penalise(l.usv_slack(k), 1.0, penalty);
        }
        for li in 0..l.links {
            m.penalise(l.los_slack(li, k), 1.0, penalty);
        }
    }
}

/// See the module docs. Rows touch only P_USV[k−1] and P_USV[k], so the pattern is fixed.
pub(super) fn usv_rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) -> Result<(), PlanError> {
    let l = p.layout;
    if !l.obstacles {
        return Ok(());
    }
    let at = |k: usize| p.inside([r.usv_p[k][0], r.usv_p[k][1], 0.0]);
    for k in 1..=l.k {
        let p0 = (k == 1).then_some([p.start.usv[0], p.start.usv[1], 0.0]);
        let rows = sample_rows(p, at(k - 1), at(k), KEEP_OUT_MARGIN, USV_ROWS, true, p0)?;
        for (t, c, rhs) in rows {
            let row = m.row(rhs);
            if k > 1 {
                for i in 0..2 {
                    m.a.push(row, l.usv_p(k - 1) + i, (1.0 - t) * c[i]);
                }
            }
            for i in 0..2 {
                m.a.push(row, l.usv_p(k) + i, t * c[i]);
            }
            m.a.push(row, l.usv_slack(k), -1.0);
        }
    }
    Ok(())
}

/// See the module docs: per planned link and step, the keep-out field at least
/// `KEEP_OUT_MARGIN` below the link at its interior samples (the ends are held by the floor
/// rows and the USV's rows). Rows touch the link's two ends.
pub(super) fn los_rows(p: &TeamProblem, r: &Trajectory, m: &mut Assembly) -> Result<(), PlanError> {
    let l = p.layout;
    let Some(set) = p.links.as_ref() else {
        return Ok(());
    };
    for k in 1..=l.k {
        for (li, &link) in set.links[k].iter().enumerate() {
            link_rows(p, r, m, k, link, l.los_slack(li, k))?;
        }
    }
    Ok(())
}

/// The line-of-sight rows of `link` at step k, linearised about `r`, sharing the slack in
/// column `slack` (a planned link's here, a bridge's in `bridges`).
pub(super) fn link_rows(
    p: &TeamProblem,
    r: &Trajectory,
    m: &mut Assembly,
    k: usize,
    link: Link,
    slack: usize,
) -> Result<(), PlanError> {
    let l = p.layout;
    let (a, b) = ends(r, k, link);
    let (a, b) = (p.inside(a), p.inside(b));
    let rows = sample_rows(p, a, b, KEEP_OUT_MARGIN, LOS_ROWS, false, None)?;
    let (ca, cb) = (end_columns(l, k, Some(link.a)), end_columns(l, k, link.b));
    for (t, c, rhs) in rows {
        let row = m.row(rhs);
        for i in 0..3 {
            if let Some(col) = ca[i] {
                m.a.push(row, col, (1.0 - t) * c[i]);
            }
            if let Some(col) = cb[i] {
                m.a.push(row, col, t * c[i]);
            }
        }
        m.a.push(row, slack, -1.0);
    }
    Ok(())
}

/// `count` rows (t, c, rhs) of g = field(x_t, y_t) + margin − z_t ≤ ν linearised about the
/// reference segment a → b at the samples t = j/n of 𝓛_r with the largest g, j = 1..=n
/// (`with_end`) or 1..n: a row reads (1 − t)·c·P_a + t·c·P_b − ν ≤ rhs, c = (∇field, −1).
/// With `fixed_a`, P_a is the window's fixed start and its term is moved into rhs. Missing
/// samples are inactive rows (c = 0, rhs = `INACTIVE`), so that the pattern never
/// changes.
fn sample_rows(
    p: &TeamProblem,
    a: [f64; 3],
    b: [f64; 3],
    margin: f64,
    count: usize,
    with_end: bool,
    fixed_a: Option<[f64; 3]>,
) -> Result<Vec<(f64, [f64; 3], f64)>, PlanError> {
    let n = segment_intervals(a, b, p.scenario.acoustic.resolution);
    let last = if with_end { n } else { n - 1 };
    let mut g = Vec::with_capacity(last);
    for j in 1..=last {
        g.push((
            floor_sample(p.keep_out, margin, a, b, j as f64 / n as f64)?.0,
            j,
        ));
    }
    let picks = pick_samples(&mut g, count, apart(a, b, n));
    (0..count)
        .map(|slot| {
            let Some(&j) = picks.get(slot) else {
                return Ok((0.0, [0.0; 3], INACTIVE));
            };
            let t = j as f64 / n as f64;
            let (gv, grad) = floor_sample(p.keep_out, margin, a, b, t)?;
            let c = [grad[0], grad[1], -1.0];
            // ∇g·x − ν ≤ ∇g·x̄ − g(x̄)
            let p = lerp(a, b, t);
            let mut rhs = c[0] * p[0] + c[1] * p[1] + c[2] * p[2] - gv;
            if let Some(p0) = fixed_a {
                rhs -= (1.0 - t) * (c[0] * p0[0] + c[1] * p0[1] + c[2] * p0[2]);
            }
            Ok((t, c, rhs))
        })
        .collect()
}

/// Every keep-out violation of `t` in metres (the USV's per segment: the field's height
/// above `KEEP_OUT_MARGIN` below the surface; each link's per step: the field's height
/// above `KEEP_OUT_MARGIN` below the link), worst sample of each; empty over a grid without
/// obstacles.
pub(super) fn violations(p: &TeamProblem, t: &Trajectory) -> Vec<(f64, KeepOut)> {
    let l = p.layout;
    let mut out = Vec::new();
    let worst = |a: [f64; 3], b: [f64; 3]| {
        let (clearance, at) = p.keep_out_clearance(a, b);
        (KEEP_OUT_MARGIN - clearance, at)
    };
    for k in 1..=l.k {
        if l.obstacles {
            let [a, b] = [k - 1, k].map(|i| [t.usv_p[i][0], t.usv_p[i][1], 0.0]);
            let (v, at) = worst(a, b);
            out.push((v, KeepOut::Usv { k, at }));
        }
        if let Some(set) = &p.links {
            for (li, &link) in set.links[k].iter().enumerate() {
                let (a, b) = ends(t, k, link);
                let (v, at) = link_violation(p, a, b);
                out.push((v, KeepOut::Link { k, li, at }));
            }
        }
    }
    out
}

/// The line-of-sight violation of the link a → b (a planned link's here, a bridge's in
/// `bridges`): [`link_worst`] at its interior samples, or the whole segment's measure when a
/// sample is off the grid; and where it is worst.
pub(super) fn link_violation(p: &TeamProblem, a: [f64; 3], b: [f64; 3]) -> (f64, [f64; 3]) {
    link_worst(p, a, b).unwrap_or_else(|| {
        let (clearance, at) = p.keep_out_clearance(a, b);
        (KEEP_OUT_MARGIN - clearance, at)
    })
}

/// A link's line-of-sight violation, `KEEP_OUT_MARGIN` less its least clearance over the
/// keep-out field at the interior samples of 𝓛_r, where its rows are (its ends are the
/// vehicles, held by their own constraints: an AUV may fly ε = 0 above the floor); none when
/// a sample is off the grid (the whole segment's measure then applies).
fn link_worst(p: &TeamProblem, a: [f64; 3], b: [f64; 3]) -> Option<(f64, [f64; 3])> {
    let n = segment_intervals(a, b, p.scenario.acoustic.resolution);
    let mut worst = (f64::NEG_INFINITY, a);
    for j in 1..n {
        let (g, _) = floor_sample(p.keep_out, KEEP_OUT_MARGIN, a, b, j as f64 / n as f64).ok()?;
        if g > worst.0 {
            worst = (g, lerp(a, b, j as f64 / n as f64));
        }
    }
    // a link too short to have interior samples keeps its sight
    Some(if n < 2 { (0.0, a) } else { worst })
}

/// The error text of a keep-out violation: the constraint, the vehicle or link, the step,
/// the position and the obstacle.
pub(super) fn detail(p: &TeamProblem, what: KeepOut) -> String {
    let why = |at: [f64; 3]| {
        p.obstacle_text(at)
            .unwrap_or_else(|| "below the floor or off the grid".into())
    };
    match what {
        KeepOut::Usv { k, at } => format!(
            "{OBSTACLE}: the USV between steps {} and {k} passes ({:.1}, {:.1}), which is {}",
            k - 1,
            at[0],
            at[1],
            why(at)
        ),
        KeepOut::Link { k, li, at } => {
            let link = p
                .links
                .as_ref()
                .map_or("link".into(), |s| describe(s.links[k][li]));
            format!(
                "line of sight C1_13 ({OBSTACLE}): the {link} at step {k} passes \
                 ({:.1}, {:.1}, {:.1}), which is {}",
                at[0],
                at[1],
                at[2],
                why(at)
            )
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plan::Graph;
    use crate::scenario::Scenario;
    use crate::scp::ScpProblem;
    use crate::seafloor::Seafloor;
    use crate::team::LinkSet;
    use crate::trajectory::Start;
    use crate::vehicle::{AuvModel, UsvModel};

    /// 1 km × 1 km at −100 m, 25 m cells, a NODATA hole of 60 m about (250, 0).
    fn holed() -> Seafloor {
        let (n, d, o) = (41, 25.0, -500.0);
        let nodata = (0..n * n)
            .map(|k| {
                let (x, y) = (o + (k % n) as f64 * d, o + (k / n) as f64 * d);
                (x - 250.0).hypot(y) <= 60.0
            })
            .collect();
        let lattice = crate::seafloor::Lattice::new(n, n, o, o, d, d);
        Seafloor::from_nodes(lattice, vec![-100.0; n * n], nodata).unwrap()
    }

    /// One AUV, K = 2: the USV and the AUV at the given positions per step, at rest.
    fn team(usv: [[f64; 2]; 3], auv: [[f64; 3]; 3]) -> Trajectory {
        Trajectory {
            usv_p: usv.to_vec(),
            usv_u: vec![[0.0; 2]; 2],
            auv_p: vec![auv.to_vec()],
            auv_v: vec![vec![[0.0; 3]; 3]],
            auv_u: vec![vec![[0.0; 3]; 2]],
        }
    }

    /// The error of an infeasible keep-out constraint names the constraint, the vehicle or
    /// link, the step, the position and the obstacle.
    #[test]
    fn infeasible_names_the_obstacle_the_vehicle_the_step_and_the_position() {
        let mut s = Scenario::default();
        s.team.auvs = 1;
        s.horizon.steps = 2;
        let floor = holed();
        let field = floor.keep_out();
        let auv = AuvModel::new(&s.auv, s.horizon.dt).unwrap();
        let usv = UsvModel {
            dt: s.horizon.dt,
            max_speed: s.usv.max_speed,
        };
        let start = |t: &Trajectory| Start {
            usv: t.usv_p[0],
            auvs: vec![crate::plan::AuvState {
                position: t.auv_p[0][0],
                velocity: [0.0; 3],
            }],
        };
        let problem = |t: &Trajectory| TeamProblem::new(&s, &floor, &field, auv, usv, start(t));
        // the USV runs through the hole, the AUV well south of it
        let t = team(
            [[0.0, 0.0], [150.0, 0.0], [300.0, 0.0]],
            [
                [0.0, -200.0, -50.0],
                [150.0, -200.0, -50.0],
                [300.0, -200.0, -50.0],
            ],
        );
        let m = problem(&t).infeasible(&t).to_string();
        assert!(
            m.starts_with(
                "step1: a constraint cannot hold: obstacle (NODATA/land cells are kept out of): \
                 the USV between steps 1 and 2 passes ("
            ) && m.contains("which is over a NODATA cell"),
            "{m}"
        );
        // the AUV through it
        let t = team(
            [[0.0, -200.0], [150.0, -200.0], [300.0, -200.0]],
            [
                [0.0, 20.0, -50.0],
                [150.0, 20.0, -50.0],
                [300.0, 20.0, -50.0],
            ],
        );
        let m = problem(&t).infeasible(&t).to_string();
        assert!(
            m.contains("AUV 0 between steps 1 and 2 passes (")
                && m.contains("-50.0), which is over a NODATA cell"),
            "{m}"
        );
        // P5: the A2U link sees through it, both vehicles clear of it
        let t = team([[150.0, 0.0]; 3], [[350.0, 0.0, -50.0]; 3]);
        let graph = Graph {
            a2u: vec![0; 3],
            a2a: vec![vec![]; 3],
            exact: true,
            solve_time_s: 0.0,
        };
        let p5 = problem(&t).with_links(LinkSet::from_graph(&graph, 150.0, 30.0));
        let m = p5.infeasible(&t).to_string();
        assert!(
            m.starts_with(
                "step3: a constraint cannot hold: line of sight C1_13 (obstacle (NODATA/land \
                 cells are kept out of)): the A2U link AUV 0–USV at step 1 passes ("
            ) && m.contains("which is over a NODATA cell"),
            "{m}"
        );
        // every violation is measured: the link's at both steps, none of the paths'
        let v = violations(&p5, &t);
        assert_eq!(v.len(), 4);
        assert!(matches!(v[0], (u, KeepOut::Usv { k: 1, .. }) if u < 0.0));
        assert!(matches!(v[1], (u, KeepOut::Link { k: 1, li: 0, .. }) if u > 1.0));
    }
}
