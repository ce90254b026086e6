//! What flying a plan costs, counted before anything is flown: the RK4 steps, the samples kept,
//! the positions the estimators solve for, and those times the Monte Carlo runs. Each count
//! comes from the plan's duration and the `[simulation]` and `[navigation]` periods, in
//! floating point (so that a plan lasting 10³⁰⁰ s gives a count that compares, not one that
//! wraps), and is checked against a limit before it becomes a `usize`: a tiny step or a plan
//! lasting years is refused with a message, instead of hanging or running out of memory.

use super::run::SimError;
use crate::plan::Plan;

/// Most RK4 steps of one simulation, over every AUV and both flights (the plan's final stages
/// and its Step 1 paths). A step of the 6-DoF model under its controller takes about 2.5 µs
/// on one core: at most about 40 minutes of flying.
pub const MAX_STEPS: f64 = 1e9;
/// Most samples kept of one simulation, over every AUV and both flights. A sample takes about
/// 150 bytes with what is measured from it: at most about 1.5 GB.
pub const MAX_SAMPLES: f64 = 1e7;
/// Most positions the estimators solve for in one flight: vehicles (the AUVs and the USV) ×
/// acoustic epochs. Ten estimates over the default plan's 1,206 positions take 0.5 s a run,
/// and the cost grows a little faster than the count: at most about a minute a run.
pub const MAX_POSITIONS: f64 = 1e5;
/// Most positions × runs of a Monte Carlo (`--runs`): at most a few hours.
pub const MAX_RUN_POSITIONS: f64 = 2e7;

/// The counts of one simulation, each within its limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cost {
    /// The plan's duration, s: its windows × K × δ.
    pub duration: f64,
    /// Number of AUVs flown.
    pub auvs: usize,
    /// The sampling period, s (`navigation.sample_period`).
    pub sample_period: f64,
    /// Samples per AUV and flight after the one at t = 0.
    pub samples: usize,
    /// RK4 steps per sampling period (at least 1).
    pub substeps: usize,
    /// Acoustic epochs per flight, the one at t = 0 included.
    pub epochs: usize,
    /// Monte Carlo runs.
    pub runs: usize,
}

/// A count for a message: "2000", "6.0e10".
fn count(x: f64) -> String {
    if x < 1e6 {
        format!("{x:.0}")
    } else {
        format!("{x:.1e}")
    }
}

/// A duration for a message: "2000 s", "3.0e9 s".
fn seconds(x: f64) -> String {
    if x.is_finite() && x < 1e6 {
        format!("{} s", (x * 1e3).round() / 1e3)
    } else {
        format!("{x:.1e} s")
    }
}

/// `x` ≤ `limit` (false for NaN).
fn within(x: f64, limit: f64) -> bool {
    x <= limit
}

impl Cost {
    /// The counts of flying `plan` (read from `plan_name`) `runs` times, or
    /// [`SimError::TooLong`] naming the setting and the plan's duration when one is above its
    /// limit. The settings must have passed the scenario's validation (positive, finite
    /// periods).
    pub fn of(plan: &Plan, plan_name: &str, runs: usize) -> Result<Cost, SimError> {
        let s = &plan.scenario;
        let nav = &s.navigation;
        let step = s.simulation.step;
        let windows = plan.windows.len();
        let duration = windows as f64 * s.horizon.steps as f64 * s.horizon.dt;
        let how_long = format!(
            "{plan_name} lasts {} ({windows} window{} of K = {} steps of δ = {} s)",
            seconds(duration),
            if windows == 1 { "" } else { "s" },
            s.horizon.steps,
            s.horizon.dt
        );
        let too_long = |what: String, limit: f64, instead: &str| SimError::TooLong {
            plan: how_long.clone(),
            what,
            limit: count(limit),
            instead: instead.into(),
        };
        let auvs = s.team.auvs;
        // every AUV is flown twice: the plan's final stages and its Step 1 paths
        let flown = 2.0 * auvs as f64;
        let samples = (duration / nav.sample_period).round();
        let substeps = (nav.sample_period / step).round().max(1.0);
        let steps = samples * substeps * flown;
        if !within(steps, MAX_STEPS) {
            return Err(too_long(
                format!(
                    "at simulation.step = {step} s its {auvs} AUV{} take {} RK4 steps over the \
                     two flights (its final stages and its Step 1 paths)",
                    if auvs == 1 { "" } else { "s" },
                    count(steps)
                ),
                MAX_STEPS,
                "a longer simulation.step, or a shorter plan",
            ));
        }
        let kept = (samples + 1.0) * flown;
        if !within(kept, MAX_SAMPLES) {
            return Err(too_long(
                format!(
                    "at navigation.sample_period = {} s its {auvs} AUV{} keep {} samples over the \
                     two flights",
                    nav.sample_period,
                    if auvs == 1 { "" } else { "s" },
                    count(kept)
                ),
                MAX_SAMPLES,
                "a longer navigation.sample_period, or a shorter plan",
            ));
        }
        let per = (nav.acoustic_period / nav.sample_period).round().max(1.0);
        let epochs = (samples / per).floor() + 1.0;
        let vehicles = auvs as f64 + 1.0;
        let positions = vehicles * epochs;
        if !within(positions, MAX_POSITIONS) {
            return Err(too_long(
                format!(
                    "at navigation.acoustic_period = {} s the estimators solve for {} vehicles × \
                     {} epochs = {} positions per flight",
                    nav.acoustic_period,
                    count(vehicles),
                    count(epochs),
                    count(positions)
                ),
                MAX_POSITIONS,
                "a longer navigation.acoustic_period, or a shorter plan",
            ));
        }
        let work = positions * runs as f64;
        if !within(work, MAX_RUN_POSITIONS) {
            return Err(SimError::TooManyRuns {
                runs,
                positions: count(positions),
                work: count(work),
                limit: count(MAX_RUN_POSITIONS),
                most: (MAX_RUN_POSITIONS / positions).floor() as usize,
            });
        }
        // every count is now a whole number far below usize::MAX
        Ok(Cost {
            duration,
            auvs,
            sample_period: nav.sample_period,
            samples: samples as usize,
            substeps: substeps as usize,
            epochs: epochs as usize,
            runs,
        })
    }
}
