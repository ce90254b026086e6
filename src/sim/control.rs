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
//! The loops ask for an acceleration (PD on heading and pitch, with gains set as natural
//! frequencies; P on surge speed; an integral of the depth error on the pitch command trims
//! out what the model's cancellation misses) and invert the vehicle model for it: each
//! actuator's effectiveness (yaw or pitch acceleration per radian of fin, surge acceleration
//! per newton) and the unforced acceleration at the current state are read off the model, and
//! the actuator supplies the difference (feedback linearisation, within the actuators' limits).
//! It knows the model exactly, which flatters tracking a little against a real vehicle's
//! controller. The controller closes its
//! loops on the true state, as if navigation were perfect: every navigation policy is then
//! compared on the same flight and the same measurements.

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
/// Integral gain of the depth loop, rad per metre·second, and its limit, rad.
const K_DEPTH_I: f64 = 0.002;
const MAX_DEPTH_I: f64 = 0.3;
/// Gain from depth error to pitch, rad per metre.
const K_DEPTH_P: f64 = 0.05;

/// One AUV's tracking controller (its only state is the depth loop's integral).
#[derive(Debug, Clone)]
pub struct Controller {
    depth_integral: f64,
    top: f64,
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
        }
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
        let mut vd = [0.0; 3];
        for i in 0..3 {
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
        let dz = r.position[2] - p[2];
        self.depth_integral =
            (self.depth_integral + K_DEPTH_I * dz * dt).clamp(-MAX_DEPTH_I, MAX_DEPTH_I);
        let climb = (vd[2] / u.max(MIN_SPEED)).clamp(-0.5, 0.5).asin();
        let theta_d = (climb + K_DEPTH_P * dz + self.depth_integral).clamp(-MAX_PITCH, MAX_PITCH);

        // effectiveness of each actuator at this state, from the model
        // (with the current: the model's forces act on the velocity through the water)
        let still = remus::ned_from_shoal(current);
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
        let surge_acc = K_SPEED * (speed - u);
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
        Actuators {
            thrust: thrust.clamp(0.0, model.max_thrust),
            rudder: rudder.clamp(-model.max_fin, model.max_fin),
            stern: stern.clamp(-model.max_fin, model.max_fin),
        }
    }
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
