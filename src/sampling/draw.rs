//! How a random sample becomes a step under the vehicle models (a choice the paper leaves
//! open; docs/baseline.md).
//!
//! An AUV's sample is its next velocity V\[k+1\]. Under the discrete model of eq. (8) (ZOH by
//! default) the input that reaches it is unique, U\[k\] = (V\[k+1\] − A_v V\[k\]) / B_v per axis,
//! and so is the waypoint P\[k+1\] = P\[k\] + A_p V\[k\] + B_p U\[k\]: sampling velocities is
//! sampling waypoints from the set the model can reach in one step (an affine image of the
//! speed ball), and every sample is an input sequence the model flies exactly.
//!
//! The draw: the horizontal velocity uniform on the disc of radius V_max, its heading drawn
//! uniformly within the turn C1_14 allows from the current heading (any heading when either
//! speed is below auv.min_heading_speed); then the vertical velocity uniform on the interval
//! that keeps the waypoint between the floor clearance and the surface clearance (C2_2 and
//! C1_4 at the waypoint, on the floor under the new horizontal position) and ‖V‖ ≤ V_max
//! (C1_7). The USV's sample is its velocity, uniform on the disc of radius usv.max_speed
//! (eq. (9)), turning no faster than the AUVs ([`usv_velocity`]).

use super::validity::{Limits, Reject};
use crate::seafloor::Seafloor;
use crate::vehicle::AuvModel;
use rand::Rng;
use std::f64::consts::PI;

/// The fraction of a limit a draw goes up to.
const INSIDE: f64 = 1.0 - 1e-9;

/// One AUV step: the input, the waypoint and the velocity it reaches.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AuvStep {
    /// U\[k\], m/s².
    pub u: [f64; 3],
    /// P\[k+1\], m.
    pub p: [f64; 3],
    /// V\[k+1\], m/s.
    pub v: [f64; 3],
}

/// The input that takes velocity `v0` to `v1` in one step of `model` (per axis; an axis with
/// no input gain keeps its free response).
pub fn input_for(model: &AuvModel, v0: [f64; 3], v1: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| {
        if model.vu[i] != 0.0 {
            (v1[i] - model.vv[i] * v0[i]) / model.vu[i]
        } else {
            0.0
        }
    })
}

/// On axis i the next waypoint is affine in the next velocity V': P' = P + A_p V + B_p (V' −
/// A_v V)/B_v = `free` + `gain`·V'. This is `free`, the waypoint at V' = 0.
fn free(model: &AuvModel, p0: [f64; 3], v0: [f64; 3], i: usize) -> f64 {
    p0[i] + model.pv[i] * v0[i] - model.pu[i] * model.vv[i] * v0[i] / model.vu[i]
}

/// The `gain` of [`free`]'s map, B_p/B_v (0 for Euler, whose next waypoint no input moves).
fn gain(model: &AuvModel, i: usize) -> f64 {
    model.pu[i] / model.vu[i]
}

/// Draw one AUV step from (p0, v0); `Err` when the drawn horizontal position is off the grid
/// or no depth between the floor and the surface clearance is reachable there.
pub fn auv_step<R: Rng>(
    rng: &mut R,
    l: &Limits,
    model: &AuvModel,
    floor: &Seafloor,
    p0: [f64; 3],
    v0: [f64; 3],
) -> Result<AuvStep, Reject> {
    // horizontal: uniform on the disc, heading within the turn C1_14 allows
    // (a hair inside every limit, so rounding in the model's step cannot cross it)
    let speed = l.max_speed * INSIDE * rng.gen::<f64>().sqrt();
    let s0 = v0[0].hypot(v0[1]);
    let heading = if s0 >= l.min_heading_speed && speed >= l.min_heading_speed {
        v0[1].atan2(v0[0]) + l.max_turn * INSIDE * rng.gen_range(-1.0..=1.0)
    } else {
        rng.gen_range(-PI..PI)
    };
    let (vx, vy) = (speed * heading.cos(), speed * heading.sin());
    let ux = input_for(model, v0, [vx, vy, 0.0]);
    let x = p0[0] + model.pv[0] * v0[0] + model.pu[0] * ux[0];
    let y = p0[1] + model.pv[1] * v0[1] + model.pu[1] * ux[1];
    let z_floor = floor.elevation(x, y).map_err(|_| Reject::Grid)?;
    // vertical: z(V_z) = a + b·V_z, kept in [floor + ε, −surface clearance], |V_z| ≤ √(V² − s²)
    let vz_max = ((l.max_speed * INSIDE).powi(2) - speed * speed)
        .max(0.0)
        .sqrt();
    let (lo, hi) = (
        z_floor + l.floor_clearance + 1e-9,
        -l.surface_clearance - 1e-9,
    );
    let (a, b) = (free(model, p0, v0, 2), gain(model, 2));
    let (mut vz_lo, mut vz_hi) = (-vz_max, vz_max);
    if b > 0.0 {
        vz_lo = vz_lo.max((lo - a) / b);
        vz_hi = vz_hi.min((hi - a) / b);
    } else if !(lo..=hi).contains(&a) {
        return Err(Reject::Floor); // Euler: the next depth is fixed by the current velocity
    }
    if vz_lo.partial_cmp(&vz_hi).map_or(true, |o| o.is_gt()) {
        return Err(Reject::Floor);
    }
    let vz = rng.gen_range(vz_lo..=vz_hi);
    let u = input_for(model, v0, [vx, vy, vz]);
    let (p, v) = model.step(p0, v0, u);
    Ok(AuvStep { u, p, v })
}

