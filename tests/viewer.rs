//! The 3D viewer: `shoal view` writes one HTML file, and headless Chromium renders it from
//! file:// with no console or page errors and no network, its canvas drawn, its time slider
//! moving the displayed step, the layers of a simulation's tracks toggled (tests/viewer/check.mjs,
//! driven by playwright-core).
//!
//! Needs node, `npm ci --prefix tests/viewer` and Debian's chromium (`apt-get install -y
//! --no-install-recommends chromium`); `.ci/run` installs them. Without them the browser test
//! fails, saying so, unless SHOAL_SKIP_BROWSER=1.

mod common;

use shoal::scenario::{self, Scenario};
use shoal::seafloor::Seafloor;
use std::path::{Path, PathBuf};
use std::process::Command;

/// 2 AUVs, K = 5, 2 windows: a plan with every ingredient (links, window boundary), fast.
fn small_plan() -> (shoal::plan::Plan, shoal::seafloor::Seafloor) {
    let s = scenario::default_with(&[
        "team.auvs=2".into(),
        "horizon.steps=5".into(),
        "windows=2".into(),
    ])
    .expect("valid overrides");
    common::plan_scenario(&s).expect("plan")
}

fn out_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("viewer")
        .join(name);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn manifest() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// What is missing to run the browser check, with how to install it.
fn missing_browser_tools() -> Vec<String> {
    let mut missing = vec![];
    let node = Command::new("node").arg("--version").output();
    if !node.is_ok_and(|o| o.status.success()) {
        missing.push("node (Node.js 20+, e.g. apt-get install -y nodejs npm)".to_string());
    }
    if !manifest()
        .join("tests/viewer/node_modules/playwright-core")
        .is_dir()
    {
        missing.push("playwright-core: run `npm ci --prefix tests/viewer`".to_string());
    }
    let chromium = std::env::var("CHROMIUM").unwrap_or_else(|_| "/usr/bin/chromium".into());
    if !Path::new(&chromium).exists() {
        missing.push(format!(
            "Chromium at {chromium}: apt-get install -y --no-install-recommends chromium"
        ));
    }
    missing
}

#[test]
fn the_viewer_renders_in_headless_chromium_and_its_slider_moves_the_step() {
    if std::env::var("SHOAL_SKIP_BROWSER").as_deref() == Ok("1") {
        eprintln!("SHOAL_SKIP_BROWSER=1: the browser check of the viewer is skipped");
        return;
    }
    let missing = missing_browser_tools();
    assert!(
        missing.is_empty(),
        "the viewer's browser test needs:\n  {}\n(or set SHOAL_SKIP_BROWSER=1 to skip it)",
        missing.join("\n  ")
    );
    let (mut p, floor) = small_plan();
    // text from the plan must not break out of the page's <script> elements
    p.scenario_source = "</script><script>console.error('injected')</script><!--".into();
    let dir = out_dir("browser");
    let html = dir.join("mission.html");
    let shot = dir.join("viewer.png");
    let _ = std::fs::remove_file(&shot);
    // with a simulation: its tracks and their layer toggles too
    let sim = shoal::sim::simulate(&p, "plan.json", &floor, 1).expect("simulate");
    shoal::viewer::write_html_with_sim(&p, &floor, Some(&sim), &html).expect("write the viewer");
    let out = Command::new("node")
        .arg(manifest().join("tests/viewer/check.mjs"))
        .arg(&html)
        .arg(&shot)
        .output()
        .expect("run node");
    let log = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "browser check failed:\n{log}");
    assert!(log.contains("viewer OK"), "{log}");
    let png = std::fs::read(&shot).expect("screenshot saved");
    assert!(
        png.starts_with(b"\x89PNG") && png.len() > 10_000,
        "screenshot"
    );
    eprintln!("{log}screenshot: {}", shot.display());
}

