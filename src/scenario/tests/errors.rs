//! Bad input: every error names the file, the line, the key and what is allowed.

use super::*;

/// The error names the file, the line and the key.
fn assert_located(e: &ScenarioError, line: usize, key: &str) {
    let msg = e.to_string();
    assert!(msg.contains(&format!("{FILE} line {line}")), "{msg}");
    assert!(msg.contains(key), "{msg}");
    assert_eq!(e.line(), Some(line), "{msg}");
    assert_eq!(e.key(), Some(key), "{msg}");
}

#[test]
fn example_message_from_the_brief() {
    let text = "\n\n\n\n\n\n\n\n\n\n[acoustic]\nsonar_range = -5\n";
    let e = parse(text).unwrap_err();
    assert_eq!(
        e.to_string(),
        "mission.toml line 12: acoustic.sonar_range = -5: must be a positive number of \
         metres (d_s, the sonar range)"
    );
}

#[test]
fn unknown_key_top_level_and_nested() {
    let e = parse("seed = 1\nfoo = 2\n").unwrap_err();
    assert!(matches!(e, ScenarioError::UnknownKey { .. }), "{e:?}");
    assert_located(&e, 2, "foo");
    assert!(
        e.to_string()
            .contains("allowed top-level keys: seed, windows"),
        "{e}"
    );

    let e = parse("[acoustic]\nsonar_range = 100\nsonar_rnage = 3\n").unwrap_err();
    assert!(matches!(e, ScenarioError::UnknownKey { .. }), "{e:?}");
    assert_located(&e, 3, "acoustic.sonar_rnage");
    assert!(
        e.to_string().contains(
            "allowed keys in [acoustic]: sonar_range, band_tolerance, max_range, resolution"
        ),
        "{e}"
    );

    let e = parse("[seafloor.synthetic]\nsize = [1000, 1000]\nbumps = 3\n").unwrap_err();
    assert_located(&e, 3, "seafloor.synthetic.bumps");

    let e = parse("[nope]\nx = 1\n").unwrap_err();
    assert_located(&e, 1, "nope");

    let e = parse("auv.speed = 1\n").unwrap_err();
    assert_located(&e, 1, "auv.speed");

    let e = parse("[initial]\nusv = [0, 0]\nauvs = []\nextra = 1\n").unwrap_err();
    assert_located(&e, 4, "initial.extra");
}

