//! End-to-end tests: plan with the library and the `shoal` binary, then verify with the
//! independent checker.

mod common;
use common::{plan_and_check, plan_scenario, shoal};

use shoal::scenario::{self, Scenario};
use shoal::PlanError;

/// `shoal plan --no-plot -o DIR` with `extra` arguments, DIR a fresh directory `name`:
/// (DIR, exit code, stdout, stderr).
fn plan_cli(name: &str, extra: &[&str]) -> (std::path::PathBuf, i32, String, String) {
    let dir = fresh_dir(name);
    let (code, out, err) = common::run(
        shoal()
            .args(["plan", "--no-plot", "-o", dir.to_str().unwrap()])
            .args(extra),
    );
    (dir, code, out, err)
}

/// An empty directory for a test's outputs.
fn fresh_dir(name: &str) -> std::path::PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A small scenario that still exercises every constraint family: 2 AUVs, 8 steps, 2 windows.
fn small(seed: u64) -> Scenario {
    scenario::default_with(&[
        format!("seed={seed}"),
        "team.auvs=2".into(),
        "horizon.steps=8".into(),
        "windows=2".into(),
    ])
    .expect("valid overrides")
}

#[test]
fn small_plans_over_several_seeds_pass_the_independent_check() {
    for seed in [1, 2, 3] {
        let (p, _) = plan_and_check(&small(seed)).expect("plan");
        assert_eq!(p.windows.len(), 2);
        // windows chain: window 1 starts where window 0's final plan ended
        let a = &p.windows[0].final_.auvs[0];
        let b = &p.windows[1].step1.auvs[0];
        assert_eq!(a.position.last(), b.position.first());
    }
}

#[test]
fn destination_objective_moves_the_usv_towards_the_destination() {
    let mut s = small(4);
    s.usv.objective = scenario::UsvObjective::Destination;
    s.usv.destination = [-2000.0, 500.0];
    let (p, _) = plan_and_check(&s).expect("plan");
    let end = *p.windows[1].final_.usv.position.last().unwrap();
    let d0 = (2000f64).hypot(500.0);
    let d1 = (end[0] + 2000.0).hypot(end[1] - 500.0);
    assert!(d1 < d0 - 100.0, "USV did not approach: {d0} → {d1}");
}

#[test]
fn an_initial_auv_beyond_sonar_range_is_refused_naming_c1_6() {
    let mut s = small(1);
    s.windows = 1;
    s.initial = Some(scenario::Initial {
        usv: [0.0, 0.0],
        auvs: vec![[10.0, 0.0, -40.0], [0.0, 400.0, -40.0]],
    });
    let err = plan_scenario(&s).map(|(p, _)| p).unwrap_err();
    let msg = err.to_string();
    assert!(matches!(err, PlanError::InvalidStart { .. }), "{msg}");
    assert!(msg.contains("AUV 1") && msg.contains("C1_6"), "{msg}");
}

#[test]
fn unstable_euler_is_refused_with_the_reason() {
    let s = scenario::default_with(&["auv.discretisation=euler".into()]).unwrap();
    let msg = plan_scenario(&s).map(|(p, _)| p).unwrap_err().to_string();
    assert!(msg.contains("unstable") && msg.contains("zoh"), "{msg}");
}

#[test]
fn cli_plans_writes_outputs_and_check_passes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let st = shoal()
        .args([
            "plan",
            "--set",
            "team.auvs=2",
            "--set",
            "horizon.steps=6",
            "-o",
        ])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    for f in ["plan.json", "usv.csv", "auv0.csv", "auv1.csv"] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    let st = shoal()
        .arg("check")
        .arg(out.join("plan.json"))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&st.stdout);
    assert!(st.status.success(), "{text}");
    // the plan echoes the resolved scenario with its seed
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("plan.json")).unwrap()).unwrap();
    assert_eq!(json["format"], "shoal-plan/5");
    assert_eq!(json["scenario"]["seed"], 1);
    assert_eq!(json["scenario"]["team"]["auvs"], 2);
}

