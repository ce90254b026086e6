//! What the viewer page needs from a plan, as one JSON object: the seafloor around the mission
//! (cropped and downsampled), the final-stage paths of every window, the planned links per step,
//! and the metrics. Nothing else of the plan is embedded. With a simulation (`shoal view
//! --sim`), also each AUV's executed track and one estimate's track ([`SimData`]).

use super::ViewerError;
use crate::plan::{Link, Metrics, Plan, Window};
use crate::seafloor::{Lattice, Seafloor};
use crate::sim::policy::Policy;
use crate::sim::SimRecord;
use serde::Serialize;

/// Largest number of mesh vertices along either axis of the floor sent to the page.
pub const MAX_FLOOR_VERTICES: usize = 256;

/// Quantised elevation marking a NODATA node.
const NODATA_CODE: u16 = u16::MAX;

/// The data the viewer page shows of a plan, embedded in the page as one JSON object.
#[derive(Debug, Serialize)]
pub struct ViewerData {
    /// The page's title: N, the number of windows, K and the seed.
    pub title: String,
    /// Version of shoal that wrote the plan.
    pub shoal_version: String,
    /// Where the plan's scenario came from: "embedded default" or the path of the file.
    pub scenario_source: String,
    /// The scenario's seed.
    pub seed: u64,
    /// N, the number of AUVs.
    pub auvs: usize,
    /// K, the number of steps per window.
    pub steps: usize,
    /// δ, the time step, seconds.
    pub dt: f64,
    /// d_s, the acoustic range, metres.
    pub sonar_range: f64,
    /// d_t, the band tolerance: links are kept in \[d_s − d_t, d_s\], metres.
    pub band_tolerance: f64,
    /// Every AUV's colour on the page, `#rrggbb`: its figures' colour (`figures::vehicle_colour`)
    /// tinted for the dark background ([`auv_colour`]).
    pub auv_colours: Vec<String>,
    /// The floor mesh around the mission.
    pub floor: FloorData,
    /// Every window of the plan, in order.
    pub windows: Vec<WindowData>,
    /// The mission's metrics over every window (`Plan::metrics`).
    pub metrics: Metrics,
    /// The simulated tracks, when the page shows a simulation; absent otherwise.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sim: Option<SimData>,
}

/// The estimate the page shows by default: the planned chain's ranges, the factor graph, on the
/// final stages' flight.
pub const DEFAULT_ESTIMATE: (Policy, &str, &str) = (Policy::Chain, "factor_graph", "final");

/// The estimates the page shows, in order of preference: the first one the simulation holds
/// (an estimator that failed leaves its estimate out of sim.json).
pub const SHOWN_ESTIMATES: [(Policy, &str, &str); 8] = [
    DEFAULT_ESTIMATE,
    (Policy::Chain, "ekf", "final"),
    (Policy::AllLinks, "factor_graph", "final"),
    (Policy::AllLinks, "ekf", "final"),
    (Policy::A2u, "factor_graph", "final"),
    (Policy::A2u, "ekf", "final"),
    (Policy::DeadReckoning, "factor_graph", "final"),
    (Policy::DeadReckoning, "ekf", "final"),
];

/// What the page shows of a simulation (`sim.json`): the executed positions and one estimate's,
/// per AUV per epoch, rounded to 0.1 m.
#[derive(Debug, Serialize)]
pub struct SimData {
    /// Seed of the simulation.
    pub seed: u64,
    /// Time of each epoch, seconds since the start of the mission, rounded to 1 ms.
    pub times: Vec<f64>,
    /// `[auv][epoch]`: executed positions \[x, y, z\], metres, rounded to 0.1 m.
    pub executed: Vec<Vec<[f64; 3]>>,
    /// The estimate shown; none when every estimate of the final stages' flight failed.
    pub estimate: Option<EstimateData>,
}

/// One estimate's track as the page shows it.
#[derive(Debug, Serialize)]
pub struct EstimateData {
    /// Its policy: "dead_reckoning", "a2u", "chain" or "all_links".
    pub policy: String,
    /// Its estimator: "factor_graph" or "ekf".
    pub estimator: String,
    /// The flight it estimated: "final" or "step1".
    pub flown: String,
    /// RMS error over every AUV and epoch, metres.
    pub team_rmse_m: f64,
    /// `[auv][epoch]`: estimated positions \[x, y, z\], metres, rounded to 0.1 m.
    pub position: Vec<Vec<[f64; 3]>>,
}

