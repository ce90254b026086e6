//! The team problem of one window: the variables (states, inputs, slacks of the USV and N AUVs
//! over k = 0..=K), the constraints and the objective terms that P2 (Step 1, `step1`) and P5
//! (Step 3, `step3`) share, and its SCvx glue (`scp`). P5 adds the acoustic links (`Links`).
//!
//! Departures from the paper, each for a reason:
//! - OF1_8 does not depend on k, so it enters once (w8 absorbs the paper's factor K).
//! - OF1_1 sums the AUV inputs only: the USV's input is a velocity, not a per-mass force.
//! - C2_2 is linearised about the previous iterate (value and gradient of Z), not frozen, and is
//!   imposed at every sample of every segment between waypoints (the rule of 𝓛_r), not only at
//!   the waypoints: 100 s apart, a seamount can sit between two waypoints.
//! - C2_3/C2_4 are replaced by C1_14 as a disjunction with convex restriction pieces (`heading`).
//! - Obstacles (NODATA and land cells): every floor constraint (C2_2 rows, the true violation,
//!   the first guess) uses the keep-out field of `Seafloor::keep_out`, in which every obstacle
//!   cell lies above the surface, instead of the floor; over a grid with obstacles the USV too
//!   keeps the field 0.25 m below the surface along its segments, P5 keeps every planned
//!   link's line of sight over it (`keep_out`), and the first guess goes round obstacles
//!   (`detour`). The objective's height term and the plan's records use the floor itself.
//! - The whole is solved by SCvx (`scp`), with a trust region and a merit function.

pub(crate) mod assemble;
mod detour;
mod guess;
mod heading;
mod keep_out;
mod layout;

pub use layout::Layout;

use crate::conic::{ConicSolution, ConicSolver, Pattern};
use crate::linearise::usv_away;
use crate::planner::PlanError;
use crate::scenario::{DepthObjective, Scenario, UsvObjective};
use crate::scp::{self, Evaluation, ScpOutcome, ScpProblem};
use crate::seafloor::Seafloor;
use crate::step3::LinkSet;
use crate::trajectory::{Start, Trajectory};
use crate::vehicle::{AuvModel, UsvModel};
use assemble::h2;
use clarabel::solver::SolverStatus;
use heading::HeadingRule;

/// Turn (rad per step) the convex model keeps below ψ̇_max·δ (constraint tightening).
const HEADING_MARGIN: f64 = 0.005;

/// P2 for one window.
pub struct TeamProblem<'a> {
    pub(crate) scenario: &'a Scenario,
    pub(crate) floor: &'a Seafloor,
    /// The keep-out field of `floor` (`Seafloor::keep_out`): what the constraints see.
    pub(crate) keep_out: &'a Seafloor,
    auv: AuvModel,
    usv: UsvModel,
    start: Start,
    pub(crate) layout: Layout,
    /// C1_14, with the model's cone tightened by `HEADING_MARGIN`.
    heading: HeadingRule,
    /// P5's planned links and their bands (None for P2).
    pub(crate) links: Option<LinkSet>,
    solver: Option<ConicSolver>,
}

/// The unweighted objective terms for a trajectory (P2's, plus P5's when links are set).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Terms {
    pub energy: f64,
    /// Σ z.
    pub depth: f64,
    /// Σ (z − Z(x, y)).
    pub height: f64,
    pub usv: f64,
    /// OF1_5: Σ_k Σ ‖P_i − P_j‖² over pairs not joined by an A2A edge at k, m².
    pub spread: f64,
    /// OF1_3 as C5_2's slack: Σ_k metres by which the A2U link is outside its band.
    pub band_a2u: f64,
    /// OF1_4 as C5_3's slack: Σ_k Σ metres by which A2A edges are outside their bands.
    pub band_a2a: f64,
}