/// Draw one AUV step from (p0, v0) whose waypoint lies within ρ·d_s of `to` (the next link's
/// other end): the waypoint uniform on the horizontal disc of radius ρ·d_s about `to` and in
/// the water column there within ρ·d_s of it, the velocity and input the model needs to reach it
/// (the inverse of the map of [`auv_step`]). The step may break the speed or heading limit;
/// the caller tests it. Half the tree's draws are these (ours; docs/baseline.md measures
/// what they buy: little at the default tree).
pub fn auv_step_towards<R: Rng>(
    rng: &mut R,
    l: &Limits,
    model: &AuvModel,
    floor: &Seafloor,
    p0: [f64; 3],
    v0: [f64; 3],
    to: [f64; 3],
) -> Result<AuvStep, Reject> {
    let r = l.link_range * rng.gen::<f64>().sqrt();
    let a = rng.gen_range(-PI..PI);
    let (x, y) = (to[0] + r * a.cos(), to[1] + r * a.sin());
    let z_floor = floor.elevation(x, y).map_err(|_| Reject::Grid)?;
    let half = (l.link_range.powi(2) - r * r).max(0.0).sqrt() * INSIDE;
    let lo = (z_floor + l.floor_clearance + 1e-9).max(to[2] - half);
    let hi = (-l.surface_clearance - 1e-9).min(to[2] + half);
    if lo.partial_cmp(&hi).map_or(true, |o| o.is_gt()) {
        return Err(Reject::Floor);
    }
    let target = [x, y, rng.gen_range(lo..=hi)];
    // the map of `free` and `gain`, solved for V'
    let v1: [f64; 3] =
        std::array::from_fn(|i| (target[i] - free(model, p0, v0, i)) * model.vu[i] / model.pu[i]);
    if v1.iter().any(|c| !c.is_finite()) {
        return Err(Reject::Speed); // Euler: no input moves the next waypoint
    }
    let u = input_for(model, v0, v1);
    let (p, v) = model.step(p0, v0, u);
    Ok(AuvStep { u, p, v })
}

/// Draw the USV's velocity, uniform on the disc of radius usv.max_speed, its heading within
/// the AUVs' turn per step (ψ̇_max·δ) of its last velocity `u0` (any heading from rest): the
/// model of eq. (9) lets the USV turn at will, but a USV that turns faster than the AUVs can
/// leaves the chain behind (ours; docs/baseline.md).
pub fn usv_velocity<R: Rng>(rng: &mut R, l: &Limits, u0: [f64; 2]) -> [f64; 2] {
    let speed = l.usv_max_speed * INSIDE * rng.gen::<f64>().sqrt();
    let heading = if u0[0].hypot(u0[1]) >= l.min_heading_speed {
        u0[1].atan2(u0[0]) + l.max_turn * rng.gen_range(-1.0..=1.0)
    } else {
        rng.gen_range(-PI..PI)
    };
    [speed * heading.cos(), speed * heading.sin()]
}