/// The simulated tracks of `sim` for a plan of `auvs` AUVs, with the first estimate of
/// [`SHOWN_ESTIMATES`] it holds (none when it holds none of them). Fails with
/// [`ViewerError::Sim`] when the simulation's team is not the plan's, or its arrays do not fit
/// its epochs or hold non-finite values.
pub fn sim(sim: &SimRecord, auvs: usize) -> Result<SimData, ViewerError> {
    let bad = |why: String| Err(ViewerError::Sim(why));
    if sim.auvs != auvs {
        return bad(format!(
            "it simulates {} AUVs, the plan has {auvs}",
            sim.auvs
        ));
    }
    let epochs = sim.times.len();
    if epochs == 0 {
        return bad("it has no epochs".into());
    }
    if !sim.times.iter().all(|t| t.is_finite()) || sim.times.windows(2).any(|t| t[1] <= t[0]) {
        return bad("its epoch times are not finite and increasing".into());
    }
    let shown = SHOWN_ESTIMATES
        .iter()
        .find_map(|&(policy, estimator, flown)| {
            sim.estimates
                .iter()
                .find(|e| e.policy == policy && e.estimator == estimator && e.flown == flown)
        });
    let track = |what: &str, t: &[Vec<[f64; 3]>]| -> Result<Vec<Vec<[f64; 3]>>, ViewerError> {
        if t.len() != auvs {
            return Err(ViewerError::Sim(format!(
                "{what} has {} AUVs, the plan {auvs}",
                t.len()
            )));
        }
        t.iter()
            .enumerate()
            .map(|(i, ps)| {
                if ps.len() != epochs {
                    return Err(ViewerError::Sim(format!(
                        "{what} of AUV {i} has {} epochs, times {epochs}",
                        ps.len()
                    )));
                }
                if !ps.iter().flatten().all(|v| v.is_finite()) {
                    return Err(ViewerError::Sim(format!(
                        "{what} of AUV {i} has a non-finite position"
                    )));
                }
                Ok(ps.iter().map(|p| p.map(dm)).collect())
            })
            .collect()
    };
    Ok(SimData {
        seed: sim.seed,
        times: sim.times.iter().map(|t| (t * 1e3).round() / 1e3).collect(),
        executed: track("flight.executed", &sim.flight.executed)?,
        estimate: shown
            .map(|est| -> Result<EstimateData, ViewerError> {
                Ok(EstimateData {
                    policy: est.policy.name().into(),
                    estimator: est.estimator.clone(),
                    flown: est.flown.clone(),
                    team_rmse_m: est.metrics.team_rmse_m,
                    position: track("the estimate's position", &est.position)?,
                })
            })
            .transpose()?,
    })
}

/// The floor mesh: `nx × ny` vertices at (x0 + i·dx, y0 + j·dy), row j = 0 southernmost.
#[derive(Debug, Serialize)]
pub struct FloorData {
    /// Where the floor came from: "synthetic" or "file".
    pub source: String,
    /// Number of nodes along x of the full grid the mesh was cut from.
    pub grid_nx: usize,
    /// Number of nodes along y of the full grid the mesh was cut from.
    pub grid_ny: usize,
    /// Node spacing along x of the full grid, metres.
    pub grid_dx: f64,
    /// The vertices, written as the six fields `nx`, `ny`, `x0`, `y0`, `dx`, `dy`.
    #[serde(flatten)]
    pub lattice: Lattice,
    /// Elevation of the deepest data vertex, metres (0 when no vertex has data).
    pub z_lo: f64,
    /// Elevation of the shallowest data vertex, metres (0 when no vertex has data).
    pub z_hi: f64,
    /// Base64 of nx·ny little-endian u16: z = z_lo + q·(z_hi − z_lo)/65534, q = 65535 NODATA.
    pub z: String,
}

/// One window as the page shows it: its final-stage paths and its planned links.
#[derive(Debug, Serialize)]
pub struct WindowData {
    /// Window index w, from 0.
    pub index: usize,
    /// Time of step k = 0 of this window, seconds since the start of the mission.
    pub start_time: f64,
    /// Status of the final stage: "converged", "max_iterations", "stalled" or
    /// "solver_trouble".
    pub status: String,
    /// SCP iterations of the final stage.
    pub iterations: usize,
    /// Line-of-sight rounds of Algorithm 1, lines 18–22.
    pub los_rounds: usize,
    /// Final stage: USV \[x, y\] per step k = 0..=K, metres, rounded to 1 cm.
    pub usv: Vec<[f64; 2]>,
    /// Final stage: per AUV, \[x, y, z\] per step k = 0..=K, metres, rounded to 1 cm.
    pub auvs: Vec<Vec<[f64; 3]>>,
    /// Per step: the planned links [a, b], b = null for the A2U link.
    pub links: Vec<Vec<(usize, Option<usize>)>>,
    /// [k, a, b] of every link-step outside its band.
    pub out_of_band: Vec<(usize, usize, Option<usize>)>,
    /// This window's metrics.
    pub metrics: Metrics,
}

