//! The tracking controller that flies an AUV along its plan in time: guidance towards the
//! moving reference point, then a speed loop on the thrust, a heading loop on the rudder and a
//! depth loop (through pitch) on the stern planes, within the actuators' limits.
//!
//! Guidance (shoal's frame): the desired velocity over ground is the reference's velocity plus
//! a pull towards the reference's position, v_d = v_ref + (p_ref − p)/T_pull, its horizontal
//! part limited to the top speed. The vehicle steers its velocity through the water,
//! v_d − c, where c is the current at the vehicle (a DVL measuring both bottom and water
//! track knows it), so it crabs across a current instead of being carried off its track.
//!
//! The depth loop is a REMUS-style outer loop on the pitch. It asks for a vertical speed, the
//! plan's own (feed-forward of the planned flight-path angle) plus the depth error over 8 s,
//! limited to 0.5 m/s (a REMUS autopilot's depth-rate limit); turns it into a flight-path angle
//! γ = asin(ż/V) at the speed through the water V (so the loop's gain in pitch per metre is
//! scheduled as 1/V and its bandwidth does not change with speed); and adds the angle of
//! attack the vehicle trims at for that speed ([`super::envelope::trim`]: 6.7 N of buoyancy
//! is held down by body lift, −3.6° at 1.25 m/s, −2.5° at 1.5 m/s) and a small integral for
//! what the trim misses. The integral stops while the pitch command or the stern planes are at
//! their limit (anti-windup): winding up there only makes the vehicle overshoot once it
//! recovers.
//!
//! The inner loops ask for an acceleration (PD on heading and pitch, with gains set as natural
//! frequencies; P on surge speed) and invert the vehicle model for it: each actuator's
//! effectiveness (yaw or pitch acceleration per radian of fin, surge acceleration per newton)
//! and the unforced acceleration at the current state are read off the model, and the actuator
//! supplies the difference (feedback linearisation, within the actuators' limits). It knows
//! the model exactly, which flatters tracking a little against a real vehicle's controller.
//! The controller closes its loops on the true state, as if navigation were perfect: every
//! navigation policy is then compared on the same flight and the same measurements.
//!
//! It flies the plan's speed even where the vehicle cannot hold its depth (below about
//! 1.14 m/s through the water, see docs/simulation.md, "What the vehicle can fly"): a plan
//! that asks for it is shown sinking, as the vehicle would, rather than flown faster than
//! planned.

use super::envelope::trim;
use super::reference::RefPoint;
use super::remus::{self, Actuators, Remus100, RigidState};
use std::f64::consts::PI;

/// Time constant of the pull towards the reference position, s.
const T_PULL: f64 = 20.0;
/// Slowest commanded surge speed, m/s: below it the fins lose authority.
const MIN_SPEED: f64 = 0.5;
/// Natural frequency and damping of the heading loop, rad/s.
const W_HEADING: f64 = 0.4;
/// Natural frequency of the pitch loop, rad/s.
const W_PITCH: f64 = 0.5;
/// Damping ratio of both attitude loops.
const ZETA: f64 = 0.9;
/// Bandwidth of the speed loop, 1/s.
const K_SPEED: f64 = 0.5;
/// Largest commanded pitch, rad (30°).
const MAX_PITCH: f64 = PI / 6.0;
/// Time constant of the depth loop, s: the vertical speed asked for per metre of depth error
/// is 1/T_DEPTH.
const T_DEPTH: f64 = 8.0;
/// Largest vertical speed the depth loop asks for, m/s (a REMUS autopilot's depth-rate limit;
/// 20° of flight path at 1.5 m/s).
const MAX_DEPTH_RATE: f64 = 0.5;
/// Integral gain of the depth loop, rad per metre·second, and its limit, rad: it trims out
/// what the trim's feed-forward misses (the roll the propeller torque gives, a current).
const K_DEPTH_I: f64 = 0.002;
const MAX_DEPTH_I: f64 = 0.1;
/// Speeds of the controller's table of trim angles of attack, m/s: from `TRIM_FROM` by
/// `TRIM_STEP`, `TRIM_COUNT` of them (to 2.5 m/s).
const TRIM_FROM: f64 = 0.3;
const TRIM_STEP: f64 = 0.05;
const TRIM_COUNT: usize = 45;

