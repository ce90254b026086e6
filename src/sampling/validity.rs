//! Whether one sampled step is valid: the constraints of P1 that a single step of one vehicle,
//! or one acoustic link, can break. Each test names the constraint it holds ([`Reject`]), so a
//! tree that finds nothing can say why.
//!
//! The per-vehicle tests are the checker's families for one step (`shoal check`, `src/check/`)
//! without their tolerances: a sample the tests accept passes those families, and a sample they
//! reject fails one of them (the property test `sampler_agrees_with_the_checker` holds this).
//! The chain test is stronger than the checker's connectivity, as the paper's P1 is: the AUV
//! nearest the USV and a path graph through every AUV (C1_10, C1_11), each link within d_s and
//! in line of sight (C1_13), where the checker asks only that every AUV reach the USV.

use crate::scenario::Scenario;
use crate::seafloor::Seafloor;

/// The constraint a sampled step breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Reject {
    /// A waypoint off the seafloor grid.
    Grid,
    /// C1_4: above −auv.surface_clearance.
    Surface,
    /// C2_2 at the waypoint: closer to the floor than auv.floor_clearance.
    Floor,
    /// C2_2 along the segment from the last waypoint (𝓛_r).
    Segment,
    /// A segment or a link over a NODATA or land cell.
    Obstacle,
    /// C1_7: faster than auv.max_speed (or the USV's usv.max_speed).
    Speed,
    /// C1_14: a heading rate above auv.max_heading_rate.
    Heading,
    /// C1_5: farther than d_max from the USV.
    MaxRange,
    /// C1_6 at k = K: farther than d_s from the USV.
    Terminal,
    /// Too far from the USV to be within d_s by k = K at full speed (ours: a node that cannot
    /// meet C1_6 is not grown).
    Unreachable,
    /// A chain link (A2U or A2A) longer than d_s.
    LinkRange,
    /// C1_13: a chain link without line of sight over the floor.
    LineOfSight,
}

impl Reject {
    /// Every reason, in report order.
    pub const ALL: [Reject; 12] = [
        Reject::Grid,
        Reject::Surface,
        Reject::Floor,
        Reject::Segment,
        Reject::Obstacle,
        Reject::Speed,
        Reject::Heading,
        Reject::MaxRange,
        Reject::Terminal,
        Reject::Unreachable,
        Reject::LinkRange,
        Reject::LineOfSight,
    ];

    /// The constraint's name as reports print it.
    pub fn name(self) -> &'static str {
        match self {
            Reject::Grid => "off the seafloor grid",
            Reject::Surface => "C1_4 underwater",
            Reject::Floor => "C2_2 floor clearance (waypoint)",
            Reject::Segment => "C2_2 floor clearance (segment)",
            Reject::Obstacle => "no obstacle (NODATA/land)",
            Reject::Speed => "C1_7 speed",
            Reject::Heading => "C1_14 heading rate",
            Reject::MaxRange => "C1_5 range ≤ d_max",
            Reject::Terminal => "C1_6 sonar range at k = K",
            Reject::Unreachable => "C1_6 unreachable by k = K",
            Reject::LinkRange => "chain link within ρ·d_s",
            Reject::LineOfSight => "C1_13 line of sight",
        }
    }
}

/// The scenario's limits that a step is tested against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// K, steps per window.
    pub steps: usize,
    /// δ, s.
    pub dt: f64,
    /// C1_7, m/s.
    pub max_speed: f64,
    /// The USV's speed limit, m/s.
    pub usv_max_speed: f64,
    /// C1_14 as a turn per step, ψ̇_max·δ, rad.
    pub max_turn: f64,
    /// Below this horizontal speed the heading is undefined (no C1_14), m/s.
    pub min_heading_speed: f64,
    /// ε of C2_2, m.
    pub floor_clearance: f64,
    /// C1_4: z ≤ −surface_clearance, m.
    pub surface_clearance: f64,
    /// d_s, m.
    pub sonar_range: f64,
    /// The longest link, ρ·d_s (`acoustic.link_margin`), m: links planned to be heard, as P5's.
    pub link_range: f64,
    /// d_max, m.
    pub max_range: f64,
    /// r of 𝓛_r, m.
    pub resolution: f64,
}

