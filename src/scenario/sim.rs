//! The sections `shoal simulate` reads: `[current]` (the ocean current
//! the vehicles feel), `[navigation]` (the sensors and acoustic modems, each default a typical
//! value for a REMUS 100-class vehicle, with its source) and `[simulation]` (the integrator).
//! The MPC planner plans in `[current]`'s velocity and profile too (`sim::current::planned`;
//! not in its grid files): the AUVs' planned velocities are through the water.

use serde::{Deserialize, Serialize};

/// `[current]`: a horizontal ocean current, irrotational and constant in time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Current {
    /// Velocity [east, north] at the surface, m/s.
    pub velocity: [f64; 2],
    /// Depth profile: pairs [depth (m, ≥ 0), factor], depths increasing; the current at depth d
    /// is `velocity` times the factor interpolated linearly in d (held beyond the ends).
    /// Empty: the same at every depth.
    pub profile: Vec<[f64; 2]>,
    /// Grid file of the current's east component u(x, y) at the surface, m/s (ESRI ASCII or
    /// GeoTIFF, in the planner's frame; a relative path is from the plan file's directory).
    /// With `file_north`, the grids replace `velocity`; both or neither.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file_east: Option<String>,
    /// Grid file of the current's north component v(x, y) at the surface, m/s (see
    /// `file_east`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file_north: Option<String>,
}

impl Default for Current {
    fn default() -> Self {
        Current {
            // ours: a weak tidal current (shelf currents are typically 0.1–0.5 m/s), across
            // the default mission's first course (east), so that tracking it shows
            velocity: [0.0, 0.1],
            profile: Vec::new(),
            file_east: None,
            file_north: None,
        }
    }
}

/// `[navigation]`: what each vehicle measures, and how the acoustic modems range.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Navigation {
    /// Sampling period of the DVL, the heading, the depth sensor and the USV's GPS, s.
    pub sample_period: f64,
    /// DVL velocity noise, m/s (1σ per axis and sample).
    pub dvl_noise: f64,
    /// DVL scale-factor error, as a fraction (1σ, one draw per AUV and mission).
    pub dvl_scale: f64,
    /// Highest altitude above the floor at which the DVL keeps bottom lock, m; above it the
    /// DVL measures the velocity through the water (water track), blind to the current.
    pub dvl_max_altitude: f64,
    /// Heading noise of the compass / AHRS, rad (1σ per sample).
    pub heading_noise: f64,
    /// Heading bias of the compass / AHRS, rad (1σ, one draw per AUV and mission).
    pub heading_bias: f64,
    /// Depth (pressure) sensor noise, m (1σ per sample).
    pub depth_noise: f64,
    /// USV GPS noise, m (1σ per horizontal axis and fix).
    pub gps_noise: f64,
    /// Error of each AUV's position at the start of the mission (a GPS fix before the dive),
    /// m (1σ per axis).
    pub initial_noise: f64,
    /// Period of the acoustic cycle, s: every link pings once per cycle.
    pub acoustic_period: f64,
    /// Speed of sound, m/s (one-way travel time × speed = range).
    pub sound_speed: f64,
    /// Acoustic range noise, m (1σ).
    pub range_noise: f64,
    /// Probability that a ping is received at short range.
    pub packet_success: f64,
    /// How fast reception falls with range d: p(d) = packet_success · (1 − (d / d_s)^falloff)
    /// below the sonar range d_s (`acoustic.sonar_range`), 0 beyond it or without line of sight.
    pub range_falloff: f64,
    /// Whether the estimators estimate each AUV's compass bias and DVL scale error (unknowns
    /// with the priors above) or treat them as noise drawn anew each acoustic cycle.
    pub estimate_biases: bool,
}

impl Default for Navigation {
    fn default() -> Self {
        Navigation {
            sample_period: 1.0,
            // a 1.2 MHz DVL (the REMUS 100's): noise of order 1 cm/s per ping at 1–2 m/s and
            // a long-term accuracy of ±0.2 % ± 1 mm/s (Teledyne RDI Workhorse Navigator 1200
            // kHz specification); bottom track to about 30 m altitude
            dvl_noise: 0.01,
            dvl_scale: 0.002,
            dvl_max_altitude: 30.0,
            // a magnetic compass / AHRS: about 1° of bias after calibration and 0.5° of noise
            // (Kinsey, Eustice, Whitcomb, "A survey of underwater vehicle navigation: recent
            // advances and new challenges", IFAC MCMC 2006: magnetic compasses 1–10°,
            // gyrocompasses 0.1°)
            heading_noise: 0.5_f64.to_radians(),
            heading_bias: 1.0_f64.to_radians(),
            // a strain-gauge pressure sensor: 0.1 % of a 100 m full scale
            depth_noise: 0.1,
            // a single-frequency GPS receiver: a few metres (U.S. GPS SPS Performance
            // Standard, 2020: ≤ 8 m 95 % horizontal, typically 2–4 m)
            gps_noise: 3.0,
            initial_noise: 3.0,
            // one-way travel-time ranging with synchronised clocks (Eustice, Singh, Leonard,
            // Whitcomb, "Synchronous-clock one-way-travel-time acoustic navigation for
            // underwater vehicles", J. Field Robotics 28(1), 2011): a cycle of ~10 s shares
            // the channel among the team; range error of order 1 m (timing, and a sound speed
            // known to ~0.3 %, 0.5 m at 150 m)
            acoustic_period: 10.0,
            sound_speed: 1500.0,
            range_noise: 1.0,
            // ours: 90 % of packets at short range, 74 % at 0.8·d_s, 47 % at 0.9·d_s
            packet_success: 0.9,
            range_falloff: 6.0,
            estimate_biases: true,
        }
    }
}

/// `[simulation]`: how a plan is flown.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Simulation {
    /// Fixed step of the RK4 integrator of the 6-DoF vehicle model, s.
    pub step: f64,
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation { step: 0.05 }
    }
}

/// The current's depth factor at depth `d` (m, ≥ 0) of a `profile` as [`Current::profile`].
pub fn profile_factor(profile: &[[f64; 2]], d: f64) -> f64 {
    match profile {
        [] => 1.0,
        [only] => only[1],
        _ => {
            let i = profile.partition_point(|p| p[0] <= d);
            if i == 0 {
                return profile[0][1];
            }
            if i == profile.len() {
                return profile[i - 1][1];
            }
            let (a, b) = (profile[i - 1], profile[i]);
            a[1] + (b[1] - a[1]) * (d - a[0]) / (b[0] - a[0])
        }
    }
}

/// d(factor)/d(depth) of [`profile_factor`] at depth `d` (m, ≥ 0), 1/m: the slope of the
/// piece holding `d` (0 beyond the ends and for fewer than two pairs; at a node, the slope of
/// the piece below it, as `profile_factor` places the node there).
pub fn profile_slope(profile: &[[f64; 2]], d: f64) -> f64 {
    if profile.len() < 2 {
        return 0.0;
    }
    let i = profile.partition_point(|p| p[0] <= d);
    if i == 0 || i == profile.len() {
        return 0.0;
    }
    let (a, b) = (profile[i - 1], profile[i]);
    (b[1] - a[1]) / (b[0] - a[0])
}
