//! The independent checker on hand-built plans: a valid plan passes, and breaking exactly one
//! constraint fails exactly the family that owns it. Trajectories are rolled out with the
//! closed-form solution of the continuous AUV model derived here (not the checker's RK4, not
//! `crate::vehicle`), so the dynamics test also cross-checks the checker's integrator.
//!
//! The builder gives each window identical `step1` and `final` stages and an honest Step 2
//! graph and link report ([`graph::fill_graph`]); tests that tamper with "the plan" tamper with
//! the final stage. `graph` holds the tests of the Step 2 / Step 3 families, `malformed` those
//! of truncated and non-finite plans.

mod graph;
mod malformed;

use shoal::check::{
    check_plan, check_plan_against, load_floor, CheckError, CheckReport, LimitChange, LimitsError,
};
use shoal::mission::FloorSource;
use shoal::plan::{
    AuvPath, AuvState, InitialState, ModelRecord, ObjectiveTerms, Plan, Stage, UsvPath, Window,
    FORMAT,
};
use shoal::scenario::{Discretisation, Scenario, UsvObjective};
use shoal::seafloor::{Lattice, Seafloor};
use shoal::vehicle::{AuvModel, Damping, UsvModel};

// ---------------------------------------------------------------------------------------------
// Floors
// ---------------------------------------------------------------------------------------------

/// A square grid of `n × n` nodes, spacing `d`, south-west node at (x0, y0); `f` gives the
/// elevation of a node (None: NODATA).
fn grid(x0: f64, y0: f64, d: f64, n: usize, f: impl Fn(f64, f64) -> Option<f64>) -> Seafloor {
    let mut z = Vec::with_capacity(n * n);
    let mut nodata = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let v = f(x0 + i as f64 * d, y0 + j as f64 * d);
            z.push(v.unwrap_or(f64::NAN));
            nodata.push(v.is_none());
        }
    }
    Seafloor::from_nodes(Lattice::new(n, n, x0, y0, d, d), z, nodata).unwrap()
}

/// Flat floor at −100 m, 5 m cells, covering [−300, 300]².
fn flat() -> Seafloor {
    grid(-300.0, -300.0, 5.0, 121, |_, _| Some(-100.0))
}

// ---------------------------------------------------------------------------------------------
// Plans
// ---------------------------------------------------------------------------------------------

/// What a plan is built from: the scenario, the start, and every input of every window.
#[derive(Clone)]
struct Spec {
    s: Scenario,
    usv0: [f64; 2],
    auv0: Vec<[f64; 3]>,
    /// [window][k]
    usv_u: Vec<Vec<[f64; 2]>>,
    /// [window][auv][k]
    auv_u: Vec<Vec<Vec<[f64; 3]>>>,
}

const K: usize = 4;
const DT: f64 = 10.0;

fn rates(s: &Scenario) -> [f64; 3] {
    let a = &s.auv;
    let surge = -a.damping_surge / (a.mass - a.added_mass_surge);
    let heave = -a.damping_heave / (a.mass - a.added_mass_heave);
    [surge, surge, heave]
}

/// Coefficients (pv, pu, vv, vu) of one axis: closed form of ṗ = v, v̇ = −e v + u over δ with
/// constant u (ZOH), or eq. (8) (Euler).
fn coefficients(e: f64, dt: f64, kind: Discretisation) -> (f64, f64, f64, f64) {
    match kind {
        Discretisation::Zoh => {
            let g = -(-e * dt).exp_m1() / e; // (1 − e^{−eδ})/e
            (g, (dt - g) / e, (-e * dt).exp(), g)
        }
        Discretisation::Euler => (dt, 0.0, 1.0 - dt * e, dt),
    }
}

/// Two AUVs cruising east at about 1 m/s, 50 and 60 m deep, turning gently left; the USV goes
/// east at 0.9 m/s. `windows` windows of K = 4 steps of δ = 10 s.
fn spec(windows: usize) -> Spec {
    let mut s = Scenario::default();
    s.team.auvs = 2;
    s.windows = windows;
    s.horizon.steps = K;
    s.horizon.dt = DT;
    // a cruise floor the hand-built AUVs keep (they ramp to 1 m/s: 0.79 m/s at k = 1)
    s.auv.min_speed = 0.5;
    let e = rates(&s)[0];
    let auv = |w: usize| -> Vec<Vec<[f64; 3]>> {
        (0..2)
            .map(|_| {
                (0..K)
                    .map(|k| {
                        let th = 0.01 * (w * K + k) as f64;
                        [e * th.cos(), e * th.sin(), 0.0] // terminal speed 1 m/s
                    })
                    .collect()
            })
            .collect()
    };
    Spec {
        s,
        usv0: [0.0, 0.0],
        auv0: vec![[20.0, 10.0, -50.0], [-20.0, -10.0, -60.0]],
        usv_u: (0..windows).map(|_| vec![[0.9, 0.0]; K]).collect(),
        auv_u: (0..windows).map(auv).collect(),
    }
}

