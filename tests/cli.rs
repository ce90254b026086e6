//! End-to-end tests: plan with the library and the `shoal` binary, then verify with the
//! independent checker.

mod common;
use common::{plan_and_check, plan_scenario, shoal};

use shoal::scenario::{self, Scenario};
use shoal::PlanError;

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
    assert_eq!(json["format"], "shoal-plan/2");
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
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("grid_edge");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, out, err) = common::run(shoal().args([
        "plan",
        "--no-plot",
        "-o",
        dir.to_str().unwrap(),
        "--set",
        "seafloor.synthetic.size=[5000.0, 5000.0]",
    ]));
    assert_eq!(code, 0, "{out}\n{err}");
    let text = std::fs::read_to_string(dir.join("plan.json")).unwrap();
    assert!(!text.contains("null, ") || !text.contains("\"merit_before\": null"));
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
    let (p, _) = plan_and_check(&s).expect("plan");
    assert_eq!(p.windows[0].step1.status, "max_iterations");
    assert_eq!(p.warnings.len(), 2, "{:?}", p.warnings);
    assert!(p.warnings[0].starts_with("window 0: step 1 (P2) stopped at scp.max_iterations = 1"));
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("unconverged");
    let _ = std::fs::remove_dir_all(&dir);
    let (code, out, err) = common::run(shoal().args([
        "plan",
        "--no-plot",
        "-o",
        dir.to_str().unwrap(),
        "--set",
        "scp.max_iterations=1",
    ]));
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
