//! What every benchmark starts from: the default scenario with N AUVs on its synthetic floor,
//! the vehicle models and the first window's start.

// each bench binary compiles this module and uses part of it
#![allow(dead_code)]

use shoal::mission::{initial_state, scenario_floor, FloorSource};
use shoal::scenario::Scenario;
use shoal::seafloor::Seafloor;
use shoal::team::{LinkSet, TeamProblem};
use shoal::trajectory::Start;
use shoal::trajectory::Trajectory;
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

impl Setup {
    /// A window problem of this set-up (P2's until given links).
    pub fn problem(&self) -> TeamProblem<'_> {
        TeamProblem::new(
            &self.scenario,
            &self.floor,
            &self.keep_out,
            self.auv,
            self.usv,
            self.start.clone(),
        )
    }
}

/// The default scenario with `n` AUVs (K = 20, δ = 100 s, d_s = 150 m, seed 1).
pub fn setup(n: usize) -> Setup {
    let steps = Scenario::default().horizon.steps;
    setup_steps(n, steps)
}

/// The default scenario with `n` AUVs and its window of K·δ = 2000 s cut into `steps` steps.
pub fn setup_steps(n: usize, steps: usize) -> Setup {
    let mut scenario = Scenario::default();
    scenario.team.auvs = n;
    let window = scenario.horizon.dt * scenario.horizon.steps as f64;
    scenario.horizon.steps = steps;
    scenario.horizon.dt = window / steps as f64;
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

/// Step 1's plan (P2's SCP run on `p2`), and P5 about it as the planner builds it: Step 2's
/// chain as its links, with its lanes term; and Step 3's first trust radius.
pub fn step3<'b>(b: &'b Setup, p2: &mut TeamProblem) -> (Trajectory, TeamProblem<'b>, f64) {
    let s = &b.scenario;
    let step1 = shoal::step1::solve(p2, None, &mut |_| {})
        .expect("P2")
        .0
        .iterate;
    let graph = shoal::step2::solve(
        &step1,
        &b.floor,
        s.acoustic.resolution,
        s.acoustic.sonar_range,
        s.acoustic.graph,
    );
    let top = s.acoustic.link_margin * s.acoustic.sonar_range;
    let links = LinkSet::from_graph(&graph, top, s.acoustic.band_tolerance);
    let p5 = b.problem().with_links(links).with_lanes(&step1);
    let radius = s.acoustic.band_tolerance.min(s.scp.trust_region);
    (step1, p5, radius)
}