fn objective(s: &Scenario, floor: &Seafloor, usv: &UsvPath, auvs: &[AuvPath]) -> ObjectiveTerms {
    let energy = auvs
        .iter()
        .flat_map(|a| &a.input)
        .map(|u| u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
        .sum();
    let depth = auvs
        .iter()
        .flat_map(|a| &a.position[1..])
        .map(|p| p[2])
        .sum();
    let (p0, pk) = (usv.position[0], *usv.position.last().unwrap());
    let (usv_term, w_usv) = match s.usv.objective {
        UsvObjective::Away => (
            (pk[0] - p0[0]).powi(2) + (pk[1] - p0[1]).powi(2),
            -s.w8(), // weights.w8_scaling
        ),
        UsvObjective::Destination => {
            let d = s.usv.destination;
            (
                (pk[0] - d[0]).powi(2) + (pk[1] - d[1]).powi(2),
                s.weights.w8_2,
            )
        }
    };
    let height = auvs
        .iter()
        .flat_map(|a| &a.position[1..])
        .map(|p| p[2] - floor.elevation(p[0], p[1]).unwrap_or(f64::NAN))
        .sum();
    let of1_2 = match s.weights.of1_2 {
        shoal::scenario::DepthObjective::Height => height,
        shoal::scenario::DepthObjective::Depth => depth,
    };
    ObjectiveTerms {
        energy,
        depth,
        height,
        usv: usv_term,
        // the team's terms per AUV (weights.scaling)
        total: s.weights.per_auv(s.team.auvs) * (s.weights.w1 * energy + s.weights.w2 * of1_2)
            + w_usv * usv_term,
        ..ObjectiveTerms::default()
    }
}

fn auv_path(s: &Scenario, p: Vec<[f64; 3]>, v: Vec<[f64; 3]>, u: Vec<[f64; 3]>) -> AuvPath {
    let vmin = s.auv.min_heading_speed;
    AuvPath {
        surge_speed: v.iter().map(|v| v[0].hypot(v[1])).collect(),
        heading: v
            .iter()
            .map(|v| (v[0].hypot(v[1]) >= vmin).then(|| v[1].atan2(v[0])))
            .collect(),
        position: p,
        velocity: v,
        input: u,
    }
}

/// Roll the spec out into a plan on `floor`. `start` may replace the state a window starts
/// from (to break the chain).
fn build_with(
    spec: &Spec,
    floor: &Seafloor,
    start: impl Fn(usize, &mut [f64; 2], &mut Vec<AuvState>),
) -> Plan {
    let s = &spec.s;
    let (k, dt) = (s.horizon.steps, s.horizon.dt);
    let e = rates(s);
    let co: Vec<_> = e
        .iter()
        .map(|&e| coefficients(e, dt, s.auv.discretisation))
        .collect();
    let initial = InitialState {
        origin: "explicit".into(),
        usv: spec.usv0,
        auvs: spec
            .auv0
            .iter()
            .map(|p| AuvState {
                position: *p,
                velocity: [0.0; 3],
            })
            .collect(),
    };
    let (mut usv_at, mut auvs_at) = (initial.usv, initial.auvs.clone());
    let mut windows = Vec::new();
    for w in 0..s.windows {
        start(w, &mut usv_at, &mut auvs_at);
        let mut up = vec![usv_at];
        for u in &spec.usv_u[w] {
            let p = *up.last().unwrap();
            up.push([p[0] + dt * u[0], p[1] + dt * u[1]]);
        }
        let usv = UsvPath {
            position: up,
            input: spec.usv_u[w].clone(),
        };
        let mut auvs = Vec::new();
        for (n, st) in auvs_at.iter().enumerate() {
            let (mut p, mut v) = (vec![st.position], vec![st.velocity]);
            for u in &spec.auv_u[w][n] {
                let (p0, v0) = (*p.last().unwrap(), *v.last().unwrap());
                let mut p1 = [0.0; 3];
                let mut v1 = [0.0; 3];
                for i in 0..3 {
                    let (pv, pu, vv, vu) = co[i];
                    p1[i] = p0[i] + pv * v0[i] + pu * u[i];
                    v1[i] = vv * v0[i] + vu * u[i];
                }
                p.push(p1);
                v.push(v1);
            }
            auvs.push(auv_path(s, p, v, spec.auv_u[w][n].clone()));
        }
        usv_at = *usv.position.last().unwrap();
        auvs_at = auvs
            .iter()
            .map(|a| AuvState {
                position: *a.position.last().unwrap(),
                velocity: *a.velocity.last().unwrap(),
            })
            .collect();
        windows.push(Window {
            index: w,
            start_time: (w * k) as f64 * dt,
            courses: Vec::new(),
            graph: Default::default(),
            links: Default::default(),
            metrics: Default::default(),
            sampling: None,
            final_: Stage {
                status: "converged".into(),
                iterations: 1,
                solve_time_s: 0.0,
                objective: objective(s, floor, &usv, &auvs),
                max_violation: 0.0,
                usv: usv.clone(),
                auvs: auvs.clone(),
                scp: converged_log(),
            },
            step1: Stage {
                status: "converged".into(),
                iterations: 1,
                solve_time_s: 0.0,
                objective: objective(s, floor, &usv, &auvs),
                max_violation: 0.0,
                usv,
                auvs,
                scp: converged_log(),
            },
        });
    }
    let damping = Damping {
        surge: e[0],
        heave: e[2],
        yaw: -s.auv.damping_yaw / (s.auv.inertia_yaw - s.auv.added_inertia_yaw),
    };
    let model = ModelRecord {
        damping,
        auv: AuvModel {
            dt,
            rate: e,
            pv: std::array::from_fn(|i| co[i].0),
            pu: std::array::from_fn(|i| co[i].1),
            vv: std::array::from_fn(|i| co[i].2),
            vu: std::array::from_fn(|i| co[i].3),
        },
        usv: UsvModel {
            dt,
            max_speed: s.usv.max_speed,
        },
    };
    let mut plan = Plan {
        warnings: vec![],
        current: shoal::sim::current::still(),
        format: FORMAT.into(),
        method: shoal::plan::METHOD_MPC.into(),
        shoal_version: "test".into(),
        scenario_source: "test".into(),
        overrides: vec![],
        scenario: s.clone(),
        seafloor: FloorSource::file(None).record(floor),
        model,
        initial,
        windows,
        metrics: Default::default(),
    };
    graph::fill_graph(&mut plan);
    record_metrics(&mut plan, floor);
    plan
}

/// The metrics the planner records, for the plan's final stages (the "recorded metrics"
/// family holds them against its own recomputation).
fn record_metrics(plan: &mut Plan, floor: &Seafloor) {
    use shoal::metrics::{mission_metrics, MetricParams};
    let s = &plan.scenario;
    let p = MetricParams {
        dt: s.horizon.dt,
        sonar_range: s.acoustic.sonar_range,
        resolution: s.acoustic.resolution,
        swath_width: s.auv.swath_width,
        survey_altitude: s.auv.survey_altitude,
    };
    for w in &mut plan.windows {
        w.metrics = mission_metrics(&[(&w.final_, &w.links.links)], floor, &p, &[[0.0; 3]]);
    }
    let parts: Vec<_> = plan
        .windows
        .iter()
        .map(|w| (&w.final_, w.links.links.as_slice()))
        .collect();
    let times = vec![[0.0; 3]; parts.len()];
    plan.metrics = mission_metrics(&parts, floor, &p, &times);
}

fn build(spec: &Spec, floor: &Seafloor) -> Plan {
    build_with(spec, floor, |_, _, _| {})
}

fn failing(r: &CheckReport) -> Vec<&'static str> {
    r.failures().iter().map(|f| f.name).collect()
}

