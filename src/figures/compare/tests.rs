//! Tests of the comparison figure: the files, their title and legend, grouping by scenario,
//! method colours, errors, log ticks, jitter and medians.

use super::axis::power_of_ten;
use super::runs::{jitter, median};
use super::*;

/// A run with a plan.
fn run(method: &str, auvs: usize, seed: u64, status: &str, wall_s: f64) -> Row {
    let mut r = Row::key("default", method, auvs, seed);
    r.status = status.into();
    r.wall_s = wall_s;
    let k = seed as f64;
    r.energy = 0.02 * (auvs as f64) * (1.0 + 0.1 * k);
    r.mean_height_m = if method == "mpc" {
        12.0 + k
    } else {
        40.0 + 2.0 * k
    };
    r.explored_km2 = 0.1 * auvs as f64 + 0.01 * k;
    r.usv_moved_m = 100.0 + k;
    r
}

/// Twelve runs: two methods, N = 1 and 3, one violated and one failed.
fn rows() -> Vec<Row> {
    let mut rows = Vec::new();
    for seed in 1..=3 {
        rows.push(run("mpc", 1, seed, "passed", 2.0 + seed as f64));
        let status = if seed == 2 { "violated" } else { "passed" };
        rows.push(run("mpc", 3, seed, status, 10.0 + seed as f64));
        rows.push(run(
            "rrt-like",
            1,
            seed,
            "passed",
            200.0 + 60.0 * seed as f64,
        ));
        if seed == 3 {
            let mut r = Row::key("default", "rrt-like", 3, seed);
            r.status = "failed".into();
            r.error = "no tree reached the goal".into();
            r.wall_s = 600.0;
            rows.push(r);
        } else {
            rows.push(run("rrt-like", 3, seed, "passed", 400.0 + seed as f64));
        }
    }
    rows
}

const TITLE: &str = "MPC vs RRT-like, default scenario, seeds 1–3";

#[test]
fn writes_a_png_and_an_svg_with_the_title_and_every_method() {
    let rows = rows();
    assert_eq!(rows.len(), 12);
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("figs");
    let written = write_compare(&rows, TITLE, &out).unwrap();
    let png_path = out.join("compare.png");
    let svg_path = out.join("compare.svg");
    assert_eq!(written, vec![png_path.clone(), svg_path.clone()]);
    assert!(png_path.is_file() && svg_path.is_file());

    let bytes = std::fs::read(&png_path).unwrap();
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.width, WIDTH);
    assert!(
        info.height >= 2 * PANEL_H && info.height <= 2 * PANEL_H + 400,
        "{}",
        info.height
    );
    let pixels = &buf[..info.buffer_size()];
    let inked = pixels.chunks(3).filter(|p| p != &[255, 255, 255]).count();
    assert!(inked * 50 > pixels.len() / 3, "the PNG is nearly blank");

    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    let texts: Vec<&str> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    let all = texts.join("\n");
    assert!(texts.contains(&TITLE), "no title in {all}");
    for needle in [
        "mpc: 6 runs, 1 violated",
        "rrt-like: 6 runs, 1 made no plan",
        "1 no plan",
        PAPER_LABEL,
        "team size N",
        "wall time (s, log scale)",
        "explored area (km²)",
    ] {
        assert!(all.contains(needle), "no {needle:?} in {all}");
    }
    // log ticks: decades only
    assert!(texts.contains(&"100") && texts.contains(&"1000"), "{all}");
}

#[test]
fn several_scenarios_are_grouped_and_named() {
    let mut rows = rows();
    rows.extend(rows.clone().into_iter().map(|mut r| {
        r.scenario = "ridge".into();
        r
    }));
    let fig = Compare::new(&rows, TITLE).unwrap();
    assert_eq!(fig.slots.len(), 4);
    assert_eq!(fig.scenarios, ["default", "ridge"]);
    let dir = tempfile::tempdir().unwrap();
    write_compare(&rows, TITLE, dir.path()).unwrap();
    let svg = std::fs::read_to_string(dir.path().join("compare.svg")).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let texts: Vec<&str> = doc
        .descendants()
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    for needle in ["default", "ridge", "team size N, by scenario"] {
        assert!(texts.contains(&needle), "no {needle:?} in {texts:?}");
    }
}

#[test]
fn methods_take_fixed_colours_and_others_a_further_palette() {
    let mut rows = rows();
    let mut other = run("ompl-rrtstar", 1, 1, "passed", 50.0);
    other.scenario = "default".into();
    rows.insert(0, other);
    let fig = Compare::new(&rows, TITLE).unwrap();
    let names: Vec<&str> = fig.methods.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["mpc", "rrt-like", "ompl-rrtstar"]);
    assert_eq!(fig.methods[0].colour, MPC);
    assert_eq!(fig.methods[1].colour, RRT_LIKE);
    assert_eq!(fig.methods[2].colour, FURTHER[0]);
}

#[test]
fn no_rows_or_only_failed_runs_are_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let err = write_compare(&[], TITLE, dir.path()).unwrap_err();
    assert!(matches!(err, FigureError::Compare(_)), "{err}");
    assert!(err.to_string().contains("no runs"), "{err}");

    let failed: Vec<Row> = rows()
        .into_iter()
        .map(|mut r| {
            r.status = "failed".into();
            r
        })
        .collect();
    let err = write_compare(&failed, TITLE, dir.path()).unwrap_err();
    assert!(matches!(err, FigureError::Compare(_)), "{err}");
    assert!(err.to_string().contains("none of the 12 runs"), "{err}");
    assert!(!dir.path().join("compare.png").exists());
}

#[test]
fn log_ticks_and_jitter() {
    assert_eq!(power_of_ten(2.0), "100");
    assert_eq!(power_of_ten(-2.0), "0.01");
    assert_eq!(power_of_ten(-5.0), "10⁻⁵");
    assert_eq!(power_of_ten(12.0), "10¹²");
    assert_eq!(power_of_ten(0.5), "");
    for seed in 0..100 {
        let j = jitter(seed);
        assert!((-0.5..0.5).contains(&j));
        assert_eq!(j, jitter(seed));
    }
    assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
    assert_eq!(median(&mut [4.0, 1.0]), Some(2.5));
    assert_eq!(median(&mut []), None);
}
