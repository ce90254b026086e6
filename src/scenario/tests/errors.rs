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

/// One bad override per validation rule (and per kind of value the deserialiser refuses):
/// (overrides, the key the message must name).
const EVERY_RULE: &[(&[&str], &str)] = &[
    (&["windows=0"], "windows"),
    (&["windows=-1"], "windows"),
    (&["seed=-1"], "seed"),
    (&["team.auvs=0"], "team.auvs"),
    (&["team.auvs=-3"], "team.auvs"),
    (&["team.auvs=1.5"], "team.auvs"),
    (&["horizon.steps=0"], "horizon.steps"),
    (&["horizon.steps=-1"], "horizon.steps"),
    (&["horizon.dt=0"], "horizon.dt"),
    (&["horizon.terminal_margin=3"], "horizon.terminal_margin"),
    (&["acoustic.sonar_range=-5"], "acoustic.sonar_range"),
    (&["acoustic.band_tolerance=0"], "acoustic.band_tolerance"),
    (&["acoustic.max_range=100"], "acoustic.max_range"),
    (&["acoustic.link_margin=0"], "acoustic.link_margin"),
    (&["acoustic.link_margin=1.5"], "acoustic.link_margin"),
    (&["acoustic.link_margin=0.1"], "acoustic.link_margin"),
    (&["acoustic.los_shrink=0"], "acoustic.los_shrink"),
    (&["acoustic.los_rounds=0"], "acoustic.los_rounds"),
    (&["acoustic.resolution=0"], "acoustic.resolution"),
    (&["acoustic.graph=\"ring\""], "acoustic.graph"),
    (&["auv.max_speed=0"], "auv.max_speed"),
    (&["auv.max_heading_rate=0"], "auv.max_heading_rate"),
    (&["auv.min_heading_speed=3"], "auv.min_heading_speed"),
    (&["auv.floor_clearance=-1"], "auv.floor_clearance"),
    (&["auv.surface_clearance=-1"], "auv.surface_clearance"),
    (&["auv.min_separation=-1"], "auv.min_separation"),
    (&["auv.swath_width=0"], "auv.swath_width"),
    (&["auv.survey_altitude=0"], "auv.survey_altitude"),
    (&["auv.discretisation=\"rk4\""], "auv.discretisation"),
    (&["auv.mass=0"], "auv.mass"),
    (&["auv.added_mass_surge=1"], "auv.added_mass_surge"),
    (&["auv.added_mass_heave=1"], "auv.added_mass_heave"),
    (&["auv.damping_surge=1"], "auv.damping_surge"),
    (&["auv.damping_heave=1"], "auv.damping_heave"),
    (&["auv.inertia_yaw=0"], "auv.inertia_yaw"),
    (&["auv.added_inertia_yaw=1"], "auv.added_inertia_yaw"),
    (&["auv.damping_yaw=1"], "auv.damping_yaw"),
    (&["usv.max_speed=0"], "usv.max_speed"),
    (&["usv.objective=\"north\""], "usv.objective"),
    (&["usv.destination=[nan, 0]"], "usv.destination"),
    (&["usv.initial_heading=inf"], "usv.initial_heading"),
    (&["usv.courses=0"], "usv.courses"),
    (&["usv.away_from=\"home\""], "usv.away_from"),
    (&["weights.w1=-1"], "weights.w1"),
    (&["weights.w_lanes=-1"], "weights.w_lanes"),
    (&["weights.of1_2=\"up\""], "weights.of1_2"),
    (&["weights.scaling=\"max\""], "weights.scaling"),
    (&["weights.w8_scaling=\"x\""], "weights.w8_scaling"),
    (&["seafloor.file=\"floor.png\""], "seafloor.file"),
    (&["seafloor.values=\"depth\""], "seafloor.values"),
    (&["seafloor.values=\"height\""], "seafloor.values"),
    (
        &["seafloor.file=\"a.asc\"", "seafloor.origin=[91, 0]"],
        "seafloor.origin",
    ),
    (&["seafloor.origin=[43, 5]"], "seafloor.origin"),
    (
        &["seafloor.file=\"a.asc\"", "seafloor.crs=\"WGS84\""],
        "seafloor.crs",
    ),
    (&["seafloor.crs=\"EPSG:4326\""], "seafloor.crs"),
    (
        &[
            "seafloor.file=\"a.asc\"",
            "seafloor.origin=[43, 5]",
            "seafloor.crs=\"EPSG:32631\"",
        ],
        "seafloor.origin",
    ),
    (
        &["seafloor.synthetic.size=[0, 100]"],
        "seafloor.synthetic.size",
    ),
    (&["seafloor.synthetic.cell=0"], "seafloor.synthetic.cell"),
    (
        &["seafloor.synthetic.size=[1e6, 100]"],
        "seafloor.synthetic.size",
    ),
    (
        &["seafloor.synthetic.base_depth=nan"],
        "seafloor.synthetic.base_depth",
    ),
    (
        &["seafloor.synthetic.slope=[0, inf]"],
        "seafloor.synthetic.slope",
    ),
    (
        &["seafloor.synthetic.seamounts=10001"],
        "seafloor.synthetic.seamounts",
    ),
    (
        &["seafloor.synthetic.valleys=10001"],
        "seafloor.synthetic.valleys",
    ),
    (
        &["seafloor.synthetic.relief=[2, 1]"],
        "seafloor.synthetic.relief",
    ),
    (
        &["seafloor.synthetic.radius=[0, 1]"],
        "seafloor.synthetic.radius",
    ),
    (
        &["seafloor.synthetic.depth_range=[-50, -140]"],
        "seafloor.synthetic.depth_range",
    ),
    (&["scp.max_iterations=0"], "scp.max_iterations"),
    (&["scp.tolerance=0"], "scp.tolerance"),
    (&["scp.step1_max_iterations=0"], "scp.step1_max_iterations"),
    (&["scp.step1_tolerance=0"], "scp.step1_tolerance"),
    (&["scp.feasibility_tol=0"], "scp.feasibility_tol"),
    (&["scp.trust_region=0"], "scp.trust_region"),
    (&["scp.min_trust_region=300"], "scp.min_trust_region"),
    (&["scp.penalty=0"], "scp.penalty"),
    (&["current.velocity=[5, 0]"], "current.velocity"),
    (&["current.file_east=\"u.asc\""], "current.file_east"),
    (&["current.file_north=\"v.asc\""], "current.file_north"),
    (
        &[
            "current.file_east=\"u.png\"",
            "current.file_north=\"v.asc\"",
        ],
        "current.file_east",
    ),
    (&["current.profile=[[10, 1], [5, 1]]"], "current.profile[1]"),
    (&["navigation.sample_period=0"], "navigation.sample_period"),
    (&["navigation.dvl_noise=-1"], "navigation.dvl_noise"),
    (&["navigation.dvl_scale=0.5"], "navigation.dvl_scale"),
    (
        &["navigation.dvl_max_altitude=0"],
        "navigation.dvl_max_altitude",
    ),
    (&["navigation.heading_noise=-1"], "navigation.heading_noise"),
    (&["navigation.heading_bias=1"], "navigation.heading_bias"),
    (&["navigation.depth_noise=-1"], "navigation.depth_noise"),
    (&["navigation.gps_noise=0"], "navigation.gps_noise"),
    (&["navigation.initial_noise=0"], "navigation.initial_noise"),
    (
        &["navigation.acoustic_period=0"],
        "navigation.acoustic_period",
    ),
    (
        &["navigation.acoustic_period=2.5"],
        "navigation.acoustic_period",
    ),
    (&["navigation.sound_speed=0"], "navigation.sound_speed"),
    (&["navigation.range_noise=0"], "navigation.range_noise"),
    (
        &["navigation.packet_success=0"],
        "navigation.packet_success",
    ),
    (&["navigation.range_falloff=0"], "navigation.range_falloff"),
    (
        &["navigation.estimate_biases=2"],
        "navigation.estimate_biases",
    ),
    (&["simulation.step=1"], "simulation.step"),
    (&["simulation.step=0.15"], "simulation.step"),
    (&["sampling.samples=0"], "sampling.samples"),
    (&["sampling.tree_budget=0"], "sampling.tree_budget"),
    (&["sampling.attempts=0"], "sampling.attempts"),
    (
        &[
            "initial.usv=[inf, 0]",
            "team.auvs=1",
            "initial.auvs=[[0, 0, -1]]",
        ],
        "initial.usv",
    ),
    (
        &[
            "team.auvs=2",
            "initial.usv=[0, 0]",
            "initial.auvs=[[0, 0, -1]]",
        ],
        "initial.auvs",
    ),
    (
        &[
            "team.auvs=1",
            "initial.usv=[0, 0]",
            "initial.auvs=[[0, 0, 1]]",
        ],
        "initial.auvs[0]",
    ),
];

