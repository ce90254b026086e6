//! What the REMUS 100 model can fly, independent of any controller: the steady trim of the
//! 6-DoF model ([`super::remus`]) in the vertical plane at a speed through the water and a
//! flight-path angle, and the envelope it bounds (the slowest speed at which depth can be
//! held, the steepest climb and dive at each speed). Also the tools that measured how the
//! tracking controller uses that envelope: a depth step at a fixed speed, and the controller's
//! [`Trace`] along one AUV's flight of a plan.
//!
//! **Trim.** Straight flight at constant velocity through still water, wings level: surge
//! speed u = V cos α, heave w = V sin α, no rotation, pitch θ = γ + α (γ the flight-path angle,
//! climbing positive; α the angle of attack). The generalized force on the vehicle
//! ([`Remus100::forces`]) must vanish in surge, heave and pitch. Heave and pitch do not depend
//! on the thrust and are linear in the stern-plane angle δs: for each α, pitch gives δs, heave
//! is the residual in α (solved by a scan and bisection), and surge then gives the thrust. The
//! propeller's roll torque is left out (it rolls the vehicle a few degrees, which changes
//! little in the vertical plane). A trim is **flyable** when its fin angle is within the
//! vehicle's limit and its thrust within [0, max_thrust].
//!
//! What sets the envelope: the REMUS 100 is 6.7 N buoyant and its centre of gravity sits
//! 19.6 mm below its centre of buoyancy. To hold a depth it must make 6.7 N of down force from
//! body lift (∝ u·w, so a nose-down angle of attack that grows as 1/u² as the speed falls) and
//! hold the pitch that gives it against the righting moment W·z_G·sin θ and the Munk moment,
//! with stern planes whose moment grows as u². Below some speed the planes cannot hold that
//! pitch: no controller can keep the depth there.

use super::control::{Controller, Trace};
use super::current::CurrentField;
use super::flight::{fly_auv, Stopped};
use super::reference::{RefPoint, Reference};
use super::remus::{self, Actuators, Remus100, RigidState};
use crate::plan::Plan;
use crate::seafloor::Seafloor;

/// A steady straight flight of the vehicle in the vertical plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trim {
    /// Speed through the water, m/s.
    pub speed: f64,
    /// Flight-path angle, rad (climbing positive).
    pub gamma: f64,
    /// Angle of attack, rad (w/u > 0: the flow meets the hull from below, nose above the path).
    pub alpha: f64,
    /// Pitch, rad (nose up positive): γ + α.
    pub pitch: f64,
    /// Stern-plane angle, rad (positive: trailing edge down, the nose pitches down).
    pub stern: f64,
    /// Thrust, N.
    pub thrust: f64,
}

impl Trim {
    /// The share of the fin limit the trim uses (1 at the limit).
    pub fn fin_share(&self, model: &Remus100) -> f64 {
        self.stern.abs() / model.max_fin
    }

    /// Whether the vehicle can hold it: the fin within its limit, the thrust within [0, max].
    pub fn flyable(&self, model: &Remus100) -> bool {
        self.stern.abs() <= model.max_fin && (0.0..=model.max_thrust).contains(&self.thrust)
    }
}

/// The state of a trim at angle of attack `alpha`.
fn trim_state(speed: f64, gamma: f64, alpha: f64) -> RigidState {
    RigidState {
        nu: [speed * alpha.cos(), 0.0, speed * alpha.sin(), 0.0, 0.0, 0.0],
        eta: [0.0, 0.0, 10.0, 0.0, gamma + alpha, 0.0],
    }
}

/// For angle of attack `alpha`: the stern angle that zeroes the pitching moment (unclamped),
/// and the heave force left with it.
fn heave_residual(model: &Remus100, speed: f64, gamma: f64, alpha: f64) -> (f64, f64) {
    let s = trim_state(speed, gamma, alpha);
    let still = [0.0; 3];
    let probe = 0.01;
    let f0 = model.forces(&s, &Actuators::default(), still);
    let f1 = model.forces(
        &s,
        &Actuators {
            stern: probe,
            ..Actuators::default()
        },
        still,
    );
    let (m0, dm) = (f0[4], (f1[4] - f0[4]) / probe);
    let (z0, dz) = (f0[2], (f1[2] - f0[2]) / probe);
    if dm.abs() < 1e-12 {
        return (f64::NAN, f64::NAN);
    }
    let stern = -m0 / dm;
    (stern, z0 + dz * stern)
}