#[test]
fn cli_init_writes_a_scenario_that_plans_and_bad_keys_name_file_line_and_key() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("mission.toml");
    assert!(shoal().arg("init").arg(&f).status().unwrap().success());
    let text = std::fs::read_to_string(&f).unwrap();
    assert_eq!(
        scenario::from_toml_str(&text, "x", &[]).unwrap(),
        Scenario::default()
    );
    std::fs::write(&f, "seed = 1\n[acoustic]\nsonar_range = -5\n").unwrap();
    let st = shoal().arg("plan").arg(&f).output().unwrap();
    let err = String::from_utf8_lossy(&st.stderr);
    assert_eq!(st.status.code(), Some(2));
    assert!(
        err.contains("mission.toml") && err.contains("line 3"),
        "{err}"
    );
    assert!(err.contains("acoustic.sonar_range"), "{err}");
}

#[test]
fn cli_seafloor_export_round_trips_through_the_ascii_reader() {
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("floor.asc");
    let st = shoal()
        .args(["seafloor", "export", "-o"])
        .arg(&f)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    let read = shoal::seafloor::Seafloor::read_esri_ascii(&f).unwrap();
    let s = Scenario::default();
    let made = shoal::seafloor::Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    assert_eq!(read.fingerprint(), made.fingerprint());
}

/// Regression: the error chain repeated the OS message ("No such file or directory (os error
/// 2): No such file or directory (os error 2)"), since the library's messages quote their
/// source and also name it as the source.
#[test]
fn regression_missing_file_error_said_its_cause_twice() {
    let st = shoal()
        .args(["seafloor", "info", "/nonexistent/floor.tif"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&st.stderr);
    assert_eq!(st.status.code(), Some(2));
    assert_eq!(err.matches("os error 2").count(), 1, "{err}");
    assert!(err.contains("/nonexistent/floor.tif"), "{err}");
}

/// Regression: `shoal seafloor info FILE | head -1` panicked in println! once `head` had
/// closed the pipe; it now ends quietly, as other command-line filters do.
#[cfg(unix)]
#[test]
fn regression_closed_stdout_panicked() {
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let f = dir.path().join("floor.asc");
    assert!(shoal()
        .args(["seafloor", "export", "-o"])
        .arg(&f)
        .output()
        .unwrap()
        .status
        .success());
    let mut child = shoal()
        .args(["seafloor", "info"])
        .arg(&f)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take()); // the reader goes away before shoal writes
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!err.contains("panicked"), "{err}");
}

/// Regression (issue 13): `shoal plan --set 'seafloor.synthetic.size=[5000.0, 5000.0]'` passed
/// its in-memory check and wrote a plan that `shoal check` could not read ("invalid type:
/// null, expected f64"): the first guess ran off the grid, the SCP's first merit was infinite,
/// and serde wrote it as null. The measure is finite now, and `shoal plan` checks the file it
/// wrote, read back.
#[test]
fn regression_a_plan_near_the_grid_edge_reads_back_and_checks() {
    let (dir, code, out, err) = plan_cli(
        "grid_edge",
        &["--set", "seafloor.synthetic.size=[5000.0, 5000.0]"],
    );
    assert_eq!(code, 0, "{out}\n{err}");
    let text = std::fs::read_to_string(dir.join("plan.json")).unwrap();
    assert!(!text.contains("\"merit_before\": null") && !text.contains("\"ratio\": null"));
    let (code, out, err) =
        common::run(shoal().args(["check", dir.join("plan.json").to_str().unwrap()]));
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(out.contains("every constraint holds"), "{out}");
}

