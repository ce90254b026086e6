//! shoal — localization-aware path planning for one USV and N AUVs, after Eskandari, Savkin and
//! Deghat, "Integrated Localization and Path Planning for an Ocean Exploring Team of Autonomous
//! Underwater Vehicles with Consensus Graph Model Predictive Control" (`../shared/paper.md`).
//!
//! Module map (paper ↔ code):
//! - [`scenario`]: every parameter (Section V defaults), TOML loading and validation.
//! - [`seafloor`]: Z(x, y), bilinear, gradient, segment query 𝓛_r, ESRI ASCII, synthetic floor.
//! - [`vehicle`]: AUV model eqs. (5)–(8) (zero-order hold or Euler), USV model eq. (9).
//! - [`team`]: the window's variables, constraints and objective, shared by P2 and P5.
//! - [`step1`]: Step 1, problem P2, solved by [`scp`] (SCvx trust region) over [`conic`] (Clarabel).
//! - [`step2`]: Step 2, P3 (A2U link) and P4 (A2A path, [`graph`]) per step.
//! - [`step3`]: Step 3, problem P5 with the line-of-sight loop (Algorithm 1, lines 17–22).
//! - [`plan`]: the plan file (`shoal-plan/2`); [`output`]: atomic writing of plan.json and CSVs;
//!   [`positions`]: a plan's positions in latitude/longitude or the grid's projected CRS.
//! - [`metrics`]: the plan's metrics (energy, swept area, height, connectivity, heading rate).
//! - [`check`]: independent verification of a plan against the seafloor.
//! - [`viewer`]: the plan as one self-contained, interactive 3D HTML page (three.js).
//! - [`figures`]: PNG and SVG figures of a plan (the paper's Fig. 4 panels, time series, metrics).

// Numeric kernels index several parallel arrays (x, y, z of positions, gradients and
// coefficients) with one loop variable; iterator chains would obscure the maths.
#![allow(clippy::needless_range_loop)]

pub mod check;
pub mod conic;
pub mod figures;
pub mod graph;
pub mod linearise;
pub mod metrics;
pub mod output;
pub mod plan;
pub mod planner;
pub mod positions;
pub mod report;
pub mod scenario;
pub mod scp;
pub mod seafloor;
pub mod step1;
pub mod step2;
pub mod step3;
pub mod team;
pub mod trajectory;
pub mod vehicle;
pub mod viewer;