/// The check fails exactly `families`, and the table says so.
#[track_caller]
fn assert_fails_exactly(r: &CheckReport, families: &[&str]) {
    assert_eq!(failing(r), families, "\n{}", r.table());
    assert!(!r.passed());
    let table = r.table();
    for f in families {
        let row = table.lines().find(|l| l.starts_with(f)).unwrap();
        assert!(row.contains("FAIL"), "{row}");
    }
}

// ---------------------------------------------------------------------------------------------
// A valid plan
// ---------------------------------------------------------------------------------------------

#[test]
fn a_valid_plan_passes_every_family() {
    let floor = flat();
    let plan = build(&spec(2), &floor);
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());
    assert!(r.table().contains("PASS: every constraint family holds"));
    for f in &r.families {
        assert!(f.checked > 0, "{} checked nothing", f.name);
    }
    // heading is checked wherever both speeds are above 0.1 m/s: k = 1→2 … in window 0
    assert!(r.family("C1_14 heading rate").unwrap().checked >= 2 * (2 * K - 1));
    // the dynamics agree to rounding, far inside the tolerance
    let dynamics = r.family("C1_1 AUV dynamics (position)").unwrap();
    assert!(dynamics.worst_margin > -1e-9, "{dynamics:?}");
    assert_eq!(r.objectives.len(), 4); // two windows, two stages each
}

#[test]
fn a_valid_euler_plan_passes_and_a_zoh_plan_is_not_an_euler_plan() {
    let floor = flat();
    let mut sp = spec(1);
    sp.s.auv.discretisation = Discretisation::Euler;
    sp.s.horizon.dt = 2.0; // |1 − δ·e_heave| ≤ 1 needs δ ≤ 5 s
    sp.s.auv.min_speed = 0.0; // at δ = 2 s the AUVs ramp up slower than the spec's floor
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());

    // the ZOH plan read as Euler: wrong dynamics and a wrong model record
    let mut zoh = build(&spec(1), &floor);
    zoh.scenario.auv.discretisation = Discretisation::Euler;
    let r = check_plan(&zoh, &floor);
    assert_fails_exactly(
        &r,
        &[
            "model record",
            "C1_1 AUV dynamics (position)",
            "C1_1 AUV dynamics (velocity)",
        ],
    );
}

// ---------------------------------------------------------------------------------------------
// Breaking one constraint fails one family
// ---------------------------------------------------------------------------------------------

#[test]
fn auv_too_fast_fails_c1_7_only() {
    let floor = flat();
    let mut sp = spec(1);
    let e = rates(&sp.s)[0];
    sp.auv_u[0][0] = vec![[3.0 * e, 0.0, 0.0]; K]; // terminal speed 3 m/s > V_max = 2
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["C1_7 AUV speed"]);
    let f = r.family("C1_7 AUV speed").unwrap();
    assert!(f.where_.contains("AUV 0"), "{}", f.where_);
    assert!(f.worst_margin < -0.3);
}

/// Two AUVs doing the same thing 6 m apart, inside the default separation of 10 m: the
/// separation family fails, and only it; stating a separation of 5 m for the check passes it.
#[test]
fn two_auvs_within_the_separation_fail_its_family_only() {
    let floor = flat();
    let mut sp = spec(1);
    sp.auv0[1] = [20.0, 4.0, -50.0];
    sp.auv_u[0][1] = sp.auv_u[0][0].clone();
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["AUV separation"]);
    let f = r.family("AUV separation").unwrap();
    assert!((f.worst_margin + 4.0).abs() < 1e-6, "{f:?}");
    assert!(f.where_.contains("AUVs 0 and 1"), "{}", f.where_);
    let mut stated = plan.scenario.clone();
    stated.auv.min_separation = 5.0;
    let r = check_plan_against(&plan, &floor, &stated, "from a test").unwrap();
    assert!(r.passed(), "\n{}", r.table());
}

#[test]
fn usv_too_fast_fails_usv_speed_only() {
    let floor = flat();
    let mut sp = spec(1);
    sp.usv_u[0][2] = [1.6, 0.3]; // > 1.5 m/s
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["USV speed"]);
    assert!(r
        .family("USV speed")
        .unwrap()
        .where_
        .contains("input k = 2"));
}