/// Regression (issue 13): `--set scp.max_iterations=1` printed a clean PASS for a plan that is
/// feasible but far from converged. The plan now records a warning per unconverged stage,
/// `shoal plan` prints them, and the check's last line says the plan is unconverged.
#[test]
fn regression_an_unconverged_plan_says_so() {
    let mut s = small(1);
    s.windows = 1;
    s.scp.max_iterations = 1;
    // the vehicle without its envelope: with the cruise floor the team cannot barely move,
    // and within the flight-path angle one SCP iteration already takes it past a tenth of its
    // reach
    s.auv.min_speed = 0.0;
    s.auv.max_flight_path_angle = shoal::scenario::NO_ANGLE_LIMIT;
    // OF1_8 per m² (the paper's weighting): with weights.w8_scaling = "energy" this window of
    // 8 steps weighs it 2.5× and goes past a tenth of its reach in one SCP iteration
    s.weights.w8_scaling = shoal::scenario::W8Scaling::None;
    let (p, _) = plan_and_check(&s).expect("plan");
    assert_eq!(p.windows[0].step1.status, "max_iterations");
    // (and, without the angle limit, that the team barely moves in one iteration)
    let stopped: Vec<&String> = p
        .warnings
        .iter()
        .filter(|w| w.contains("stopped at scp.max_iterations = 1"))
        .collect();
    assert_eq!(stopped.len(), 2, "{:?}", p.warnings);
    assert!(stopped[0].starts_with("window 0: step 1 (P2) stopped at scp.max_iterations = 1"));
    // and a team that barely moves in an unconverged window is put down to the SCP, not to the
    // weights (with the cruise floor the team moves in one SCP iteration here: its USV is held
    // at its start to see the warning)
    let mut still = p.windows.clone();
    let start = still[0].final_.usv.position[0];
    still[0].final_.usv.position.fill(start);
    let floor = shoal::Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    let warnings = shoal::advice::warnings(&still, &s, &floor);
    assert!(
        warnings.iter().any(|w| w.contains("the team barely moves")
            && w.contains("the window's SCP did not converge")),
        "{warnings:?}"
    );
    // (2: with the REMUS envelope one SCP iteration leaves two AUVs of the default plan
    // closer than their separation, and the plan says it stopped at its iteration limit)
    let (dir, code, out, err) = plan_cli("unconverged", &["--set", "scp.max_iterations=2"]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(
        err.contains("warning: window 0: step 3 (P5) stopped at scp.max_iterations"),
        "{err}"
    );
    assert!(
        out.contains("but the plan is unconverged in 2 stage(s)"),
        "{out}"
    );
    let (code, out, _) =
        common::run(shoal().args(["check", dir.join("plan.json").to_str().unwrap()]));
    assert_eq!(code, 0);
    assert!(out.contains("but 2 stage(s) did not converge"), "{out}");
}

/// Regression: an interrupted `shoal plan` left hidden temporary files (up to
/// 840 KB) and a mixed set (a new plan.json beside an earlier run's CSVs). The set is now
/// staged inside the output directory and moved into place after its check; Ctrl-C removes the
/// staging directory and leaves the earlier set as it was.
#[cfg(unix)]
#[test]
fn regression_an_interrupted_plan_leaves_the_earlier_outputs_untouched() {
    let dir = fresh_dir("interrupted");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("plan.json"), "earlier").unwrap();
    // its handler is set before it prints this
    let done = common::interrupt_when(
        shoal()
            .args(["plan", "--no-plot", "-o", dir.to_str().unwrap()])
            .args(["--set", "team.auvs=20", "--set", "horizon.steps=40"]),
        |line| line.starts_with("planning"),
        std::time::Duration::ZERO,
    );
    let rest = done.stderr;
    assert_eq!(done.code, Some(130), "{rest}");
    assert!(rest.contains("interrupted: nothing was written"), "{rest}");
    let left: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, ["plan.json"], "only the earlier file is left");
    assert_eq!(
        std::fs::read_to_string(dir.join("plan.json")).unwrap(),
        "earlier"
    );
}

/// Regression: Ctrl-C in a multi-window `shoal plan` dropped the windows already planned. A
/// first Ctrl-C once a window is done now lets the window under way end and writes the windows
/// planned by then: a whole plan, recorded as such, that passes its check (exit 130).
#[cfg(unix)]
#[test]
fn regression_ctrl_c_in_a_multi_window_plan_dropped_the_finished_windows() {
    let dir = fresh_dir("interrupted-windows");
    let done = common::interrupt_when(
        shoal()
            .args(["plan", "--no-plot", "-o", dir.to_str().unwrap()])
            .args([
                "--set",
                "team.auvs=2",
                "--set",
                "horizon.steps=6",
                "--set",
                "windows=8",
            ]),
        |line| line.contains("window 0: step 3"),
        std::time::Duration::ZERO,
    );
    let rest = done.stderr;
    assert_eq!(done.code, Some(130), "{rest}");
    assert!(rest.contains("interrupt: "), "{rest}");
    assert!(rest.contains("windows planned before Ctrl-C"), "{rest}");
    let plan = shoal::output::read_plan(&dir.join("plan.json")).unwrap();
    let done = plan.windows.len();
    assert!((1..8).contains(&done), "{done} windows");
    assert_eq!(plan.scenario.windows, done);
    assert!(
        plan.warnings[0].starts_with("interrupted:"),
        "{:?}",
        plan.warnings
    );
    let (code, out, err) =
        common::run(shoal().args(["check", dir.join("plan.json").to_str().unwrap()]));
    assert_eq!(code, 0, "{out}{err}");
}

