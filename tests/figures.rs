//! Figures: `shoal plot` and `shoal plan --plot/--no-plot` write every figure as a PNG that
//! decodes and an SVG that parses, with the axis labels in it; bad input names the file.

mod common;
use common::shoal;

use shoal::figures::{FIGURES, TABLE};
use shoal::mission::scenario_floor;
use shoal::scenario;
use std::path::{Path, PathBuf};

/// A small plan (2 AUVs, 6 steps, 2 windows) written to `dir/plan.json`.
fn small_plan(dir: &Path) -> (shoal::plan::Plan, PathBuf) {
    let s = scenario::default_with(&[
        "team.auvs=2".into(),
        "horizon.steps=6".into(),
        "windows=2".into(),
    ])
    .unwrap();
    let (p, _) = common::plan_scenario(&s).expect("plan");
    let path = dir.join("plan.json");
    shoal::output::write_plan(&p, &path).unwrap();
    (p, path)
}

/// Axis labels (or, for the table, row labels) that each figure's SVG must contain.
fn labels(stem: &str) -> &'static [&'static str] {
    match stem {
        "seafloor" | "step1-top" | "links-top" | "final-top" => {
            &["x, east (m)", "y, north (m)", "floor elevation z (m)"]
        }
        "step1-3d" | "links-3d" | "final-3d" => &["x, east (m)", "y, north (m)", "z (m)"],
        "link-lengths" => &["time t (s)", "link length (m)", "A2U link"],
        "speed" => &["time t (s)", "speed (m/s)", "AUV 1", "USV"],
        "heading-rate" => &["time t (s)", "heading rate", "mrad/s"],
        "depth" => &["time t (s)", "z (m)", "AUV 0", "AUV 1"],
        "metrics" => &["input energy", "explored area", "window 1", "mission"],
        other => panic!("no labels listed for figure {other}"),
    }
}

/// Checks that `dir/STEM.png` decodes, is at least 800×300 and is not nearly blank.
fn assert_png(dir: &Path, stem: &str) {
    let png = dir.join(format!("{stem}.png"));
    let bytes = std::fs::read(&png).unwrap_or_else(|e| panic!("{}: {e}", png.display()));
    let mut reader = png::Decoder::new(std::io::Cursor::new(bytes))
        .read_info()
        .unwrap_or_else(|e| panic!("{stem}.png does not decode: {e}"));
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert!(
        info.width >= 800 && info.height >= 300,
        "{stem}.png is {}×{}",
        info.width,
        info.height
    );
    let pixels = &buf[..info.buffer_size()];
    let inked = pixels.chunks(3).filter(|p| p != &[255, 255, 255]).count();
    assert!(inked * 50 > pixels.len() / 3, "{stem}.png is nearly blank");
}

/// `dir/STEM.svg`, checked to parse as an SVG with no raster placeholder left, and the text of
/// its `<text>` elements, one a line.
fn svg_text(dir: &Path, stem: &str) -> String {
    let svg_path = dir.join(format!("{stem}.svg"));
    let svg = std::fs::read_to_string(&svg_path).unwrap();
    let doc =
        roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{stem}.svg is not XML: {e}"));
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    // Depth rasters are embedded as PNG data, not left as placeholders.
    assert!(
        !svg.contains("#010203"),
        "{stem}.svg has a raster placeholder"
    );
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .collect::<Vec<_>>()
        .join("\n")
}

fn assert_figures(dir: &Path) {
    for stem in FIGURES.iter().chain([&TABLE]) {
        assert_png(dir, stem);
        let text = svg_text(dir, stem);
        for label in labels(stem) {
            assert!(text.contains(label), "{stem}.svg lacks \"{label}\"");
        }
        assert!(
            text.contains("N = 2, seed 1, windows 0–1"),
            "{stem}.svg: no scenario in title"
        );
    }
}