impl Limits {
    /// The limits of `s`.
    pub fn of(s: &Scenario) -> Limits {
        Limits {
            steps: s.horizon.steps,
            dt: s.horizon.dt,
            max_speed: s.auv.max_speed,
            usv_max_speed: s.usv.max_speed,
            max_turn: s.auv.max_heading_rate * s.horizon.dt,
            min_heading_speed: s.auv.min_heading_speed,
            floor_clearance: s.auv.floor_clearance,
            surface_clearance: s.auv.surface_clearance,
            sonar_range: s.acoustic.sonar_range,
            link_range: s.acoustic.link_margin * s.acoustic.sonar_range,
            max_range: s.acoustic.max_range,
            resolution: s.acoustic.resolution,
        }
    }
}

/// Euclidean distance.
pub fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The USV at the surface.
pub fn surface(usv: [f64; 2]) -> [f64; 3] {
    [usv[0], usv[1], 0.0]
}

/// Horizontal speed and heading of a velocity.
fn heading(v: [f64; 3]) -> (f64, f64) {
    (v[0].hypot(v[1]), v[1].atan2(v[0]))
}

/// Angle wrapped into [−π, π).
pub fn wrap(x: f64) -> f64 {
    use std::f64::consts::PI;
    (x + PI).rem_euclid(2.0 * PI) - PI
}

/// The cheap tests of one AUV step to `(p, v)` at step `k` from velocity `v0`, the USV at
/// `usv`: speed, heading rate, C1_4, the grid, C1_5, C1_6 at K and whether C1_6 can still be
/// met. No floor query but the grid's extent.
pub fn auv_waypoint(
    l: &Limits,
    floor: &Seafloor,
    k: usize,
    v0: [f64; 3],
    p: [f64; 3],
    v: [f64; 3],
    usv: [f64; 2],
) -> Result<(), Reject> {
    if p.iter().chain(&v).any(|c| !c.is_finite()) {
        return Err(Reject::Grid);
    }
    if dist(v, [0.0; 3]) > l.max_speed {
        return Err(Reject::Speed); // C1_7
    }
    let ((s0, h0), (s1, h1)) = (heading(v0), heading(v));
    if s0 >= l.min_heading_speed && s1 >= l.min_heading_speed && wrap(h1 - h0).abs() > l.max_turn {
        return Err(Reject::Heading); // C1_14, eq. (8)
    }
    if p[2] > -l.surface_clearance {
        return Err(Reject::Surface); // C1_4
    }
    if !floor.contains(p[0], p[1]) {
        return Err(Reject::Grid);
    }
    let d = dist(p, surface(usv));
    if d > l.max_range {
        return Err(Reject::MaxRange); // C1_5
    }
    if k == l.steps && d > l.sonar_range {
        return Err(Reject::Terminal); // C1_6
    }
    // both may close at full speed over the steps left
    let left = l.steps.saturating_sub(k) as f64 * l.dt * (l.max_speed + l.usv_max_speed);
    if d > l.sonar_range + left {
        return Err(Reject::Unreachable);
    }
    Ok(())
}

/// The floor tests of one AUV segment a → b: C2_2 at b and at every sample of 𝓛_r, and no
/// sample over an obstacle cell. Both ends must be on the grid.
pub fn auv_segment(l: &Limits, floor: &Seafloor, a: [f64; 3], b: [f64; 3]) -> Result<(), Reject> {
    let z = floor.elevation(b[0], b[1]).map_err(|_| Reject::Grid)?;
    if b[2] - z < l.floor_clearance {
        return Err(Reject::Floor);
    }
    clear_of_obstacles(l, floor, a, b)?;
    let c = floor
        .segment_clearance(a, b, l.resolution)
        .map_err(|_| Reject::Grid)?;
    if c.min_clearance < l.floor_clearance {
        return Err(Reject::Segment);
    }
    Ok(())
}

