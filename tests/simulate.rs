//! `shoal simulate`: flying the default plan, measuring and estimating it.

use shoal::sim::policy::Policy;
use shoal::sim::record::{EstimateRecord, SimRecord};
use shoal::sim::{run, simulate, SimError};
use shoal::{Planner, Scenario, Seafloor};
use std::sync::OnceLock;

/// The default scenario's plan and floor, made once for every test.
fn default_plan() -> &'static (shoal::Plan, Seafloor) {
    static PLAN: OnceLock<(shoal::Plan, Seafloor)> = OnceLock::new();
    PLAN.get_or_init(|| {
        let s = Scenario::default();
        let floor = Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
        let plan = Planner::new(&s, &floor).run().unwrap();
        (plan, floor)
    })
}

fn default_sim() -> &'static SimRecord {
    static SIM: OnceLock<SimRecord> = OnceLock::new();
    SIM.get_or_init(|| {
        let (plan, floor) = default_plan();
        simulate(plan, "plan.json", floor, 1).unwrap()
    })
}

fn estimate<'a>(
    r: &'a SimRecord,
    flown: &str,
    policy: Policy,
    estimator: &str,
) -> &'a EstimateRecord {
    r.estimates
        .iter()
        .find(|e| e.flown == flown && e.policy == policy && e.estimator == estimator)
        .unwrap()
}

#[test]
fn the_default_plan_is_flown_close_to_its_waypoints_and_off_the_floor() {
    let m = &default_sim().flight.metrics;
    for (n, rms) in m.tracking_rms_m.iter().enumerate() {
        assert!(*rms < 5.0, "AUV {n} tracked its plan to {rms} m RMS");
    }
    assert_eq!(
        m.samples_below_floor, 0,
        "an executed path went through the floor"
    );
    assert_eq!(m.samples_off_grid, 0);
}

/// Regression: plans that `shoal check` passed put the simulated REMUS 100s into the floor
/// (seed 4 at N = 5: 120 samples below it), stopping mid-window or creeping at 0.6–1.1 m/s
/// where the fins lose authority, and climbing or diving at up to 90°. With the envelope
/// (the depth rating, the flight-path angle, the cruise floor) the flight stays off the floor.
#[test]
fn regression_plans_within_the_checker_flew_into_the_floor() {
    let mut s = Scenario::default();
    s.team.auvs = 5;
    s.seed = 4;
    let floor = Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    let plan = Planner::new(&s, &floor).run().unwrap();
    let m = simulate(&plan, "plan.json", &floor, 1)
        .unwrap()
        .flight
        .metrics;
    assert_eq!(m.samples_below_floor, 0, "{m:?}");
}

#[test]
fn the_same_seed_gives_the_same_simulation_byte_for_byte() {
    let (plan, floor) = default_plan();
    let again = simulate(plan, "plan.json", floor, 1).unwrap();
    assert_eq!(
        serde_json::to_vec(default_sim()).unwrap(),
        serde_json::to_vec(&again).unwrap()
    );
    let other = simulate(plan, "plan.json", floor, 2).unwrap();
    assert_ne!(default_sim().flight.depth, other.flight.depth);
    // the flight itself does not depend on the seed
    assert_eq!(default_sim().flight.executed, other.flight.executed);
}

#[test]
fn dead_reckoning_drifts_by_a_few_percent_of_the_distance_travelled() {
    let dr = estimate(default_sim(), "final", Policy::DeadReckoning, "ekf");
    let pct = dr.metrics.end_percent_of_distance;
    // a 1° compass bias alone is 1.7 % of the distance, across the track
    assert!(
        (0.3..6.0).contains(&pct),
        "dead reckoning drifted {pct} % of distance"
    );
    // and its error grows: the last epoch's is larger than the first quarter's
    let e = &dr.metrics.team_rmse_over_time_m;
    assert!(e[e.len() - 1] > e[e.len() / 4]);
}