#[test]
fn plot_writes_every_figure_as_png_and_svg_and_plan_plots_by_default() {
    let dir = tempfile::tempdir().unwrap();
    let (p, plan_path) = small_plan(dir.path());

    // The library returns every path it wrote.
    let floor = shoal::check::load_floor(&p, None).unwrap();
    let lib_dir = dir.path().join("lib");
    let written = shoal::figures::write_all(&p, &floor, &lib_dir).unwrap();
    assert_eq!(written.len(), 2 * (FIGURES.len() + 1));
    assert!(written.iter().all(|f| f.exists()));

    // The command, with -o.
    let out = dir.path().join("figs");
    let st = shoal()
        .arg("plot")
        .arg(&plan_path)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    assert_figures(&out);

    // Without -o: `figures` beside the plan.
    let st = shoal().arg("plot").arg(&plan_path).output().unwrap();
    assert!(
        st.status.success(),
        "{}",
        String::from_utf8_lossy(&st.stderr)
    );
    assert!(dir.path().join("figures/final-top.png").exists());
}

#[test]
fn plan_plots_unless_told_not_to() {
    let dir = tempfile::tempdir().unwrap();
    let run = |out: &Path, extra: &[&str]| {
        let st = shoal()
            .args([
                "plan",
                "--set",
                "team.auvs=2",
                "--set",
                "horizon.steps=4",
                "-o",
            ])
            .arg(out)
            .args(extra)
            .output()
            .unwrap();
        assert!(
            st.status.success(),
            "{}",
            String::from_utf8_lossy(&st.stderr)
        );
    };
    let with = dir.path().join("with");
    run(&with, &[]);
    assert!(with.join("figures/final-top.png").exists());
    assert!(with.join("figures/metrics.svg").exists());
    let without = dir.path().join("without");
    run(&without, &["--no-plot"]);
    assert!(without.join("plan.json").exists());
    assert!(!without.join("figures").exists());
}

#[test]
fn bad_plans_are_refused_naming_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("figs");
    let plot = |plan: &Path| {
        let st = shoal()
            .arg("plot")
            .arg(plan)
            .arg("-o")
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(st.status.code(), Some(2));
        String::from_utf8_lossy(&st.stderr).into_owned()
    };

    let missing = dir.path().join("missing.json");
    let err = plot(&missing);
    assert!(err.contains("missing.json"), "{err}");

    let other = dir.path().join("other.json");
    std::fs::write(&other, r#"{"format": "shoal-plan/1"}"#).unwrap();
    let err = plot(&other);
    assert!(
        err.contains("other.json") && err.contains("shoal-plan/1"),
        "{err}"
    );

    let broken = dir.path().join("broken.json");
    std::fs::write(&broken, "{ not json").unwrap();
    let err = plot(&broken);
    assert!(err.contains("broken.json"), "{err}");
    assert!(!out.exists(), "nothing is written for a bad plan");
}

#[test]
fn a_plan_with_missing_vehicles_is_refused_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let (mut p, _) = small_plan(dir.path());
    p.windows[1].final_.auvs.pop();
    let path = dir.path().join("cut.json");
    shoal::output::write_plan(&p, &path).unwrap();
    let st = shoal().arg("plot").arg(&path).output().unwrap();
    let err = String::from_utf8_lossy(&st.stderr);
    assert_eq!(st.status.code(), Some(2), "{err}");
    assert!(
        err.contains("cut.json") && err.contains("window 1 final has 1 AUVs"),
        "{err}"
    );
}

