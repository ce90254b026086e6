//! Flying a plan: every AUV's 6-DoF model under its tracking controller in the current, the USV
//! on its path, sampled at the navigation sensors' rate.

use super::budget::Cost;
use super::control::{Controller, Trace};
use super::current::CurrentField;
use super::reference::Reference;
use super::remus::{self, Remus100, RigidState};
use crate::plan::Plan;
use crate::seafloor::Seafloor;
use std::sync::atomic::{AtomicBool, Ordering};

/// One AUV at one sample time, in shoal's frame (x east, y north, z up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Position, m.
    pub position: [f64; 3],
    /// Velocity over ground, m/s.
    pub ground_velocity: [f64; 3],
    /// Velocity through the water (over ground less the current), m/s.
    pub water_velocity: [f64; 3],
    /// Heading of the body's x axis, rad from +x towards +y.
    pub heading: f64,
    /// Height above the floor, m (None outside the grid).
    pub altitude: Option<f64>,
    /// Where the plan wanted it at this time, m.
    pub reference: [f64; 3],
    /// Thrust commanded, N.
    pub thrust: f64,
}

/// The executed mission.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    /// Sample times, s: 0, T_s, 2·T_s, …, the mission's duration.
    pub times: Vec<f64>,
    /// `[auv][sample]`.
    pub auvs: Vec<Vec<Sample>>,
    /// The USV's position at each sample, m (z = 0).
    pub usv: Vec<[f64; 3]>,
}

/// Why a flight stopped before the end of the mission.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stopped {
    /// The cancel flag was raised.
    Cancelled,
    /// An AUV's 6-DoF state stopped being finite: the model diverged (in a current it cannot
    /// fly against, say).
    Diverged {
        /// The AUV.
        auv: usize,
        /// The last sample time at which its state was finite, s.
        time: f64,
        /// The current there, m/s (x east, y north, z up).
        current: [f64; 3],
    },
}

/// Fly `reference` from `plan`'s initial state: RK4 steps of `step` seconds, `cost.substeps`
/// of them per sample, `cost.samples` samples after t = 0, every `cost.sample_period` seconds
/// (the counts of [`super::budget::Cost`], checked against their limits). Stops at the next
/// sample once `cancel` is raised, or when an AUV's state is no longer finite.
#[allow(clippy::too_many_arguments)]
pub fn fly(
    plan: &Plan,
    reference: &Reference,
    floor: &Seafloor,
    current: &CurrentField,
    model: &Remus100,
    cost: &Cost,
    cancel: Option<&AtomicBool>,
) -> Result<Flight, Stopped> {
    let (samples, sample_period) = (cost.samples, cost.sample_period);
    let times: Vec<f64> = (0..=samples).map(|i| i as f64 * sample_period).collect();
    let usv = times
        .iter()
        .map(|&t| {
            let p = reference.usv(t);
            [p[0], p[1], 0.0]
        })
        .collect();
    let cancelled = || cancel.is_some_and(|c| c.load(Ordering::Relaxed));
    let mut auvs = Vec::with_capacity(reference.auvs());
    for n in 0..reference.auvs() {
        auvs.push(fly_auv(
            plan,
            reference,
            floor,
            current,
            model,
            cost,
            n,
            &cancelled,
            &mut |_, _, _| {},
        )?);
    }
    Ok(Flight { times, auvs, usv })
}

/// One AUV's flight of [`fly`]; `watch` sees the time, the state and the controller's
/// [`Trace`] at every RK4 step, before the step.
#[allow(clippy::too_many_arguments)]
pub fn fly_auv(
    plan: &Plan,
    reference: &Reference,
    floor: &Seafloor,
    current: &CurrentField,
    model: &Remus100,
    cost: &Cost,
    n: usize,
    cancelled: &dyn Fn() -> bool,
    watch: &mut dyn FnMut(f64, &RigidState, &Trace),
) -> Result<Vec<Sample>, Stopped> {
    let (samples, substeps, sample_period) = (cost.samples, cost.substeps, cost.sample_period);
    let h = sample_period / substeps as f64;
    let start = &plan.initial.auvs[n];
    let mut s = initial_state(start.position, start.velocity, reference, n);
    let mut ctl = Controller::new(model);
    let mut out = Vec::with_capacity(samples + 1);
    let mut thrust = 0.0;
    for i in 0..=samples {
        let t = i as f64 * sample_period;
        if cancelled() {
            return Err(Stopped::Cancelled);
        }
        out.push(sample(model, floor, current, &s, reference, n, t, thrust));
        if i == samples {
            break;
        }
        for j in 0..substeps {
            let tj = t + j as f64 * h;
            let p = remus::shoal_from_ned([s.eta[0], s.eta[1], s.eta[2]]);
            let c = current.at(p);
            let r = reference.auv(n, tj);
            let a = ctl.command(model, &s, &r, c, h);
            watch(tj, &s, &ctl.trace());
            thrust = a.thrust;
            s = model.step(&s, &a, remus::ned_from_shoal(c), h);
        }
        if !s.eta.iter().chain(&s.nu).all(|x| x.is_finite()) {
            let last = out[out.len() - 1].position;
            return Err(Stopped::Diverged {
                auv: n,
                time: t,
                current: current.at(last),
            });
        }
    }
    Ok(out)
}

/// Level flight at the planned start: surge at the planned horizontal speed, heading along the
/// planned velocity (or towards the reference 10 s on when the AUV starts at rest).
fn initial_state(p: [f64; 3], v: [f64; 3], reference: &Reference, n: usize) -> RigidState {
    let speed = v[0].hypot(v[1]);
    let heading = if speed > 0.1 {
        v[1].atan2(v[0])
    } else {
        let ahead = reference.auv(n, 10.0).position;
        (ahead[1] - p[1]).atan2(ahead[0] - p[0])
    };
    let ned = remus::ned_from_shoal(p);
    RigidState {
        nu: [speed, 0.0, 0.0, 0.0, 0.0, 0.0],
        eta: [
            ned[0],
            ned[1],
            ned[2],
            0.0,
            0.0,
            remus::heading_ned_from_shoal(heading),
        ],
    }
}

#[allow(clippy::too_many_arguments)]
fn sample(
    model: &Remus100,
    floor: &Seafloor,
    current: &CurrentField,
    s: &RigidState,
    reference: &Reference,
    n: usize,
    t: f64,
    thrust: f64,
) -> Sample {
    let position = remus::shoal_from_ned([s.eta[0], s.eta[1], s.eta[2]]);
    let c = current.at(position);
    let zero = remus::Actuators::default();
    let d = model.derivative(s, &zero, remus::ned_from_shoal(c));
    let ground_velocity = remus::shoal_from_ned([d[6], d[7], d[8]]);
    let water_velocity = [
        ground_velocity[0] - c[0],
        ground_velocity[1] - c[1],
        ground_velocity[2] - c[2],
    ];
    Sample {
        position,
        ground_velocity,
        water_velocity,
        heading: remus::heading_shoal_from_ned(s.eta[5]),
        altitude: floor
            .elevation(position[0], position[1])
            .ok()
            .map(|z| position[2] - z),
        reference: reference.auv(n, t).position,
        thrust,
    }
}