impl<'a> TeamProblem<'a> {
    /// The window of `scenario` from `start` over `floor`, whose keep-out field
    /// (`floor.keep_out()`, built once per plan by the caller) is `keep_out`.
    pub fn new(
        scenario: &'a Scenario,
        floor: &'a Seafloor,
        keep_out: &'a Seafloor,
        auv: AuvModel,
        usv: UsvModel,
        start: Start,
    ) -> TeamProblem<'a> {
        let layout = Layout {
            k: scenario.horizon.steps,
            n: scenario.team.auvs,
            links: 0,
            obstacles: floor.has_obstacles(),
        };
        TeamProblem {
            scenario,
            floor,
            keep_out,
            auv,
            usv,
            start,
            layout,
            heading: HeadingRule::new(
                scenario.auv.max_heading_rate,
                (scenario.auv.max_heading_rate - HEADING_MARGIN / scenario.horizon.dt).max(0.0),
                scenario.horizon.dt,
                scenario.auv.min_heading_speed,
            ),
            links: None,
            solver: None,
        }
    }

    /// The same window with P5's planned links (Step 3): adds the band slacks to the layout.
    pub fn with_links(mut self, links: LinkSet) -> TeamProblem<'a> {
        self.layout.links = links.per_step();
        self.links = Some(links);
        self.solver = None;
        self
    }

    /// "step1" (P2) or "step3" (P5), for errors.
    pub fn stage(&self) -> &'static str {
        if self.links.is_some() {
            "step3"
        } else {
            "step1"
        }
    }

    pub fn layout(&self) -> Layout {
        self.layout
    }

    pub fn start(&self) -> &Start {
        &self.start
    }

    /// Unweighted objective terms (OF1_1, OF1_2, OF1_8 or OF1_8_2).
    pub fn terms(&self, t: &Trajectory) -> Terms {
        let energy = t
            .auv_u
            .iter()
            .flatten()
            .map(|u| u.iter().map(|c| c * c).sum::<f64>())
            .sum();
        let depth = t
            .auv_p
            .iter()
            .flat_map(|p| p[1..].iter())
            .map(|p| p[2])
            .sum();
        let height = t
            .auv_p
            .iter()
            .flat_map(|p| p[1..].iter())
            .map(|p| p[2] - self.floor_linearisation(*p).0)
            .sum();
        let (spread, band_a2u, band_a2a) = match &self.links {
            Some(links) => links.terms(t),
            None => (0.0, 0.0, 0.0),
        };
        let pk = t.usv_p[self.layout.k];
        let usv = match self.scenario.usv.objective {
            UsvObjective::Away => {
                -usv_away([pk[0] - self.start.usv[0], pk[1] - self.start.usv[1]]).0
            }
            UsvObjective::Destination => {
                let d = self.scenario.usv.destination;
                (pk[0] - d[0]).powi(2) + (pk[1] - d[1]).powi(2)
            }
        };
        Terms {
            energy,
            depth,
            height,
            usv,
            spread,
            band_a2u,
            band_a2a,
        }
    }

    /// Weighted objective J of P2.
    pub fn objective(&self, t: &Terms) -> f64 {
        self.weighted(t).iter().sum()
    }

    /// The weighted terms of J: w1·OF1_1, w2·OF1_2, the USV term, −w5·OF1_5, w3·OF1_3,
    /// w4·OF1_4 (the last three zero without links).
    fn weighted(&self, t: &Terms) -> [f64; 6] {
        let w = &self.scenario.weights;
        let usv = match self.scenario.usv.objective {
            UsvObjective::Away => -w.w8 * t.usv,
            UsvObjective::Destination => w.w8_2 * t.usv,
        };
        let of1_2 = match w.of1_2 {
            DepthObjective::Height => t.height,
            DepthObjective::Depth => t.depth,
        };
        [
            w.w1 * t.energy,
            w.w2 * of1_2,
            usv,
            -w.w5 * t.spread,
            w.w3 * t.band_a2u,
            w.w4 * t.band_a2a,
        ]
    }

    /// Worst floor-clearance violation (metres) of the segment k−1 → k of AUV n over the
    /// keep-out field, sampled by the seafloor's own 𝓛_r rule, and where it occurs.
    fn floor_violation(&self, t: &Trajectory, n: usize, k: usize) -> (f64, [f64; 3]) {
        let (a, b) = (t.auv_p[n][k - 1], t.auv_p[n][k]);
        match self
            .keep_out
            .segment_clearance(a, b, self.scenario.acoustic.resolution)
        {
            Ok(c) => (self.scenario.auv.floor_clearance - c.min_clearance, c.at),
            // Outside the grid: only possible for a reference the bounds have not yet acted on.
            Err(_) => (f64::INFINITY, b),
        }
    }

    /// Heading violation at step k of AUV n: (the continuous violation v in m/s for the merit,
    /// the turn beyond θ in rad as the checker measures it); see `heading`.
    fn heading_violation(&self, t: &Trajectory, n: usize, k: usize) -> (f64, f64) {
        let a = h2(t.auv_v[n][k - 1]);
        let b = h2(t.auv_v[n][k]);
        (self.heading.violation(a, b), self.heading.excess(a, b))
    }

    /// p with its horizontal position clamped into the grid.
    pub(crate) fn inside(&self, p: [f64; 3]) -> [f64; 3] {
        let e = self.floor.extent();
        [
            p[0].clamp(e.x_min, e.x_max),
            p[1].clamp(e.y_min, e.y_max),
            p[2],
        ]
    }

    /// Z and ∇Z at the horizontal position of p, clamped into the grid (a first guess may
    /// coast past its edge; the grid bounds bring every later iterate back inside).
    pub(crate) fn floor_linearisation(&self, p: [f64; 3]) -> (f64, [f64; 2]) {
        let [x, y, _] = self.inside(p);
        self.floor
            .elevation_and_gradient(x, y)
            .unwrap_or((0.0, [0.0; 2]))
    }

    /// The same for the keep-out field.
    pub(crate) fn keep_out_linearisation(&self, p: [f64; 3]) -> (f64, [f64; 2]) {
        let [x, y, _] = self.inside(p);
        self.keep_out
            .elevation_and_gradient(x, y)
            .unwrap_or((0.0, [0.0; 2]))
    }

    /// The trajectory of the solver's x: its inputs, rolled through the vehicle models from
    /// the window's start. The solver meets the dynamics rows only to its own tolerance
    /// (residuals of 1e-4 m were seen on 3 km USV paths); re-simulating makes the plan exactly
    /// what the vehicles would do under the planned inputs, and the SCP then evaluates that.
    fn extract(&self, x: &[f64]) -> Trajectory {
        let l = self.layout;
        let usv_u = (0..l.k)
            .map(|k| [x[l.usv_u(k)], x[l.usv_u(k) + 1]])
            .collect();
        let auv_u = (0..l.n)
            .map(|n| {
                (0..l.k)
                    .map(|k| std::array::from_fn(|i| x[l.auv_u(n, k) + i]))
                    .collect()
            })
            .collect();
        Trajectory::simulate(&self.start, usv_u, auv_u, &self.auv, &self.usv)
    }

    /// Solve P2 by SCvx from `guess`.
    pub fn solve(&mut self, guess: Trajectory) -> Result<ScpOutcome<Trajectory>, PlanError> {
        let mut settings = self.scenario.scp.clone();
        if self.links.is_some() {
            // P5 starts from Step 1's converged plan: moves of a band's width, not of the
            // Step 1 radius (the default 200 m was rejected three times in a row)
            settings.trust_region = settings
                .trust_region
                .min(self.scenario.acoustic.band_tolerance);
        }
        scp::solve(self, guess, &settings)
    }
}

