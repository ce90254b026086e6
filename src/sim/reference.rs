//! The plan as functions of time: where each vehicle should be at any instant of the mission,
//! between the waypoints as well as on them.
//!
//! Between waypoints k and k + 1 an AUV follows the planner's own model under the zero-order
//! hold of input U\[k\] (eqs. (5)–(7), `auv.discretisation = "zoh"`): its state at τ ∈ [0, δ] is
//! that model discretised with step τ. Under the paper's forward Euler (eq. (8)) the model says
//! nothing between waypoints, and the reference is the straight segment at constant velocity.
//! The USV moves at constant velocity U_USV\[k\] between its waypoints (eq. (9)). The plan's AUV
//! velocities are through the water: over ground the current the plan was made in
//! (`Plan::current`), taken at the step's start as the planner does, adds to them.

use super::current::CurrentField;
use crate::plan::{Plan, Stage};
use crate::scenario::Discretisation;
use crate::vehicle::AuvModel;

/// Which of a window's stages is flown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flown {
    /// Step 3's plan (P5, the chain): what `shoal plan` hands the team.
    Final,
    /// Step 1's paths (P2, no chain): for comparison, what the team would fly without the
    /// planner's graph.
    Step1,
}

/// The plan's reference trajectories over the whole mission.
#[derive(Debug, Clone)]
pub struct Reference {
    dt: f64,
    steps: usize,
    rates: [f64; 3],
    zoh: bool,
    /// Per window: its start time and the stage flown.
    windows: Vec<(f64, Stage)>,
    /// The current the plan was made in (its V is through the water; `Plan::current`).
    current: CurrentField,
}

/// A point of an AUV's reference: position and velocity, m and m/s (x east, y north, z up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefPoint {
    /// Position, m.
    pub position: [f64; 3],
    /// Velocity, m/s.
    pub velocity: [f64; 3],
}

impl Reference {
    /// The reference of `plan`'s `flown` stages.
    pub fn new(plan: &Plan, flown: Flown) -> Reference {
        let s = &plan.scenario;
        Reference {
            dt: s.horizon.dt,
            steps: s.horizon.steps,
            rates: plan.model.auv.rate,
            zoh: s.auv.discretisation == Discretisation::Zoh,
            windows: plan
                .windows
                .iter()
                .map(|w| {
                    let st = match flown {
                        Flown::Final => w.final_.clone(),
                        Flown::Step1 => w.step1.clone(),
                    };
                    (w.start_time, st)
                })
                .collect(),
            current: CurrentField::new(&plan.current),
        }
    }

    /// Number of AUVs.
    pub fn auvs(&self) -> usize {
        self.windows.first().map_or(0, |w| w.1.auvs.len())
    }

    /// Duration of the mission, s: every window's K·δ.
    pub fn duration(&self) -> f64 {
        self.windows.len() as f64 * self.window_duration()
    }

    /// Duration of one window, K·δ, s.
    pub fn window_duration(&self) -> f64 {
        self.steps as f64 * self.dt
    }

    /// The window and step holding time `t` (the last step's end belongs to the last window),
    /// and the time into that step.
    pub fn locate(&self, t: f64) -> (usize, usize, f64) {
        let w = ((t / self.window_duration()).floor().max(0.0) as usize)
            .min(self.windows.len().saturating_sub(1));
        let into = t - self.windows[w].0;
        let k = ((into / self.dt).floor().max(0.0) as usize).min(self.steps - 1);
        (w, k, (into - k as f64 * self.dt).clamp(0.0, self.dt))
    }

    /// The step k of window w nearest time t (for the planned links of that instant).
    pub fn nearest_step(&self, t: f64) -> (usize, usize) {
        let (w, k, tau) = self.locate(t);
        (w, if tau > 0.5 * self.dt { k + 1 } else { k })
    }

    /// AUV `n`'s reference at time `t`.
    pub fn auv(&self, n: usize, t: f64) -> RefPoint {
        let (w, k, tau) = self.locate(t);
        let path = &self.windows[w].1.auvs[n];
        let (p0, v0, u) = (path.position[k], path.velocity[k], path.input[k]);
        if self.zoh {
            if tau <= 0.0 {
                let c = self.current.at(p0);
                return RefPoint {
                    position: p0,
                    velocity: std::array::from_fn(|i| v0[i] + c[i]),
                };
            }
            match AuvModel::from_rates(self.rates, tau, Discretisation::Zoh) {
                Ok(m) => {
                    // the planned V is through the water; over ground the plan's current
                    // c(P[k]) adds to it over the step, as the planner's model has it
                    let (position, velocity) = m.step(p0, v0, u);
                    let c = self.current.at(p0);
                    RefPoint {
                        position: std::array::from_fn(|i| position[i] + tau * c[i]),
                        velocity: std::array::from_fn(|i| velocity[i] + c[i]),
                    }
                }
                // rates were validated when the plan was made; fall back to the segment
                Err(_) => self.segment(path.position[k], path.position[k + 1], tau),
            }
        } else {
            self.segment(path.position[k], path.position[k + 1], tau)
        }
    }

    fn segment(&self, a: [f64; 3], b: [f64; 3], tau: f64) -> RefPoint {
        let f = tau / self.dt;
        let mut position = [0.0; 3];
        let mut velocity = [0.0; 3];
        for i in 0..3 {
            position[i] = a[i] + f * (b[i] - a[i]);
            velocity[i] = (b[i] - a[i]) / self.dt;
        }
        RefPoint { position, velocity }
    }

    /// The USV's position at time `t` (eq. (9): constant velocity between waypoints).
    pub fn usv(&self, t: f64) -> [f64; 2] {
        let (w, k, tau) = self.locate(t);
        let path = &self.windows[w].1.usv;
        let (p, u) = (path.position[k], path.input[k]);
        [p[0] + tau * u[0], p[1] + tau * u[1]]
    }

    /// The planned links at step k of window w: the A2U link first, then the A2A edges, as
    /// pairs of vehicle indices (the USV is index N). Empty for Step 1's paths (no graph).
    pub fn links(plan: &Plan, w: usize, k: usize) -> Vec<(usize, usize)> {
        let n = plan.scenario.team.auvs;
        plan.windows
            .get(w)
            .and_then(|win| win.links.links.get(k))
            .map(|ls| ls.iter().map(|l| (l.a, l.b.unwrap_or(n))).collect())
            .unwrap_or_default()
    }
}
