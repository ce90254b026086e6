//! Arbitrary bytes, TOML-like text, mutated templates and overrides never panic.

use super::*;

fn tomlish() -> impl Strategy<Value = String> {
    let key = prop_oneof![
        Just("seed"),
        Just("windows"),
        Just("team.auvs"),
        Just("auvs"),
        Just("sonar_range"),
        Just("acoustic.max_range"),
        Just("usv.destination"),
        Just("destination"),
        Just("initial.auvs"),
        Just("usv"),
        Just("auvs"),
        Just("file"),
        Just("size"),
        Just("x.y.z"),
        Just("\"quoted key\""),
    ];
    let value = prop_oneof![
        Just("1".to_string()),
        Just("-1".to_string()),
        Just("0".to_string()),
        Just("1e400".to_string()),
        Just("nan".to_string()),
        Just("-inf".to_string()),
        Just("\"away\"".to_string()),
        Just("\"\"".to_string()),
        Just("[1, 2]".to_string()),
        Just("[[1, 2, -3]]".to_string()),
        Just("[[1, 2, 3], [\"a\"]]".to_string()),
        Just("{ usv = [0, 0], auvs = [] }".to_string()),
        Just("[]".to_string()),
        Just("true".to_string()),
        Just("1979-05-27T07:32:00Z".to_string()),
        Just("9223372036854775807".to_string()),
        any::<f64>().prop_map(|f| format!("{f:?}")),
        any::<i64>().prop_map(|i| i.to_string()),
        "[ -~]{0,12}",
    ];
    let header = prop_oneof![
        Just("[team]"),
        Just("[acoustic]"),
        Just("[auv]"),
        Just("[usv]"),
        Just("[seafloor]"),
        Just("[seafloor.synthetic]"),
        Just("[initial]"),
        Just("[[initial]]"),
        Just("[scp]"),
        Just("[bogus]"),
        Just("["),
    ];
    let line = prop_oneof![
        3 => (key, value).prop_map(|(k, v)| format!("{k} = {v}")),
        1 => header.prop_map(str::to_string),
        1 => "[ -~]{0,20}",
    ];
    prop::collection::vec(line, 0..12).prop_map(|ls| ls.join("\n"))
}

fn override_text() -> impl Strategy<Value = String> {
    prop_oneof![
        Just("seed=7".to_string()),
        Just("team.auvs=2".to_string()),
        Just("initial.usv=[0,0]".to_string()),
        Just("usv=3".to_string()),
        Just("acoustic.sonar_range=x".to_string()),
        Just("initial={usv=[0,0],auvs=[[0,0,-1]]}".to_string()),
        "[ -~]{0,30}",
        any::<String>(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        let text = String::from_utf8_lossy(&bytes);
        let _ = from_toml_str(&text, FILE, &[]);
    }

    #[test]
    fn arbitrary_tomlish_text_never_panics(
        text in tomlish(),
        overrides in prop::collection::vec(override_text(), 0..4),
    ) {
        match from_toml_str(&text, FILE, &overrides) {
            Ok(s) => prop_assert!(validate(&s).is_ok()),
            Err(e) => {
                // Every message names its source.
                let msg = e.to_string();
                prop_assert!(msg.starts_with(FILE) || msg.starts_with("--set "), "{}", msg);
            }
        }
    }

    #[test]
    fn mutated_template_never_panics(
        cut in any::<prop::sample::Index>(),
        len in 0usize..40,
        insert in "[ -~\n]{0,8}",
        overrides in prop::collection::vec(override_text(), 0..3),
    ) {
        let t = default_toml();
        let mut bytes = t.into_bytes();
        let at = cut.index(bytes.len());
        let end = (at + len).min(bytes.len());
        bytes.splice(at..end, insert.bytes());
        let text = String::from_utf8_lossy(&bytes);
        if let Err(e) = from_toml_str(&text, FILE, &overrides) {
            let msg = e.to_string();
            prop_assert!(msg.starts_with(FILE) || msg.starts_with("--set "), "{}", msg);
        }
    }

    #[test]
    fn arbitrary_overrides_on_the_default_never_panic(
        overrides in prop::collection::vec(override_text(), 0..4),
    ) {
        let _ = default_with(&overrides);
    }
}