/// Issue 13: `--json` prints one JSON summary on stdout for scripts (nothing else there), and
/// `--quiet` prints nothing on stdout and no progress.
#[test]
fn plan_json_and_quiet() {
    let small = ["--set", "team.auvs=2", "--set", "horizon.steps=6"];
    let (_, code, out, err) = plan_cli("json_quiet", &[&small[..], &["--json"]].concat());
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).expect("stdout is one JSON document");
    assert_eq!(v["check"]["passed"], true);
    assert_eq!(v["seed"], 1);
    let files: Vec<&str> = v["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert_eq!(files, ["auv0.csv", "auv1.csv", "plan.json", "usv.csv"]);
    assert_eq!(v["windows"][0]["step3"]["status"], "converged");
    assert!(v["metrics"]["explored_area_km2"].as_f64().unwrap() > 0.0);
    let (_, code, out, err) = plan_cli("json_quiet", &[&small[..], &["--quiet"]].concat());
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "");
    assert!(!err.contains("window 0"), "{err}");
}

/// Regression (issue 13): an AUV starting 35 m below the floor was said to be "less than ε
/// above" it.
#[test]
fn regression_an_auv_below_the_floor_is_said_to_be_below_it() {
    let mut s = small(1);
    s.windows = 1;
    s.initial = Some(scenario::Initial {
        usv: [0.0, 0.0],
        auvs: vec![[10.0, 0.0, -40.0], [0.0, 20.0, -140.0]],
    });
    let msg = plan_scenario(&s).map(|(p, _)| p).unwrap_err().to_string();
    assert!(
        msg.contains("AUV 1 at z = -140.00 m is") && msg.contains("m below the floor"),
        "{msg}"
    );
    assert!(!msg.contains("less than"), "{msg}");
}

/// Regression (issue 13): a plan of another format was refused without saying what to do.
#[test]
fn regression_a_plan_of_another_format_says_to_plan_again() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("old_format");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("plan.json");
    std::fs::write(&path, r#"{"format": "shoal-plan/4"}"#).unwrap();
    let msg = shoal::output::read_plan(&path).unwrap_err().to_string();
    assert!(
        msg.contains("\"shoal-plan/4\" is not \"shoal-plan/5\""),
        "{msg}"
    );
    assert!(msg.contains("plan the scenario again"), "{msg}");
}

/// Regression (issue 13): an error in the `--seafloor X` given named `--set seafloor.file=X`,
/// which the user never wrote.
#[test]
fn regression_a_seafloor_flag_error_names_the_flag() {
    let (_, code, _, err) = plan_cli("seafloor_flag", &["--seafloor", "floor.txt"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("error: --seafloor floor.txt: seafloor.file"),
        "{err}"
    );
    assert!(!err.contains("--set"), "{err}");
}

/// Regression: `shoal compare --seeds 1-1000000000` made the billion seeds in memory (7.75 GB)
/// and aborted. The seeds of a range are counted from its ends, and a comparison of more than
/// 1 000 000 runs (scenarios × planners × team sizes × seeds) is refused before any run.
#[test]
fn regression_a_huge_compare_is_refused() {
    let (code, _, stderr) = common::run(shoal().args(["compare", "--seeds", "1-1000000000"]));
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains(
            "--seeds 1-1000000000: 1 000 000 000 seeds; a comparison has at most 1 000 000 runs"
        ),
        "{stderr}"
    );
    let auvs: Vec<String> = (1..=40).map(|n| n.to_string()).collect();
    let (code, _, stderr) =
        common::run(shoal().args(["compare", "--seeds", "1-20000", "--auvs", &auvs.join(",")]));
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains(
            "1 scenario × 2 planners × 40 team sizes × 20 000 seeds make 1 600 000 runs; a \
             comparison has at most 1 000 000 runs"
        ),
        "{stderr}"
    );
    // the library's parser
    use shoal::compare::parse_seeds;
    assert_eq!(parse_seeds("3-5").unwrap(), [3, 4, 5]);
    assert_eq!(parse_seeds("1,4,7").unwrap(), [1, 4, 7]);
    let max = u64::MAX.to_string();
    let e = parse_seeds(&format!("0-{max}")).unwrap_err().to_string();
    assert!(e.contains("18 446 744 073 709 551 616 seeds"), "{e}");
    for (bad, want) in [
        ("5-1", "the range runs backwards (5 > 1)"),
        ("x", "\"x\" is not a whole number"),
        ("-3", "\"\" is not a whole number"),
    ] {
        let e = parse_seeds(bad).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("--seeds {bad}: ")) && e.contains(want),
            "{e}"
        );
    }
    // a team size the scenario does not allow is refused before any run
    let study = shoal::compare::Study {
        auvs: vec![1, 1_000_000_000_000],
        seeds: vec![1],
        ..shoal::compare::Study::default()
    };
    let e = shoal::compare::run(&study, &mut |_, _| panic!("no run is made"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("team.auvs = 1000000000000: must be"), "{e}");
}