/// The USV's step a → b: its speed, the grid, and no sample of 𝓛_r over an obstacle cell.
pub fn usv_step(l: &Limits, floor: &Seafloor, a: [f64; 2], b: [f64; 2]) -> Result<(), Reject> {
    if !(b[0].is_finite() && b[1].is_finite() && floor.contains(b[0], b[1])) {
        return Err(Reject::Grid);
    }
    if (b[0] - a[0]).hypot(b[1] - a[1]) > l.usv_max_speed * l.dt {
        return Err(Reject::Speed);
    }
    clear_of_obstacles(l, floor, surface(a), surface(b))
}

/// An acoustic link a–b: within ρ·d_s, in line of sight over the floor (every sample of 𝓛_r at
/// or above it) and over no obstacle cell.
pub fn link(l: &Limits, floor: &Seafloor, a: [f64; 3], b: [f64; 3]) -> Result<(), Reject> {
    if dist(a, b) > l.link_range {
        return Err(Reject::LinkRange);
    }
    clear_of_obstacles(l, floor, a, b)?;
    let c = floor
        .segment_clearance(a, b, l.resolution)
        .map_err(|_| Reject::Grid)?;
    if c.min_clearance < 0.0 {
        return Err(Reject::LineOfSight);
    }
    Ok(())
}

/// No sample of 𝓛_r on a → b over an obstacle cell.
fn clear_of_obstacles(
    l: &Limits,
    floor: &Seafloor,
    a: [f64; 3],
    b: [f64; 3],
) -> Result<(), Reject> {
    if !floor.has_obstacles() {
        return Ok(());
    }
    match floor.segment_obstacle(a, b, l.resolution) {
        Ok(None) => Ok(()),
        Ok(Some(_)) => Err(Reject::Obstacle),
        Err(_) => Err(Reject::Grid),
    }
}

/// The paper's chain at one step, with the USV at `usv` and the AUVs at `auvs`: the AUV
/// nearest the USV (P3's A2U link) links it, and an order of the AUVs whose consecutive pairs
/// are links ([`link`]) exists (a Hamiltonian path, P4's A2A graph), found by depth-first
/// search (exponential in N at worst, as Remark III.1 says; fine for the teams a sampling
/// planner can serve). Returns the order, or the constraint that fails.
pub fn find_chain(
    l: &Limits,
    floor: &Seafloor,
    usv: [f64; 2],
    auvs: &[[f64; 3]],
) -> Result<Vec<usize>, Reject> {
    let n = auvs.len();
    if let Some(a2u) = crate::step2::p3_a2u::a2u_link(usv, auvs) {
        link(l, floor, auvs[a2u], surface(usv))?;
    }
    let mut edge = vec![false; n * n];
    for i in 0..n {
        for j in i + 1..n {
            let e = link(l, floor, auvs[i], auvs[j]).is_ok();
            edge[i * n + j] = e;
            edge[j * n + i] = e;
        }
    }
    fn extend(n: usize, edge: &[bool], order: &mut Vec<usize>, used: &mut [bool]) -> bool {
        if order.len() == n {
            return true;
        }
        let last = *order.last().expect("started");
        for j in 0..n {
            if !used[j] && edge[last * n + j] {
                used[j] = true;
                order.push(j);
                if extend(n, edge, order, used) {
                    return true;
                }
                order.pop();
                used[j] = false;
            }
        }
        false
    }
    for first in 0..n {
        let mut used = vec![false; n];
        used[first] = true;
        let mut order = vec![first];
        if extend(n, &edge, &mut order, &mut used) {
            return Ok(order);
        }
    }
    Err(Reject::LinkRange)
}

/// The A2A edges `[i, j]` (i < j) of a chain, in chain order (the plan's `graph.a2a[k]`).
pub fn chain_edges(order: &[usize]) -> Vec<[usize; 2]> {
    order
        .windows(2)
        .map(|w| [w[0].min(w[1]), w[0].max(w[1])])
        .collect()
}
