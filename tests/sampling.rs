//! The sampling baselines: the RRT-like planner of the paper's Section V (`shoal plan --method
//! rrt-like`) and another planner's waypoints (`shoal plan --waypoints`), checked by the same
//! checker as the MPC's plans.

mod common;
use common::shoal;

use shoal::mission::FloorSource;
use shoal::sampling::waypoints::{self, WaypointsFile, WaypointsWindow, WAYPOINTS_FORMAT};
use shoal::scenario::{self, Scenario};
use shoal::{check, PlanError, Planner, Provenance, Seafloor};

/// The default scenario with `sets`, for a vehicle without the envelope (no depth rating to
/// speak of, any flight-path angle, no cruise floor): the sampling baseline, the paper's,
/// does not plan within it, and the comparisons hold both planners to the same rules.
fn scenario_with(sets: &[&str]) -> Scenario {
    let sets: Vec<String> = NO_ENVELOPE
        .iter()
        .chain(sets)
        .map(|s| s.to_string())
        .collect();
    scenario::default_with(&sets).expect("valid overrides")
}

/// The overrides that take the vehicle's envelope away: the paper's vehicle (no depth rating,
/// no angle limit, no cruise floor, no separation), in still water (the sampler and a replayed
/// plan have no current), with links up to d_s.
const NO_ENVELOPE: [&str; 6] = [
    "auv.max_depth=1000",
    "auv.max_flight_path_angle=1.57",
    "auv.min_speed=0",
    "auv.min_separation=0",
    "current.velocity=[0.0, 0.0]",
    "acoustic.link_margin=1",
];

fn floor_of(s: &Scenario) -> Seafloor {
    Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap()
}

fn rrt_like(s: &Scenario, floor: &Seafloor) -> Result<shoal::Plan, PlanError> {
    shoal::sampling::plan(s, floor, &Provenance::in_memory(s), &mut |_| {})
}

#[test]
fn rrt_like_plans_pass_the_checker_for_one_three_and_five_auvs() {
    for n in [1, 3, 5] {
        let s = scenario_with(&[&format!("team.auvs={n}")]);
        let floor = floor_of(&s);
        let plan = rrt_like(&s, &floor).unwrap();
        let report = check(&plan, &floor);
        assert!(report.passed(), "N = {n}:\n{}", report.table());
        assert_eq!(plan.method, "rrt-like");
        let w = &plan.windows[0];
        assert!(w.step1.sampled() && w.final_.sampled());
        let sampling = w.sampling.as_ref().unwrap();
        assert_eq!(sampling.steps.len(), s.horizon.steps);
        assert!(sampling.drawn >= sampling.kept && sampling.kept >= s.horizon.steps as u64);
        assert!(sampling
            .steps
            .iter()
            .all(|st| st.kept >= 1 && st.kept <= s.sampling.tree_budget as u64));
        // the chain held at every step, by construction
        assert_eq!(plan.metrics.connected_fraction, 1.0);
        assert_eq!(plan.metrics.chain_fraction, 1.0);
        assert_eq!(plan.unconverged_stages(), 0);
    }
}

#[test]
fn the_same_seed_gives_the_same_rrt_like_plan() {
    let s = scenario_with(&["team.auvs=3"]);
    let floor = floor_of(&s);
    let (a, b) = (rrt_like(&s, &floor).unwrap(), rrt_like(&s, &floor).unwrap());
    assert_eq!(a.windows[0].final_.auvs, b.windows[0].final_.auvs);
    assert_eq!(a.windows[0].final_.usv, b.windows[0].final_.usv);
    assert_eq!(a.windows[0].graph.a2a, b.windows[0].graph.a2a);
    // and another seed another plan
    let s2 = scenario_with(&["team.auvs=3", "seed=2"]);
    let c = rrt_like(&s2, &floor_of(&s2)).unwrap();
    assert_ne!(a.windows[0].final_.usv, c.windows[0].final_.usv);
}

#[test]
fn rrt_like_windows_follow_one_another() {
    let s = scenario_with(&["team.auvs=2", "windows=2", "horizon.steps=10"]);
    let floor = floor_of(&s);
    let plan = rrt_like(&s, &floor).unwrap();
    let report = check(&plan, &floor);
    assert!(report.passed(), "{}", report.table());
    assert_eq!(plan.windows.len(), 2);
}

