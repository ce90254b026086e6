//! The plan's data as the figures use it: paths concatenated across windows, step times, the
//! extent of the mission, and the label every title carries.

use super::FigureError;
use crate::plan::{self, Link, Plan};
use crate::seafloor::Seafloor;

/// Which stage of each window a figure shows.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(crate) enum Stage {
    /// Step 1 (P2).
    Step1,
    /// Step 3 (P5 after the line-of-sight loop): the plan the team executes.
    Final,
}

pub(crate) struct Scene<'a> {
    pub plan: &'a Plan,
    pub floor: &'a Seafloor,
    /// Number of AUVs.
    pub n: usize,
    /// Steps in mission order: (window, k, time in s). Step 0 of a later window is the last step
    /// of the one before, so it appears once, as that window's k = 0 is skipped.
    pub steps: Vec<(usize, usize, f64)>,
    label: String,
}

impl<'a> Scene<'a> {
    /// Checks that every array the figures index has the length the plan format promises.
    pub fn new(plan: &'a Plan, floor: &'a Seafloor) -> Result<Scene<'a>, FigureError> {
        let bad = |why: String| Err(FigureError::Plan(why));
        let n = plan.scenario.team.auvs;
        let k_steps = plan.scenario.horizon.steps;
        if plan.windows.is_empty() {
            return bad("it has no windows".into());
        }
        for w in &plan.windows {
            for (name, st) in [("step1", &w.step1), ("final", &w.final_)] {
                let here = format!("window {} {name}", w.index);
                if st.auvs.len() != n {
                    return bad(format!("{here} has {} AUVs, not {n}", st.auvs.len()));
                }
                if st.usv.position.len() != k_steps + 1 {
                    return bad(format!(
                        "{here}: the USV has not K + 1 = {} positions",
                        k_steps + 1
                    ));
                }
                for (i, a) in st.auvs.iter().enumerate() {
                    let lens = [a.position.len(), a.velocity.len(), a.heading.len()];
                    if lens.iter().any(|&l| l != k_steps + 1) {
                        return bad(format!(
                            "{here}: AUV {i} has not K + 1 = {} states",
                            k_steps + 1
                        ));
                    }
                }
            }
            let steps_ok = |len: usize| len == 0 || len == k_steps + 1;
            let l = &w.links;
            let g = &w.graph;
            let links_ok = steps_ok(l.links.len())
                && l.bands.len() == l.links.len()
                && l.links
                    .iter()
                    .zip(&l.bands)
                    .all(|(a, b)| a.len() == b.len())
                && l.links
                    .iter()
                    .flatten()
                    .all(|k| k.a < n && k.b.map_or(true, |b| b < n));
            let graph_ok = steps_ok(g.a2u.len())
                && steps_ok(g.a2a.len())
                && g.a2u.iter().all(|&a| a < n)
                && g.a2a.iter().flatten().all(|e| e[0] < n && e[1] < n);
            if !(links_ok && graph_ok) {
                return bad(format!(
                    "window {}: graph or links are not K + 1 = {} steps of AUVs below {n}",
                    w.index,
                    k_steps + 1
                ));
            }
        }
        let dt = plan.scenario.horizon.dt;
        let mut steps = Vec::new();
        for (w, win) in plan.windows.iter().enumerate() {
            for k in usize::from(w > 0)..=k_steps {
                steps.push((w, k, win.start_time + k as f64 * dt));
            }
        }
        let last = plan.windows.len() - 1;
        let windows = if last == 0 {
            "window 0".to_string()
        } else {
            format!("windows 0–{last}")
        };
        let label = format!("N = {n}, seed {}, {windows}", plan.scenario.seed);
        Ok(Scene {
            plan,
            floor,
            n,
            steps,
            label,
        })
    }

    /// "WHAT — N = 5, seed 1, windows 0–1".
    pub fn title(&self, what: &str) -> String {
        format!("{what} — {}", self.label)
    }

    /// What a panel of stage `s` shows ("Final paths (Step 3, P5)"), or, in a sampling
    /// planner's plan, whose stages are both its sampled paths, "Sampled paths (rrt-like)".
    pub fn paths_name(&self, s: Stage) -> String {
        match (self.plan.method.as_str(), s) {
            (plan::METHOD_MPC, Stage::Step1) => "Step 1 paths (P2)".into(),
            (plan::METHOD_MPC, Stage::Final) => "Final paths (Step 3, P5)".into(),
            (method, _) => format!("Sampled paths ({method})"),
        }
    }

    /// What the links panel shows: Step 2's links over Step 1's positions, or a sampling
    /// planner's chain over its paths.
    pub fn links_name(&self) -> String {
        match self.plan.method.as_str() {
            plan::METHOD_MPC => "Step 2 links over Step 1 positions".into(),
            method => format!("Chain links over the sampled paths ({method})"),
        }
    }

    pub fn stage(&self, w: usize, s: Stage) -> &'a plan::Stage {
        match s {
            Stage::Step1 => &self.plan.windows[w].step1,
            Stage::Final => &self.plan.windows[w].final_,
        }
    }

    pub fn times(&self) -> Vec<f64> {
        self.steps.iter().map(|s| s.2).collect()
    }

    /// Start times of windows 1, 2, …, s.
    pub fn window_starts(&self) -> Vec<(usize, f64)> {
        let w = &self.plan.windows;
        w.iter().skip(1).map(|w| (w.index, w.start_time)).collect()
    }

    pub fn auv_path(&self, s: Stage, n: usize) -> Vec<[f64; 3]> {
        let st = |w| self.stage(w, s);
        self.steps
            .iter()
            .map(|&(w, k, _)| st(w).auvs[n].position[k])
            .collect()
    }

    pub fn usv_path(&self, s: Stage) -> Vec<[f64; 2]> {
        let st = |w| self.stage(w, s);
        self.steps
            .iter()
            .map(|&(w, k, _)| st(w).usv.position[k])
            .collect()
    }

    /// The Step 2 links per step, in mission order, from `graph` (A2U link, then A2A edges).
    pub fn graph_links(&self) -> Vec<Vec<Link>> {
        self.steps
            .iter()
            .map(|&(w, k, _)| {
                let g = &self.plan.windows[w].graph;
                let a2u = g.a2u.get(k).map(|&a| Link { a, b: None });
                let a2a = g.a2a.get(k).into_iter().flatten();
                a2u.into_iter()
                    .chain(a2a.map(|e| Link {
                        a: e[0],
                        b: Some(e[1]),
                    }))
                    .collect()
            })
            .collect()
    }

    /// [x_min, x_max, y_min, y_max] of every vehicle in both stages, metres.
    pub fn bbox(&self) -> [f64; 4] {
        crate::plan::bbox(self.plan.positions()).unwrap_or_else(|| {
            let e = self.floor.extent();
            [e.x_min, e.x_max, e.y_min, e.y_max]
        })
    }

    /// Length of a link at (window, k) in a stage: AUV to AUV, or AUV to the USV at z = 0.
    pub fn link_length(&self, s: Stage, w: usize, k: usize, l: Link) -> f64 {
        let st = self.stage(w, s);
        let a = st.auvs[l.a].position[k];
        let b = match l.b {
            Some(b) => st.auvs[b].position[k],
            None => {
                let u = st.usv.position[k];
                [u[0], u[1], 0.0]
            }
        };
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    }
}