/// What a message must say besides the key: what is allowed, as the word or as a range.
fn says_what_is_allowed(msg: &str) -> bool {
    [
        "allowed",
        "≥",
        "≤",
        "<",
        ">",
        " from ",
        "at most",
        "one of",
        "positive",
        "finite",
        "whole number",
        "true or false",
        "path of a grid file",
    ]
    .iter()
    .any(|w| msg.contains(w))
}

/// Regression: several validation errors named no setting, or named it without saying what
/// it may be ("applies to a grid file", "must be a non-negative integer" for team.auvs = -3).
/// Every rule's message names its dotted key and what is allowed.
#[test]
fn regression_every_validation_error_names_its_key_and_what_is_allowed() {
    let mut bad = Vec::new();
    for (overrides, key) in EVERY_RULE {
        // with the gdal feature, GDAL is asked to read a grid of any other extension
        if cfg!(feature = "gdal") && overrides.iter().any(|o| o.contains(".png")) {
            continue;
        }
        let e = match default_with(&set(overrides)) {
            Err(e) => e,
            Ok(_) => panic!("{overrides:?} was accepted"),
        };
        let msg = e.to_string();
        if !(msg.contains(key) && says_what_is_allowed(&msg) && e.key() == Some(*key)) {
            bad.push(format!("{overrides:?} ({key}): {msg}"));
        }
    }
    assert!(
        bad.is_empty(),
        "{} messages:\n{}",
        bad.len(),
        bad.join("\n")
    );
}

/// The integer ranges the deserialiser's errors name are the ones `validate` checks.
#[test]
fn integer_ranges_agree_with_validate() {
    use super::validate::INTEGER_RANGES;
    for (key, lo, hi) in INTEGER_RANGES {
        let ok = |n: u64| default_with(&[format!("{key}={n}")]).is_ok();
        assert!(ok(*lo), "{key} = {lo}");
        if *lo > 0 {
            assert!(!ok(lo - 1), "{key} = {}", lo - 1);
        }
        if let Some(hi) = hi {
            assert!(!ok(hi + 1), "{key} = {}", hi + 1);
        }
        // a negative value names the range
        let e = default_with(&[format!("{key}=-1")])
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(&super::validate::integer_text(key).unwrap()),
            "{e}"
        );
    }
}
