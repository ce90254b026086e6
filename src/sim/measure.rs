//! What the vehicles measure during a flight: each AUV's dead reckoning (DVL velocity rotated by
//! its compass heading, integrated between acoustic cycles), its depth, the USV's GPS fixes and
//! every acoustic ping of every cycle, received or not. Drawn once per flight from the seed, so
//! every navigation policy is judged on the same measurements.

use super::estimate::Cov3;
use super::flight::Flight;
use crate::scenario::Navigation;
use crate::seafloor::Seafloor;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};

/// Each AUV's sensor errors, drawn once per mission.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorErrors {
    /// DVL scale-factor error (fraction).
    pub dvl_scale: f64,
    /// Compass heading bias, rad.
    pub heading_bias: f64,
}

/// One AUV's dead reckoning from epoch e to e + 1.
#[derive(Debug, Clone, PartialEq)]
pub struct Increment {
    /// Measured displacement, m.
    pub delta: [f64; 3],
    /// Its covariance when the estimators do not estimate the biases: the white noise plus
    /// the biases as if drawn anew each cycle, m².
    pub cov: Cov3,
    /// Its white noise alone (DVL and heading noise), m²: the covariance when the estimators
    /// estimate each AUV's biases.
    pub white: Cov3,
    /// Fraction of the interval's samples with DVL bottom lock.
    pub bottom_lock: f64,
}

/// One ping of one acoustic cycle between vehicles `a` < `b` (the USV is index N), as
/// sim.json records it.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Ping {
    /// Epoch (acoustic cycle) index.
    pub epoch: usize,
    /// One end.
    pub a: usize,
    /// The other end.
    pub b: usize,
    /// True distance between the executed positions, m.
    pub distance: f64,
    /// Whether the straight path between them clears the floor (the segment query 𝓛_r on the
    /// executed positions).
    pub line_of_sight: bool,
    /// Whether the ping was received.
    pub received: bool,
    /// Measured range (travel time × sound speed), m (meaningful when received).
    pub range: f64,
}

/// Everything measured over a flight, per epoch e = 0..=E (one acoustic cycle apart).
#[derive(Debug, Clone, PartialEq)]
pub struct Measurements {
    /// Seconds between epochs (the acoustic cycle).
    pub period: f64,
    /// Number of epochs, E + 1.
    pub epochs: usize,
    /// `[auv]`.
    pub errors: Vec<SensorErrors>,
    /// `[auv]`: the start position each AUV believes (its fix before the dive), m.
    pub initial: Vec<[f64; 3]>,
    /// `[auv][e]`, e = 0..E−1: dead reckoning from e to e + 1.
    pub odometry: Vec<Vec<Increment>>,
    /// `[auv][e]`: measured z, m.
    pub depth: Vec<Vec<f64>>,
    /// `[e]`: the USV's GPS fix [x, y], m.
    pub gps: Vec<[f64; 2]>,
    /// Every ping of every cycle, by epoch, then pair.
    pub pings: Vec<Ping>,
}

