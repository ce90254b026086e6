//! The synthetic seafloor of the paper's Fig. 4(a).

use serde::{Deserialize, Serialize};

/// Parameters of the synthetic seafloor of Fig. 4(a): a gently sloping floor with seeded
/// seamounts and valleys. Generated from `seed` of the scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SyntheticParams {
    /// Extent in x and y, metres; the grid is centred on the origin (the USV's start).
    pub size: [f64; 2],
    /// Grid cell size, metres.
    pub cell: f64,
    /// Floor elevation at the origin, metres (negative).
    pub base_depth: f64,
    /// Regional slope [dZ/dx, dZ/dy] (dimensionless, metres per metre).
    pub slope: [f64; 2],
    /// Number of seamounts (Gaussian bumps rising from the floor).
    pub seamounts: usize,
    /// Number of valleys (Gaussian troughs).
    pub valleys: usize,
    /// Range of bump heights / trough depths, metres.
    pub relief: [f64; 2],
    /// Range of bump / trough radii (Gaussian σ), metres.
    pub radius: [f64; 2],
    /// Elevation bounds: the floor is clamped into [shallowest, deepest] is NOT done; instead
    /// the generator rescales so that the floor lies within `depth_range` = [deepest, shallowest].
    pub depth_range: [f64; 2],
}

impl Default for SyntheticParams {
    fn default() -> Self {
        SyntheticParams {
            size: [12_000.0, 12_000.0],
            cell: 25.0,
            base_depth: -100.0,
            slope: [-0.002, 0.001],
            seamounts: 40,
            valleys: 25,
            relief: [15.0, 45.0],
            radius: [150.0, 600.0],
            depth_range: [-140.0, -50.0],
        }
    }
}
