//! The commented template of `shoal init`: every key, valid TOML, the defaults.

use super::*;

#[test]
fn template_parses_to_exactly_the_default() {
    let t = default_toml();
    assert_eq!(parse(&t).unwrap(), Scenario::default());
    // Independently of our loader, too.
    let s: Scenario = toml::from_str(&t).unwrap();
    assert_eq!(s, Scenario::default());
    assert_eq!(default_with(&[]).unwrap(), Scenario::default());
}

#[test]
fn template_has_every_key_and_only_those() {
    let mut want = Vec::new();
    leaf_keys(&full_default_table(), "", &mut want);
    let want: BTreeSet<String> = want.into_iter().collect();
    let got = template_assignments(&default_toml());
    assert_eq!(got, want);
    // Spot checks that the walk saw the nested and optional keys.
    for k in [
        "seed",
        "seafloor.synthetic.depth_range",
        "seafloor.file",
        "initial.auvs",
    ] {
        assert!(want.contains(k), "{k}");
    }
}

#[test]
fn template_documents_every_key_and_section() {
    let t = full_default_table();
    let mut keys = Vec::new();
    leaf_keys(&t, "", &mut keys);
    section_keys(&t, "", &mut keys);
    for k in keys {
        let d = template::doc(&k);
        assert!(
            d.is_some_and(|d| !d.is_empty()),
            "no comment for `{k}` in template.rs"
        );
    }
    let text = default_toml();
    for sym in [
        "δ", "K:", "N:", "d_s", "d_t", "d_max", "ε", "V_max", "ψ̇_max", "OF1_8_2", "C1_4", "C1_7",
        "C1_14", "C2_2", "w8_2",
    ] {
        assert!(text.contains(sym), "template never mentions {sym}");
    }
}

#[test]
fn template_values_come_from_default() {
    // Change a default through an override and check the rendering path agrees.
    let text = default_toml();
    assert!(text.contains(&format!(
        "sonar_range = {:?}",
        Scenario::default().acoustic.sonar_range
    )));
    assert!(text.contains("# file = \"bathymetry.tif\""));
    assert!(text.contains("# origin = [43.2, 5.3]"));
    assert!(text.contains("# crs = \"EPSG:4326\""));
    assert!(text.contains("# file_east = \"current_u.asc\""));
    assert!(text.contains("# file_north = \"current_v.asc\""));
    assert!(text.contains("values = \"elevation\""));
    assert!(text.contains("# [initial]"));
}

#[test]
fn uncommented_optional_parts_are_valid() {
    let s = parse(&template_uncommented()).unwrap();
    let d = Scenario::default();
    assert_eq!(s.initial, Some(example_initial(&d)));
    assert_eq!(s.seafloor.file.as_deref(), Some(EXAMPLE_FLOOR_FILE));
    let mut expect = full_default();
    expect.initial = Some(example_initial(&d));
    assert_eq!(s, expect);
    // Every example AUV is within d_s of the USV (C1_6 at k = 0) and under water.
    for p in &s.initial.unwrap().auvs {
        assert!(p[0].hypot(p[1]) <= d.acoustic.sonar_range);
        assert!(p[2] < -d.auv.surface_clearance);
    }
}

#[test]
fn default_is_valid() {
    assert_eq!(validate(&Scenario::default()), Ok(()));
    assert_eq!(validate(&full_default()), Ok(()));
}