impl ScpProblem for TeamProblem<'_> {
    type Iterate = Trajectory;
    type Error = PlanError;

    fn solve_model(
        &mut self,
        reference: &Trajectory,
        radius: f64,
        penalty: f64,
    ) -> Result<(Trajectory, f64, ConicSolution), PlanError> {
        let m = self.assemble(reference, radius, penalty)?;
        let nvar = self.layout.variables();
        let solver = match &mut self.solver {
            Some(s) => {
                s.update(&m.p.vals, &m.q, &m.a.vals, &m.b)?;
                s
            }
            None => {
                // positions in units of d_s (see `Layout::scale`)
                let scale = self.layout.scale(self.scenario.acoustic.sonar_range);
                self.solver.insert(ConicSolver::with_scale(
                    Pattern::new(nvar, nvar, &m.p),
                    &m.p,
                    &m.q,
                    Pattern::new(m.b.len(), nvar, &m.a),
                    &m.a,
                    &m.b,
                    &m.cones,
                    scale,
                )?)
            }
        };
        let sol = solver.solve();
        if matches!(
            sol.status,
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible
        ) {
            let culprit = solver.diagnose(&m.b, &m.groups).map(str::to_string);
            return Err(PlanError::ConvexInfeasible {
                stage: self.stage(),
                status: format!("{:?}", sol.status),
                culprit,
            });
        }
        if !sol.usable() {
            return Err(PlanError::Solver {
                stage: self.stage(),
                status: format!("{:?}", sol.status),
                iterations: sol.iterations,
            });
        }
        let t = self.extract(&sol.x);
        // model merit L(x*) = ½x*ᵀPx* + qᵀx* + constant: the convex terms exact, OF1_8 and the
        // height term linearised, the slacks penalised
        let model = sol.objective + m.constant;
        Ok((t, model, sol))
    }

    fn evaluate(&self, t: &Trajectory) -> Evaluation {
        let l = self.layout;
        let dt = self.scenario.horizon.dt;
        let (mut sum, mut worst) = (0.0, 0.0f64);
        for n in 0..l.n {
            for k in 1..=l.k {
                let (f, _) = self.floor_violation(t, n, k);
                let (g, angle) = self.heading_violation(t, n, k);
                sum += f.max(0.0) + dt * g;
                worst = worst.max(f).max(angle);
            }
        }
        for (v, _) in self.keep_out_violations(t) {
            sum += v.max(0.0);
            worst = worst.max(v);
        }
        let weighted = self.weighted(&self.terms(t));
        Evaluation {
            objective: weighted.iter().sum(),
            violation: sum,
            max_violation: worst,
            magnitude: weighted.iter().map(|v| v.abs()).sum(),
        }
    }

    fn infeasible(&self, t: &Trajectory) -> PlanError {
        let l = self.layout;
        let eps = self.scenario.auv.floor_clearance;
        let mut worst = (0.0, String::new());
        for n in 0..l.n {
            for k in 1..=l.k {
                let (f, at) = self.floor_violation(t, n, k);
                if f > worst.0 {
                    let passes = format!(
                        "AUV {n} between steps {} and {k} passes ({:.1}, {:.1}, {:.1})",
                        k - 1,
                        at[0],
                        at[1],
                        at[2]
                    );
                    let detail = match self.obstacle_text(at) {
                        Some(why) => format!("{}: {passes}, which is {why}", keep_out::OBSTACLE),
                        None => {
                            let floor = self.floor.elevation(at[0], at[1]).unwrap_or(f64::NAN);
                            format!(
                                "seafloor clearance C2_2: {passes} where the floor is at \
                                 z = {floor:.1} m; it needs {eps:.1} m of clearance and has \
                                 {:.2} m",
                                at[2] - floor
                            )
                        }
                    };
                    worst = (f, detail);
                }
                let (_, angle) = self.heading_violation(t, n, k);
                if angle > worst.0 {
                    worst = (
                        angle,
                        format!(
                            "heading rate C1_14: AUV {n} turns {:.3} rad more than ψ̇_max·δ \
                             between steps {} and {k}",
                            angle,
                            k - 1
                        ),
                    );
                }
            }
        }
        for (v, what) in self.keep_out_violations(t) {
            if v > worst.0 {
                worst = (v, self.keep_out_detail(what));
            }
        }
        PlanError::Infeasible {
            stage: self.stage(),
            detail: worst.1,
        }
    }
}