#[test]
fn a_tree_that_finds_nothing_names_the_step_and_the_constraint() {
    // one draw per vehicle: five AUVs cannot keep a chain of links in range
    let s = scenario_with(&["sampling.attempts=1", "sampling.samples=1"]);
    let err = rrt_like(&s, &floor_of(&s)).unwrap_err();
    let PlanError::NoValidTree { k, drawn, .. } = &err else {
        panic!("{err}");
    };
    assert!(*k >= 1 && *k <= s.horizon.steps && *drawn >= 1);
    let text = err.to_string();
    assert!(text.contains(&format!("step {k}")), "{text}");
    assert!(
        text.contains("chain link within") || text.contains("C1_13") || text.contains("C2_2"),
        "{text}"
    );
    assert!(text.contains("sampling.attempts"), "{text}");
}

/// The final paths of an MPC plan as a waypoints file.
fn waypoints_of(plan: &shoal::Plan) -> WaypointsFile {
    WaypointsFile {
        format: WAYPOINTS_FORMAT.into(),
        method: "mpc-replayed".into(),
        seed: Some(plan.scenario.seed),
        solve_time_s: 1.0,
        notes: "the MPC's own paths".into(),
        windows: plan
            .windows
            .iter()
            .map(|w| WaypointsWindow {
                usv: w.final_.usv.position.clone(),
                auvs: w.final_.auvs.iter().map(|a| a.position.clone()).collect(),
                samples_drawn: 0,
                samples_kept: 0,
                solve_time_s: 1.0,
            })
            .collect(),
    }
}

#[test]
fn the_mpc_plan_as_waypoints_checks_and_keeps_its_paths() {
    let s = scenario_with(&["team.auvs=3"]);
    let floor = floor_of(&s);
    let mpc = Planner::new(&s, &floor).run().unwrap();
    let file = waypoints_of(&mpc);
    let plan = waypoints::plan(&s, &floor, &Provenance::in_memory(&s), &file, "mpc.json").unwrap();
    let report = check(&plan, &floor);
    assert!(report.passed(), "{}", report.table());
    assert_eq!(plan.method, "mpc-replayed");
    let (a, b) = (&mpc.windows[0].final_, &plan.windows[0].final_);
    for (pa, pb) in a.auvs.iter().zip(&b.auvs) {
        for (x, y) in pa.position.iter().zip(&pb.position) {
            for i in 0..3 {
                assert!((x[i] - y[i]).abs() < 1e-6, "{x:?} vs {y:?}");
            }
        }
        for (x, y) in pa.input.iter().zip(&pb.input) {
            for i in 0..3 {
                assert!((x[i] - y[i]).abs() < 1e-8, "{x:?} vs {y:?}");
            }
        }
    }
    let (ea, eb) = (a.objective.energy, b.objective.energy);
    assert!((ea - eb).abs() <= 1e-6 * ea, "{ea} vs {eb}");
}

#[test]
fn waypoints_that_do_not_fit_are_refused_naming_the_field() {
    let s = scenario_with(&["team.auvs=2", "horizon.steps=4"]);
    let floor = floor_of(&s);
    let prov = Provenance {
        seafloor: FloorSource::synthetic(),
        ..Provenance::in_memory(&s)
    };
    let mpc = Planner::new(&s, &floor).run().unwrap();
    let mut file = waypoints_of(&mpc);
    file.windows[0].auvs[1].pop();
    let err = waypoints::plan(&s, &floor, &prov, &file, "w.json").unwrap_err();
    assert!(
        err.to_string()
            .contains("w.json: windows[0].auvs[1]: 4 waypoints for K + 1 = 5"),
        "{err}"
    );
    let mut file = waypoints_of(&mpc);
    file.windows[0].usv[0][0] += 1.0;
    let err = waypoints::plan(&s, &floor, &prov, &file, "w.json").unwrap_err();
    assert!(err.to_string().contains("windows[0].usv[0]"), "{err}");
    // a file that is not one
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("w.json");
    let mut bad = waypoints_of(&mpc);
    bad.method = "mpc".into();
    std::fs::write(&path, serde_json::to_string(&bad).unwrap()).unwrap();
    let err = waypoints::read(&path).unwrap_err().to_string();
    assert!(err.contains("w.json") && err.contains("method"), "{err}");
    bad.format = "shoal-waypoints/0".into();
    std::fs::write(&path, serde_json::to_string(&bad).unwrap()).unwrap();
    let err = waypoints::read(&path).unwrap_err().to_string();
    assert!(err.contains("shoal-waypoints/1"), "{err}");
}