#[test]
fn wrong_type() {
    let e = parse("[acoustic]\nsonar_range = \"far\"\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 2, "acoustic.sonar_range");
    assert!(e.to_string().contains("expected a number"), "{e}");

    let e = parse("\nseed = 1.5\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 2, "seed");

    let e = parse("[usv]\ndestination = [1, 2, 3]\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 2, "usv.destination");
    assert!(e.to_string().contains("an array of 2 numbers"), "{e}");

    let e = parse("team = 5\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 1, "team");

    let e = parse("[initial]\nusv = [0, 0]\nauvs = [\n  [0, 0, -1],\n  [0, \"x\", -1],\n]\n")
        .unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 5, "initial.auvs[1][1]");

    let e = parse("[auv]\ndiscretisation = \"rk4\"\n").unwrap_err();
    assert!(matches!(e, ScenarioError::OutOfRange { .. }), "{e:?}");
    assert_located(&e, 2, "auv.discretisation");
    assert!(e.to_string().contains("\"zoh\", \"euler\""), "{e}");

    let e = parse("[team]\nauvs = -3\n").unwrap_err();
    assert!(matches!(e, ScenarioError::OutOfRange { .. }), "{e:?}");
    assert_located(&e, 2, "team.auvs");
}

#[test]
fn fixed_size_arrays_have_exact_length() {
    let sch = super::schema::Schema::new();
    assert_eq!(sch.fixed_len("usv.destination"), Some(2));
    assert_eq!(sch.fixed_len("seafloor.synthetic.depth_range"), Some(2));
    assert_eq!(sch.fixed_len("initial.usv"), Some(2));
    assert_eq!(sch.fixed_len("initial.auvs"), None);
    assert_eq!(sch.fixed_len("initial.auvs[]"), Some(3));

    // toml_edit alone would read [1, 2, 3] as [1, 2]; we refuse it.
    let e =
        parse("[team]\nauvs = 1\n[initial]\nusv = [0, 0]\nauvs = [[0, 0, -1, 7]]\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 5, "initial.auvs[0]");
    assert!(e.to_string().contains("an array of 4 elements"), "{e}");

    let e = parse("[seafloor.synthetic]\nrelief = [1]\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 2, "seafloor.synthetic.relief");

    let e = parse_with("", &["usv.destination=[1, 2, 3]"]).unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_eq!(e.source_name(), "--set usv.destination=[1, 2, 3]");
}

#[test]
fn wrong_type_of_sections_enums_and_dates() {
    let e = parse("[[initial]]\nusv = [0, 0]\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 1, "initial");
    let e = parse("[auv]\ndiscretisation = 3\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 2, "auv.discretisation");
    assert!(e.to_string().contains("found integer 3"), "{e}");
    let e = parse("seed = 1979-05-27\n").unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_located(&e, 1, "seed");
}

#[test]
fn missing_key_in_initial() {
    let e = parse("seed = 2\n[initial]\nauvs = [[0, 0, -10]]\n").unwrap_err();
    assert!(matches!(e, ScenarioError::MissingKey { .. }), "{e:?}");
    assert_located(&e, 2, "initial.usv");
    // the USV alone is a start: the AUVs are drawn from the seed about it
    let s = parse("seed = 2\n[initial]\nusv = [10, 20]\n").unwrap();
    assert_eq!(s.initial.unwrap().auvs, Vec::<[f64; 3]>::new());
}

#[test]
fn syntax_error() {
    let e = parse("seed = 1\n[acoustic\nsonar_range = 3\n").unwrap_err();
    match &e {
        ScenarioError::Syntax {
            source_name, line, ..
        } => {
            assert_eq!(source_name, FILE);
            assert_eq!(*line, 2);
        }
        other => panic!("{other:?}"),
    }
    assert!(
        e.to_string().starts_with("mission.toml line 2, column"),
        "{e}"
    );
    let e = parse("seed = 1\nseed = 2\n").unwrap_err();
    assert!(matches!(e, ScenarioError::Syntax { line: 2, .. }), "{e:?}");
}

#[test]
fn out_of_range_rules() {
    // (file text, key at fault, line). Every rule of validate().
    let cases: &[(&str, &str, usize)] = &[
        ("windows = 0", "windows", 1),
        ("[team]\nauvs = 0", "team.auvs", 2),
        ("[team]\nauvs = 65", "team.auvs", 2),
        ("[horizon]\nsteps = 0", "horizon.steps", 2),
        ("[horizon]\nsteps = 1001", "horizon.steps", 2),
        ("[horizon]\ndt = 0", "horizon.dt", 2),
        ("[horizon]\ndt = inf", "horizon.dt", 2),
        ("[acoustic]\nsonar_range = -5", "acoustic.sonar_range", 2),
        ("[acoustic]\nsonar_range = nan", "acoustic.sonar_range", 2),
        (
            "[acoustic]\nband_tolerance = 0",
            "acoustic.band_tolerance",
            2,
        ),
        (
            "[acoustic]\nband_tolerance = 150",
            "acoustic.band_tolerance",
            2,
        ),
        ("[acoustic]\nmax_range = 149", "acoustic.max_range", 2),
        ("[acoustic]\nresolution = 0", "acoustic.resolution", 2),
        // regression (issue 13): 1e-12 grew the planner to 24 GB; 1e308 sampled nothing
        ("[acoustic]\nresolution = 1e-12", "acoustic.resolution", 2),
        ("[acoustic]\nresolution = 1e308", "acoustic.resolution", 2),
        ("[auv]\nmax_speed = 0", "auv.max_speed", 2),
        ("[auv]\nmax_heading_rate = 0", "auv.max_heading_rate", 2),
        (
            "[auv]\nmin_heading_speed = -0.1",
            "auv.min_heading_speed",
            2,
        ),
        ("[auv]\nmin_heading_speed = 2", "auv.min_heading_speed", 2),
        ("[auv]\nfloor_clearance = -1", "auv.floor_clearance", 2),
        ("[auv]\nsurface_clearance = -1", "auv.surface_clearance", 2),
        ("[auv]\nmass = 0", "auv.mass", 2),
        ("[auv]\nadded_mass_surge = 1", "auv.added_mass_surge", 2),
        ("[auv]\nadded_mass_heave = 0.5", "auv.added_mass_heave", 2),
        ("[auv]\ndamping_surge = 4.86", "auv.damping_surge", 2),
        ("[auv]\ndamping_heave = 1", "auv.damping_heave", 2),
        ("[auv]\ninertia_yaw = 0", "auv.inertia_yaw", 2),
        (
            "[auv]\nadded_inertia_yaw = 4.88",
            "auv.added_inertia_yaw",
            2,
        ),
        ("[auv]\ndamping_yaw = 18.8", "auv.damping_yaw", 2),
        ("[usv]\nmax_speed = 0", "usv.max_speed", 2),
        ("[usv]\ndestination = [nan, 0]", "usv.destination", 2),
        ("[usv]\ninitial_heading = inf", "usv.initial_heading", 2),
        ("[usv]\ncourses = 0", "usv.courses", 2),
        ("[usv]\ncourses = 73", "usv.courses", 2),
        ("[weights]\nw1 = -1", "weights.w1", 2),
        ("[weights]\nw5 = -1e-9", "weights.w5", 2),
        ("[weights]\nw8_2 = -1", "weights.w8_2", 2),
        ("[weights]\nw_lanes = -1", "weights.w_lanes", 2),
        ("[seafloor]\nfile = \"\"", "seafloor.file", 2),
        (
            "[seafloor.synthetic]\nsize = [0, 100]",
            "seafloor.synthetic.size",
            2,
        ),
        (
            "[seafloor.synthetic]\ncell = 0",
            "seafloor.synthetic.cell",
            2,
        ),
        (
            "[seafloor.synthetic]\nsize = [250001, 100]",
            "seafloor.synthetic.size",
            2,
        ),
        (
            "[seafloor.synthetic]\nbase_depth = nan",
            "seafloor.synthetic.base_depth",
            2,
        ),
        (
            "[seafloor.synthetic]\nslope = [0, inf]",
            "seafloor.synthetic.slope",
            2,
        ),
        (
            "[seafloor.synthetic]\nseamounts = 10001",
            "seafloor.synthetic.seamounts",
            2,
        ),
        (
            "[seafloor.synthetic]\nvalleys = 10001",
            "seafloor.synthetic.valleys",
            2,
        ),
        (
            "[seafloor.synthetic]\nrelief = [0, 1]",
            "seafloor.synthetic.relief",
            2,
        ),
        (
            "[seafloor.synthetic]\nrelief = [2, 1]",
            "seafloor.synthetic.relief",
            2,
        ),
        (
            "[seafloor.synthetic]\nradius = [-1, 1]",
            "seafloor.synthetic.radius",
            2,
        ),
        (
            "[seafloor.synthetic]\nradius = [5, 4]",
            "seafloor.synthetic.radius",
            2,
        ),
        (
            "[seafloor.synthetic]\ndepth_range = [-50, -140]",
            "seafloor.synthetic.depth_range",
            2,
        ),
        (
            "[seafloor.synthetic]\ndepth_range = [-140, 0]",
            "seafloor.synthetic.depth_range",
            2,
        ),
        (
            "[seafloor]\nfile = \"a.asc\"\ncrs = \"WGS84\"",
            "seafloor.crs",
            3,
        ),
        ("[seafloor]\ncrs = \"EPSG:4326\"", "seafloor.crs", 2),
        (
            "[seafloor]\nfile = \"a.asc\"\norigin = [43, 5]\ncrs = \"EPSG:32631\"",
            "seafloor.origin",
            4,
        ),
        ("[scp]\nmax_iterations = 0", "scp.max_iterations", 2),
        ("[scp]\ntolerance = 0", "scp.tolerance", 2),
        ("[scp]\nstep1_tolerance = 0", "scp.step1_tolerance", 2),
        (
            "[scp]\nstep1_max_iterations = 0",
            "scp.step1_max_iterations",
            2,
        ),
        ("[scp]\nfeasibility_tol = -1", "scp.feasibility_tol", 2),
        ("[scp]\ntrust_region = 0", "scp.trust_region", 2),
        ("[scp]\nmin_trust_region = 0", "scp.min_trust_region", 2),
        ("[scp]\nmin_trust_region = 200", "scp.min_trust_region", 2),
        ("[scp]\npenalty = 0", "scp.penalty", 2),
        (
            "[team]\nauvs = 1\n[initial]\nusv = [inf, 0]\nauvs = [[0, 0, -1]]",
            "initial.usv",
            4,
        ),
        (
            "[team]\nauvs = 2\n[initial]\nusv = [0, 0]\nauvs = [[0, 0, -1], [0, 0, 0]]",
            "initial.auvs[1]",
            5,
        ),
        (
            "[team]\nauvs = 1\n[initial]\nusv = [0, 0]\nauvs = [[0, nan, -1]]",
            "initial.auvs[0]",
            5,
        ),
    ];
    for (text, key, line) in cases {
        let e = parse(text).unwrap_err();
        assert!(
            matches!(e, ScenarioError::OutOfRange { .. }),
            "{text}: {e:?}"
        );
        assert_located(&e, *line, key);
    }
}

#[test]
fn max_range_below_sonar_range_says_so() {
    let e = parse("[acoustic]\nsonar_range = 500\n").unwrap_err();
    let msg = e.to_string();
    // The rule is on max_range; it was broken by setting sonar_range on line 2.
    assert_eq!(e.key(), Some("acoustic.max_range"));
    assert_eq!(e.line(), Some(2));
    assert!(msg.contains("400 (default)"), "{msg}");
    assert!(msg.contains("d_s > d_max is an error"), "{msg}");
}

#[test]
fn initial_length_mismatch_names_both_numbers() {
    let text = "[initial]\nusv = [0, 0]\nauvs = [[0, 0, -10], [5, 5, -10]]\n";
    let e = parse(text).unwrap_err();
    assert!(matches!(e, ScenarioError::OutOfRange { .. }), "{e:?}");
    assert_located(&e, 3, "initial.auvs");
    let msg = e.to_string();
    assert!(msg.contains("team.auvs = 5"), "{msg}");
    assert!(msg.contains("lists 2"), "{msg}");
}

#[test]
fn bad_override_syntax() {
    for o in [
        "novalue",
        "=3",
        "acoustic..sonar_range=1",
        "acoustic.sonar_range=",
        "initial.auvs[0]=[1,2,3]",
        "usv.destination.x=1",
        " . =1",
    ] {
        let e = parse_with("", &[o]).unwrap_err();
        assert!(matches!(e, ScenarioError::BadOverride { .. }), "{o}: {e:?}");
        assert!(e.to_string().starts_with("--set "), "{e}");
        assert_eq!(e.line(), None);
    }
}

#[test]
fn override_of_unknown_key() {
    let e = parse_with("", &["acoustic.sonar_rnage=1"]).unwrap_err();
    assert!(matches!(e, ScenarioError::UnknownKey { .. }), "{e:?}");
    assert_eq!(e.key(), Some("acoustic.sonar_rnage"));
    assert_eq!(e.source_name(), "--set acoustic.sonar_rnage=1");
    let msg = e.to_string();
    assert!(msg.starts_with("--set acoustic.sonar_rnage=1: "), "{msg}");
    assert!(
        msg.contains("allowed keys in [acoustic]: sonar_range"),
        "{msg}"
    );

    let e = parse_with("", &["nope.x=1"]).unwrap_err();
    assert!(matches!(e, ScenarioError::UnknownKey { .. }), "{e:?}");
    assert_eq!(e.key(), Some("nope"));
    assert!(
        e.to_string().contains("allowed top-level keys: seed"),
        "{e}"
    );
}

#[test]
fn override_errors_are_reported_against_the_override() {
    let text = "[acoustic]\nsonar_range = 100\n";
    let e = parse_with(text, &["seed=3", "acoustic.sonar_range=far"]).unwrap_err();
    assert!(matches!(e, ScenarioError::WrongType { .. }), "{e:?}");
    assert_eq!(e.source_name(), "--set acoustic.sonar_range=far");
    assert_eq!(e.line(), None);
    assert_eq!(e.key(), Some("acoustic.sonar_range"));

    let e = parse_with(text, &["acoustic.sonar_range=-1"]).unwrap_err();
    assert!(matches!(e, ScenarioError::OutOfRange { .. }), "{e:?}");
    assert_eq!(
        e.to_string(),
        "--set acoustic.sonar_range=-1: acoustic.sonar_range = -1: must be a positive number \
         of metres (d_s, the sonar range)"
    );

    // A cross-key rule broken by an override is blamed on the override.
    let e = default_with(&set(&["acoustic.sonar_range=500"])).unwrap_err();
    assert_eq!(e.source_name(), "--set acoustic.sonar_range=500");
    assert_eq!(e.key(), Some("acoustic.max_range"));

    let e = parse_with("", &["initial.auvs=[[0,0,-10]]"]).unwrap_err();
    assert!(matches!(e, ScenarioError::MissingKey { .. }), "{e:?}");
    assert_eq!(e.source_name(), "--set initial.auvs=[[0,0,-10]]");
    assert_eq!(e.key(), Some("initial.usv"));

    let e = parse_with("", &["team.auvs=2", "initial={usv=[0,0], auvs=[[0,0,-1]]}"]).unwrap_err();
    assert_eq!(
        e.source_name(),
        "--set initial={usv=[0,0], auvs=[[0,0,-1]]}"
    );
    assert!(e.to_string().contains("team.auvs = 2"), "{e}");

    let e = default_with(&set(&["usv.objective=north"])).unwrap_err();
    assert!(matches!(e, ScenarioError::OutOfRange { .. }), "{e:?}");
    assert_eq!(e.source_name(), "--set usv.objective=north");
    assert!(e.to_string().contains("\"away\", \"destination\""), "{e}");

    // The file's own errors still come first and name the file.
    let e = parse_with("bogus = 1\n", &["seed=2"]).unwrap_err();
    assert_eq!(e.source_name(), FILE);
    assert_eq!(e.line(), Some(1));
}

#[test]
fn embedded_default_errors_name_it() {
    let e = from_toml_str("[horizon\n", EMBEDDED_DEFAULT, &[]).unwrap_err();
    assert!(e.to_string().starts_with("embedded default line 1"), "{e}");
}

/// Every float of the scenario, anywhere (arrays included), is checked for finiteness.
#[test]
fn every_float_must_be_finite() {
    let mut keys = Vec::new();
    let t = full_default_table();
    leaf_keys(&t, "", &mut keys);
    let base = template_uncommented();
    let lookup = |key: &str| -> toml::Value {
        let mut v = toml::Value::Table(t.clone());
        for seg in key.split('.') {
            v = v.get(seg).cloned().unwrap();
        }
        v
    };
    let mut checked = 0;
    for key in keys {
        let v = lookup(&key);
        let variants: Vec<(String, String)> = match &v {
            toml::Value::Float(_) => vec![("nan".into(), key.clone())],
            toml::Value::Array(a) => (0..a.len())
                .filter_map(|i| match &a[i] {
                    toml::Value::Float(_) => {
                        let parts: Vec<String> = (0..a.len())
                            .map(|j| {
                                if j == i {
                                    "nan".into()
                                } else {
                                    a[j].to_string()
                                }
                            })
                            .collect();
                        Some((format!("[{}]", parts.join(", ")), key.clone()))
                    }
                    toml::Value::Array(inner) => {
                        // initial.auvs: poison element i's x.
                        let mut rows: Vec<String> = a.iter().map(|r| r.to_string()).collect();
                        let mut row: Vec<String> = inner.iter().map(|x| x.to_string()).collect();
                        row[0] = "nan".into();
                        rows[i] = format!("[{}]", row.join(", "));
                        Some((format!("[{}]", rows.join(", ")), format!("{key}[{i}]")))
                    }
                    _ => None,
                })
                .collect(),
            _ => vec![],
        };
        for (value, want_key) in variants {
            let o = format!("{key}={value}");
            let e = from_toml_str(&base, FILE, std::slice::from_ref(&o)).unwrap_err();
            assert!(matches!(e, ScenarioError::OutOfRange { .. }), "{o}: {e:?}");
            assert_eq!(e.key(), Some(want_key.as_str()), "{o}: {e}");
            checked += 1;
        }
    }
    assert!(checked > 40, "only {checked} floats checked");
}

#[test]
fn errors_are_deterministic() {
    let text = "windows = 0\n[team]\nauvs = 0\n";
    let a = parse(text).unwrap_err().to_string();
    let b = parse(text).unwrap_err().to_string();
    assert_eq!(a, b);
    assert!(a.contains("windows"), "{a}");
    let v = validate(
        &parse("")
            .map(|mut s| {
                s.windows = 0;
                s.team.auvs = 0;
                s
            })
            .unwrap(),
    )
    .unwrap_err();
    assert_eq!(v.len(), 2);
    assert_eq!(v[0].key, "windows");
    assert_eq!(v[1].key, "team.auvs");
}

/// Regression (issue 13): a seed beyond TOML's integers (a u64) was "found string".
#[test]
fn regression_a_u64_seed_is_not_called_a_string() {
    let e = crate::scenario::default_with(&["seed=18446744073709551615".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(
            "found 18446744073709551615, beyond TOML's integers (at most 9223372036854775807)"
        ),
        "{e}"
    );
}
