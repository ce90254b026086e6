//! The 3D viewer: `shoal view` writes one HTML file, and headless Chromium renders it from
//! file:// with no console or page errors and no network, its canvas drawn, its time slider
//! moving the displayed step (tests/viewer/check.mjs, driven by playwright-core).
//!
//! Needs node, `npm ci --prefix tests/viewer` and Debian's chromium (`apt-get install -y
//! --no-install-recommends chromium`); `.ci/run` installs them. Without them the browser test
//! fails, saying so, unless SHOAL_SKIP_BROWSER=1.

mod common;

use shoal::scenario;
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
    shoal::viewer::write_html(&p, &floor, &html).expect("write the viewer");
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
