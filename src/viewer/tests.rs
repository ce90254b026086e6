use super::data::{auv_colour, base64, floor_mesh, MAX_FLOOR_VERTICES};
use super::*;
use crate::seafloor::Lattice;

#[test]
fn vendored_three_is_the_pinned_release_and_loads_through_the_import_map() {
    assert!(THREE_CORE.contains(&format!(
        "const t=\"{}\"",
        THREE_VERSION.split('.').nth(1).unwrap()
    )));
    assert_eq!(THREE_MODULE.matches(CORE_IMPORT).count(), 2, "core imports");
    let rewritten = THREE_MODULE.replace(CORE_IMPORT, "\"three/core\"");
    assert!(!rewritten.contains("three.core.min.js"));
    assert!(ORBIT_CONTROLS.contains("} from 'three';"));
    assert!(THREE_LICENSE.contains("MIT License"));
}

#[test]
fn every_embedded_source_can_sit_in_a_script_element() {
    for (name, s) in [
        ("three core", THREE_CORE),
        ("three", THREE_MODULE),
        ("OrbitControls", ORBIT_CONTROLS),
        ("scene.js", SCENE_JS),
        ("viewer.js", VIEWER_JS),
    ] {
        assert!(embeddable(s), "{name}");
    }
    assert!(!embeddable("x = '</SCRIPT>'"));
    assert!(
        !THREE_LICENSE.contains("--"),
        "the licence sits in an HTML comment"
    );
}

#[test]
fn script_safe_json_has_no_angle_bracket_and_parses_the_same() {
    let v = serde_json::json!({ "s": "</script><!-- x" });
    let safe = script_safe(&serde_json::to_string(&v).unwrap());
    assert!(!safe.contains('<'));
    assert_eq!(serde_json::from_str::<serde_json::Value>(&safe).unwrap(), v);
}

#[test]
fn fill_replaces_markers_in_order_and_leaves_values_alone() {
    let out = fill(
        "a @X@ b @Y@ c @X@",
        &[("@X@", "@Y@"), ("@Y@", "2"), ("@X@", "3")],
    );
    assert_eq!(out, "a @Y@ b 2 c 3");
}

#[test]
fn base64_matches_rfc_4648_vectors() {
    for (input, expected) in [
        ("", ""),
        ("f", "Zg=="),
        ("fo", "Zm8="),
        ("foo", "Zm9v"),
        ("foob", "Zm9vYg=="),
        ("fooba", "Zm9vYmE="),
        ("foobar", "Zm9vYmFy"),
    ] {
        assert_eq!(base64(input.as_bytes()), expected);
    }
}

fn decode(s: &str) -> Vec<u16> {
    let value = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let mut bytes = vec![];
    for chunk in s.as_bytes().chunks(4) {
        let v = chunk
            .iter()
            .take_while(|&&c| c != b'=')
            .enumerate()
            .fold(0u32, |v, (k, &c)| v | (u32::from(value(c)) << (18 - 6 * k)));
        let n = chunk.iter().filter(|&&c| c != b'=').count() - 1;
        bytes.extend_from_slice(&v.to_be_bytes()[1..=n]);
    }
    bytes
        .chunks(2)
        .map(|b| u16::from_le_bytes([b[0], b[1]]))
        .collect()
}

#[test]
fn the_floor_is_cropped_around_the_mission_and_quantised() {
    // 101 × 101 nodes 10 m apart from (0, 0), z = −(i + j), one NODATA node at (50, 50).
    let n = 101;
    let z: Vec<f64> = (0..n * n)
        .map(|k| -((k % n + k / n) as f64) - 1.0)
        .collect();
    let mut nodata = vec![false; n * n];
    nodata[50 * n + 50] = true;
    let floor = Seafloor::from_nodes(Lattice::new(n, n, 0.0, 0.0, 10.0, 10.0), z, nodata).unwrap();
    // vehicles within [400, 600]², margin 100 m: the crop is [300, 700]² (41 × 41 nodes)
    let f = floor_mesh(&floor, "file", [400.0, 600.0, 400.0, 600.0], 100.0);
    let l = f.lattice;
    assert_eq!((l.nx, l.ny, l.x0, l.y0, l.dx), (41, 41, 300.0, 300.0, 10.0));
    let q = decode(&f.z);
    assert_eq!(q.len(), 41 * 41);
    assert_eq!((f.z_lo, f.z_hi), (-141.0, -61.0));
    assert_eq!(q[20 * 41 + 20], u16::MAX, "NODATA");
    let back = |k: usize| f.z_lo + f64::from(q[k]) * (f.z_hi - f.z_lo) / 65534.0;
    assert!((back(0) - -61.0).abs() < 1e-9);
    assert!((back(3 * 41 + 5) - -69.0).abs() < 2e-3);
    // a mission wider than the grid: the whole grid, no stride needed
    let l = floor_mesh(&floor, "file", [-5e3, 5e3, -5e3, 5e3], 100.0).lattice;
    assert_eq!((l.nx, l.ny, l.x0, l.dx), (101, 101, 0.0, 10.0));
}