/// Regression: Ctrl-C in `shoal compare` printed nothing and lost every finished run. It now
/// stops after the run under way, writes the finished runs' runs.csv and summary.md marked
/// incomplete, says so, and exits with code 130.
#[cfg(unix)]
#[test]
fn regression_an_interrupted_compare_writes_its_finished_runs() {
    let dir = fresh_dir("compare-interrupted");
    // not a terminal: a line per run; interrupt after the first
    let done = common::interrupt_when(
        shoal()
            .args(["compare", "--no-plot", "-o", dir.to_str().unwrap()])
            .args(["--set", "horizon.steps=6", "--auvs", "1", "--seeds", "1-30"])
            .args(["--methods", "mpc"]),
        |line| line.starts_with("[1/30]"),
        std::time::Duration::ZERO,
    );
    let rest = done.stderr;
    assert_eq!(done.code, Some(130), "{rest}");
    let rows = csv::Reader::from_path(dir.join("runs.csv"))
        .unwrap()
        .records()
        .count();
    assert!((1..30).contains(&rows), "{rows} rows");
    assert!(
        rest.contains(&format!(
            "interrupted after {rows} of 30 runs: wrote {} with the {rows} finished runs \
             (incomplete)",
            dir.join("runs.csv").display()
        )),
        "{rest}"
    );
    let summary = std::fs::read_to_string(dir.join("summary.md")).unwrap();
    assert!(
        summary.starts_with(&format!(
            "**Incomplete**: the comparison was interrupted after {rows} of its 30 runs"
        )),
        "{summary}"
    );
    assert!(!dir.join("compare.png").exists());
}

/// Regression: `shoal check` trusted the limits recorded in the plan. `--scenario FILE` and
/// `--set KEY=VALUE` state the vehicle's own: the report says which limits it used and names
/// the stated and the recorded value where they differ; a different team size is refused.
#[test]
fn regression_check_holds_the_plan_to_the_limits_the_user_states() {
    let (dir, code, out, err) = plan_cli(
        "check-limits",
        &["-q", "--set", "team.auvs=1", "--set", "horizon.steps=3"],
    );
    assert_eq!(code, 0, "{out}\n{err}");
    let plan = dir.join("plan.json");
    let mission = dir.join("mission.toml");
    let (code, _, _) = common::run(shoal().arg("init").arg(&mission));
    assert_eq!(code, 0);
    let check = |args: &[&str]| common::run(shoal().arg("check").arg(&plan).args(args));

    let (code, out, _) = check(&[]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.starts_with("limits: as recorded in the plan\n"),
        "{out}"
    );

    // the AUV's limit of the user's vehicle: 0.5 m/s (and a cruise floor below it); the plan
    // flew faster
    let m = mission.to_str().unwrap();
    let (code, out, _) = check(&[
        "--scenario",
        m,
        "--set",
        "team.auvs=1",
        "--set",
        "horizon.steps=3",
        "--set",
        "auv.max_speed=0.5",
        "--set",
        "auv.min_speed=0.4",
    ]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.starts_with(&format!(
            "limits: from {m} with --set team.auvs=1 --set horizon.steps=3 --set \
             auv.max_speed=0.5 --set auv.min_speed=0.4\n  auv.max_speed = 0.5 (stated), 2 as \
             recorded in the plan\n"
        )),
        "{out}"
    );
    let row = out
        .lines()
        .find(|l| l.starts_with("C1_7 AUV speed"))
        .unwrap();
    assert!(row.ends_with("FAIL"), "{row}");

    // --set alone applies over the plan's recorded scenario
    let (code, out, _) = check(&["--set", "auv.max_speed=0.5", "--set", "auv.min_speed=0.4"]);
    assert_eq!(code, 1, "{out}");
    assert!(
        out.starts_with(
            "limits: as recorded in the plan with --set auv.max_speed=0.5 --set \
             auv.min_speed=0.4\n"
        ),
        "{out}"
    );
    // a stated limit the plan keeps
    let (code, out, _) = check(&["--set", "acoustic.max_range=1000"]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("  acoustic.max_range = 1000 (stated), 400 as recorded in the plan\n"),
        "{out}"
    );

    // the default scenario's 5 AUVs are not the plan's 1: refused, naming both
    let (code, _, err) = check(&["--scenario", m]);
    assert_eq!(code, 2);
    assert!(
        err.contains("give team.auvs = 5, but the plan was made with team.auvs = 1"),
        "{err}"
    );
    // a bad override names itself
    let (code, _, err) = check(&["--set", "auv.max_speed=-1"]);
    assert_eq!(code, 2);
    assert!(err.contains("--set auv.max_speed=-1"), "{err}");
}