/// One AUV's tracking controller (its only state is the depth loop's integral).
#[derive(Debug, Clone)]
pub struct Controller {
    depth_integral: f64,
    top: f64,
    /// The level trim's angle of attack at each table speed, rad.
    trim_alpha: Vec<f64>,
    last: Trace,
}

/// What the controller decided at its last command, for diagnosing a flight.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Trace {
    /// Depth error, reference minus vehicle (z up), m.
    pub depth_error: f64,
    /// The depth loop's integral, rad.
    pub integral: f64,
    /// Commanded pitch (nose up positive), rad.
    pub pitch_command: f64,
    /// Achieved pitch (nose up positive), rad.
    pub pitch: f64,
    /// Stern-plane angle the loop asked for before the fin limit, rad.
    pub stern_wanted: f64,
    /// Stern-plane angle commanded (within the limit), rad.
    pub stern: f64,
    /// Commanded surge speed, m/s.
    pub speed_command: f64,
    /// Surge speed, m/s.
    pub speed: f64,
}

fn wrap(a: f64) -> f64 {
    (a + PI).rem_euclid(2.0 * PI) - PI
}

impl Controller {
    /// A controller at rest for `model`.
    pub fn new(model: &Remus100) -> Controller {
        Controller {
            depth_integral: 0.0,
            top: top_speed(model),
            trim_alpha: trim_table(model),
            last: Trace::default(),
        }
    }

    /// The level trim's angle of attack at `speed` m/s through the water, rad (linear between
    /// the table's speeds, its ends held beyond them).
    fn trim_alpha(&self, speed: f64) -> f64 {
        let x = ((speed - TRIM_FROM) / TRIM_STEP).clamp(0.0, (TRIM_COUNT - 1) as f64);
        let i = (x.floor() as usize).min(TRIM_COUNT - 2);
        let f = x - i as f64;
        self.trim_alpha[i] * (1.0 - f) + self.trim_alpha[i + 1] * f
    }

    /// What the last command decided.
    pub fn trace(&self) -> Trace {
        self.last
    }

