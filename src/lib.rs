//! shoal — localization-aware path planning for one USV and N AUVs, after Eskandari, Savkin and
//! Deghat, "Integrated Localization and Path Planning for an Ocean Exploring Team of Autonomous
//! Underwater Vehicles with Consensus Graph Model Predictive Control" (arXiv 2505.07484).
//!
//! Plan the paper's experiment and check the plan:
//!
//! ```no_run
//! let scenario = shoal::Scenario::default();
//! let floor = shoal::Seafloor::synthetic(&scenario.seafloor.synthetic, scenario.seed)?;
//! let plan = shoal::Planner::new(&scenario, &floor).run()?;
//! assert!(shoal::check(&plan, &floor).passed());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Module map (paper ↔ code):
//! - [`scenario`]: every parameter (Section V defaults), TOML loading and validation.
//! - [`seafloor`]: Z(x, y), bilinear, gradient, segment query 𝓛_r, grid files, synthetic floor.
//! - [`planner`]: Algorithm 1's loop ([`Planner`]); [`mission`]: its set-up (initial state,
//!   the floor a scenario names, each window's start); [`error`]: what can stop a plan.
//! - Inside the planner (hidden from these docs, public for the benchmarks): `team`, the
//!   window problem, one file per constraint family; `step1` (P2), `step2` (P3 and P4, the
//!   longest Hamiltonian path), `step3` (P5 with the line-of-sight loop); `scp` (SCvx) over
//!   `conic` (Clarabel); `vehicle` (eqs. (5)–(9)); `linearise` (the nonconvex terms'
//!   gradients).
//! - [`plan`]: the plan file (`shoal-plan/5`); [`output`]: atomic writing of plan.json and CSVs;
//!   [`positions`]: a plan's positions in latitude/longitude or the grid's projected CRS.
//! - [`check`](mod@check): independent verification of a plan against the seafloor
//!   ([`check()`](fn@check) runs it).
//! - [`report`]: the plan's summary table; [`viewer`]: the plan as one self-contained,
//!   interactive 3D HTML page (three.js); [`figures`]: PNG and SVG figures of a plan.

// Numeric kernels index several parallel arrays (x, y, z of positions, gradients and
// coefficients) with one loop variable; iterator chains would obscure the maths.
#![allow(clippy::needless_range_loop)]
#![warn(missing_docs)]

pub mod advice;
mod atomic_file;
pub mod check;
pub mod compare;
pub mod error;
pub mod figures;
pub mod mission;
pub mod output;
pub mod output_set;
pub mod plan;
pub mod planner;
pub mod positions;
pub mod report;
pub mod sampling;
pub mod scenario;
pub mod seafloor;
pub mod sim;
pub mod sweep;
pub mod viewer;

#[doc(hidden)]
pub mod conic;
#[doc(hidden)]
pub mod linearise;
#[doc(hidden)]
pub mod metrics;
#[doc(hidden)]
pub mod scp;
#[doc(hidden)]
pub mod step1;
#[doc(hidden)]
pub mod step2;
#[doc(hidden)]
pub mod step3;
#[doc(hidden)]
pub mod team;
#[doc(hidden)]
pub mod trajectory;
#[doc(hidden)]
pub mod vehicle;

pub use error::PlanError;
pub use plan::Plan;
pub use planner::{Planner, Progress, Provenance};
pub use scenario::Scenario;
pub use seafloor::Seafloor;

/// Check every constraint of `plan` against `floor` ([`check::check_plan`]).
pub fn check(plan: &Plan, floor: &Seafloor) -> check::CheckReport {
    check::check_plan(plan, floor)
}