#[test]
fn shoal_view_writes_one_self_contained_file() {
    let (p, _) = small_plan();
    let dir = out_dir("cli");
    let plan_path = dir.join("plan.json");
    shoal::output::write_plan(&p, &plan_path).unwrap();
    let html = dir.join("mission.html");
    let _ = std::fs::remove_file(&html);
    let out = Command::new(env!("CARGO_BIN_EXE_shoal"))
        .args([
            "view",
            plan_path.to_str().unwrap(),
            "-o",
            html.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stdout).contains("mission.html"));
    let text = std::fs::read_to_string(&html).unwrap();
    assert!(text.starts_with("<!doctype html>"));
    assert!(text.contains("data-module=\"three\""));
    assert!(text.contains("data-module=\"shoal/viewer\" data-entry"));
    // the plan data: only what the page needs
    let start = "<script id=\"plan-data\" type=\"application/json\">";
    let json = &text[text.find(start).unwrap() + start.len()..];
    let json = &json[..json.find("</script>").unwrap()];
    let data: serde_json::Value = serde_json::from_str(json).unwrap();
    let keys: Vec<&str> = data
        .as_object()
        .unwrap()
        .keys()
        .map(|k| k.as_str())
        .collect();
    for k in ["floor", "windows", "metrics", "auvs", "steps", "dt"] {
        assert!(keys.contains(&k), "{k} in {keys:?}");
    }
    for k in ["scenario", "model", "initial"] {
        assert!(!keys.contains(&k), "{k} in {keys:?}");
    }
    assert_eq!(data["windows"].as_array().unwrap().len(), 2);
    assert_eq!(data["windows"][1]["auvs"][0].as_array().unwrap().len(), 6);
    // every AUV in its figures' colour, tinted (viewer::data::auv_colour; check.mjs finds them
    // in the legend): AUV 0's #1f77b4 and AUV 1's #ff7f0e mixed 35 % with white
    assert_eq!(
        data["auv_colours"],
        serde_json::json!(["#6da7ce", "#ffac62"])
    );
    // nothing loaded from elsewhere
    for external in ["<link", " src=\"", " src='"] {
        assert!(!text.contains(external), "{external}");
    }
    assert!(text.contains("MIT License"), "three.js licence");
    let size = text.len();
    assert!((500_000..2_000_000).contains(&size), "{size} bytes");
    // no leftover temporary files beside it
    let entries = std::fs::read_dir(&dir).unwrap().count();
    assert_eq!(entries, 2, "plan.json and mission.html only");
}