/// Regression: `shoal check` trusted the limits recorded in the plan, so a plan whose
/// recorded auv.max_speed was raised by hand passed. Against the limits the user states it
/// fails, the report names both values, and only the stated limits change (the USV's speed
/// limit is also in the plan's model record, which stays the plan's own).
#[test]
fn regression_a_hand_raised_limit_fails_against_the_stated_one() {
    let floor = flat();
    let mission = spec(1).s; // V_max = 2 m/s, the USV's 1.5 m/s
    let mut sp = spec(1);
    let e = rates(&sp.s)[0];
    sp.auv_u[0][0] = vec![[3.0 * e, 0.0, 0.0]; K]; // terminal speed 3 m/s
    sp.s.auv.max_speed = 3.5; // raised by hand
    let plan = build(&sp, &floor);
    assert!(check_plan(&plan, &floor).passed());
    let r = check_plan_against(&plan, &floor, &mission, "from mission.toml").unwrap();
    assert_fails_exactly(&r, &["C1_7 AUV speed"]);
    assert_eq!(
        r.limits.changed,
        [LimitChange {
            key: "auv.max_speed",
            stated: 2.0,
            recorded: 3.5
        }]
    );
    assert_eq!(
        r.limits.lines(),
        [
            "limits: from mission.toml",
            "  auv.max_speed = 2 (stated), 3.5 as recorded in the plan"
        ]
    );
    assert_eq!(
        check_plan(&plan, &floor).limits.lines(),
        ["limits: as recorded in the plan"]
    );

    // a slower USV than the plan's: its speed fails, its model record is the plan's own
    let mut slow = mission.clone();
    slow.usv.max_speed = 0.5;
    slow.weights.w1 = 1.0; // not a limit: named, not used
    let honest = build(&spec(1), &floor);
    let r = check_plan_against(&honest, &floor, &slow, "from slow.toml").unwrap();
    assert_fails_exactly(&r, &["USV speed"]);
    assert_eq!(r.limits.ignored, ["weights.w1"]);
    assert!(r.limits.lines()[2].contains("not limits, the plan's own (not used): weights.w1"));

    // the same limits as recorded: every family as check_plan has it
    let same = check_plan_against(&honest, &floor, &honest.scenario, "from the plan").unwrap();
    assert_eq!(same.families, check_plan(&honest, &floor).families);
    assert!(same.limits.changed.is_empty());

    // the plan's geometry is not a limit: a different team is refused, naming both
    let mut team = mission.clone();
    team.team.auvs = 3;
    let e = check_plan_against(&honest, &floor, &team, "from team.toml").unwrap_err();
    assert!(matches!(
        e,
        LimitsError::Geometry {
            key: "team.auvs",
            ..
        }
    ));
    let text = e.to_string();
    assert!(
        text.contains(
            "from team.toml give team.auvs = 3, but the plan was made with team.auvs = 2"
        ),
        "{text}"
    );
}

#[test]
fn auv_near_the_surface_fails_c1_4_only() {
    let floor = flat();
    let mut sp = spec(1);
    sp.auv0[1][2] = -1.5; // above −surface_clearance = −2 m
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["C1_4 underwater"]);
    let f = r.family("C1_4 underwater").unwrap();
    assert!((f.worst_margin + 0.5).abs() < 1e-12, "{f:?}");
}

#[test]
fn below_the_depth_rating_fails_the_depth_rating_only() {
    let floor = flat();
    let mut sp = spec(1);
    sp.s.auv.max_depth = 55.0; // AUV 1 runs at −60 m
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["depth rating"]);
    let f = r.family("depth rating").unwrap();
    assert!(f.where_.contains("AUV 1"), "{}", f.where_);
    assert!((f.worst_margin + 5.0).abs() < 1e-9, "{f:?}");
}

#[test]
fn a_steep_climb_fails_the_flight_path_angle_only() {
    let floor = flat();
    let mut sp = spec(1);
    let heave = rates(&sp.s)[2];
    for u in &mut sp.auv_u[0][0] {
        u[2] = 0.2 * heave; // climbs at 0.2 m/s (terminal): 11° at 1 m/s
    }
    sp.s.auv.max_flight_path_angle = 0.1; // 5.7°
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["flight-path angle"]);
    let f = r.family("flight-path angle").unwrap();
    assert!(f.where_.contains("AUV 0"), "{}", f.where_);
    // within the default 0.3 rad (17°) the same climb passes
    sp.s.auv.max_flight_path_angle = 0.3;
    let r = check_plan(&build(&sp, &floor), &floor);
    assert!(r.passed(), "\n{}", r.table());
}

#[test]
fn a_slow_auv_fails_the_cruise_floor_only() {
    let floor = flat();
    let mut sp = spec(1);
    sp.s.auv.min_speed = 0.9; // k = 1 is at 0.79 m/s, ramping from rest
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["cruise floor"]);
    let f = r.family("cruise floor").unwrap();
    assert!(f.where_.contains("k = 1"), "{}", f.where_);
}

/// Regression: a plan may pass its waypoints at cruise speed and stop between them. Under the
/// zero-order hold the velocity runs along the line between consecutive waypoints' velocities,
/// so a reversal passes through rest however fast its ends: the floor fails between them.
#[test]
fn regression_a_reversal_between_fast_waypoints_fails_the_cruise_floor() {
    let floor = flat();
    let mut sp = spec(1);
    let e = rates(&sp.s)[0];
    sp.s.auv.max_heading_rate = 1.0; // C1_14 allows the reversal
    sp.auv_u[0][0][2] = [-e, 0.0, 0.0];
    let r = check_plan(&build(&sp, &floor), &floor);
    let f = r.family("cruise floor").unwrap();
    assert!(!f.passed(), "\n{}", r.table());
    assert!(f.where_.contains("between the waypoints"), "{}", f.where_);
}

/// A flat floor at −100 m, 5 m cells, with one node at `peak` raised to −10 m: a 5 m pyramid.
fn pyramid(peak: [f64; 2]) -> Seafloor {
    let d = 5.0;
    grid(peak[0] - 60.0 * d, peak[1] - 60.0 * d, d, 121, |x, y| {
        let at_peak = (x - peak[0]).abs() < 1e-6 && (y - peak[1]).abs() < 1e-6;
        Some(if at_peak { -10.0 } else { -100.0 })
    })
}

