//! A team trajectory over one window (USV and N AUVs, k = 0..=K), the state a window starts from,
//! and the conversion to the plan file's per-vehicle paths.

use crate::plan::{AuvPath, AuvState, UsvPath};
use crate::vehicle::{AuvModel, UsvModel};

/// The state of the team at step k = 0 of a window.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    pub usv: [f64; 2],
    pub auvs: Vec<AuvState>,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Trajectory {
    /// P_USV\[k\], k = 0..=K.
    pub usv_p: Vec<[f64; 2]>,
    /// U_USV\[k\], k = 0..K−1.
    pub usv_u: Vec<[f64; 2]>,
    /// P_n\[k\], n = 0..N−1, k = 0..=K.
    pub auv_p: Vec<Vec<[f64; 3]>>,
    /// V_n\[k\].
    pub auv_v: Vec<Vec<[f64; 3]>>,
    /// U_n\[k\], k = 0..K−1.
    pub auv_u: Vec<Vec<[f64; 3]>>,
}

impl Trajectory {
    pub fn steps(&self) -> usize {
        self.usv_u.len()
    }

    /// Roll the models forward from `start` under the given inputs, in still water.
    pub fn simulate(
        start: &Start,
        usv_u: Vec<[f64; 2]>,
        auv_u: Vec<Vec<[f64; 3]>>,
        auv: &AuvModel,
        usv: &UsvModel,
    ) -> Trajectory {
        Self::simulate_in(start, usv_u, auv_u, auv, usv, &|_| [0.0; 3])
    }

    /// Roll the models forward from `start` under the given inputs in the current `drift`
    /// (m/s at a position): eq. (8) with its ϖ term, the AUV's velocity V being through the
    /// water and its position moving over ground by δ·c(P\[k\]) more each step,
    /// P\[k+1\] = P\[k\] + pv·V\[k\] + pu·U\[k\] + δ·c(P\[k\]). The USV's input of eq. (9) is
    /// its velocity over ground.
    pub fn simulate_in(
        start: &Start,
        usv_u: Vec<[f64; 2]>,
        auv_u: Vec<Vec<[f64; 3]>>,
        auv: &AuvModel,
        usv: &UsvModel,
        drift: &dyn Fn([f64; 3]) -> [f64; 3],
    ) -> Trajectory {
        let mut usv_p = vec![start.usv];
        for u in &usv_u {
            usv_p.push(usv.step(*usv_p.last().expect("non-empty"), *u));
        }
        let mut auv_p = Vec::new();
        let mut auv_v = Vec::new();
        for (s, inputs) in start.auvs.iter().zip(&auv_u) {
            let (mut p, mut v) = (vec![s.position], vec![s.velocity]);
            for u in inputs {
                let at = *p.last().expect("non-empty");
                let (pn, vn) = auv.step(at, *v.last().expect("non-empty"), *u);
                let c = drift(at);
                let pn = std::array::from_fn(|i| pn[i] + auv.dt * c[i]);
                p.push(pn);
                v.push(vn);
            }
            auv_p.push(p);
            auv_v.push(v);
        }
        Trajectory {
            usv_p,
            usv_u,
            auv_p,
            auv_v,
            auv_u,
        }
    }

    /// State at the last step, the start of the next window (Algorithm 1, line 7).
    pub fn end(&self) -> Start {
        Start {
            usv: *self.usv_p.last().expect("non-empty"),
            auvs: self
                .auv_p
                .iter()
                .zip(&self.auv_v)
                .map(|(p, v)| AuvState {
                    position: *p.last().expect("non-empty"),
                    velocity: *v.last().expect("non-empty"),
                })
                .collect(),
        }
    }

    pub fn usv_path(&self) -> UsvPath {
        UsvPath {
            position: self.usv_p.clone(),
            input: self.usv_u.clone(),
        }
    }

    /// Per-AUV paths with surge speed ‖(V_x, V_y)‖ and heading atan2(V_y, V_x) (null below
    /// `min_heading_speed`), as the paper recovers them after eq. (8).
    pub fn auv_paths(&self, min_heading_speed: f64) -> Vec<AuvPath> {
        (0..self.auv_p.len())
            .map(|n| {
                let v = &self.auv_v[n];
                AuvPath {
                    position: self.auv_p[n].clone(),
                    velocity: v.clone(),
                    input: self.auv_u[n].clone(),
                    surge_speed: v.iter().map(|v| v[0].hypot(v[1])).collect(),
                    heading: v
                        .iter()
                        .map(|v| (v[0].hypot(v[1]) >= min_heading_speed).then(|| v[1].atan2(v[0])))
                        .collect(),
                }
            })
            .collect()
    }
}