/// The viewer data of `plan` on `floor` (the floor it was planned on), with the floor mesh cut
/// around the vehicles' positions. Fails with [`ViewerError::Plan`] when the plan has no
/// windows, or a window's final stage has missing or non-finite positions, or links that do
/// not fit the team.
pub fn build(plan: &Plan, floor: &Seafloor) -> Result<ViewerData, ViewerError> {
    build_with_sim(plan, floor, None)
}

/// [`build`], with the tracks of `sim` (see [`sim`]) when given.
pub fn build_with_sim(
    plan: &Plan,
    floor: &Seafloor,
    sim_record: Option<&SimRecord>,
) -> Result<ViewerData, ViewerError> {
    let n = plan.scenario.team.auvs;
    let windows = plan
        .windows
        .iter()
        .map(|w| window(w, n))
        .collect::<Result<Vec<_>, _>>()?;
    if windows.is_empty() {
        return Err(ViewerError::Plan("it has no windows".into()));
    }
    let margin = (2.0 * plan.scenario.acoustic.sonar_range).max(100.0);
    Ok(ViewerData {
        title: format!(
            "shoal: N = {n} AUVs, {} window(s) of K = {} steps, seed {}",
            windows.len(),
            plan.scenario.horizon.steps,
            plan.scenario.seed
        ),
        shoal_version: plan.shoal_version.clone(),
        scenario_source: plan.scenario_source.clone(),
        seed: plan.scenario.seed,
        auvs: n,
        steps: plan.scenario.horizon.steps,
        dt: plan.scenario.horizon.dt,
        sonar_range: plan.scenario.acoustic.sonar_range,
        band_tolerance: plan.scenario.acoustic.band_tolerance,
        auv_colours: (0..n).map(auv_colour).collect(),
        floor: floor_mesh(floor, &plan.seafloor.source, bounds(&windows), margin),
        windows,
        metrics: plan.metrics.clone(),
        sim: sim_record.map(|r| sim(r, n)).transpose()?,
    })
}

/// How far an AUV's figure colour is mixed with white for the page's dark background: a tint, as
/// the light half of a tab20-style palette, which keeps the hue. At 0.35 the darkest (AUV 10's
/// indigo) reaches an HSL lightness of 0.57; raising every colour to a fixed HSL lightness
/// instead turned AUV 8's olive into the yellow of the A2A links.
pub const TINT: f64 = 0.35;

/// AUV `i`'s colour on the page: its figures' colour tinted by [`TINT`], as `#rrggbb`.
pub fn auv_colour(i: usize) -> String {
    let plotters::style::RGBColor(r, g, b) = crate::figures::vehicle_colour(Some(i));
    let tint = |v: u8| (f64::from(v) + (255.0 - f64::from(v)) * TINT).round() as u8;
    format!("#{:02x}{:02x}{:02x}", tint(r), tint(g), tint(b))
}

fn window(w: &Window, n: usize) -> Result<WindowData, ViewerError> {
    let bad = |why: String| ViewerError::Plan(format!("window {}: {why}", w.index));
    let stage = &w.final_;
    let steps = stage.usv.position.len();
    if steps == 0 {
        return Err(bad("the final stage has no USV positions".into()));
    }
    if stage.auvs.len() != n {
        return Err(bad(format!(
            "the final stage has {} AUV paths, the scenario {n} AUVs",
            stage.auvs.len()
        )));
    }
    let finite = |v: &[f64]| v.iter().all(|x| x.is_finite());
    if !stage.usv.position.iter().all(|p| finite(p)) {
        return Err(bad("a USV position is not finite".into()));
    }
    let mut auvs = Vec::with_capacity(n);
    for (i, a) in stage.auvs.iter().enumerate() {
        if a.position.len() != steps {
            return Err(bad(format!(
                "AUV {i} has {} positions, the USV {steps}",
                a.position.len()
            )));
        }
        if !a.position.iter().all(|p| finite(p)) {
            return Err(bad(format!("a position of AUV {i} is not finite")));
        }
        auvs.push(a.position.iter().map(|p| p.map(cm)).collect());
    }
    let ok = |l: &Link| l.a < n && l.b.iter().all(|&b| b < n);
    if let Some(l) = w.links.links.iter().flatten().find(|l| !ok(l)) {
        return Err(bad(format!(
            "link {l:?} names an AUV beyond the {n} of the team"
        )));
    }
    if w.links.links.len() > steps {
        return Err(bad(format!(
            "{} steps of links for {steps} positions",
            w.links.links.len()
        )));
    }
    Ok(WindowData {
        index: w.index,
        start_time: w.start_time,
        status: stage.status.clone(),
        iterations: stage.iterations,
        los_rounds: w.links.los_rounds,
        usv: stage.usv.position.iter().map(|p| p.map(cm)).collect(),
        auvs,
        links: w
            .links
            .links
            .iter()
            .map(|ls| ls.iter().map(|l| (l.a, l.b)).collect())
            .collect(),
        out_of_band: w
            .links
            .out_of_band
            .iter()
            .filter(|o| ok(&o.link))
            .map(|o| (o.k, o.link.a, o.link.b))
            .collect(),
        metrics: w.metrics.clone(),
    })
}