/// Regression: a waypoints file holding 1e308 planned, then failed to read its own plan back
/// ("…/.shoal-staging-…/plan.json is not a shoal plan": a file already deleted). Waypoints
/// that cannot be flown are refused up front, naming the file, the vehicle and the index.
#[test]
fn regression_waypoints_off_the_floor_are_refused_naming_file_vehicle_and_index() {
    let sets = ["team.auvs=1", "horizon.steps=2"];
    let s = scenario_with(&sets);
    let floor = floor_of(&s);
    let prov = Provenance::in_memory(&s);
    let mpc = Planner::new(&s, &floor).run().unwrap();
    let refused = |edit: &dyn Fn(&mut WaypointsFile)| {
        let mut file = waypoints_of(&mpc);
        edit(&mut file);
        waypoints::plan(&s, &floor, &prov, &file, "w.json")
            .unwrap_err()
            .to_string()
    };
    let e = refused(&|f| f.windows[0].auvs[0][2][0] = 1e308);
    assert!(
        e.starts_with("w.json: windows[0].auvs[0][2]: AUV 0's waypoint k = 2, [1e308, ")
            && e.contains("outside the seafloor grid, which covers x from"),
        "{e}"
    );
    let e = refused(&|f| f.windows[0].auvs[0][1][2] = f64::NAN);
    assert!(
        e.starts_with("w.json: windows[0].auvs[0][1]: AUV 0's waypoint k = 1")
            && e.contains("not finite"),
        "{e}"
    );
    let e = refused(&|f| f.windows[0].auvs[0][1][2] = -1e7);
    assert!(
        e.contains("z = -10000000.0 m is beyond any floor; allowed is |z| ≤"),
        "{e}"
    );
    let e = refused(&|f| f.windows[0].usv[2][1] = -1e9);
    assert!(
        e.starts_with("w.json: windows[0].usv[2]: the USV's waypoint k = 2")
            && e.contains("outside the seafloor grid"),
        "{e}"
    );

    // the command line: exit 2, the file named, no staging file, nothing written
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("far.json");
    let mut file = waypoints_of(&mpc);
    file.windows[0].auvs[0][2][0] = 1e308;
    std::fs::write(&path, serde_json::to_string(&file).unwrap()).unwrap();
    let out = dir.path().join("out");
    let (code, _, stderr) = common::run(
        shoal()
            .args([
                "plan",
                "--no-plot",
                "--set",
                sets[0],
                "--set",
                sets[1],
                "--waypoints",
            ])
            .arg(&path)
            .arg("-o")
            .arg(&out),
    );
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("far.json: windows[0].auvs[0][2]: AUV 0's waypoint k = 2"),
        "{stderr}"
    );
    assert!(!stderr.contains("staging"), "{stderr}");
    assert!(!out.join("plan.json").exists());
}