#[test]
fn a_seamount_between_two_good_waypoints_fails_the_segment_check_only() {
    let sp = {
        let mut sp = spec(1);
        sp.s.acoustic.resolution = 1.0;
        sp
    };
    // where AUV 0's segment k = 1 → 2 has its midpoint (the floor does not change the rollout)
    let probe = build(&sp, &flat());
    let (a, b) = (
        probe.windows[0].final_.auvs[0].position[1],
        probe.windows[0].final_.auvs[0].position[2],
    );
    let mid = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    let half = ((b[0] - a[0]).hypot(b[1] - a[1])) / 2.0;
    assert!(half > 3.0, "segment too short for the test: {half}");
    let floor = pyramid(mid);
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    // the peak also stands in the way of the A2A link leaving AUV 0 at k = 1
    assert_fails_exactly(
        &r,
        &[
            "C2_2 floor clearance (segments)",
            "planned chain line of sight",
        ],
    );
    let seg = r.family("C2_2 floor clearance (segments)").unwrap();
    assert!(seg.where_.contains("k = 1→2, AUV 0"), "{}", seg.where_);
    assert!(seg.worst_margin < -20.0, "{seg:?}");
    // both waypoints are well clear
    let wp = r.family("C2_2 floor clearance (waypoints)").unwrap();
    assert!(wp.worst_margin > 10.0, "{wp:?}");
}

#[test]
fn a_waypoint_too_close_to_the_floor_fails_both_clearance_families() {
    let floor = flat();
    let mut sp = spec(1);
    sp.auv0[0][2] = -97.0; // 3 m above the floor, ε = 5 m
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(
        &r,
        &[
            "C2_2 floor clearance (waypoints)",
            "C2_2 floor clearance (segments)",
        ],
    );
    let f = r.family("C2_2 floor clearance (waypoints)").unwrap();
    assert!((f.worst_margin + 2.0).abs() < 1e-9, "{f:?}");
}

#[test]
fn a_sample_over_nodata_fails_the_obstacle_family_only() {
    // AUV 0 starts at (20, 10): make the south-west node of its cell, 4.5 m away on both axes,
    // NODATA. The bilinear floor there is −100·(1 − 0.1·0.1) = −99 m, still far below.
    let sp = spec(1);
    let bad = [15.5, 5.5];
    let floor = grid(15.5 - 60.0 * 5.0, 5.5 - 60.0 * 5.0, 5.0, 121, |x, y| {
        ((x - bad[0]).abs() > 1e-6 || (y - bad[1]).abs() > 1e-6).then_some(-100.0)
    });
    let r = check_plan(&build(&sp, &floor), &floor);
    // a NODATA node is stored at 0 m: the A2A link leaving AUV 0 at k = 1 runs into it too;
    // and every link from AUV 0 at k = 0 starts over an obstacle cell, so it has no line of
    // sight: AUV 0 is cut off
    assert_fails_exactly(
        &r,
        &[
            "no obstacle (NODATA/land)",
            "acoustic connectivity (range + line of sight)",
            "planned chain line of sight",
        ],
    );
    let f = r.family("no obstacle (NODATA/land)").unwrap();
    assert!(f.where_.contains("k = 0→1, AUV 0"), "{}", f.where_);
}

#[test]
fn a_usv_over_an_obstacle_cell_fails_the_obstacle_family() {
    // the USV runs east along y = 0 from the origin; a NODATA node at (30, 5) makes the cells
    // of y in [0, 5] beside it obstacles, though the floor along y = 0 stays at −100 m
    let sp = spec(1);
    let floor = grid(-300.0, -300.0, 5.0, 121, |x, y| {
        ((x - 30.0).abs() > 1e-6 || (y - 5.0).abs() > 1e-6).then_some(-100.0)
    });
    let r = check_plan(&build(&sp, &floor), &floor);
    assert!(
        failing(&r).contains(&"no obstacle (NODATA/land)"),
        "{}",
        r.table()
    );
    let f = r.family("no obstacle (NODATA/land)").unwrap();
    assert!(
        f.where_.contains("window 0, k = 2→3, USV: sample")
            && f.where_.contains("is over a NODATA cell"),
        "{}",
        f.where_
    );
    // the same path over the grid without the hole is clear
    assert!(check_plan(&build(&sp, &flat()), &flat()).passed());
}

#[test]
fn leaving_the_grid_fails_the_grid_family_without_panicking() {
    let floor = grid(-300.0, -300.0, 5.0, 121, |_, _| Some(-100.0));
    let mut sp = spec(1);
    sp.auv0[0] = [299.0, 10.0, -50.0];
    sp.usv0 = [290.0, 0.0];
    let r = check_plan(&build(&sp, &floor), &floor);
    let failing = failing(&r);
    assert!(failing.contains(&"inside the seafloor grid"), "{failing:?}");
    let f = r.family("C2_2 floor clearance (waypoints)").unwrap();
    assert_eq!(f.worst_margin, f64::NEG_INFINITY);
    assert!(f.where_.contains("outside"), "{}", f.where_);
}

#[test]
fn too_far_from_the_usv_at_k_fails_c1_6_only() {
    let floor = flat();
    let mut sp = spec(1);
    // AUV 1 starts 100 m west of the USV and keeps west; the USV runs east at 1.5 m/s
    sp.auv0[1] = [-100.0, 0.0, -60.0];
    let e = rates(&sp.s)[0];
    sp.auv_u[0][1] = vec![[-e, 0.0, 0.0]; K];
    sp.usv_u[0] = vec![[1.5, 0.0]; K];
    // a third AUV waits between them and relays AUV 1 to the USV, so the team stays
    // acoustically connected (without it, AUV 1 would be cut off at K as well)
    sp.s.team.auvs = 3;
    sp.auv0.push([-30.0, 0.0, -55.0]);
    sp.auv_u[0].push(vec![[0.0; 3]; K]);
    sp.s.auv.min_speed = 0.0; // the relay waits: no cruise floor
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["C1_6 sonar range at k = 0, K"]);
    let f = r.family("C1_6 sonar range at k = 0, K").unwrap();
    assert!(
        f.where_.contains(&format!("k = {K}, AUV 1")),
        "{}",
        f.where_
    );
}