#[test]
fn large_floors_are_downsampled_to_at_most_256_vertices_per_axis() {
    let (nx, ny) = (1201, 700);
    let z = vec![-50.0; nx * ny];
    let floor = Seafloor::from_nodes(
        Lattice::new(nx, ny, 0.0, 0.0, 5.0, 5.0),
        z,
        vec![false; nx * ny],
    )
    .unwrap();
    let f = floor_mesh(&floor, "file", [0.0, 6000.0, 0.0, 3500.0], 100.0);
    let l = f.lattice;
    assert!(l.nx <= MAX_FLOOR_VERTICES && l.ny <= MAX_FLOOR_VERTICES);
    assert_eq!((l.nx, l.dx, l.dy), (241, 25.0, 25.0));
    assert!(l.x0 + (l.nx - 1) as f64 * l.dx <= 6000.0);
    assert_eq!((f.z_lo, f.z_hi), (-50.0, -50.0));
}

/// (hue in degrees, HSL lightness) of an sRGB colour.
fn hue_lightness([r, g, b]: [f64; 3]) -> (f64, f64) {
    let (max, min) = (r.max(g).max(b), r.min(g).min(b));
    let d = max - min;
    let h = if d == 0.0 {
        0.0
    } else if max == r {
        60.0 * ((g - b) / d).rem_euclid(6.0)
    } else if max == g {
        60.0 * ((b - r) / d + 2.0)
    } else {
        60.0 * ((r - g) / d + 4.0)
    };
    (h, (max + min) / 2.0)
}

fn rgb(hex: &str) -> [f64; 3] {
    let v = |k: usize| f64::from(u8::from_str_radix(&hex[k..k + 2], 16).unwrap());
    [v(1), v(3), v(5)]
}

/// Every AUV of the 20-colour palette: on the page, its figures' hue, lighter than in the
/// figures and light enough for the dark background, and at least 60 (RGB, of 255) from the
/// USV's and both link colours that scene.js draws.
#[test]
fn auv_colours_keep_the_figures_hues_and_stay_clear_of_the_link_colours() {
    let page_colour = |key: &str| {
        let at = SCENE_JS.find(&format!("{key}: '#")).expect(key) + key.len() + 3;
        rgb(&SCENE_JS[at..at + 7])
    };
    let others = ["usv", "a2u", "a2a"].map(page_colour);
    for i in 0..20 {
        let plotters::style::RGBColor(r, g, b) = crate::figures::vehicle_colour(Some(i));
        let figure = [r, g, b].map(|v| f64::from(v) / 255.0);
        let shown = rgb(&auv_colour(i));
        let (hf, lf) = hue_lightness(figure);
        let (hs, ls) = hue_lightness(shown.map(|v| v / 255.0));
        let dh = (hf - hs).abs().min(360.0 - (hf - hs).abs());
        assert!(
            dh < 1.0 || figure.iter().all(|&v| v == figure[0]),
            "AUV {i}: hue {hf} → {hs}"
        );
        assert!(ls >= lf && ls >= 0.55, "AUV {i}: lightness {lf} → {ls}");
        for (o, name) in others.iter().zip(["USV", "A2U", "A2A"]) {
            let d = o
                .iter()
                .zip(&shown)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt();
            assert!(
                d >= 60.0,
                "AUV {i} ({}) is {d:.0} from the {name} colour",
                auv_colour(i)
            );
        }
    }
}