#[test]
fn cli_rrt_like_writes_a_plan_that_checks() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let (code, stdout, stderr) = common::run(shoal().args([
        "plan",
        "--method",
        "rrt-like",
        "--set",
        "team.auvs=2",
        "--set",
        NO_ENVELOPE[0],
        "--set",
        NO_ENVELOPE[1],
        "--set",
        NO_ENVELOPE[2],
        "--no-plot",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(stderr.contains("valid team samples"), "{stderr}");
    let plan = shoal::output::read_plan(&out.join("plan.json")).unwrap();
    assert_eq!(plan.method, "rrt-like");
    let (code, stdout, _) =
        common::run(shoal().args(["check", out.join("plan.json").to_str().unwrap()]));
    assert_eq!(code, 0, "{stdout}");
    // a waypoints file that is not there: the file named, nothing written
    let (code, _, stderr) = common::run(shoal().args([
        "plan",
        "--waypoints",
        dir.path().join("none.json").to_str().unwrap(),
        "-o",
        dir.path().join("w").to_str().unwrap(),
    ]));
    assert_ne!(code, 0);
    assert!(stderr.contains("none.json"), "{stderr}");
    assert!(!dir.path().join("w").join("plan.json").exists());
}

#[test]
fn compare_runs_both_planners_on_the_same_scenarios_and_the_mpc_wins_p2() {
    let study = shoal::compare::Study {
        bases: vec![shoal::compare::Base {
            name: "default".into(),
            scenario: scenario_with(&["horizon.steps=8"]),
            dir: ".".into(),
        }],
        auvs: vec![1, 2],
        seeds: vec![1],
        ..shoal::compare::Study::default()
    };
    let mut seen = 0;
    let rows = shoal::compare::run(&study, &mut |i, planned| {
        assert_eq!(i, seen);
        seen += 1;
        assert!(planned.plan.is_some(), "{:?}", planned.row);
    })
    .unwrap();
    assert_eq!(rows.len(), 4);
    for pair in rows.chunks(2) {
        let (mpc, rrt) = (&pair[0], &pair[1]);
        assert_eq!(
            (mpc.method.as_str(), rrt.method.as_str()),
            ("mpc", "rrt-like")
        );
        assert_eq!((mpc.auvs, mpc.seed), (rrt.auvs, rrt.seed));
        for r in pair {
            assert_eq!(r.status, "passed", "{r:?}");
            assert!(r.wall_s > 0.0 && r.p2_objective.is_finite() && r.energy > 0.0);
            assert!(r.margin_floor_m >= 0.0 && r.margin_c1_6_m >= 0.0, "{r:?}");
        }
        assert_eq!(mpc.samples_drawn, 0);
        assert!(rrt.samples_drawn > rrt.samples_kept && rrt.samples_kept > 0);
        // both minimise P2's objective; the MPC's optimum is lower than the tree's best leaf
        assert!(mpc.p2_objective < rrt.p2_objective, "{mpc:?}\n{rrt:?}");
    }
    let groups = shoal::compare::summary(&rows);
    assert_eq!(groups.len(), 4);
    assert!(groups.iter().all(|g| g.runs == 1 && g.passed == 1));
}

#[test]
fn cli_compare_writes_the_table_and_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cmp");
    let paper: Vec<String> = NO_ENVELOPE.iter().map(|s| format!("--set={s}")).collect();
    let (code, stdout, stderr) = common::run(shoal().arg("compare").args(&paper).args([
        "--auvs",
        "1",
        "--seeds",
        "1-2",
        "--set",
        "horizon.steps=6",
        "--keep-plans",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    assert!(
        stderr.contains("[4/4] default rrt-like N = 1 seed 2: passed"),
        "{stderr}"
    );
    let csv = std::fs::read_to_string(out.join("runs.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 5, "{csv}");
    assert!(lines[0].starts_with("scenario,method,auvs,seed,status,error,wall_s,p2_objective"));
    assert!(std::fs::read_to_string(out.join("summary.md"))
        .unwrap()
        .contains("| default | rrt-like | 1 | 2 / 2 / 2 |"));
    let kept = shoal::output::read_plan(&out.join("plans/default-rrt-like-n1-s2.json")).unwrap();
    assert_eq!((kept.method.as_str(), kept.scenario.seed), ("rrt-like", 2));
    // a bad seed list is an error naming the flag
    let (code, _, stderr) =
        common::run(shoal().args(["compare", "--seeds", "5-1", "-o", out.to_str().unwrap()]));
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--seeds 5-1: the range runs backwards"),
        "{stderr}"
    );
}

#[test]
fn compare_adds_a_row_for_each_waypoints_file_timed_by_its_planner() {
    let s = scenario_with(&["horizon.steps=6", "team.auvs=2", "seed=3"]);
    let floor = floor_of(&s);
    let mpc = Planner::new(&s, &floor).run().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let name = shoal::compare::waypoints_name("default", 2, 3);
    std::fs::write(
        dir.path().join(name),
        serde_json::to_string(&waypoints_of(&mpc)).unwrap(),
    )
    .unwrap();
    let study = shoal::compare::Study {
        bases: vec![shoal::compare::Base {
            name: "default".into(),
            scenario: scenario_with(&["horizon.steps=6"]),
            dir: ".".into(),
        }],
        methods: vec![shoal::compare::Method::Mpc],
        auvs: vec![1, 2],
        seeds: vec![3],
        waypoints: Some(dir.path().to_path_buf()),
    };
    assert_eq!(study.runs(), 3);
    let rows = shoal::compare::run(&study, &mut |_, _| {}).unwrap();
    assert_eq!(rows.len(), 3);
    let replayed = &rows[2];
    assert_eq!(
        (replayed.method.as_str(), replayed.auvs),
        ("mpc-replayed", 2)
    );
    assert_eq!(replayed.status, "passed", "{replayed:?}");
    assert_eq!(replayed.wall_s, 1.0);
    // the MPC's own paths, replayed: the same energy as the MPC's row
    assert!((replayed.energy - rows[1].energy).abs() <= 1e-6 * rows[1].energy);
}

#[test]
fn a_sampled_plan_is_drawn_viewed_and_exported_like_any_plan() {
    let s = scenario_with(&["team.auvs=2", "horizon.steps=8"]);
    let floor = floor_of(&s);
    let plan = rrt_like(&s, &floor).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let figures = shoal::figures::write_all(&plan, &floor, &dir.path().join("figures")).unwrap();
    assert!(
        figures.len() >= 2 * shoal::figures::FIGURES.len(),
        "{figures:?}"
    );
    // the path panels name the sampled paths, not the MPC's steps
    let svg = std::fs::read_to_string(dir.path().join("figures/final-top.svg")).unwrap();
    assert!(svg.contains("Sampled paths (rrt-like), top view"));
    assert!(!svg.contains("Step 3, P5"));
    let csv = dir.path().join("positions.csv");
    let (rows, _) = shoal::positions::write_csv(&plan, &csv).unwrap();
    assert_eq!(rows, 3 * (s.horizon.steps + 1));
    let html = shoal::viewer::render_html(&plan, &floor).unwrap();
    assert!(html.len() > 10_000);
}
