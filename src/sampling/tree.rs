//! The tree of one window (Section V): from every node at step k − 1, 𝔯 team samples for step
//! k; the children over `tree_budget` are pruned by score; the leaf of least objective at
//! k = K is the window's plan.
//!
//! A team sample (Remark III.1's team version): the USV's velocity, then the AUVs one at a time
//! in a random chain order, the first in range and in line of sight of the USV, each next one
//! of the one before (C1_10, C1_11, C1_13), every AUV's step valid on its own
//! (`validity::auv_waypoint`, `validity::auv_segment`). Each vehicle draws until a valid step
//! or `sampling.attempts` draws; an AUV that finds none fails the sample. The AUV nearest the
//! USV, P3's A2U link, must also link it.
//!
//! The score (the paper's "energy (OF1_1), depth (OF1_2) and convergence (OF1_8_2)") is P2's
//! objective, OF1_8 or OF1_8_2 as the scenario says: the same number the MPC's Step 1
//! minimises, so the two planners are compared on one objective. Pruning ranks a node by its
//! running cost (OF1_1 and OF1_2 of its steps) plus the USV's term were the window to end
//! there.

use super::draw;
use super::validity::{self, Limits, Reject};
use crate::error::PlanError;
use crate::plan::{AuvState, SamplingReport, SamplingStep};
use crate::scenario::{DepthObjective, Scenario};
use crate::seafloor::Seafloor;
use crate::step2::p3_a2u::a2u_link;
use crate::team::TeamProblem;
use crate::trajectory::{Start, Trajectory};
use crate::vehicle::{AuvModel, UsvModel};
use rand::seq::SliceRandom;
use rand::Rng;
use std::time::Instant;

/// One node: the team at one step and how it got there from its parent.
#[derive(Debug, Clone)]
struct Node {
    /// Index of the parent in the previous step's nodes.
    parent: usize,
    usv: [f64; 2],
    usv_u: [f64; 2],
    auvs: Vec<AuvState>,
    /// U_n of the step into this node.
    auv_u: Vec<[f64; 3]>,
    /// The chain order of this step's AUVs (empty at k = 0).
    chain: Vec<usize>,
    /// Running cost: w1·Σ‖U‖² + w2·Σ OF1_2 over the steps so far (with weights.scaling).
    cost: f64,
    /// `cost` plus the USV's term at this node: the pruning rank.
    rank: f64,
}

/// A window's tree, found.
#[derive(Debug, Clone)]
pub struct Grown {
    /// The team's paths, k = 0..=K.
    pub trajectory: Trajectory,
    /// The chain order of the AUVs at k = 1..=K (index k − 1).
    pub chains: Vec<Vec<usize>>,
    /// What the tree did.
    pub report: SamplingReport,
}

/// Grows one window's tree from `start`; `problem` is the window's P2 (its objective scores
/// the leaves); `progress` hears of every step as it ends.
pub struct Tree<'a, R: Rng> {
    pub(super) scenario: &'a Scenario,
    pub(super) floor: &'a Seafloor,
    pub(super) auv: AuvModel,
    pub(super) usv: UsvModel,
    pub(super) rng: &'a mut R,
    pub(super) problem: &'a TeamProblem<'a>,
}

/// Draw counters of one step.
#[derive(Default)]
struct Counts {
    drawn: u64,
    rejected: [u64; Reject::ALL.len()],
}

impl Counts {
    fn reject(&mut self, r: Reject) -> Reject {
        self.rejected[r as usize] += 1;
        r
    }
}