/// The largest angle of attack a trim may have, rad (15°): Prestero fitted the coefficients at
/// small angles of attack. At 0.5 m/s the model has a level "trim" at α = −20°, nose down,
/// where the hydrostatic righting moment balances the Munk moment; nothing in the model's
/// fit supports flying there.
pub const MAX_TRIM_ALPHA_DEG: f64 = 15.0;

/// The trim at `speed` m/s through the water and flight-path angle `gamma` rad, with the
/// smallest angle of attack within ±[`MAX_TRIM_ALPHA_DEG`] (None when there is none there, or
/// at no speed).
pub fn trim(model: &Remus100, speed: f64, gamma: f64) -> Option<Trim> {
    if speed.is_nan() || speed <= 0.0 || !gamma.is_finite() {
        return None;
    }
    let limit = MAX_TRIM_ALPHA_DEG.to_radians();
    // 0.25° steps: two trims closer than that are not told apart
    let steps = 60;
    let at = |a: f64| heave_residual(model, speed, gamma, a).1;
    // scan outwards from α = 0 so the first sign change found is the smallest |α|
    let mut best: Option<(f64, f64)> = None;
    for side in [1.0, -1.0] {
        let mut a0 = 0.0;
        let mut r0 = at(a0);
        for i in 1..=steps {
            let a1 = side * limit * i as f64 / steps as f64;
            let r1 = at(a1);
            if r0 == 0.0 || r0.signum() != r1.signum() {
                if best.map_or(true, |(lo, _)| a0.abs().min(a1.abs()) < lo) {
                    let (mut lo, mut hi, mut rlo) = (a0, a1, r0);
                    for _ in 0..60 {
                        let mid = 0.5 * (lo + hi);
                        let rm = at(mid);
                        if rm.signum() == rlo.signum() {
                            lo = mid;
                            rlo = rm;
                        } else {
                            hi = mid;
                        }
                    }
                    best = Some((a0.abs().min(a1.abs()), 0.5 * (lo + hi)));
                }
                break;
            }
            a0 = a1;
            r0 = r1;
        }
    }
    let (_, alpha) = best?;
    let (stern, _) = heave_residual(model, speed, gamma, alpha);
    let s = trim_state(speed, gamma, alpha);
    let f = model.forces(
        &s,
        &Actuators {
            stern: stern.clamp(-model.max_fin, model.max_fin),
            ..Actuators::default()
        },
        [0.0; 3],
    );
    // the stern angle is outside the clamp's reach when unflyable: surge's part of it is small
    // (its lift acts across the body), so the thrust is read with it clamped
    Some(Trim {
        speed,
        gamma,
        alpha,
        pitch: gamma + alpha,
        stern,
        thrust: -f[0],
    })
}

