//! A plan's and a floor's numbers as arrays over the mission's steps (the arrays `RawPlan`
//! hands to numpy).

use numpy::ndarray::{Array1, Array2, Array3};
use shoal::plan::{AuvPath, Plan};
use shoal::seafloor::Seafloor;

/// The steps of the mission: (window, k) for every step of every window's final stage, window
/// w > 0 without its k = 0 (window w − 1's last step, the same instant and state).
fn mission_steps(p: &Plan) -> Vec<(usize, usize)> {
    let mut steps = Vec::new();
    for (w, win) in p.windows.iter().enumerate() {
        let last = win.final_.usv.position.len().saturating_sub(1);
        let first = usize::from(w > 0);
        steps.extend((first..=last).map(|k| (w, k)));
    }
    steps
}

/// The inputs of the mission: (window, k) for k = 0..K of every window.
fn mission_inputs(p: &Plan) -> Vec<(usize, usize)> {
    p.windows
        .iter()
        .enumerate()
        .flat_map(|(w, win)| (0..win.final_.usv.input.len()).map(move |k| (w, k)))
        .collect()
}

/// An AUV quantity over (step, vehicle, axis), NaN where the plan has no entry.
fn auv_array(
    p: &Plan,
    steps: &[(usize, usize)],
    get: impl Fn(&AuvPath, usize) -> Option<[f64; 3]>,
) -> Array3<f64> {
    let n = p.scenario.team.auvs;
    let mut a = Array3::from_elem((steps.len(), n, 3), f64::NAN);
    for (t, &(w, k)) in steps.iter().enumerate() {
        for (v, path) in p.windows[w].final_.auvs.iter().take(n).enumerate() {
            if let Some(x) = get(path, k) {
                for d in 0..3 {
                    a[[t, v, d]] = x[d];
                }
            }
        }
    }
    a
}

fn usv_array(p: &Plan, steps: &[(usize, usize)], input: bool) -> Array2<f64> {
    let mut a = Array2::from_elem((steps.len(), 2), f64::NAN);
    for (t, &(w, k)) in steps.iter().enumerate() {
        let usv = &p.windows[w].final_.usv;
        let series = if input { &usv.input } else { &usv.position };
        if let Some(x) = series.get(k) {
            a[[t, 0]] = x[0];
            a[[t, 1]] = x[1];
        }
    }
    a
}

/// AUV positions, (steps, N, 3).
pub(crate) fn positions(p: &Plan) -> Array3<f64> {
    auv_array(p, &mission_steps(p), |a, k| a.position.get(k).copied())
}

/// AUV velocities, (steps, N, 3).
pub(crate) fn velocities(p: &Plan) -> Array3<f64> {
    auv_array(p, &mission_steps(p), |a, k| a.velocity.get(k).copied())
}

/// AUV inputs, (steps − 1, N, 3).
pub(crate) fn inputs(p: &Plan) -> Array3<f64> {
    auv_array(p, &mission_inputs(p), |a, k| a.input.get(k).copied())
}

/// USV positions, (steps, 2).
pub(crate) fn usv_positions(p: &Plan) -> Array2<f64> {
    usv_array(p, &mission_steps(p), false)
}

/// USV inputs (its velocity), (steps − 1, 2).
pub(crate) fn usv_inputs(p: &Plan) -> Array2<f64> {
    usv_array(p, &mission_inputs(p), true)
}

/// Time of every step, (steps,), seconds since the start of the mission.
pub(crate) fn times(p: &Plan) -> Array1<f64> {
    let dt = p.scenario.horizon.dt;
    let t: Vec<f64> = mission_steps(p)
        .iter()
        .map(|&(w, k)| p.windows[w].start_time + k as f64 * dt)
        .collect();
    Array1::from(t)
}

/// The window of every step, (steps,).
pub(crate) fn window_of_step(p: &Plan) -> Array1<i64> {
    let w: Vec<i64> = mission_steps(p).iter().map(|&(w, _)| w as i64).collect();
    Array1::from(w)
}

/// The planned links, (steps, N, 2): per step the A2U link (AUV, −1) first, then the N − 1
/// A2A edges (i, j) of the chain in path order; −1 pads a step with fewer links.
pub(crate) fn links(p: &Plan) -> Array3<i64> {
    let steps = mission_steps(p);
    let n = p.scenario.team.auvs;
    let mut a = Array3::from_elem((steps.len(), n, 2), -1i64);
    for (t, &(w, k)) in steps.iter().enumerate() {
        if let Some(links) = p.windows[w].links.links.get(k) {
            for (l, link) in links.iter().take(n).enumerate() {
                a[[t, l, 0]] = link.a as i64;
                a[[t, l, 1]] = link.b.map_or(-1, |b| b as i64);
            }
        }
    }
    a
}

/// The floor's heights, (ny, nx), NaN at NODATA nodes.
pub(crate) fn floor_heights(f: &Seafloor) -> Array2<f64> {
    let (z, nodata) = f.nodes();
    let mut a = Array2::from_elem((f.ny(), f.nx()), f64::NAN);
    for (idx, (v, &missing)) in z.iter().zip(nodata).enumerate() {
        if !missing {
            a[[idx / f.nx(), idx % f.nx()]] = *v;
        }
    }
    a
}