impl<R: Rng> Tree<'_, R> {
    /// Grow the tree of window `window` from `start`.
    pub fn grow(
        &mut self,
        window: usize,
        start: &Start,
        progress: &mut dyn FnMut(usize, &SamplingStep),
    ) -> Result<Grown, PlanError> {
        let s = self.scenario;
        let (k_max, r, budget) = (s.horizon.steps, s.sampling.samples, s.sampling.tree_budget);
        let root = Node {
            parent: 0,
            usv: start.usv,
            usv_u: [0.0; 2],
            auvs: start.auvs.clone(),
            auv_u: Vec::new(),
            chain: Vec::new(),
            cost: 0.0,
            rank: 0.0,
        };
        let mut levels: Vec<Vec<Node>> = vec![vec![root]];
        let mut report = SamplingReport {
            samples: r,
            tree_budget: budget,
            ..SamplingReport::default()
        };
        let mut total = [0u64; Reject::ALL.len()];
        for k in 1..=k_max {
            let clock = Instant::now();
            let mut counts = Counts::default();
            let mut children = Vec::new();
            for (i, node) in levels[k - 1].iter().enumerate() {
                for _ in 0..r {
                    if let Ok(mut child) = self.child(node, k, &mut counts) {
                        child.parent = i;
                        children.push(child);
                    }
                }
            }
            for (t, c) in total.iter_mut().zip(counts.rejected) {
                *t += c;
            }
            if children.is_empty() {
                return Err(PlanError::NoValidTree {
                    window,
                    k,
                    nodes: levels[k - 1].len(),
                    drawn: counts.drawn,
                    why: reasons(&counts.rejected),
                });
            }
            let valid = children.len() as u64;
            if children.len() > budget {
                children.sort_by(|a, b| a.rank.total_cmp(&b.rank));
                children.truncate(budget);
            }
            let step = SamplingStep {
                drawn: counts.drawn,
                valid,
                kept: children.len() as u64,
                time_s: clock.elapsed().as_secs_f64(),
            };
            report.drawn += step.drawn;
            report.kept += step.valid;
            report.steps.push(step);
            progress(k, &step);
            levels.push(children);
        }
        report.rejected = Reject::ALL
            .iter()
            .zip(total)
            .filter(|(_, n)| *n > 0)
            .map(|(r, n)| (r.name().to_string(), n))
            .collect();
        // the leaf of least objective (P2's, exactly as the plan records it)
        let leaves = levels.last().expect("K ≥ 1 levels").len();
        let mut best: Option<(f64, Grown)> = None;
        for leaf in 0..leaves {
            let (trajectory, chains) = self.path(&levels, leaf, start);
            let j = self.problem.objective(&self.problem.terms(&trajectory));
            if best.as_ref().map_or(true, |(b, _)| j < *b) {
                let grown = Grown {
                    trajectory,
                    chains,
                    report: SamplingReport::default(),
                };
                best = Some((j, grown));
            }
        }
        let (_, mut grown) = best.expect("at least one leaf");
        grown.report = report;
        Ok(grown)
    }

    /// The team's paths from the root to leaf `leaf` of the last level.
    fn path(
        &self,
        levels: &[Vec<Node>],
        leaf: usize,
        start: &Start,
    ) -> (Trajectory, Vec<Vec<usize>>) {
        let mut nodes = Vec::with_capacity(levels.len());
        let mut i = leaf;
        for level in levels.iter().skip(1).rev() {
            nodes.push(&level[i]);
            i = level[i].parent;
        }
        nodes.reverse();
        let n = start.auvs.len();
        let usv_u = nodes.iter().map(|nd| nd.usv_u).collect();
        let auv_u = (0..n)
            .map(|a| nodes.iter().map(|nd| nd.auv_u[a]).collect())
            .collect();
        let chains = nodes.iter().map(|nd| nd.chain.clone()).collect();
        let t = Trajectory::simulate(start, usv_u, auv_u, &self.auv, &self.usv);
        (t, chains)
    }

    /// One team sample from `node` for step k, or the constraint that failed it.
    fn child(&mut self, node: &Node, k: usize, counts: &mut Counts) -> Result<Node, Reject> {
        let l = Limits::of(self.scenario);
        let attempts = self.scenario.sampling.attempts;
        let floor = self.floor;
        // the USV
        let mut last = Reject::Grid;
        let mut usv = None;
        for _ in 0..attempts {
            counts.drawn += 1;
            let u = draw::usv_velocity(self.rng, &l, node.usv_u);
            let p = self.usv.step(node.usv, u);
            match validity::usv_step(&l, floor, node.usv, p) {
                Ok(()) => {
                    usv = Some((u, p));
                    break;
                }
                Err(r) => last = counts.reject(r),
            }
        }
        let (usv_u, usv_p) = usv.ok_or(last)?;
        // the AUVs, in a random chain order from the USV
        let n = node.auvs.len();
        let mut order: Vec<usize> = (0..n).collect();
        order.shuffle(self.rng);
        let mut placed: Vec<Option<draw::AuvStep>> = vec![None; n];
        for (i, &a) in order.iter().enumerate() {
            let to = match i {
                0 => validity::surface(usv_p),
                _ => placed[order[i - 1]].expect("placed before").p,
            };
            let st = node.auvs[a];
            let mut found = None;
            for _ in 0..attempts {
                counts.drawn += 1;
                // half the draws from the vehicle's reach, half from the link's
                let (p0, v0) = (st.position, st.velocity);
                let step = match self.rng.gen_bool(0.5) {
                    true => draw::auv_step(self.rng, &l, &self.auv, floor, p0, v0),
                    false => draw::auv_step_towards(self.rng, &l, &self.auv, floor, p0, v0, to),
                }
                .and_then(|step| {
                    validity::auv_waypoint(&l, floor, k, st.velocity, step.p, step.v, usv_p)?;
                    validity::link(&l, floor, step.p, to)?;
                    validity::auv_segment(&l, floor, st.position, step.p)?;
                    Ok(step)
                });
                match step {
                    Ok(step) => {
                        found = Some(step);
                        break;
                    }
                    Err(r) => last = counts.reject(r),
                }
            }
            placed[a] = Some(found.ok_or(last)?);
        }
        let steps: Vec<draw::AuvStep> = placed.into_iter().map(|p| p.expect("placed")).collect();
        let points: Vec<[f64; 3]> = steps.iter().map(|st| st.p).collect();
        // P3's A2U link, the AUV nearest the USV, links it too
        if let Some(a2u) = a2u_link(usv_p, &points) {
            if a2u != order[0] {
                validity::link(&l, floor, points[a2u], validity::surface(usv_p))
                    .map_err(|r| counts.reject(r))?;
            }
        }
        let cost = node.cost + self.running_cost(&steps);
        Ok(Node {
            parent: 0,
            usv: usv_p,
            usv_u,
            auvs: steps
                .iter()
                .map(|st| AuvState {
                    position: st.p,
                    velocity: st.v,
                })
                .collect(),
            auv_u: steps.iter().map(|st| st.u).collect(),
            chain: order,
            cost,
            rank: cost + self.problem.usv_term(usv_p),
        })
    }

    /// w1·Σ‖U‖² + w2·Σ OF1_2 of one step's AUV moves, weighted as P2 weighs them.
    fn running_cost(&self, steps: &[draw::AuvStep]) -> f64 {
        let w = &self.scenario.weights;
        let per_auv = w.per_auv(steps.len());
        let energy: f64 = steps.iter().flat_map(|st| st.u).map(|u| u * u).sum();
        let of1_2: f64 = steps
            .iter()
            .map(|st| match w.of1_2 {
                DepthObjective::Height => {
                    st.p[2] - self.floor.elevation(st.p[0], st.p[1]).unwrap_or(0.0)
                }
                DepthObjective::Depth => st.p[2],
            })
            .sum();
        per_auv * (w.w1 * energy + w.w2 * of1_2)
    }
}

/// "C2_2 floor clearance (segment) 812, C1_13 line of sight 40": the rejections, most first.
fn reasons(rejected: &[u64]) -> String {
    let mut list: Vec<(Reject, u64)> = Reject::ALL
        .iter()
        .copied()
        .zip(rejected.iter().copied())
        .filter(|(_, n)| *n > 0)
        .collect();
    list.sort_by_key(|r| std::cmp::Reverse(r.1));
    if list.is_empty() {
        return "nothing (no draw was made)".into();
    }
    list.iter()
        .map(|(r, n)| format!("{} ({n})", r.name()))
        .collect::<Vec<_>>()
        .join(", ")
}