/// The slowest speed through the water, m/s, at which the vehicle can hold level flight using
/// at most `fin_share` of its stern-plane limit (bisection between 0.2 and 3 m/s; the trim's
/// fin angle falls as the speed rises).
pub fn min_level_speed(model: &Remus100, fin_share: f64) -> f64 {
    let ok = |v: f64| trim(model, v, 0.0).is_some_and(|t| t.fin_share(model) <= fin_share);
    let (mut lo, mut hi) = (0.2, 3.0);
    if ok(lo) {
        return lo;
    }
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if ok(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// The steady flight-path angles the vehicle can hold at `speed` m/s through the water using
/// at most `fin_share` of its fin limit and no more than its thrust: (steepest climb, steepest
/// dive), rad, searched from −45° to 45° in steps of 0.1°; None when there is none. Below the
/// slowest level speed both are dives: the vehicle cannot but sink, at no less than
/// speed·sin(climb).
pub fn flight_path_range(model: &Remus100, speed: f64, fin_share: f64) -> Option<(f64, f64)> {
    let ok = |g: f64| {
        trim(model, speed, g).is_some_and(|t| {
            t.fin_share(model) <= fin_share && (0.0..=model.max_thrust).contains(&t.thrust)
        })
    };
    let held: Vec<f64> = (-450..=450)
        .map(|i| (i as f64 * 0.1).to_radians())
        .filter(|&g| ok(g))
        .collect();
    let climb = held.iter().copied().fold(f64::NAN, f64::max);
    let dive = held.iter().copied().fold(f64::NAN, f64::min);
    (!held.is_empty()).then_some((climb, dive))
}

/// How the vehicle under its controller followed a depth step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepResult {
    /// Largest depth error below the reference (vehicle deeper), m (≥ 0).
    pub below: f64,
    /// Largest depth error above the reference (vehicle shallower), m (≥ 0).
    pub above: f64,
    /// Depth error at the end, m (z up: positive is above the reference).
    pub final_error: f64,
    /// Share of the time the stern planes were at their limit.
    pub saturated: f64,
}

/// Fly the controller along a straight course at a constant `speed` m/s (horizontal, still
/// water) at 30 m depth for `lead` s, then a depth change of `dz` m (z up: negative dives) at
/// a vertical speed of `rate` m/s, then level for as long again; from level trim at that
/// speed. The largest errors are over the whole run.
pub fn depth_step(model: &Remus100, speed: f64, dz: f64, rate: f64, lead: f64) -> StepResult {
    let h = remus::RECOMMENDED_STEP;
    let ramp = (dz / rate.abs().max(1e-6)).abs();
    let total = 2.0 * lead + ramp;
    let z0 = -30.0;
    let reference = |t: f64| {
        let (z, vz) = if t < lead {
            (z0, 0.0)
        } else if t < lead + ramp {
            (
                z0 + dz.signum() * rate.abs() * (t - lead),
                dz.signum() * rate.abs(),
            )
        } else {
            (z0 + dz, 0.0)
        };
        RefPoint {
            position: [speed * t, 0.0, z],
            velocity: [speed, 0.0, vz],
        }
    };
    let start = trim(model, speed, 0.0);
    let alpha = start.map_or(0.0, |t| t.alpha);
    let mut s = RigidState::from_shoal([0.0, 0.0, z0], 0.0, speed);
    s.nu[0] = speed * alpha.cos();
    s.nu[2] = speed * alpha.sin();
    s.eta[4] = alpha;
    let mut ctl = Controller::new(model);
    let (mut below, mut above, mut sat, mut n) = (0.0_f64, 0.0_f64, 0usize, 0usize);
    let mut err = 0.0;
    let mut t = 0.0;
    while t < total {
        let r = reference(t);
        let a = ctl.command(model, &s, &r, [0.0; 3], h);
        let tr = ctl.trace();
        err = tr.depth_error;
        // depth_error is reference − vehicle (z up): positive when the vehicle is deeper
        below = below.max(err);
        above = above.max(-err);
        sat += usize::from(tr.stern_wanted.abs() > model.max_fin);
        n += 1;
        s = model.step(&s, &a, [0.0; 3], h);
        if !s.eta.iter().chain(&s.nu).all(|x| x.is_finite()) {
            break;
        }
        t += h;
    }
    StepResult {
        below,
        above,
        final_error: -err,
        saturated: sat as f64 / n.max(1) as f64,
    }
}

/// One second of one AUV's flight with the controller's view of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TracePoint {
    /// Time, s.
    pub time: f64,
    /// The reference's horizontal speed through the water (its velocity less the current at
    /// its position), m/s.
    pub planned_speed: f64,
    /// The reference's vertical speed, m/s (z up).
    pub planned_climb: f64,
    /// The vehicle's depth error, vehicle minus reference (z up: negative is below), m.
    pub below: f64,
    /// The controller's trace at the second's first step.
    pub trace: Trace,
    /// Share of the second's steps with the stern planes at their limit.
    pub saturated: f64,
}