/// Regression (issue 13): with one AUV the link legends listed A2A links, and with K = 1 the
/// heading-rate plot was empty without a word. The legends now leave A2A out for one AUV, and
/// an empty heading-rate plot says why in its title.
#[test]
fn regression_one_auv_one_step_figures_say_what_they_show() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("figures_n1_k1");
    let _ = std::fs::remove_dir_all(&dir);
    let s = scenario::default_with(&["team.auvs=1".into(), "horizon.steps=1".into()]).unwrap();
    let (floor, _) = scenario_floor(&s, Path::new("")).unwrap();
    let p = shoal::Planner::new(&s, &floor).run().expect("plan");
    shoal::figures::write_all(&p, &floor, &dir).expect("figures");
    let svg = |stem: &str| std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
    let note = "AUV heading rates: none (no two steps with a heading)";
    assert!(
        svg("heading-rate").contains(note),
        "no note on the empty plot"
    );
    for stem in ["links-top", "links-3d", "link-lengths"] {
        let text = svg(stem);
        assert!(text.contains("A2U link"), "{stem}: no A2U entry");
        assert!(
            !text.contains("A2A link"),
            "{stem} lists A2A links for one AUV"
        );
    }
}

/// `shoal simulate`'s figures of the default plan: both as a PNG that decodes and an SVG that
/// parses; the error plot's legend names every policy, both estimators and the Step 1 flight,
/// the top view the estimate it shows; a record that does not fit the plan is refused.
#[test]
fn sim_figures_show_every_policy_and_the_estimate_as_png_and_svg() {
    use shoal::figures::{write_sim, write_sim_with, FigureError, SIM_FIGURES};
    use shoal::sim::policy::Policy;
    use shoal::{Planner, Scenario, Seafloor};

    let s = Scenario::default();
    let floor = Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    let plan = Planner::new(&s, &floor).run().expect("plan");
    let sim = shoal::sim::simulate(&plan, "plan.json", &floor, 1).expect("simulation");
    let dir = tempfile::tempdir().unwrap();
    let written = write_sim(&plan, &floor, &sim, dir.path()).expect("figures");
    assert_eq!(written.len(), 2 * SIM_FIGURES.len());
    for stem in SIM_FIGURES {
        for ext in ["png", "svg"] {
            let f = dir.path().join(format!("{stem}.{ext}"));
            assert!(written.contains(&f), "{} not returned", f.display());
            let len = std::fs::metadata(&f).unwrap().len();
            assert!(len > 20_000, "{} has {len} bytes", f.display());
        }
        assert_png(dir.path(), stem);
    }

    let text = svg_text(dir.path(), "sim-error");
    let expected = [
        "dead reckoning",
        "A2U only",
        "planned chain",
        "all links",
        "factor graph",
        "EKF",
        "Step 1 paths (no chain), all links",
        "planned links received",
        "time t (s)",
        "team position error (m)",
        "simulation seed 1",
        "N = 5, seed 1, window 0",
    ];
    for label in expected {
        assert!(text.contains(label), "sim-error.svg lacks \"{label}\"");
    }
    let text = svg_text(dir.path(), "sim-tracks");
    let expected = [
        "x, east (m)",
        "y, north (m)",
        "floor elevation z (m)",
        "USV",
        "AUV 4",
        "planned path",
        "executed path",
        "estimate: planned chain, factor graph",
        "2-σ ellipse",
    ];
    for label in expected {
        assert!(text.contains(label), "sim-tracks.svg lacks \"{label}\"");
    }

    // Another estimate on request; one the record lacks, or a record of another team, is an
    // error, not a panic.
    let other = dir.path().join("ekf");
    write_sim_with(&plan, &floor, &sim, &other, Policy::AllLinks, "ekf").expect("figures");
    assert!(svg_text(&other, "sim-tracks").contains("estimate: all links, EKF"));
    let err = write_sim_with(&plan, &floor, &sim, &other, Policy::Chain, "kalman").unwrap_err();
    assert!(
        matches!(&err, FigureError::Sim(why) if why.contains("kalman")),
        "{err}"
    );
    let mut cut = sim.clone();
    cut.flight.executed.pop();
    let err = write_sim(&plan, &floor, &cut, &other).unwrap_err();
    assert!(matches!(err, FigureError::Sim(_)), "{err}");
}