/// Regression: `shoal check` echoed the terminal escape codes of a plan's warnings (and of its
/// recorded statuses) to the terminal. They are printed escaped, visibly.
#[test]
fn regression_check_escapes_terminal_codes_from_the_plan() {
    let (dir, code, out, err) = plan_cli(
        "check-escapes",
        &["-q", "--set", "team.auvs=1", "--set", "horizon.steps=2"],
    );
    assert_eq!(code, 0, "{out}\n{err}");
    let plan = dir.join("plan.json");
    let mut json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(&plan).unwrap()).unwrap();
    json["warnings"] = serde_json::json!(["\u{1b}[2J\u{1b}]0;owned\u{7}cleared\r\u{202e}txt"]);
    json["windows"][0]["final"]["status"] = serde_json::json!("\u{1b}[32mconverged");
    std::fs::write(&plan, serde_json::to_string(&json).unwrap()).unwrap();
    let (code, out, err) = common::run(shoal().arg("check").arg(&plan));
    assert_eq!(code, 1, "{out}\n{err}");
    for text in [&out, &err] {
        assert!(
            !text
                .chars()
                .any(|c| c.is_control() && c != '\n' || c == '\u{202e}'),
            "{text:?}"
        );
    }
    assert!(
        err.contains("warning: \\u{1b}[2J\\u{1b}]0;owned\\u{7}cleared\\u{d}\\u{202e}txt"),
        "{err}"
    );
    assert!(out.contains("\\u{1b}[32mconverged"), "{out}");
}

#[test]
fn plan_fly_flies_the_plan_and_prints_flown_beside_planned() {
    let small = ["--set", "team.auvs=2", "--set", "horizon.steps=6"];
    let (dir, code, out, err) = plan_cli("plan_fly", &[&small[..], &["--fly"]].concat());
    assert_eq!(code, 0, "{out}{err}");
    let sim = dir.join("sim.json");
    let r: shoal::sim::SimRecord =
        serde_json::from_slice(&std::fs::read(&sim).expect("sim.json written")).unwrap();
    assert_eq!(r.auvs, 2);
    assert_eq!(r.plan, dir.join("plan.json").display().to_string());
    for row in [
        "flown beside planned",
        "samples below the floor",
        "closest two AUVs",
        "planned-link pings received",
        "epochs every AUV linked to the USV",
        "chain error at the last window's end",
    ] {
        assert!(out.contains(row), "{row}: {out}");
    }
    // the flight is part of the plan's set: its manifest lists it, and a plan written without
    // --fly takes the earlier plan's flight away with it
    let manifest = std::fs::read_to_string(dir.join(shoal::output_set::MANIFEST)).unwrap();
    assert!(manifest.contains("\"sim.json\""), "{manifest}");
    let (code, out, err) = common::run(
        shoal()
            .args(["plan", "--no-plot", "-o", dir.to_str().unwrap()])
            .args(small),
    );
    assert_eq!(code, 0, "{out}{err}");
    assert!(
        !sim.exists(),
        "a flight of an earlier plan stands beside the new one"
    );
    // for scripts: the JSON summary says where the flight is and what it measured
    let (code, out, err) = common::run(
        shoal()
            .args([
                "plan",
                "--no-plot",
                "--json",
                "--fly",
                "-o",
                dir.to_str().unwrap(),
            ])
            .args(small),
    );
    assert_eq!(code, 0, "{out}{err}");
    let json: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(json["flight"]["sim"], sim.display().to_string());
    assert!(
        json["flight"]["metrics"]["samples_below_floor"].is_u64(),
        "{out}"
    );
    assert!(json["files"].to_string().contains("sim.json"), "{out}");
}
