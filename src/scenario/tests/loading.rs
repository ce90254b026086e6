//! Loading scenario files and `--set` overrides.

use super::*;

#[test]
fn empty_file_is_the_default() {
    assert_eq!(parse("").unwrap(), Scenario::default());
    assert_eq!(parse("# only a comment\n\n").unwrap(), Scenario::default());
}

#[test]
fn overrides_change_exactly_the_named_key() {
    let s = parse_with(
        "",
        &[
            "acoustic.sonar_range=120",
            "seed=7",
            "usv.destination=[100,2]",
            "seafloor.synthetic.cell = 50",
            "team.auvs=3",
        ],
    )
    .unwrap();
    let mut want = Scenario::default();
    want.acoustic.sonar_range = 120.0;
    want.seed = 7;
    want.usv.destination = [100.0, 2.0];
    want.seafloor.synthetic.cell = 50.0;
    want.team.auvs = 3;
    assert_eq!(s, want);
}

#[test]
fn overrides_apply_over_the_file_and_later_wins() {
    let text = "seed = 3\n[acoustic]\nsonar_range = 100.0\n";
    let s = parse_with(text, &["acoustic.sonar_range=90", "seed=4", "seed=5"]).unwrap();
    let mut want = Scenario::default();
    want.seed = 5;
    want.acoustic.sonar_range = 90.0;
    assert_eq!(s, want);
    // Into inline tables and dotted keys of the file as well.
    let s = parse_with(
        "acoustic = { sonar_range = 100.0 }\nusv.max_speed = 1.0\n",
        &["acoustic.max_range=300", "usv.destination=[1,2]"],
    )
    .unwrap();
    assert_eq!(s.acoustic.sonar_range, 100.0);
    assert_eq!(s.acoustic.max_range, 300.0);
    assert_eq!(s.usv.max_speed, 1.0);
    assert_eq!(s.usv.destination, [1.0, 2.0]);
}

#[test]
fn bare_string_override() {
    let s = default_with(&set(&[
        "usv.objective=destination",
        "auv.discretisation = euler",
    ]))
    .unwrap();
    assert_eq!(s.usv.objective, UsvObjective::Destination);
    assert_eq!(s.auv.discretisation, Discretisation::Euler);
    let s = default_with(&set(&["seafloor.file=floors/a b.asc"])).unwrap();
    assert_eq!(s.seafloor.file.as_deref(), Some("floors/a b.asc"));
    let s = default_with(&set(&["seafloor.file=\"quoted.asc\""])).unwrap();
    assert_eq!(s.seafloor.file.as_deref(), Some("quoted.asc"));
}

#[test]
fn initial_can_be_given_by_overrides() {
    let s = default_with(&set(&[
        "team.auvs=2",
        "initial={usv=[1,2], auvs=[[0,0,-5],[10,0,-6]]}",
    ]))
    .unwrap();
    let init = s.initial.unwrap();
    assert_eq!(init.usv, [1.0, 2.0]);
    assert_eq!(init.auvs, vec![[0.0, 0.0, -5.0], [10.0, 0.0, -6.0]]);
    let s = parse_with(
        "",
        &[
            "team.auvs=1",
            "initial.usv=[0,0]",
            "initial.auvs=[[1,1,-1]]",
        ],
    )
    .unwrap();
    assert_eq!(s.initial.unwrap().auvs, vec![[1.0, 1.0, -1.0]]);
}

#[test]
fn integers_are_accepted_for_floats() {
    let s = parse("[horizon]\ndt = 50\n").unwrap();
    assert_eq!(s.horizon.dt, 50.0);
}

#[test]
fn load_reads_files_and_reports_io_and_utf8() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("m.toml");
    std::fs::write(&p, "seed = 9\n").unwrap();
    assert_eq!(load(&p, &[]).unwrap().seed, 9);
    assert_eq!(load(&p, &set(&["seed=10"])).unwrap().seed, 10);

    let missing = dir.path().join("nope.toml");
    let e = load(&missing, &[]).unwrap_err();
    assert!(matches!(e, ScenarioError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("nope.toml"), "{e}");

    let bad = dir.path().join("bad.toml");
    std::fs::write(&bad, b"seed = 1\n# caf\xe9\n").unwrap();
    let e = load(&bad, &[]).unwrap_err();
    assert!(matches!(e, ScenarioError::Syntax { line: 2, .. }), "{e:?}");
    assert!(e.to_string().contains("bad.toml line 2"), "{e}");

    std::fs::write(&p, "[acoustic]\nsonar_range = -5\n").unwrap();
    let e = load(&p, &[]).unwrap_err();
    assert!(e.to_string().contains("m.toml line 2"), "{e}");
}