fn normal(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

fn rng(seed: u64, stream: u64) -> ChaCha8Rng {
    let mut r = ChaCha8Rng::seed_from_u64(seed);
    r.set_stream(stream);
    r
}

/// The measurements of `flight` under `nav`, with links of range `sonar_range` whose line of
/// sight is sampled every `resolution` metres; `seed` draws every error.
pub fn measure(
    flight: &Flight,
    floor: &Seafloor,
    nav: &Navigation,
    sonar_range: f64,
    resolution: f64,
    seed: u64,
) -> Measurements {
    let n = flight.auvs.len();
    let per = ((nav.acoustic_period / nav.sample_period).round() as usize).max(1);
    let epochs = (flight.times.len() - 1) / per + 1;
    let ts = nav.sample_period;

    let mut r_err = rng(seed, 1);
    let errors: Vec<SensorErrors> = (0..n)
        .map(|_| SensorErrors {
            dvl_scale: nav.dvl_scale * normal(&mut r_err),
            heading_bias: nav.heading_bias * normal(&mut r_err),
        })
        .collect();
    let initial = flight
        .auvs
        .iter()
        .map(|s| {
            let p = s[0].position;
            [
                p[0] + nav.initial_noise * normal(&mut r_err),
                p[1] + nav.initial_noise * normal(&mut r_err),
                p[2] + nav.initial_noise * normal(&mut r_err),
            ]
        })
        .collect();

    // dead reckoning and depth, per AUV
    let mut r_nav = rng(seed, 2);
    let mut odometry = Vec::with_capacity(n);
    let mut depth = Vec::with_capacity(n);
    for (i, samples) in flight.auvs.iter().enumerate() {
        let e = errors[i];
        let mut lock = Vec::with_capacity(samples.len());
        let measured: Vec<[f64; 3]> = samples
            .iter()
            .map(|s| {
                let locked = s.altitude.is_some_and(|a| a <= nav.dvl_max_altitude);
                lock.push(locked);
                let v = if locked {
                    s.ground_velocity
                } else {
                    s.water_velocity
                };
                // into the heading frame, measured, and back by the measured heading
                let (sn, cs) = s.heading.sin_cos();
                let fwd = cs * v[0] + sn * v[1];
                let left = -sn * v[0] + cs * v[1];
                let k = 1.0 + e.dvl_scale;
                let fwd = k * fwd + nav.dvl_noise * normal(&mut r_nav);
                let left = k * left + nav.dvl_noise * normal(&mut r_nav);
                let up = k * v[2] + nav.dvl_noise * normal(&mut r_nav);
                let psi = s.heading + e.heading_bias + nav.heading_noise * normal(&mut r_nav);
                let (sn, cs) = psi.sin_cos();
                [cs * fwd - sn * left, sn * fwd + cs * left, up]
            })
            .collect();
        let incs = (0..epochs - 1)
            .map(|ep| {
                let (i0, i1) = (ep * per, (ep + 1) * per);
                let mut d = [0.0; 3];
                for j in i0..i1 {
                    for a in 0..3 {
                        d[a] += 0.5 * ts * (measured[j][a] + measured[j + 1][a]);
                    }
                }
                let locked = lock[i0..=i1].iter().filter(|&&l| l).count();
                Increment {
                    cov: increment_cov(d, per, nav, ts, true),
                    white: increment_cov(d, per, nav, ts, false),
                    delta: d,
                    bottom_lock: locked as f64 / (i1 - i0 + 1) as f64,
                }
            })
            .collect();
        odometry.push(incs);
        depth.push(
            (0..epochs)
                .map(|ep| samples[ep * per].position[2] + nav.depth_noise * normal(&mut r_nav))
                .collect(),
        );
    }

    let mut r_gps = rng(seed, 3);
    let gps = (0..epochs)
        .map(|ep| {
            let p = flight.usv[ep * per];
            [
                p[0] + nav.gps_noise * normal(&mut r_gps),
                p[1] + nav.gps_noise * normal(&mut r_gps),
            ]
        })
        .collect();

    // every pair pings once per cycle; the draws are made for every pair whether or not it is
    // in range, so the sequence of random numbers does not depend on the geometry
    let mut r_ping = rng(seed, 4);
    let mut pings = Vec::with_capacity(epochs * n * (n + 1) / 2);
    let position = |v: usize, ep: usize| {
        if v == n {
            flight.usv[ep * per]
        } else {
            flight.auvs[v][ep * per].position
        }
    };
    for ep in 0..epochs {
        for a in 0..=n {
            for b in a + 1..=n {
                let (pa, pb) = (position(a, ep), position(b, ep));
                let distance =
                    ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2) + (pa[2] - pb[2]).powi(2))
                        .sqrt();
                let u: f64 = r_ping.gen();
                let noise = nav.range_noise * normal(&mut r_ping);
                let line_of_sight = distance < sonar_range
                    && floor
                        .segment_clearance(pa, pb, resolution)
                        .is_ok_and(|c| c.min_clearance >= 0.0);
                let p = if line_of_sight {
                    nav.packet_success * (1.0 - (distance / sonar_range).powf(nav.range_falloff))
                } else {
                    0.0
                };
                pings.push(Ping {
                    epoch: ep,
                    a,
                    b,
                    distance,
                    line_of_sight,
                    received: u < p,
                    // a travel time is never negative
                    range: (distance + noise).max(0.0),
                });
            }
        }
    }
    Measurements {
        period: nav.acoustic_period,
        epochs,
        errors,
        initial,
        odometry,
        depth,
        gps,
        pings,
    }
}

/// The covariance the estimators are told for an increment `d` integrated over `m` samples of
/// `ts` seconds: the white noise of DVL and heading, plus, when `biases`, the biases (scale
/// along the track, heading across it) as if they were drawn anew each cycle. The biases are in
/// fact constant over the mission, so that understates the growth of dead reckoning's error
/// over many cycles; the estimators estimate them instead unless
/// `navigation.estimate_biases = false` (docs/simulation.md).
fn increment_cov(d: [f64; 3], m: usize, nav: &Navigation, ts: f64, biases: bool) -> Cov3 {
    let b = if biases { 1.0 } else { 0.0 };
    let l = d[0].hypot(d[1]);
    let t = if l > 1e-9 {
        [d[0] / l, d[1] / l]
    } else {
        [1.0, 0.0]
    };
    let nrm = [-t[1], t[0]];
    let span = m as f64 * ts;
    let white = m as f64 * ts * ts * nav.dvl_noise.powi(2);
    let speed = l / span;
    let along = white + b * (nav.dvl_scale * l).powi(2);
    let across = white
        + m as f64 * (ts * speed * nav.heading_noise).powi(2)
        + b * (nav.heading_bias * l).powi(2);
    let floor = 1e-6;
    let mut c = [[0.0; 3]; 3];
    for i in 0..2 {
        for j in 0..2 {
            c[i][j] = along * t[i] * t[j] + across * nrm[i] * nrm[j];
        }
        c[i][i] += floor;
    }
    c[2][2] = white + b * (nav.dvl_scale * d[2]).powi(2) + floor;
    c
}