#[test]
fn beyond_d_max_fails_c1_5_only() {
    let floor = flat();
    let mut sp = spec(1);
    sp.s.acoustic.max_range = 40.0; // the AUVs are ≈ 55–60 m from the USV
    let r = check_plan(&build(&sp, &floor), &floor);
    assert_fails_exactly(&r, &["C1_5 range ≤ d_max"]);
}

#[test]
fn a_sharp_turn_fails_c1_14_only() {
    let floor = flat();
    let mut sp = spec(1);
    let e = rates(&sp.s)[0];
    sp.auv_u[0][0][2] = [0.0, e, 0.0]; // input k = 2 points north while the AUV heads east
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["C1_14 heading rate"]);
    let f = r.family("C1_14 heading rate").unwrap();
    assert!(f.where_.contains("k = 2→3, AUV 0"), "{}", f.where_);
    // the rate is recomputed from the velocities, not read from the stored heading
    let v = &plan.windows[0].final_.auvs[0].velocity;
    let turn = (v[3][1].atan2(v[3][0]) - v[2][1].atan2(v[2][0])).abs();
    let want = sp.s.auv.max_heading_rate - turn / DT;
    assert!(
        (f.worst_margin - want).abs() < 1e-12,
        "{} vs {want}",
        f.worst_margin
    );
}

#[test]
fn the_stored_heading_is_not_trusted() {
    // A sharp turn with stored headings doctored to look smooth still fails C1_14, and the
    // doctored field fails its own family.
    let floor = flat();
    let mut sp = spec(1);
    let e = rates(&sp.s)[0];
    sp.auv_u[0][0][2] = [0.0, e, 0.0];
    let mut plan = build(&sp, &floor);
    let a = &mut plan.windows[0].final_.auvs[0];
    a.heading[3] = a.heading[2];
    // the forger also records the heading rate the doctored headings give
    record_metrics(&mut plan, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["C1_14 heading rate", "recorded heading"]);
}

#[test]
fn a_window_chain_gap_fails_the_chain_only() {
    let floor = flat();
    let sp = spec(2);
    let plan = build_with(&sp, &floor, |w, _, auvs| {
        if w == 1 {
            auvs[1].position[0] += 1.0; // window 1 starts 1 m east of where window 0 ended
        }
    });
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["window chain"]);
    let f = r.family("window chain").unwrap();
    assert!(
        f.where_.starts_with("window 1, k = 0, AUV 1"),
        "{}",
        f.where_
    );
    assert!((f.worst_margin + 1.0).abs() < 1e-9);

    // and window 0 must start at plan.initial
    let plan = build_with(&sp, &floor, |w, usv, _| {
        if w == 0 {
            usv[1] += 0.5;
        }
    });
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["window chain"]);
    assert!(r.family("window chain").unwrap().where_.contains("USV"));

    // and plan.initial must be the scenario's explicit [initial], if it has one
    let mut plan = build(&sp, &floor);
    plan.scenario.initial = Some(shoal::scenario::Initial {
        usv: sp.usv0,
        auvs: sp.auv0.clone(),
    });
    assert!(check_plan(&plan, &floor).passed());
    plan.scenario.initial.as_mut().unwrap().auvs[1][2] -= 2.0;
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["window chain"]);
    assert!(r
        .family("window chain")
        .unwrap()
        .where_
        .contains("scenario.initial"));
}

#[test]
fn a_tampered_input_fails_the_dynamics_only() {
    let floor = flat();
    let sp = spec(2);
    // the final plan, and Step 1's stage, which the same families check and the report names
    for (step1, named) in [
        (false, "window 1, k = 1→2, AUV 0"),
        (true, "window 1, k = 1→2, step1 AUV 0"),
    ] {
        let mut plan = build(&sp, &floor);
        let w = &mut plan.windows[1];
        let st = if step1 { &mut w.step1 } else { &mut w.final_ };
        st.auvs[0].input[1][0] += 0.01;
        // a careful forger also fixes the stored objective and the recorded metrics
        st.objective = objective(&plan.scenario, &floor, &st.usv, &st.auvs);
        record_metrics(&mut plan, &floor);
        let r = check_plan(&plan, &floor);
        assert_fails_exactly(
            &r,
            &[
                "C1_1 AUV dynamics (position)",
                "C1_1 AUV dynamics (velocity)",
            ],
        );
        let f = r.family("C1_1 AUV dynamics (velocity)").unwrap();
        assert!(f.where_.contains(named), "{}", f.where_);
    }

    // the USV model too
    let mut plan = build(&sp, &floor);
    plan.windows[0].final_.usv.input[3][1] += 0.01;
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["eq. (9) USV dynamics"]);
}

/// The checker rolls the dynamics in the current the plan records: a plan made in still water
/// but recording a current fails the position dynamics only (its velocities are through the
/// water, and the current would have carried it 0.2 m/s × δ further each step).
#[test]
fn a_plan_is_checked_in_the_current_it_records() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    assert!(check_plan(&plan, &floor).passed());
    plan.current.velocity = [0.2, 0.0];
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["C1_1 AUV dynamics (position)"]);
    let f = r.family("C1_1 AUV dynamics (position)").unwrap();
    assert!((f.worst_margin + 0.2 * DT).abs() < 1e-6, "{f:?}");
}

#[test]
fn a_tampered_objective_fails_the_objective_only() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    plan.windows[0].final_.objective.energy *= 1.001;
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["objective"]);
    assert!(r.table().contains("energy"));
}

#[test]
fn a_tampered_model_record_fails_the_model_family_only() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    plan.model.damping.heave *= 1.01;
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["model record"]);
}

#[test]
fn a_tampered_surge_speed_fails_its_family_only() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    plan.windows[0].final_.auvs[1].surge_speed[2] += 0.1;
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["recorded surge speed"]);
}

