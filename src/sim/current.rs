//! The ocean current of `[current]`: horizontal, constant in time, uniform at each depth, scaled
//! by an optional depth profile.

use crate::scenario::{profile_factor, Current};

/// The current as a field over the water column.
#[derive(Debug, Clone, PartialEq)]
pub struct CurrentField {
    velocity: [f64; 2],
    profile: Vec<[f64; 2]>,
}

impl CurrentField {
    /// The field of a scenario's `[current]`.
    pub fn new(c: &Current) -> CurrentField {
        CurrentField {
            velocity: c.velocity,
            profile: c.profile.clone(),
        }
    }

    /// Still water.
    pub fn still() -> CurrentField {
        CurrentField {
            velocity: [0.0; 2],
            profile: Vec::new(),
        }
    }

    /// The current's velocity at `p` = [x, y, z] (m, z up), m/s in shoal's frame (x east,
    /// y north, z up; the vertical component is 0).
    pub fn at(&self, p: [f64; 3]) -> [f64; 3] {
        let f = profile_factor(&self.profile, (-p[2]).max(0.0));
        [f * self.velocity[0], f * self.velocity[1], 0.0]
    }
}