#[test]
fn ranges_to_the_team_bound_the_error_dead_reckoning_lets_grow() {
    let r = default_sim();
    let dr = estimate(r, "final", Policy::DeadReckoning, "factor_graph");
    for policy in [Policy::A2u, Policy::Chain, Policy::AllLinks] {
        let e = estimate(r, "final", policy, "factor_graph");
        assert!(e.ranges_used > 0, "{policy:?} used no range");
        assert!(
            e.metrics.team_rmse_m < dr.metrics.team_rmse_m,
            "{policy:?}: {} m against dead reckoning's {} m",
            e.metrics.team_rmse_m,
            dr.metrics.team_rmse_m
        );
    }
    // the policies use nested sets of ranges
    let used = |p| estimate(r, "final", p, "ekf").ranges_used;
    assert!(used(Policy::Chain) <= used(Policy::AllLinks));
    assert!(used(Policy::A2u) <= used(Policy::AllLinks));
}

#[test]
fn simulate_changes_only_its_own_keys() {
    let (plan, _) = default_plan();
    let e = run::with_settings(plan, "plan.json", &["team.auvs=7".into()]).unwrap_err();
    assert!(matches!(e, SimError::NotSimKey(_)), "{e}");
    assert!(e.to_string().contains("team.auvs=7"), "{e}");
    let e =
        run::with_settings(plan, "plan.json", &["navigation.range_noise=-1".into()]).unwrap_err();
    assert!(e.to_string().contains("navigation.range_noise"), "{e}");
    let p = run::with_settings(plan, "plan.json", &["current.velocity=[0.3, 0]".into()]).unwrap();
    assert_eq!(p.scenario.current.velocity, [0.3, 0.0]);
}

#[test]
fn an_acoustic_cycle_that_does_not_divide_the_step_is_refused_by_name() {
    let (plan, floor) = default_plan();
    let p =
        run::with_settings(plan, "plan.json", &["navigation.acoustic_period=30".into()]).unwrap();
    let e = simulate(&p, "plan.json", floor, 1).unwrap_err();
    assert!(e.to_string().contains("navigation.acoustic_period"), "{e}");
}

