//! What every benchmark starts from: the default scenario with N AUVs on its synthetic floor,
//! the vehicle models and the first window's start.

// each bench binary compiles this module and uses part of it
#![allow(dead_code)]

use shoal::mission::{initial_state, scenario_floor, FloorSource};
use shoal::scenario::Scenario;
use shoal::seafloor::Seafloor;
use shoal::trajectory::Start;
use shoal::vehicle::{AuvModel, UsvModel};
use std::path::Path;

pub struct Setup {
    pub scenario: Scenario,
    pub floor: Seafloor,
    pub source: FloorSource,
    pub keep_out: Seafloor,
    pub auv: AuvModel,
    pub usv: UsvModel,
    pub start: Start,
}

/// The default scenario with `n` AUVs (K = 20, δ = 100 s, d_s = 150 m, seed 1).
pub fn setup(n: usize) -> Setup {
    let mut scenario = Scenario::default();
    scenario.team.auvs = n;
    let (floor, source) = scenario_floor(&scenario, Path::new("")).expect("default floor");
    let auv = AuvModel::new(&scenario.auv, scenario.horizon.dt).expect("model");
    let usv = UsvModel {
        dt: scenario.horizon.dt,
        max_speed: scenario.usv.max_speed,
    };
    let keep_out = floor.keep_out();
    let init = initial_state(&scenario, &floor, &keep_out).expect("initial state");
    let start = Start {
        usv: init.usv,
        auvs: init.auvs,
    };
    Setup {
        scenario,
        floor,
        source,
        keep_out,
        auv,
        usv,
        start,
    }
}