/// AUV `auv`'s flight of `plan`'s final stages (as [`super::flight::fly`] flies it, at
/// `plan`'s simulation step, in `current`) traced once a second.
pub fn trace_flight(
    plan: &Plan,
    floor: &Seafloor,
    current: &CurrentField,
    model: &Remus100,
    auv: usize,
) -> Result<Vec<TracePoint>, Stopped> {
    let reference = Reference::new(plan, super::reference::Flown::Final);
    let step = plan.scenario.simulation.step;
    let duration = reference.duration();
    let cost = super::budget::Cost {
        duration,
        auvs: reference.auvs(),
        sample_period: 1.0,
        samples: duration.round() as usize,
        substeps: ((1.0 / step).round() as usize).max(1),
        epochs: 0,
        runs: 1,
    };
    let mut out: Vec<TracePoint> = Vec::new();
    let mut sat = 0usize;
    let mut count = 0usize;
    fly_auv(
        plan,
        &reference,
        floor,
        current,
        model,
        &cost,
        auv,
        &|| false,
        &mut |t, s, tr| {
            let second = t.floor();
            if out.last().map_or(true, |p| p.time < second) {
                if let Some(last) = out.last_mut() {
                    last.saturated = sat as f64 / count.max(1) as f64;
                }
                sat = 0;
                count = 0;
                let r = reference.auv(auv, t);
                let c = current.at(r.position);
                out.push(TracePoint {
                    time: second,
                    planned_speed: (r.velocity[0] - c[0]).hypot(r.velocity[1] - c[1]),
                    planned_climb: r.velocity[2],
                    below: s.position_shoal()[2] - r.position[2],
                    trace: *tr,
                    saturated: 0.0,
                });
            }
            sat += usize::from(tr.stern_wanted.abs() > model.max_fin);
            count += 1;
        },
    )?;
    if let Some(last) = out.last_mut() {
        last.saturated = sat as f64 / count.max(1) as f64;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trim_is_a_steady_flight_of_the_model() {
        let model = Remus100::default();
        for (v, g) in [(1.5, 0.0), (1.5, 0.1), (2.0, -0.3), (1.25, 0.0)] {
            let t = trim(&model, v, g).expect("a trim at cruise");
            let s = trim_state(v, g, t.alpha);
            let a = Actuators {
                thrust: t.thrust,
                stern: t.stern,
                rudder: 0.0,
            };
            let f = model.forces(&s, &a, [0.0; 3]);
            for i in [0, 2, 4] {
                assert!(f[i].abs() < 1e-6, "speed {v}, γ {g}: force {i} = {}", f[i]);
            }
            // the vehicle is buoyant: body lift must push it down, nose below the path
            assert!(t.alpha < 0.0);
        }
    }

    #[test]
    fn below_the_slowest_level_speed_the_vehicle_can_only_dive() {
        let model = Remus100::default();
        let slowest = min_level_speed(&model, 1.0);
        assert!((1.0..1.3).contains(&slowest), "{slowest}");
        let (climb, _) = flight_path_range(&model, slowest - 0.05, 1.0).expect("some dive");
        assert!(climb < 0.0, "{climb}");
        let (climb, dive) = flight_path_range(&model, 1.5, 1.0).expect("cruise");
        assert!(climb > 0.0 && dive < 0.0);
        // less of the fins for trim, less of the envelope
        assert!(min_level_speed(&model, 0.75) > slowest);
    }

    #[test]
    fn the_controller_follows_a_gentle_dive_inside_the_envelope() {
        let model = Remus100::default();
        let r = depth_step(&model, 1.5, -10.0, 0.1, 60.0);
        assert!(r.below < 1.0 && r.above < 1.0, "{r:?}");
        assert!(r.final_error.abs() < 0.5, "{r:?}");
    }

    #[test]
    fn outside_the_envelope_the_vehicle_sinks_under_any_command() {
        // at 1.0 m/s level flight needs more stern plane than there is: the vehicle sinks
        let model = Remus100::default();
        assert!(trim(&model, 1.0, 0.0).is_some_and(|t| !t.flyable(&model)));
        let r = depth_step(&model, 1.0, 10.0, 0.1, 60.0);
        assert!(r.below > 5.0, "{r:?}");
    }
}