// ---------------------------------------------------------------------------------------------
// The floor's identity
// ---------------------------------------------------------------------------------------------

#[test]
fn another_floor_fails_the_identity_family() {
    let floor = flat();
    let plan = build(&spec(1), &floor);
    let other = grid(-300.0, -300.0, 5.0, 121, |_, _| Some(-100.5));
    let r = check_plan(&plan, &other);
    // the height-above-floor term of the objective is evaluated on the floor, so it differs too,
    // and so do the recorded heights above it
    assert_fails_exactly(&r, &["seafloor identity", "recorded metrics", "objective"]);
    let f = r.family("seafloor identity").unwrap();
    assert!(
        f.where_.contains("not the floor the plan was made on"),
        "{}",
        f.where_
    );
    assert_ne!(r.plan_fingerprint, r.floor_fingerprint);
}

#[test]
fn load_floor_reads_the_named_file_and_refuses_another_floor() {
    let dir = tempfile::tempdir().unwrap();
    let floor = flat();
    let good = dir.path().join("floor.asc");
    floor.write_esri_ascii(&good).unwrap();
    let other = dir.path().join("other.asc");
    grid(-300.0, -300.0, 5.0, 121, |_, _| Some(-90.0))
        .write_esri_ascii(&other)
        .unwrap();

    let mut plan = build(&spec(1), &floor);
    plan.seafloor.path = Some(good.display().to_string());
    let loaded = load_floor(&plan, None).unwrap();
    assert_eq!(loaded.fingerprint(), plan.seafloor.fingerprint);
    assert!(check_plan(&plan, &loaded).passed());

    match load_floor(&plan, Some(&other)) {
        Err(e @ CheckError::FingerprintMismatch { .. }) => {
            assert!(
                e.to_string().contains("not the floor the plan was made on"),
                "{e}"
            )
        }
        r => panic!("expected a fingerprint mismatch, got {r:?}"),
    }
    assert!(load_floor(&plan, Some(&good)).is_ok());
    let missing = dir.path().join("missing.asc");
    assert!(matches!(
        load_floor(&plan, Some(&missing)),
        Err(CheckError::ReadFloor { .. })
    ));
    plan.seafloor.path = None;
    assert!(matches!(
        load_floor(&plan, None),
        Err(CheckError::NoFloorPath)
    ));
    plan.seafloor.source = "moon".into();
    assert!(matches!(
        load_floor(&plan, None),
        Err(CheckError::UnknownSource(_))
    ));
}

#[test]
fn load_floor_regenerates_the_synthetic_floor() {
    let mut sp = spec(1);
    sp.s.seed = 7;
    sp.s.seafloor.synthetic.size = [1000.0, 1000.0];
    sp.s.seafloor.synthetic.seamounts = 3;
    sp.s.seafloor.synthetic.valleys = 2;
    let floor = Seafloor::synthetic(&sp.s.seafloor.synthetic, sp.s.seed).unwrap();
    let mut plan = build(&sp, &floor);
    plan.seafloor.source = "synthetic".into();
    let loaded = load_floor(&plan, None).unwrap();
    assert_eq!(loaded.fingerprint(), floor.fingerprint());
    // another seed is another floor
    plan.scenario.seed = 8;
    assert!(matches!(
        load_floor(&plan, None),
        Err(CheckError::FingerprintMismatch { .. })
    ));
}

#[test]
fn the_table_is_aligned_and_names_every_family() {
    let floor = flat();
    let r = check_plan(&build(&spec(1), &floor), &floor);
    let table = r.table();
    let lines: Vec<&str> = table.lines().filter(|l| !l.starts_with(' ')).collect();
    assert!(lines[0].starts_with("family"));
    let col = lines[0].find("result").unwrap();
    for (line, f) in lines[2..].iter().zip(&r.families) {
        assert!(line.starts_with(f.name), "{line}");
        let result: String = line.chars().skip(col).take(4).collect();
        assert_eq!(result, "PASS", "{line}");
    }
}

/// Regression (issue 13): the check table was 210 columns wide, the place of each worst
/// margin a seventh column. The place now goes under its row, wrapped: no line is wider than
/// the table's six columns (100 characters), and every word of every place is there.
#[test]
fn regression_the_check_table_is_at_most_100_columns_wide() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    plan.windows[0].final_.auvs[0].position[1][2] += 1000.0; // above the surface: long places
    let r = check_plan(&plan, &floor);
    let table = r.table();
    let rows = table.split("\n\n").next().unwrap();
    for line in rows.lines() {
        assert!(
            line.chars().count() <= 100,
            "{} wide: {line}",
            line.chars().count()
        );
    }
    let flat_table: Vec<&str> = rows.split_whitespace().collect();
    for f in &r.families {
        for word in f.where_.split_whitespace() {
            assert!(flat_table.contains(&word), "{word:?} of {:?}", f.where_);
        }
    }
}

/// The SCP log of a stage that converged at its first iteration: one entry that found no
/// decrease left (not accepted), its convex solve Solved.
fn converged_log() -> Vec<shoal::plan::ScpIteration> {
    vec![shoal::plan::ScpIteration {
        trust_region: 200.0,
        merit_before: 0.0,
        merit_after: 0.0,
        predicted: 0.0,
        ratio: 1.0,
        accepted: false,
        violation: 0.0,
        penalty: Some(1e3),
        extrapolated: false,
        solver_status: "Solved".into(),
        solver_iterations: 10,
        solver_time_s: 0.0,
    }]
}