    /// The actuators' commands at state `s` for reference `r` in a current `current` (shoal's
    /// frame, m/s); `dt` is the time to the next call, s.
    pub fn command(
        &mut self,
        model: &Remus100,
        s: &RigidState,
        r: &RefPoint,
        current: [f64; 3],
        dt: f64,
    ) -> Actuators {
        let p = remus::shoal_from_ned([s.eta[0], s.eta[1], s.eta[2]]);
        let top = self.top;
        // guidance: desired velocity over ground, then through the water
        let mut vd = [0.0; 2];
        for i in 0..2 {
            vd[i] = r.velocity[i] + (r.position[i] - p[i]) / T_PULL;
        }
        let h = vd[0].hypot(vd[1]);
        if h > top {
            vd[0] *= top / h;
            vd[1] *= top / h;
        }
        let w = [vd[0] - current[0], vd[1] - current[1]];
        let speed = w[0].hypot(w[1]).clamp(MIN_SPEED, top);
        let psi_d = if w[0].hypot(w[1]) > 1e-9 {
            remus::heading_ned_from_shoal(w[1].atan2(w[0]))
        } else {
            s.eta[5]
        };
        let u = s.nu[0];

        // depth through pitch (NED pitch is nose up positive; climbing is z up in shoal's frame)
        let still = remus::ned_from_shoal(current);
        let water = remus::body_to_ned(&s.eta).transpose() * nalgebra::Vector3::from(still);
        let v = (u - water[0]).max(MIN_SPEED);
        let dz = r.position[2] - p[2];
        let rate = (r.velocity[2] + dz / T_DEPTH).clamp(-MAX_DEPTH_RATE, MAX_DEPTH_RATE);
        let gamma = (rate / v).clamp(-MAX_PITCH.sin(), MAX_PITCH.sin()).asin();
        let wanted = gamma + self.trim_alpha(v) * gamma.cos() + self.depth_integral;
        let theta_d = wanted.clamp(-MAX_PITCH, MAX_PITCH);
        // anti-windup: no integration while the pitch command or the planes are at a limit
        let planes_free = self.last.stern_wanted.abs() <= model.max_fin;
        if theta_d == wanted && planes_free {
            self.depth_integral =
                (self.depth_integral + K_DEPTH_I * dz * dt).clamp(-MAX_DEPTH_I, MAX_DEPTH_I);
        }

        // effectiveness of each actuator at this state, from the model
        // (with the current: the model's forces act on the velocity through the water)
        let zero = Actuators {
            thrust: 0.0,
            rudder: 0.0,
            stern: 0.0,
        };
        let f0 = model.derivative(s, &zero, still);
        let probe =
            |a: Actuators, i: usize, by: f64| (model.derivative(s, &a, still)[i] - f0[i]) / by;
        let b_rudder = probe(
            Actuators {
                rudder: 0.01,
                ..zero
            },
            5,
            0.01,
        );
        let b_stern = probe(
            Actuators {
                stern: 0.01,
                ..zero
            },
            4,
            0.01,
        );
        let b_thrust = probe(
            Actuators {
                thrust: 1.0,
                ..zero
            },
            0,
            1.0,
        );

        let yaw_acc =
            W_HEADING * W_HEADING * wrap(psi_d - s.eta[5]) - 2.0 * ZETA * W_HEADING * s.nu[5];
        let pitch_acc =
            W_PITCH * W_PITCH * wrap(theta_d - s.eta[4]) - 2.0 * ZETA * W_PITCH * s.nu[4];
        // (the speed loop on the surge through the water, as `speed` is: on the surge over
        // ground a current along the course left the vehicle that much slower over ground
        // than planned, and the pull held it T_PULL × 0.3 m/s = 6 m behind its reference)
        let surge_acc = K_SPEED * (speed - (u - water[0]));
        // each actuator supplies what the desired acceleration lacks beyond what the vehicle
        // does unforced (the hydrodynamic and hydrostatic terms at this state: the Munk
        // moment alone would hold the nose down against a PD loop)
        let input = |acc: f64, unforced: f64, b: f64| {
            if b.abs() > 1e-9 {
                (acc - unforced) / b
            } else {
                0.0
            }
        };
        let thrust = input(surge_acc, f0[0], b_thrust);
        let rudder = input(yaw_acc, f0[5], b_rudder);
        let stern = input(pitch_acc, f0[4], b_stern);
        self.last = Trace {
            depth_error: dz,
            integral: self.depth_integral,
            pitch_command: theta_d,
            pitch: s.eta[4],
            stern_wanted: stern,
            stern: stern.clamp(-model.max_fin, model.max_fin),
            speed_command: speed,
            speed: u,
        };
        Actuators {
            thrust: thrust.clamp(0.0, model.max_thrust),
            rudder: rudder.clamp(-model.max_fin, model.max_fin),
            stern: stern.clamp(-model.max_fin, model.max_fin),
        }
    }
}

/// The level trim's angle of attack at each of the table's speeds, rad; where the model has no
/// trim within the angles it is valid for (the slowest speeds), the nearest speed's.
fn trim_table(model: &Remus100) -> Vec<f64> {
    let alphas: Vec<Option<f64>> = (0..TRIM_COUNT)
        .map(|i| trim(model, TRIM_FROM + i as f64 * TRIM_STEP, 0.0).map(|t| t.alpha))
        .collect();
    let nearest = |i: usize| {
        (0..TRIM_COUNT)
            .filter_map(|j| alphas[j].map(|a| (i.abs_diff(j), a)))
            .min_by_key(|(d, _)| *d)
            .map_or(0.0, |(_, a)| a)
    };
    (0..TRIM_COUNT)
        .map(|i| alphas[i].unwrap_or_else(|| nearest(i)))
        .collect()
}

/// The fastest steady surge speed within the thrust limit, m/s (bisection on
/// [`Remus100::steady_thrust`]).
pub fn top_speed(model: &Remus100) -> f64 {
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if model.steady_thrust(mid) <= model.max_thrust {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}
