//! The sampler's validity tests against the checker, and its draws against the model.

use super::assemble::{window, Sampled};
use super::draw;
use super::validity::{self, Limits, Reject};
use crate::check::check_plan;
use crate::mission::FloorSource;
use crate::plan::{AuvState, InitialState, ModelRecord, Plan, SamplingReport, FORMAT};
use crate::scenario::Scenario;
use crate::seafloor::{Lattice, Seafloor};
use crate::team::TeamProblem;
use crate::trajectory::{Start, Trajectory};
use crate::vehicle::{AuvModel, Damping, UsvModel};
use proptest::prelude::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::sync::OnceLock;

/// A rolling floor between −125 and −75 m, 2 km across, with a NODATA block east of the
/// origin (x in [300, 460] m, y in [−100, 100] m).
fn floor() -> &'static Seafloor {
    static FLOOR: OnceLock<Seafloor> = OnceLock::new();
    FLOOR.get_or_init(|| {
        let (n, c, x0) = (101usize, 20.0, -1000.0);
        let mut z = Vec::with_capacity(n * n);
        let mut nodata = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                let (x, y) = (x0 + i as f64 * c, x0 + j as f64 * c);
                z.push(-100.0 + 25.0 * (x / 150.0).sin() * (y / 190.0).cos());
                nodata.push((300.0..=460.0).contains(&x) && (-100.0..=100.0).contains(&y));
            }
        }
        Seafloor::from_nodes(Lattice::new(n, n, x0, x0, c, c), z, nodata).unwrap()
    })
}

/// The checker's families for one vehicle's step, which the per-vehicle tests stand for.
const VEHICLE_FAMILIES: [&str; 10] = [
    "USV speed",
    "C1_7 AUV speed",
    "C1_4 underwater",
    "C1_5 range ≤ d_max",
    "C1_6 sonar range at k = 0, K",
    "inside the seafloor grid",
    "C2_2 floor clearance (waypoints)",
    "C2_2 floor clearance (segments)",
    "no obstacle (NODATA/land)",
    "C1_14 heading rate",
];

/// A one-step plan from `start` under the given inputs, assembled as the baseline's are.
fn one_step_plan(s: &Scenario, start: &Start, usv_u: [f64; 2], auv_u: &[[f64; 3]]) -> Plan {
    let f = floor();
    let auv = AuvModel::new(&s.auv, s.horizon.dt).unwrap();
    let usv = UsvModel {
        dt: s.horizon.dt,
        max_speed: s.usv.max_speed,
    };
    let t = Trajectory::simulate(
        start,
        vec![usv_u],
        auv_u.iter().map(|u| vec![*u]).collect(),
        &auv,
        &usv,
    );
    let l = Limits::of(s);
    let points: Vec<[f64; 3]> = t.auv_p.iter().map(|p| p[1]).collect();
    let order = validity::find_chain(&l, f, t.usv_p[1], &points)
        .unwrap_or_else(|_| (0..points.len()).collect());
    let keep_out = f.keep_out();
    let problem = TeamProblem::new(s, f, &keep_out, auv, usv, start.clone());
    let w = window(
        s,
        f,
        Sampled {
            index: 0,
            trajectory: &t,
            chains: &[order],
            problem: &problem,
            time_s: 0.0,
            report: SamplingReport::default(),
            require_connected: false,
        },
    )
    .unwrap();
    Plan {
        format: FORMAT.into(),
        method: crate::plan::METHOD_RRT_LIKE.into(),
        shoal_version: "test".into(),
        scenario_source: "test".into(),
        overrides: Vec::new(),
        scenario: s.clone(),
        seafloor: FloorSource::file(Some("test".into())).record(f),
        model: ModelRecord {
            damping: Damping::from_params(&s.auv).unwrap(),
            auv,
            usv,
        },
        current: crate::sim::current::still(),
        initial: InitialState {
            origin: "explicit".into(),
            usv: start.usv,
            auvs: start.auvs.clone(),
        },
        metrics: crate::planner::mission(std::slice::from_ref(&w), f, s),
        windows: vec![w],
        warnings: Vec::new(),
    }
}

