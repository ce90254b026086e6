//! One run of a comparison: what was planned, how long it took, what the plan achieves and how
//! far inside its constraints `shoal check` finds it (docs/baseline.md lists the columns).

use crate::check::CheckReport;
use crate::error::PlanError;
use crate::plan::Plan;
use serde::{Deserialize, Serialize};

/// One run: (scenario, method, N, seed) and its measures. NaN where the run made no plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// The base scenario's name.
    pub scenario: String,
    /// "mpc" or "rrt-like".
    pub method: String,
    /// N.
    pub auvs: usize,
    /// The seed.
    pub seed: u64,
    /// "passed" (every constraint holds), "violated" (the check fails) or "failed" (no plan).
    pub status: String,
    /// Why there is no plan, or the failing check families; empty otherwise.
    pub error: String,
    /// Wall-clock time of planning (floor loading included), seconds.
    pub wall_s: f64,
    /// P2's objective (Step 1: energy, floor-hugging, the USV's term) summed over the windows,
    /// at Step 1's paths: the MPC's Step 1 optimum, or the sampled paths (both planners
    /// minimise exactly this).
    pub p2_objective: f64,
    /// OF1_1 over the mission: Σ‖U‖², (m/s²)².
    pub energy: f64,
    /// Mean height above the floor over the AUV waypoints, m (OF1_2's aim: low).
    pub mean_height_m: f64,
    /// Least height above the floor, m.
    pub min_height_m: f64,
    /// How far the USV ended from where it started, m (OF1_8's aim: far).
    pub usv_moved_m: f64,
    /// How far the USV ended from `usv.destination`, m (OF1_8_2's aim: near).
    pub usv_to_destination_m: f64,
    /// Seafloor swept at survey altitude, km².
    pub explored_km2: f64,
    /// Fraction of steps at which every AUV reaches the USV through links in range and sight.
    pub connected_fraction: f64,
    /// Fraction of steps at which the planned chain has every link in range and in sight.
    pub chain_fraction: f64,
    /// Planned link-steps outside the band [d_s − d_t, d_s].
    pub out_of_band: usize,
    /// Worst margin of C2_2 along the segments, m.
    pub margin_floor_m: f64,
    /// Worst margin of C1_6 at k = 0, K, m.
    pub margin_c1_6_m: f64,
    /// Worst margin of C1_7, m/s.
    pub margin_speed_mps: f64,
    /// Worst margin of C1_14, rad/s.
    pub margin_heading_radps: f64,
    /// Worst margin of C1_5, m.
    pub margin_c1_5_m: f64,
    /// Vehicle draws of a sampling planner (0 for the MPC).
    pub samples_drawn: u64,
    /// Valid team samples it kept as tree nodes (0 for the MPC).
    pub samples_kept: u64,
}

impl Row {
    /// A row with its key and no measures yet.
    pub fn key(scenario: &str, method: &str, auvs: usize, seed: u64) -> Row {
        Row {
            scenario: scenario.into(),
            method: method.into(),
            auvs,
            seed,
            status: String::new(),
            error: String::new(),
            wall_s: f64::NAN,
            p2_objective: f64::NAN,
            energy: f64::NAN,
            mean_height_m: f64::NAN,
            min_height_m: f64::NAN,
            usv_moved_m: f64::NAN,
            usv_to_destination_m: f64::NAN,
            explored_km2: f64::NAN,
            connected_fraction: f64::NAN,
            chain_fraction: f64::NAN,
            out_of_band: 0,
            margin_floor_m: f64::NAN,
            margin_c1_6_m: f64::NAN,
            margin_speed_mps: f64::NAN,
            margin_heading_radps: f64::NAN,
            margin_c1_5_m: f64::NAN,
            samples_drawn: 0,
            samples_kept: 0,
        }
    }

    /// Whether the run made a plan.
    pub fn planned(&self) -> bool {
        self.status != "failed"
    }

    /// Record a plan, its check and the time it took.
    pub fn measure(&mut self, plan: &Plan, report: &CheckReport, wall_s: f64) {
        let m = &plan.metrics;
        self.wall_s = wall_s;
        self.status = if report.passed() {
            "passed"
        } else {
            "violated"
        }
        .into();
        self.error = report
            .failures()
            .iter()
            .map(|f| f.name)
            .collect::<Vec<_>>()
            .join("; ");
        self.p2_objective = plan.windows.iter().map(|w| w.step1.objective.total).sum();
        self.energy = m.input_energy;
        self.mean_height_m = m.mean_height;
        self.min_height_m = m.min_height;
        self.explored_km2 = m.explored_area_km2;
        self.connected_fraction = m.connected_fraction;
        self.chain_fraction = m.chain_fraction;
        let first = plan.initial.usv;
        if let Some(last) = plan
            .windows
            .last()
            .and_then(|w| w.final_.usv.position.last())
        {
            let dest = plan.scenario.usv.destination;
            self.usv_moved_m = (last[0] - first[0]).hypot(last[1] - first[1]);
            self.usv_to_destination_m = (last[0] - dest[0]).hypot(last[1] - dest[1]);
        }
        self.out_of_band = plan.windows.iter().map(|w| w.links.out_of_band.len()).sum();
        let margin = |family: &str| report.family(family).map_or(f64::NAN, |f| f.worst_margin);
        self.margin_floor_m = margin("C2_2 floor clearance (segments)");
        self.margin_c1_6_m = margin("C1_6 sonar range at k = 0, K");
        self.margin_speed_mps = margin("C1_7 AUV speed");
        self.margin_heading_radps = margin("C1_14 heading rate");
        self.margin_c1_5_m = margin("C1_5 range ≤ d_max");
        for s in plan.windows.iter().filter_map(|w| w.sampling.as_ref()) {
            self.samples_drawn += s.drawn;
            self.samples_kept += s.kept;
        }
    }

    /// Record a run that made no plan.
    pub fn fail(&mut self, e: &PlanError, wall_s: f64) {
        self.status = "failed".into();
        self.error = e.to_string();
        self.wall_s = wall_s;
    }
}