fn cm(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

fn dm(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

/// [x_min, x_max, y_min, y_max] over every vehicle position.
fn bounds(windows: &[WindowData]) -> [f64; 4] {
    let mut b = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    let xy = windows.iter().flat_map(|w| {
        let usv = w.usv.iter().map(|p| [p[0], p[1]]);
        usv.chain(w.auvs.iter().flatten().map(|p| [p[0], p[1]]))
    });
    for [x, y] in xy {
        b = [b[0].min(x), b[1].max(x), b[2].min(y), b[3].max(y)];
    }
    b
}

/// The floor under the mission: the vehicles' bounding box grown by `margin` and by 15 % of its
/// longer side, its shorter side widened to at least half the longer one, clipped to the grid;
/// then every s-th node (the same stride on both axes) so neither axis has more than
/// [`MAX_FLOOR_VERTICES`] vertices.
pub fn floor_mesh(floor: &Seafloor, source: &str, b: [f64; 4], margin: f64) -> FloorData {
    let span = (b[1] - b[0]).max(b[3] - b[2]);
    let grow = margin.max(0.15 * span);
    let (mut xs, mut ys) = ([b[0] - grow, b[1] + grow], [b[2] - grow, b[3] + grow]);
    let long = (xs[1] - xs[0]).max(ys[1] - ys[0]);
    for r in [&mut xs, &mut ys] {
        let widen = (0.5 * long - (r[1] - r[0])).max(0.0) / 2.0;
        *r = [r[0] - widen, r[1] + widen];
    }
    let index = |v: f64, o: f64, d: f64, n: usize, up: bool| {
        let u = (v - o) / d;
        let u = if up { u.ceil() } else { u.floor() };
        u.clamp(0.0, (n - 1) as f64) as usize
    };
    let g = floor.lattice();
    let (fx, fy) = (g.nx, g.ny);
    let (i0, i1) = (
        index(xs[0], g.x0, g.dx, fx, false),
        index(xs[1], g.x0, g.dx, fx, true),
    );
    let (j0, j1) = (
        index(ys[0], g.y0, g.dy, fy, false),
        index(ys[1], g.y0, g.dy, fy, true),
    );
    let widest = (i1 - i0).max(j1 - j0);
    let stride = widest.div_ceil(MAX_FLOOR_VERTICES - 1).max(1);
    let nx = (i1 - i0) / stride + 1;
    let ny = (j1 - j0) / stride + 1;
    let nodes: Vec<Option<f64>> = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| (i0 + i * stride, j0 + j * stride)))
        .map(|(i, j)| (!floor.is_nodata(i, j)).then(|| floor.node(i, j)))
        .collect();
    let (lo, hi) = nodes
        .iter()
        .flatten()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &z| {
            (lo.min(z), hi.max(z))
        });
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
    let scale = if hi > lo {
        f64::from(NODATA_CODE - 1) / (hi - lo)
    } else {
        0.0
    };
    let mut bytes = Vec::with_capacity(2 * nodes.len());
    for z in &nodes {
        let q = z.map_or(NODATA_CODE, |z| ((z - lo) * scale).round() as u16);
        bytes.extend_from_slice(&q.to_le_bytes());
    }
    FloorData {
        source: source.to_string(),
        grid_nx: fx,
        grid_ny: fy,
        grid_dx: g.dx,
        lattice: Lattice {
            nx,
            ny,
            x0: g.x(i0),
            y0: g.y(j0),
            dx: g.dx * stride as f64,
            dy: g.dy * stride as f64,
        },
        z_lo: lo,
        z_hi: hi,
        z: base64(&bytes),
    }
}

/// Standard base64 (RFC 4648, with padding), what the page's `atob` reads.
pub fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let v = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for (k, shift) in [18, 12, 6, 0].into_iter().enumerate() {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[((v >> shift) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}