#[test]
fn shoal_view_refuses_a_directory_and_a_missing_plan() {
    let (p, floor) = small_plan();
    let dir = out_dir("errors");
    let err = shoal::viewer::write_html(&p, &floor, &dir).unwrap_err();
    assert!(err.to_string().contains("is a directory"), "{err}");
    let out = Command::new(env!("CARGO_BIN_EXE_shoal"))
        .args(["view", "no-such-plan.json", "-o"])
        .arg(dir.join("x.html"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no-such-plan.json"));
}

#[test]
fn a_plan_with_inconsistent_paths_is_refused_by_name() {
    let (mut p, floor) = small_plan();
    p.windows[1].final_.auvs[1].position.pop();
    let err = shoal::viewer::render_html(&p, &floor).unwrap_err();
    assert!(
        err.to_string().contains("window 1: AUV 1 has 5 positions"),
        "{err}"
    );
    let (mut p, _) = small_plan();
    p.windows[0].links.links[2][0].a = 7;
    let err = shoal::viewer::render_html(&p, &floor).unwrap_err();
    assert!(err.to_string().contains("names an AUV beyond"), "{err}");
}

/// The plan data embedded in a viewer page.
fn embedded_data(html: &str) -> serde_json::Value {
    let start = "<script id=\"plan-data\" type=\"application/json\">";
    let json = &html[html.find(start).unwrap() + start.len()..];
    let json = &json[..json.find("</script>").unwrap()];
    serde_json::from_str(json).unwrap()
}

#[test]
fn shoal_view_with_a_sim_embeds_every_auvs_executed_and_estimated_track() {
    let s = Scenario::default();
    let floor = Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    let plan = shoal::planner::Planner::new(&s, &floor).run().unwrap();
    let sim = shoal::sim::simulate(&plan, "plan.json", &floor, 1).unwrap();
    let n = s.team.auvs;
    let without = shoal::viewer::render_html(&plan, &floor).unwrap();
    let html = shoal::viewer::render_html_with_sim(&plan, &floor, Some(&sim)).unwrap();
    assert!(embedded_data(&without).get("sim").is_none());
    let data = embedded_data(&html);
    let d = &data["sim"];
    let epochs = sim.times.len();
    assert!(epochs > 1);
    assert_eq!(d["times"].as_array().unwrap().len(), epochs);
    let e = &d["estimate"];
    assert_eq!(
        (&e["policy"], &e["estimator"], &e["flown"]),
        (
            &serde_json::json!("chain"),
            &serde_json::json!("factor_graph"),
            &serde_json::json!("final")
        )
    );
    for (key, track) in [("executed", &d["executed"]), ("estimate", &e["position"])] {
        let per_auv = track.as_array().unwrap();
        assert_eq!(per_auv.len(), n, "{key}");
        for (i, t) in per_auv.iter().enumerate() {
            let t = t.as_array().unwrap();
            assert_eq!(t.len(), epochs, "{key} of AUV {i}");
            for v in t.iter().flat_map(|p| p.as_array().unwrap()) {
                let v = v.as_f64().unwrap();
                assert!(
                    (v * 10.0 - (v * 10.0).round()).abs() < 1e-6,
                    "{v} not to 0.1 m"
                );
            }
        }
    }
    let x = d["executed"][1][epochs / 2][0].as_f64().unwrap();
    assert!((x - sim.flight.executed[1][epochs / 2][0]).abs() <= 0.05 + 1e-9);
    let chain = sim
        .estimates
        .iter()
        .find(|e| e.policy.name() == "chain" && e.estimator == "factor_graph" && e.flown == "final")
        .unwrap();
    let y = e["position"][0][epochs - 1][1].as_f64().unwrap();
    assert!((y - chain.position[0][epochs - 1][1]).abs() <= 0.05 + 1e-9);
    // the layer toggles
    for id in ["layer-planned", "layer-executed", "layer-estimate"] {
        assert!(html.contains(&format!("id=\"{id}\"")), "{id}");
    }
    let dir = out_dir("sim");
    std::fs::write(dir.join("mission.html"), &html).unwrap();
    std::fs::write(dir.join("mission-plan-only.html"), &without).unwrap();
    eprintln!(
        "default mission: {} bytes without the sim, {} bytes with it ({epochs} epochs, {n} AUVs)",
        without.len(),
        html.len()
    );
    // the CLI
    let plan_path = dir.join("plan.json");
    let sim_path = dir.join("sim.json");
    shoal::output::write_plan(&plan, &plan_path).unwrap();
    std::fs::write(&sim_path, serde_json::to_string(&sim).unwrap()).unwrap();
    let out_path = dir.join("cli.html");
    let out = Command::new(env!("CARGO_BIN_EXE_shoal"))
        .arg("view")
        .arg(&plan_path)
        .arg("--sim")
        .arg(&sim_path)
        .arg("-o")
        .arg(&out_path)
        .output()
        .unwrap();
    assert!(out.status.success(), "{out:?}");
    let cli = embedded_data(&std::fs::read_to_string(&out_path).unwrap());
    assert_eq!(cli["sim"]["executed"].as_array().unwrap().len(), n);
}

#[test]
fn a_sim_of_another_team_or_with_misfit_arrays_is_refused_by_name() {
    let (p, floor) = small_plan();
    let sim = shoal::sim::simulate(&p, "plan.json", &floor, 1).unwrap();
    // arrays that do not fit
    let mut short = sim.clone();
    short.flight.executed[1].pop();
    let err = shoal::viewer::render_html_with_sim(&p, &floor, Some(&short)).unwrap_err();
    assert!(
        err.to_string().contains("flight.executed of AUV 1 has"),
        "{err}"
    );
    // without the chain's estimates (its estimators failed) the page shows the next one
    let mut no_chain = sim.clone();
    no_chain.estimates.retain(|e| e.policy.name() != "chain");
    let shown = shoal::viewer::data::sim(&no_chain, 2)
        .unwrap()
        .estimate
        .unwrap();
    assert_eq!(
        (shown.policy.as_str(), shown.estimator.as_str()),
        ("all_links", "factor_graph")
    );
    // another team, through the CLI: the error names the sim file
    let mut other = sim.clone();
    other.auvs = 3;
    let err = shoal::viewer::render_html_with_sim(&p, &floor, Some(&other)).unwrap_err();
    assert!(err.to_string().contains("3 AUVs, the plan has 2"), "{err}");
    let dir = out_dir("sim-mismatch");
    let plan_path = dir.join("plan.json");
    let sim_path = dir.join("other-sim.json");
    shoal::output::write_plan(&p, &plan_path).unwrap();
    std::fs::write(&sim_path, serde_json::to_string(&other).unwrap()).unwrap();
    let html = dir.join("x.html");
    let _ = std::fs::remove_file(&html);
    let out = Command::new(env!("CARGO_BIN_EXE_shoal"))
        .arg("view")
        .arg(&plan_path)
        .arg("--sim")
        .arg(&sim_path)
        .arg("-o")
        .arg(&html)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("other-sim.json") && stderr.contains("3 AUVs, the plan has 2"),
        "{stderr}"
    );
    assert!(!html.exists());
    // not a sim.json at all
    std::fs::write(&sim_path, "{}").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_shoal"))
        .arg("view")
        .arg(&plan_path)
        .arg("--sim")
        .arg(&sim_path)
        .arg("-o")
        .arg(&html)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("other-sim.json"));
}