/// Regression (issue 13): the checker verified a plan's positions but not what it claims of its
/// SCP; a stage could say "converged" on a log that says otherwise. Each claim is now held
/// against the log.
#[test]
fn regression_an_scp_status_its_log_contradicts_fails_structure() {
    let floor = flat();
    let good = build(&spec(1), &floor);
    let tamper = |f: &dyn Fn(&mut Plan)| {
        let mut p = good.clone();
        f(&mut p);
        check_plan(&p, &floor)
    };
    // "converged" on an iteration that was accepted and did not lower the merit (a converged
    // SCP ends on one that was not accepted, or on a feasible last candidate that was better)
    let r = tamper(&|p| p.windows[0].final_.scp[0].accepted = true);
    assert_fails_exactly(&r, &["structure"]);
    let better = |p: &mut Plan| {
        let it = &mut p.windows[0].final_.scp[0];
        it.accepted = true;
        it.merit_after = it.merit_before - 1.0;
    };
    let r = tamper(&better);
    assert!(r.passed(), "\n{}", r.table());
    // ... but not on one that broke a constraint beyond scp.feasibility_tol
    let r = tamper(&|p| {
        better(p);
        p.windows[0].final_.scp[0].violation = 0.1;
    });
    assert_fails_exactly(&r, &["structure"]);
    // "max_iterations" after 1 of scp.max_iterations iterations
    let r = tamper(&|p| p.windows[0].step1.status = "max_iterations".into());
    assert_fails_exactly(&r, &["structure"]);
    // iterations that disagree with the log's length
    let r = tamper(&|p| p.windows[0].step1.iterations = 7);
    assert_fails_exactly(&r, &["structure"]);
    // a convex solve that failed
    let r = tamper(&|p| p.windows[0].final_.scp[0].solver_status = "NumericalError".into());
    assert_fails_exactly(&r, &["structure"]);
    // "stalled" is a status the planner writes
    let r = tamper(&|p| p.windows[0].step1.status = "stalled".into());
    assert!(r.passed(), "\n{}", r.table());
    // so is "solver_trouble" (issue 22: the solves that failed are not in the log); a status
    // the planner never writes is refused
    let r = tamper(&|p| p.windows[0].step1.status = "solver_trouble".into());
    assert!(r.passed(), "\n{}", r.table());
    let r = tamper(&|p| p.windows[0].step1.status = "gave_up".into());
    assert_fails_exactly(&r, &["structure"]);
}

/// Regression (issue 13): the checker sampled segments at the resolution the plan claims, so a
/// plan made at a coarse r (1e308 passed) was never held to the floor between its samples. It
/// now samples at least every 5 m: the seamount between two waypoints fails the check however
/// coarse the plan's r.
#[test]
fn regression_a_coarse_resolution_does_not_hide_the_floor() {
    let mut sp = spec(1);
    sp.s.acoustic.resolution = 1.0;
    let probe = build(&sp, &flat());
    let (a, b) = (
        probe.windows[0].final_.auvs[0].position[1],
        probe.windows[0].final_.auvs[0].position[2],
    );
    // a 5 m pyramid at 1/3 of the segment, away from both ends and from its midpoint
    let peak = [a[0] + (b[0] - a[0]) / 3.0, a[1] + (b[1] - a[1]) / 3.0];
    let floor = pyramid(peak);
    let mut plan = build(&sp, &floor);
    plan.scenario.acoustic.resolution = 1e308;
    let r = check_plan(&plan, &floor);
    let seg = r.family("C2_2 floor clearance (segments)").unwrap();
    assert!(seg.worst_margin < -10.0, "{seg:?}");
}

/// Regression (issue 13): the checker verified a plan's paths but not the metrics it records;
/// a plan could claim any input energy, height or heading rate.
#[test]
fn regression_recorded_metrics_are_recomputed() {
    let floor = flat();
    let good = build(&spec(2), &floor);
    assert!(check_plan(&good, &floor).passed());
    for tamper in [
        (|p: &mut Plan| p.metrics.input_energy *= 0.5) as fn(&mut Plan),
        |p| p.windows[1].metrics.mean_height += 1.0,
        |p| p.windows[0].metrics.min_height -= 1.0,
        |p| p.metrics.max_heading_rate += 1e-3,
    ] {
        let mut p = good.clone();
        tamper(&mut p);
        assert_fails_exactly(&check_plan(&p, &floor), &["recorded metrics"]);
    }
}

/// Regression (issue 13): the connected and chain fractions and the explored area a plan
/// records were taken on trust. They are recounted with the checker's own links, and the area
/// is measured on columns across the planner's strips (within 5 %).
#[test]
fn regression_recorded_fractions_and_area_are_verified() {
    let floor = flat();
    // 40–60 m above the floor: no swath counts at the default survey altitude (15 m), and the
    // checker agrees that nothing was explored
    let high = build(&spec(2), &floor);
    assert_eq!(high.metrics.explored_area_km2, 0.0);
    assert!(check_plan(&high, &floor).passed());
    let mut surveyed = spec(2);
    surveyed.s.auv.survey_altitude = 100.0;
    let good = build(&surveyed, &floor);
    let r = check_plan(&good, &floor);
    assert!(r.passed(), "{}", r.table());
    let area = r.family("recorded explored area").unwrap();
    // two windows and the mission, and the mission's revisited area (issue 14)
    assert!(area.checked == 4 && area.worst_margin > -0.01, "{area:?}");
    for tamper in [
        (|p: &mut Plan| p.metrics.connected_fraction = 0.5) as fn(&mut Plan),
        |p| p.windows[1].metrics.chain_fraction -= 0.05,
    ] {
        let mut p = good.clone();
        tamper(&mut p);
        assert_fails_exactly(&check_plan(&p, &floor), &["recorded metrics"]);
    }
    for tamper in [
        (|p: &mut Plan| p.metrics.explored_area_km2 *= 1.1) as fn(&mut Plan),
        |p| p.windows[0].metrics.explored_area_km2 = 0.0,
        |p| p.metrics.revisited_area_km2 += 0.1 * p.metrics.explored_area_km2,
    ] {
        let mut p = good.clone();
        tamper(&mut p);
        assert_fails_exactly(&check_plan(&p, &floor), &["recorded explored area"]);
    }
}