#[test]
fn the_cli_writes_sim_json_and_prints_the_errors() {
    let dir = tempfile::tempdir().unwrap();
    let plan_path = dir.path().join("plan.json");
    shoal::output::write_plan(&default_plan().0, &plan_path).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_shoal"))
        .args(["simulate", plan_path.to_str().unwrap(), "--seed", "3"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("dead_reckoning"), "{stdout}");
    let r: SimRecord =
        serde_json::from_slice(&std::fs::read(dir.path().join("sim.json")).unwrap()).unwrap();
    assert_eq!(r.seed, 3);
    assert_eq!(r.format, shoal::sim::record::FORMAT);
}

#[test]
fn estimating_the_biases_keeps_dead_reckoning_consistent() {
    let (plan, floor) = default_plan();
    let nees = |estimate_biases: bool| {
        let p = run::with_settings(
            plan,
            "plan.json",
            &[format!("navigation.estimate_biases={estimate_biases}")],
        )
        .unwrap();
        let r = simulate(&p, "plan.json", floor, 1).unwrap();
        estimate(&r, "final", Policy::DeadReckoning, "factor_graph")
            .metrics
            .mean_nees
    };
    // 3 for a consistent 3-D estimate; the biases taken for noise drawn anew each cycle make
    // dead reckoning's covariance far too small over a window
    let (with, without) = (nees(true), nees(false));
    assert!(with < 10.0, "mean NEES {with} with the biases estimated");
    assert!(
        without > 3.0 * with,
        "mean NEES {without} without, {with} with"
    );
}

#[test]
fn regression_window_boundaries_used_their_measurements_twice() {
    let s = shoal::scenario::default_with(&["windows=2".into()]).unwrap();
    let floor = Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    let plan = Planner::new(&s, &floor).run().unwrap();
    let r = simulate(&plan, "plan.json", &floor, 1).unwrap();
    // the factor graph solves window by window; the epoch two windows share is measured once
    for policy in Policy::EVERY {
        assert_eq!(
            estimate(&r, "final", policy, "factor_graph").ranges_used,
            estimate(&r, "final", policy, "ekf").ranges_used,
            "{policy:?}"
        );
    }
    assert_eq!(
        estimate(&r, "final", Policy::Chain, "ekf")
            .metrics
            .window_end_rmse_m
            .len(),
        2
    );
}

#[test]
fn monte_carlo_summarises_every_estimate_over_the_runs() {
    let (plan, floor) = default_plan();
    let r = shoal::sim::monte_carlo(plan, "plan.json", floor, 5, 3).unwrap();
    let mc = r.monte_carlo.as_ref().unwrap();
    assert_eq!(mc.runs, 3);
    assert_eq!(mc.summary.len(), r.estimates.len());
    assert_eq!(
        mc.each.iter().map(|x| x.seed).collect::<Vec<_>>(),
        [5, 6, 7]
    );
    for s in &mc.summary {
        let t = s.team_rmse_m;
        assert!(t.min <= t.mean && t.mean <= t.max && t.std >= 0.0, "{s:?}");
    }
    // the record is the first run's
    assert_eq!(r.seed, 5);
}

/// Writes a uniform ESRI ASCII grid of `value` over `bounds` ([x_min, x_max, y_min, y_max])
/// widened by `pad` metres, nodes every `cell` metres; `nodata_at` marks one node NODATA.
fn current_grid(
    path: &std::path::Path,
    bounds: [f64; 4],
    pad: f64,
    cell: f64,
    value: f64,
    nodata_at: Option<(usize, usize)>,
) {
    let x0 = (bounds[0] - pad).floor();
    let y0 = (bounds[2] - pad).floor();
    let nx = ((bounds[1] + pad - x0) / cell).ceil() as usize + 1;
    let ny = ((bounds[3] + pad - y0) / cell).ceil() as usize + 1;
    let l = shoal::seafloor::Lattice {
        nx,
        ny,
        x0,
        y0,
        dx: cell,
        dy: cell,
    };
    let mut nodata = vec![false; nx * ny];
    if let Some((i, j)) = nodata_at {
        nodata[j * nx + i] = true;
    }
    Seafloor::from_nodes(l, vec![value; nx * ny], nodata)
        .unwrap()
        .write_esri_ascii(path)
        .unwrap();
}

/// The default plan with `[current]` grid files `u.asc` and `v.asc` (relative to the plan).
fn with_current_files(plan: &shoal::Plan) -> shoal::Plan {
    let mut p = plan.clone();
    p.scenario.current.file_east = Some("u.asc".into());
    p.scenario.current.file_north = Some("v.asc".into());
    p
}

#[test]
fn uniform_current_grids_fly_the_plan_as_the_uniform_current() {
    use shoal::sim::current::{mission_bounds, CURRENT_MARGIN};
    let (plan, floor) = default_plan();
    let dir = tempfile::tempdir().unwrap();
    let b = mission_bounds(plan, CURRENT_MARGIN);
    let [u, v] = plan.scenario.current.velocity;
    current_grid(&dir.path().join("u.asc"), b, 300.0, 100.0, u, None);
    current_grid(&dir.path().join("v.asc"), b, 300.0, 100.0, v, None);
    let p = with_current_files(plan);
    let plan_name = dir.path().join("plan.json").display().to_string();
    let r = simulate(&p, &plan_name, floor, 1).unwrap();
    let (a, b) = (&r.flight.executed, &default_sim().flight.executed);
    assert_eq!(a.len(), b.len());
    for (pa, pb) in a.iter().zip(b) {
        assert_eq!(pa.len(), pb.len());
        for (x, y) in pa.iter().zip(pb) {
            for k in 0..3 {
                assert!((x[k] - y[k]).abs() <= 1e-9, "{x:?} vs {y:?}");
            }
        }
    }
    // the same files, resolved against the plan's directory: from elsewhere they are missing
    let e = simulate(&p, "elsewhere/plan.json", floor, 1).unwrap_err();
    assert!(e.to_string().contains("current.file_east"), "{e}");
    assert!(e.to_string().contains("u.asc"), "{e}");
}

#[test]
fn current_grids_that_miss_the_mission_or_disagree_are_refused_by_name() {
    use shoal::sim::current::{mission_bounds, CURRENT_MARGIN};
    let (plan, floor) = default_plan();
    let dir = tempfile::tempdir().unwrap();
    let plan_name = dir.path().join("plan.json").display().to_string();
    let b = mission_bounds(plan, CURRENT_MARGIN);
    let p = with_current_files(plan);
    let (u, v) = (dir.path().join("u.asc"), dir.path().join("v.asc"));
    let err = |p: &shoal::Plan| simulate(p, &plan_name, floor, 1).unwrap_err().to_string();

    // the east grid covers only the west half of the mission
    let half = [b[0], 0.5 * (b[0] + b[1]), b[2], b[3]];
    current_grid(&u, half, 0.0, 50.0, 0.0, None);
    current_grid(&v, b, 0.0, 50.0, 0.1, None);
    let e = err(&p);
    assert!(e.contains("current.file_east"), "{e}");
    assert!(e.contains("covers"), "{e}");

    // both cover it, on different lattices
    current_grid(&u, b, 100.0, 50.0, 0.0, None);
    current_grid(&v, b, 100.0, 40.0, 0.1, None);
    let e = err(&p);
    assert!(
        e.contains("current.file_east") && e.contains("current.file_north") && e.contains("same"),
        "{e}"
    );

    // NODATA in the mission
    current_grid(&v, b, 100.0, 50.0, 0.1, Some((5, 5)));
    let e = err(&p);
    assert!(
        e.contains("current.file_north") && e.contains("NODATA"),
        "{e}"
    );

    // a speed beyond 3 m/s (the values in cm/s, say)
    current_grid(&v, b, 100.0, 50.0, 10.0, None);
    let e = err(&p);
    assert!(e.contains("3 m/s"), "{e}");

    // a file that is not there
    std::fs::remove_file(&v).unwrap();
    let e = err(&p);
    assert!(
        e.contains("current.file_north") && e.contains("v.asc"),
        "{e}"
    );
}

#[test]
fn only_one_current_grid_file_is_refused() {
    let (plan, floor) = default_plan();
    let e = run::with_settings(plan, "plan.json", &["current.file_east=\"u.asc\"".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("current.file_east") && e.contains("current.file_north"),
        "{e}"
    );
    // and straight to the simulation (a plan edited by hand)
    let mut p = plan.clone();
    p.scenario.current.file_north = Some("v.asc".into());
    let e = simulate(&p, "plan.json", floor, 1).unwrap_err().to_string();
    assert!(
        e.contains("current.file_north") && e.contains("current.file_east"),
        "{e}"
    );
    // a file that is not a grid
    let e = run::with_settings(
        plan,
        "plan.json",
        &[
            "current.file_east=\"u.txt\"".into(),
            "current.file_north=\"v.asc\"".into(),
        ],
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("current.file_east"), "{e}");
}

/// `shoal` with `args`: (exit code, stdout, stderr).
fn shoal_cli(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_shoal"))
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The default plan written into a fresh directory: (directory, plan.json's path).
fn written_plan(plan: &shoal::Plan) -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("plan.json");
    shoal::output::write_plan(plan, &path).unwrap();
    (dir, path.display().to_string())
}

#[test]
fn regression_a_tiny_simulation_step_is_refused() {
    // `--set simulation.step=1e-9` flew 4·10¹⁰ RK4 steps per AUV: a hang
    let (plan, floor) = default_plan();
    let e = run::with_settings(plan, "plan.json", &["simulation.step=1e-9".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("simulation.step = 1e-9") && e.contains("allowed from 0.001 to 0.2 s"),
        "{e}"
    );
    // a plan file whose own scenario holds it (planned before the rule, or edited by hand)
    let mut p = plan.clone();
    p.scenario.simulation.step = 1e-300;
    let e = simulate(&p, "out/plan.json", floor, 1).unwrap_err();
    assert!(matches!(e, SimError::PlanSetting { .. }), "{e}");
    let e = e.to_string();
    assert!(
        e.starts_with("out/plan.json: simulation.step = 1e-300") && e.contains("0.001"),
        "{e}"
    );
    // the sampling period sets a count too
    let e = run::with_settings(
        plan,
        "plan.json",
        &[
            "simulation.step=0.001".into(),
            "navigation.sample_period=1e-7".into(),
        ],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("navigation.sample_period = 1e-7") && e.contains("allowed from 0.01 to 10 s"),
        "{e}"
    );
    let e = run::with_settings(
        plan,
        "plan.json",
        &["navigation.acoustic_period=1e-3".into()],
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("navigation.acoustic_period") && e.contains("allowed from 1 to 3600 s"),
        "{e}"
    );
}

#[test]
fn regression_plan_refuses_a_tiny_simulation_step() {
    // `shoal plan --set simulation.step=1e-300` was accepted, and simulate then hung on its plan
    let dir = tempfile::tempdir().unwrap();
    let (code, _, err) = shoal_cli(&[
        "plan",
        "--no-plot",
        "-q",
        "-o",
        dir.path().to_str().unwrap(),
        "--set",
        "simulation.step=1e-300",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("simulation.step = 1e-300") && err.contains("allowed from 0.001 to 0.2 s"),
        "{err}"
    );
    assert!(!dir.path().join("plan.json").exists());
}

#[test]
fn regression_a_plan_lasting_years_is_refused_before_flying() {
    // a plan of a huge δ aborted on memory, allocating its samples
    let (plan, floor) = default_plan();
    let with = |dt: f64, set: &[&str]| {
        let mut p = plan.clone();
        p.scenario.horizon.dt = dt;
        let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
        run::with_settings(&p, "out/plan.json", &set).unwrap()
    };
    let e = simulate(&with(1.5e8, &[]), "out/plan.json", floor, 1).unwrap_err();
    assert!(matches!(e, SimError::TooLong { .. }), "{e}");
    let e = e.to_string();
    assert!(
        e.contains("out/plan.json lasts 3.0e9 s")
            && e.contains("simulation.step = 0.05 s")
            && e.contains("6.0e11 RK4 steps")
            && e.contains("above the 1.0e9 allowed"),
        "{e}"
    );
    // fine samples: within the steps allowed, above the samples
    let fine = ["simulation.step=0.01", "navigation.sample_period=0.01"];
    let e = simulate(&with(1000.0, &fine), "out/plan.json", floor, 1)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("navigation.sample_period = 0.01 s") && e.contains("samples"),
        "{e}"
    );
    // many acoustic epochs: above the positions the estimators may solve for
    let e = simulate(&with(1e4, &[]), "out/plan.json", floor, 1)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("navigation.acoustic_period = 10 s") && e.contains("positions"),
        "{e}"
    );
    // and runs × the positions of a run
    let e = shoal::sim::monte_carlo(plan, "out/plan.json", floor, 1, 100_000)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--runs 100000") && e.contains("at most 16583 runs"),
        "{e}"
    );
}

/// The default plan with AUV 0 pulled 400 m east at one step of its final stage: it fails the
/// check's dynamics.
fn tampered_plan() -> shoal::Plan {
    let mut p = default_plan().0.clone();
    p.windows[0].final_.auvs[0].position[5][0] += 400.0;
    p
}

#[test]
fn regression_simulate_refuses_a_plan_that_fails_its_check() {
    let (_dir, path) = written_plan(&tampered_plan());
    let (code, out, err) = shoal_cli(&["simulate", &path, "--no-plot"]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(
        err.contains(&format!("{path} fails its check (")) && err.contains("--unchecked"),
        "{err}"
    );
    assert!(!std::path::Path::new(&path)
        .with_file_name("sim.json")
        .exists());

    // flown anyway, loudly, and sim.json says so
    let (code, out, err) = shoal_cli(&["simulate", &path, "--no-plot", "--unchecked"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        err.contains("WARNING") && err.contains("fails its check"),
        "{err}"
    );
    assert!(out.contains("UNCHECKED"), "{out}");
    let sim = std::path::Path::new(&path).with_file_name("sim.json");
    let r: SimRecord = serde_json::from_slice(&std::fs::read(sim).unwrap()).unwrap();
    assert!(!r.check_failures.is_empty());
    assert!(
        r.check_failures.iter().any(|f| f.starts_with("C1_1")),
        "{:?}",
        r.check_failures
    );

    // a plan whose structure is broken is not flown even unchecked
    let (plan, floor) = default_plan();
    let mut p = plan.clone();
    p.initial.auvs.pop();
    let options = shoal::sim::Options {
        gate: shoal::sim::Gate::Unchecked,
        ..shoal::sim::Options::new(1, 1)
    };
    let e = shoal::sim::fly_plan(&p, "plan.json", floor, &options, &mut |_| {}).unwrap_err();
    assert!(matches!(e, SimError::Malformed { .. }), "{e}");
}

#[test]
fn regression_an_estimator_that_does_not_converge_is_reported_for_its_policy() {
    // with this current the factor graph of one policy did not converge, and simulate exited 2
    // writing nothing
    let (plan, floor) = default_plan();
    let p = run::with_settings(plan, "plan.json", &["current.velocity=[1.2,-0.3]".into()]).unwrap();
    let r = simulate(&p, "plan.json", floor, 1).unwrap();
    assert!(!r.failed_estimates.is_empty(), "every estimator converged");
    let f = &r.failed_estimates[0];
    assert_eq!(f.estimator, "factor_graph");
    let n = f.iterations.expect("a non-convergence");
    assert_eq!(f.brief(), format!("did not converge after {n} iterations"));
    // the other estimates are kept, ten in all with the failures
    assert_eq!(r.estimates.len() + r.failed_estimates.len(), 10);
    assert!(r
        .estimates
        .iter()
        .any(|e| e.policy == f.policy && e.estimator == "ekf" && e.flown == f.flown));
    let table = shoal::sim::summary::table(&r);
    assert!(
        table.contains(&format!(
            "{}: did not converge after {n} iterations",
            f.policy.name()
        )),
        "{table}"
    );
    // and the record is what view reads
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sim.json");
    shoal::sim::write(&r, &path).unwrap();
    let back: SimRecord = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(back.failed_estimates, r.failed_estimates);
    shoal::viewer::data::sim(&back, plan.scenario.team.auvs).unwrap();
}

#[test]
fn regression_every_sim_json_simulate_writes_is_read_by_view() {
    let (plan, floor) = default_plan();
    let auvs = plan.scenario.team.auvs;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sim.json");
    let round_trip = |r: &SimRecord| -> SimRecord {
        shoal::sim::write(r, &path).unwrap();
        let back: SimRecord = serde_json::from_slice(&std::fs::read(&path).unwrap()).unwrap();
        shoal::viewer::data::sim(&back, auvs).unwrap();
        back
    };
    // a Monte Carlo record
    let mc = shoal::sim::monte_carlo(plan, "plan.json", floor, 3, 2).unwrap();
    assert_eq!(round_trip(&mc).monte_carlo.unwrap().runs, 2);
    // the planned chain's factor graph failed: the page shows the next estimate
    let mut r = default_sim().clone();
    r.estimates
        .retain(|e| !(e.policy == Policy::Chain && e.estimator == "factor_graph"));
    let shown = shoal::viewer::data::sim(&round_trip(&r), auvs).unwrap();
    assert_eq!(shown.estimate.unwrap().estimator, "ekf");
    // every estimate failed: the executed tracks alone
    r.estimates.clear();
    assert!(shoal::viewer::data::sim(&round_trip(&r), auvs)
        .unwrap()
        .estimate
        .is_none());
    // a number JSON cannot hold is refused when written, by name, not left for view to trip on
    let mut r = default_sim().clone();
    r.estimates[0].metrics.mean_nees = f64::INFINITY;
    let e = shoal::sim::write(&r, &dir.path().join("bad.json"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("estimates[0].metrics.mean_nees") && e.contains("not a finite number"),
        "{e}"
    );
    assert!(!dir.path().join("bad.json").exists());

    // the command line: simulate, then view reads what it wrote
    let (_d, plan_path) = written_plan(plan);
    let sim = std::path::Path::new(&plan_path).with_file_name("sim.json");
    let html = sim.with_file_name("view.html");
    let (code, out, err) = shoal_cli(&["simulate", &plan_path, "--no-plot", "--runs", "2"]);
    assert_eq!(code, 0, "{out}{err}");
    let (code, out, err) = shoal_cli(&[
        "view",
        &plan_path,
        "--sim",
        sim.to_str().unwrap(),
        "-o",
        html.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
}

#[test]
fn regression_a_current_the_auvs_cannot_stem_stops_with_a_message() {
    // the flight's state turned NaN, and the first estimator then refused its odometry
    let (plan, floor) = default_plan();
    let p = run::with_settings(plan, "plan.json", &["current.velocity=[0,3]".into()]).unwrap();
    let e = simulate(&p, "plan.json", floor, 1).unwrap_err();
    assert!(matches!(e, SimError::Diverged { .. }), "{e}");
    let e = e.to_string();
    assert!(e.contains("6-DoF state") && e.contains("3.00 m/s"), "{e}");
}

#[test]
fn regression_runs_can_be_cancelled_and_keep_what_finished() {
    use std::sync::atomic::{AtomicBool, Ordering};
    let (plan, floor) = default_plan();
    let cancel = AtomicBool::new(false);
    let options = shoal::sim::Options {
        cancel: Some(&cancel),
        ..shoal::sim::Options::new(4, 5)
    };
    let mut done = Vec::new();
    let r = shoal::sim::fly_plan(plan, "plan.json", floor, &options, &mut |p| {
        if let shoal::sim::Progress::RunDone { finished, runs } = p {
            done.push((finished, runs));
            if finished == 2 {
                cancel.store(true, Ordering::Relaxed);
            }
        }
    })
    .unwrap();
    assert_eq!(done, [(1, 5), (2, 5)]);
    let i = r.incomplete.as_ref().unwrap();
    assert_eq!((i.runs_asked, i.runs_finished), (5, 2));
    let mc = r.monte_carlo.as_ref().unwrap();
    assert_eq!(mc.runs, 2);
    assert_eq!(mc.each.iter().map(|x| x.seed).collect::<Vec<_>>(), [4, 5]);
    assert!(shoal::sim::summary::table(&r).contains("INCOMPLETE (interrupted): 2 of 5 runs"));

    // stopped while flying: no run finished, nothing to record
    cancel.store(false, Ordering::Relaxed);
    let e = shoal::sim::fly_plan(plan, "plan.json", floor, &options, &mut |p| {
        if let shoal::sim::Progress::Flying(_) = p {
            cancel.store(true, Ordering::Relaxed);
        }
    })
    .unwrap_err();
    assert!(matches!(e, SimError::Interrupted), "{e}");
}

/// Ctrl-C during `shoal simulate --runs`: exit 130, and either the finished runs in sim.json,
/// marked incomplete (and readable by view), or a plain word that nothing was written.
#[cfg(unix)]
#[test]
fn regression_ctrl_c_keeps_the_finished_runs() {
    use std::io::BufRead;
    let (_d, plan_path) = written_plan(&default_plan().0);
    let sim = std::path::Path::new(&plan_path).with_file_name("sim.json");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_shoal"))
        .args(["simulate", &plan_path, "--no-plot", "--runs", "500"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // its handler is set before it prints this
    let mut err = std::io::BufReader::new(child.stderr.take().unwrap());
    let mut line = String::new();
    while !line.starts_with("simulating") {
        line.clear();
        assert!(
            err.read_line(&mut line).unwrap() > 0,
            "shoal simulate ended early"
        );
    }
    std::thread::sleep(std::time::Duration::from_secs(3));
    // SAFETY: sending a signal to our own child process
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let out = child.wait_with_output().unwrap();
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut err, &mut rest).unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(130), "{stdout}{rest}");
    if sim.exists() {
        let r: SimRecord = serde_json::from_slice(&std::fs::read(&sim).unwrap()).unwrap();
        let i = r.incomplete.expect("marked incomplete");
        assert!(i.runs_finished >= 1 && i.runs_finished < 500, "{i:?}");
        assert!(stdout.contains("INCOMPLETE"), "{stdout}");
    } else {
        assert!(rest.contains("nothing was written"), "{rest}");
    }
}