/// One random case: a start clustered about the USV with random velocities, and each
/// vehicle's next velocity drawn by the sampler or anywhere in a box around its limits.
fn case(seed: u64, n: usize) -> (Scenario, Start, [f64; 2], Vec<[f64; 3]>) {
    use rand::Rng;
    let mut s = Scenario::default();
    s.team.auvs = n;
    s.horizon.steps = 1;
    // k = 1 is K, where C1_6 holds every AUV within d_s of the USV: a longer range leaves
    // room for valid steps
    s.acoustic.sonar_range = 300.0;
    // the paper's vehicle, which the sampler plans for: no cruise floor (with one C1_14 always
    // applies), no angle limit, no separation, no depth rating to speak of
    s.auv.min_speed = 0.0;
    s.auv.max_depth = 1000.0;
    s.auv.max_flight_path_angle = crate::scenario::NO_ANGLE_LIMIT;
    s.auv.min_separation = 0.0;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let auv = AuvModel::new(&s.auv, s.horizon.dt).unwrap();
    let l = Limits::of(&s);
    let usv = [rng.gen_range(-60.0..60.0), rng.gen_range(-60.0..60.0)];
    let auvs: Vec<AuvState> = (0..n)
        .map(|_| AuvState {
            position: [
                usv[0] + rng.gen_range(-50.0..50.0),
                usv[1] + rng.gen_range(-50.0..50.0),
                rng.gen_range(-65.0..-10.0),
            ],
            velocity: [
                rng.gen_range(-1.4..1.4),
                rng.gen_range(-1.4..1.4),
                rng.gen_range(-0.3..0.3),
            ],
        })
        .collect();
    let start = Start { usv, auvs };
    let usv_u = match rng.gen_bool(0.8) {
        true => draw::usv_velocity(&mut rng, &l, [0.0; 2]),
        false => [rng.gen_range(-1.8..1.8), rng.gen_range(-1.8..1.8)],
    };
    let auv_u = start
        .auvs
        .iter()
        .map(|a| {
            let drawn = draw::auv_step(&mut rng, &l, &auv, floor(), a.position, a.velocity);
            // a drawn step, or one pushed off it (past a limit, often)
            match drawn {
                Ok(step) if rng.gen_bool(0.75) => step.u,
                Ok(step) => {
                    let v1: [f64; 3] =
                        std::array::from_fn(|i| step.v[i] + rng.gen_range(-0.8..0.8));
                    draw::input_for(&auv, a.velocity, v1)
                }
                Err(_) => {
                    let v1: [f64; 3] = std::array::from_fn(|_| rng.gen_range(-2.4..2.4));
                    draw::input_for(&auv, a.velocity, v1)
                }
            }
        })
        .collect();
    (s, start, usv_u, auv_u)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// The per-vehicle tests accept a step exactly when the checker's per-vehicle families
    /// pass it; the chain test accepts only steps the checker finds connected, with every
    /// planned link in sight.
    #[test]
    fn sampler_agrees_with_the_checker(seed in 0u64..1_000_000, n in 1usize..4) {
        let (s, start, usv_u, auv_u) = case(seed, n);
        let plan = one_step_plan(&s, &start, usv_u, &auv_u);
        let report = check_plan(&plan, floor());
        let l = Limits::of(&s);
        let f = floor();
        let st = &plan.windows[0].final_;
        let usv1 = st.usv.position[1];
        let mut vehicles = validity::usv_step(&l, f, start.usv, usv1);
        for (a, path) in start.auvs.iter().zip(&st.auvs) {
            let (p, v) = (path.position[1], path.velocity[1]);
            vehicles = vehicles
                .and_then(|_| validity::auv_waypoint(&l, f, 1, a.velocity, p, v, usv1))
                .and_then(|_| validity::auv_segment(&l, f, a.position, p));
        }
        let families_pass = VEHICLE_FAMILIES.iter().all(|name| {
            report.family(name).is_some_and(|fam| fam.passed())
        });
        prop_assert_eq!(
            vehicles.is_ok(),
            families_pass,
            "sampler {:?}; checker:\n{}",
            vehicles,
            report.table()
        );
        if vehicles.is_ok() {
            let points: Vec<[f64; 3]> = st.auvs.iter().map(|a| a.position[1]).collect();
            let chain = validity::find_chain(&l, f, usv1, &points);
            let connected = report
                .family("acoustic connectivity (range + line of sight)")
                .is_some_and(|fam| fam.passed());
            let in_sight = report
                .family("planned chain line of sight")
                .is_some_and(|fam| fam.passed());
            if chain.is_ok() {
                prop_assert!(connected && in_sight, "chain {:?}:\n{}", chain, report.table());
                prop_assert!(report.passed(), "{}", report.table());
            }
            if !connected {
                prop_assert!(chain.is_err());
            }
        }
    }
}

#[test]
fn the_cases_cover_both_verdicts_and_several_reasons() {
    // the property above means little unless its cases are valid and invalid, for many reasons
    let (mut valid, mut reasons) = (0, std::collections::BTreeSet::new());
    for seed in 0..200 {
        let (s, start, usv_u, auv_u) = case(seed, 2);
        let l = Limits::of(&s);
        let auv = AuvModel::new(&s.auv, s.horizon.dt).unwrap();
        let usv1 = [
            start.usv[0] + 100.0 * usv_u[0],
            start.usv[1] + 100.0 * usv_u[1],
        ];
        let mut all = validity::usv_step(&l, floor(), start.usv, usv1);
        for (a, u) in start.auvs.iter().zip(&auv_u) {
            let (p, v) = auv.step(a.position, a.velocity, *u);
            all = all
                .and_then(|_| validity::auv_waypoint(&l, floor(), 1, a.velocity, p, v, usv1))
                .and_then(|_| validity::auv_segment(&l, floor(), a.position, p));
        }
        match all {
            Ok(()) => valid += 1,
            Err(r) => {
                reasons.insert(r);
            }
        }
    }
    assert!(valid > 20, "{valid} valid cases of 200: {reasons:?}");
    for r in [
        Reject::Speed,
        Reject::Heading,
        Reject::Floor,
        Reject::Surface,
    ] {
        assert!(
            reasons.contains(&r),
            "no case rejected by {r:?}: {reasons:?}"
        );
    }
}

#[test]
fn a_drawn_step_is_the_model_under_its_input() {
    let s = Scenario::default();
    let l = Limits::of(&s);
    let auv = AuvModel::new(&s.auv, s.horizon.dt).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let (p0, v0) = ([0.0, 0.0, -40.0], [1.0, 0.5, 0.0]);
    let mut drawn = 0;
    for _ in 0..500 {
        let Ok(st) = draw::auv_step(&mut rng, &l, &auv, floor(), p0, v0) else {
            continue;
        };
        drawn += 1;
        let (p, v) = auv.step(p0, v0, st.u);
        assert_eq!((p, v), (st.p, st.v));
        // every drawn step is within the speed, heading and depth limits by construction
        let ok = validity::auv_waypoint(&l, floor(), 1, v0, st.p, st.v, [0.0, 0.0]);
        assert!(matches!(ok, Ok(()) | Err(Reject::MaxRange)), "{ok:?}");
        let z = floor().elevation(st.p[0], st.p[1]).unwrap();
        assert!(st.p[2] - z >= l.floor_clearance && st.p[2] <= -l.surface_clearance);
        // and the input recovers the velocity it was drawn for
        let u = draw::input_for(&auv, v0, st.v);
        for i in 0..3 {
            assert!((u[i] - st.u[i]).abs() < 1e-9);
        }
    }
    assert!(drawn > 400, "{drawn} of 500 draws had a depth to go to");
}

#[test]
fn find_chain_needs_the_nearest_auv_in_sight_and_a_path_in_range() {
    let s = Scenario::default();
    let l = Limits::of(&s);
    let f = floor();
    // three AUVs in a line west of the USV, 100 m apart: a chain 0–1–2
    let auvs = [
        [-60.0, 0.0, -40.0],
        [-160.0, 0.0, -40.0],
        [-260.0, 0.0, -40.0],
    ];
    let chain = validity::find_chain(&l, f, [0.0, 0.0], &auvs).unwrap();
    assert!(
        chain == vec![0, 1, 2] || chain == vec![2, 1, 0],
        "{chain:?}"
    );
    assert_eq!(validity::chain_edges(&chain).len(), 2);
    // the last one 200 m on: no path in range
    let far = [
        [-60.0, 0.0, -40.0],
        [-160.0, 0.0, -40.0],
        [-360.0, 0.0, -40.0],
    ];
    assert_eq!(
        validity::find_chain(&l, f, [0.0, 0.0], &far),
        Err(Reject::LinkRange)
    );
    // the nearest AUV out of the USV's range
    let deep = [[-200.0, 0.0, -40.0]];
    assert_eq!(
        validity::find_chain(&l, f, [0.0, 0.0], &deep),
        Err(Reject::LinkRange)
    );
    // a link across the NODATA block is an obstacle (110 m, within ρ·d_s = 120 m)
    let across = [[260.0, 0.0, -40.0], [370.0, 0.0, -40.0]];
    assert_eq!(
        validity::link(&l, f, across[0], across[1]),
        Err(Reject::Obstacle)
    );
    // and one into the floor has no line of sight
    let low = [[0.0, -500.0, -120.0], [120.0, -500.0, -120.0]];
    assert_eq!(
        validity::link(&l, f, low[0], low[1]),
        Err(Reject::LineOfSight)
    );
}
