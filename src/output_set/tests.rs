use super::*;

fn set(out: &Path, files: &[&str], passed: bool) -> Vec<String> {
    let s = OutputSet::begin(out).unwrap();
    for f in files {
        crate::output::write_atomic(&s.dir().join(f), f.as_bytes()).unwrap();
    }
    s.commit(Some(passed)).unwrap()
}

fn staging_left(out: &Path) -> usize {
    std::fs::read_dir(out)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with(STAGING))
        .count()
}

/// The pid of a process that has ended.
fn dead_pid() -> u32 {
    let mut child = std::process::Command::new("true").spawn().unwrap();
    let pid = child.id();
    child.wait().unwrap();
    pid
}

/// Regression: re-planning into a directory left auv3.csv … auv6.csv of an earlier N = 7 plan
/// beside an N = 3 one, and `--no-plot` kept the earlier figures.
#[test]
fn regression_replanning_left_stale_files() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(out.join("figures")).unwrap();
    // an earlier set, written before manifests, and a file of the user's
    for f in ["auv5.csv", "plan.json", "figures/seafloor.png", "notes.txt"] {
        std::fs::write(out.join(f), "old").unwrap();
    }
    let files = set(&out, &["plan.json", "usv.csv", "auv0.csv"], true);
    assert_eq!(files, ["auv0.csv", "plan.json", "usv.csv"]);
    assert!(!out.join("auv5.csv").exists() && !out.join("figures").exists());
    assert_eq!(
        std::fs::read_to_string(out.join("plan.json")).unwrap(),
        "plan.json"
    );
    assert!(out.join("notes.txt").exists(), "not ours: kept");
    // the manifest lists the set; the next set removes what it no longer has
    set(&out, &["plan.json", "figures/final-3d.svg"], false);
    assert!(!out.join("usv.csv").exists() && out.join("figures/final-3d.svg").exists());
    let m: Manifest =
        serde_json::from_str(&std::fs::read_to_string(out.join(MANIFEST)).unwrap()).unwrap();
    assert_eq!(m.files, ["figures/final-3d.svg", "plan.json"]);
    assert_eq!(m.check_passed, Some(false));
    assert_eq!(staging_left(&out), 0);
}

/// Regression: the metrics table's figures (figures/metrics.png, .svg) of a set written
/// before manifests survived a re-run.
#[test]
fn regression_stale_metrics_figures_survived_a_rerun_without_a_manifest() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(out.join("figures")).unwrap();
    for f in ["plan.json", "figures/metrics.png", "figures/metrics.svg"] {
        std::fs::write(out.join(f), "old").unwrap();
    }
    set(&out, &["plan.json"], true);
    assert!(!out.join("figures").exists());
}

/// Regression: `-o` naming an existing file failed only after planning.
#[test]
fn regression_an_output_that_is_a_file_is_refused_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("out");
    std::fs::write(&file, "x").unwrap();
    let e = OutputSet::begin(&file).unwrap_err().to_string();
    assert!(e.contains("is not a directory"), "{e}");
}

/// Regression: a manifest planted in the output folder listing `../x` or `/abs/x` made
/// `shoal plan -o DIR` delete those files and the folders they left empty. Such a manifest is
/// refused before any work, and nothing outside the folder is touched.
#[test]
fn regression_a_planted_manifest_deleted_files_outside_the_output_folder() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim.txt");
    let deep = dir.path().join("keep/inner.txt");
    std::fs::create_dir_all(deep.parent().unwrap()).unwrap();
    std::fs::write(&victim, "mine").unwrap();
    std::fs::write(&deep, "mine").unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(out.join("figures")).unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let abs = victim.to_string_lossy().into_owned();
    for listed in [
        "../victim.txt",
        abs.as_str(),
        "figures/../../victim.txt",
        "../keep/inner.txt",
        "./plan.json",
        "notes.txt",
        "figures/notes.txt",
        ".shoal-outputs.json",
        "",
        "figures/sub/seafloor.png",
    ] {
        let m = serde_json::json!({ "files": [listed], "check_passed": true });
        std::fs::write(out.join(MANIFEST), m.to_string()).unwrap();
        let e = OutputSet::begin(&out).unwrap_err().to_string();
        assert!(e.contains("cannot be trusted"), "{listed}: {e}");
        assert!(
            e.contains("is not a file this command writes"),
            "{listed}: {e}"
        );
    }
    // a damaged manifest is refused too
    for text in ["{", "[]", "{\"files\": 3}", "\u{1b}[31m"] {
        std::fs::write(out.join(MANIFEST), text).unwrap();
        let e = OutputSet::begin(&out).unwrap_err().to_string();
        assert!(e.contains("cannot be trusted"), "{text}: {e}");
        assert!(!e.contains('\u{1b}'), "{e}");
    }
    // a manifest that is a link is never read through
    std::fs::remove_file(out.join(MANIFEST)).unwrap();
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(&victim, out.join(MANIFEST)).unwrap();
        let e = OutputSet::begin(&out).unwrap_err().to_string();
        assert!(e.contains("not a regular file"), "{e}");
        std::fs::remove_file(out.join(MANIFEST)).unwrap();
    }
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "mine");
    assert_eq!(std::fs::read_to_string(&deep).unwrap(), "mine");
    assert_eq!(
        std::fs::read_to_string(out.join("notes.txt")).unwrap(),
        "mine"
    );
}

/// Links inside the output folder are never followed: a figures/ that links elsewhere is
/// neither emptied nor written through, and a file of the earlier set that is a link is left.
#[cfg(unix)]
#[test]
fn links_in_the_output_folder_are_never_followed() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let elsewhere = dir.path().join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    std::fs::write(elsewhere.join("seafloor.png"), "mine").unwrap();
    std::fs::write(elsewhere.join("usv.csv"), "mine").unwrap();
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    symlink(&elsewhere, out.join("figures")).unwrap();
    symlink(elsewhere.join("usv.csv"), out.join("usv.csv")).unwrap();
    let m = serde_json::json!({ "files": ["figures/seafloor.png", "usv.csv"] });
    std::fs::write(out.join(MANIFEST), m.to_string()).unwrap();
    // a new set without those files: they are not removed through the links
    set(&out, &["plan.json"], true);
    assert_eq!(
        std::fs::read_to_string(elsewhere.join("seafloor.png")).unwrap(),
        "mine"
    );
    assert_eq!(
        std::fs::read_to_string(elsewhere.join("usv.csv")).unwrap(),
        "mine"
    );
    assert!(out.join("usv.csv").is_symlink());
    // a new set with figures is refused rather than written through the link
    let s = OutputSet::begin(&out).unwrap();
    crate::output::write_atomic(&s.dir().join("figures/seafloor.png"), b"new").unwrap();
    let e = s.commit(Some(true)).unwrap_err().to_string();
    assert!(e.contains("real folders"), "{e}");
    assert_eq!(
        std::fs::read_to_string(elsewhere.join("seafloor.png")).unwrap(),
        "mine"
    );
    // and a staging-named link is not removed, nor what it points to
    symlink(&elsewhere, out.join(format!("{STAGING}host-1-abcdef"))).unwrap();
    settle_where(&out, |_, _| true);
    assert!(elsewhere.join("usv.csv").exists());
}

/// A killed run's staging directory is removed by the next run; a running process's is left.
#[test]
fn a_killed_runs_staging_is_removed_and_a_running_ones_kept() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let tag = crate::atomic_file::tag();
    let host = tag.split_once('-').map_or("", |(h, _)| h).to_string();
    let killed = out.join(format!("{STAGING}{host}-{}-abcdef", dead_pid()));
    let running = out.join(format!("{STAGING}{tag}ghijkl"));
    for d in [&killed, &running] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("plan.json"), "half").unwrap();
    }
    let s = OutputSet::begin(&out).unwrap();
    assert!(!killed.exists());
    assert!(running.exists());
    drop(s);
}

/// Every cut of a commit, as a kill there would leave it, ends in one whole set after the next
/// run opens the folder: the earlier set when the cut comes before the journal, the new one
/// after.
#[test]
fn a_commit_cut_anywhere_leaves_one_whole_set() {
    let old = [
        "plan.json",
        "usv.csv",
        "auv0.csv",
        "auv1.csv",
        "figures/depth.png",
    ];
    let new = ["plan.json", "usv.csv", "auv0.csv", "figures/speed.svg"];
    let whole = |out: &Path, files: &[&str], text: &str| {
        let mut have = Vec::new();
        collect(out, "", &mut have).unwrap();
        have.retain(|f| !f.starts_with(".shoal-") && f != "notes.txt");
        have.sort();
        let mut want: Vec<String> = files.iter().map(|f| f.to_string()).collect();
        want.sort();
        have == want
            && files
                .iter()
                .all(|f| std::fs::read_to_string(out.join(f)).unwrap() == text)
    };
    let mut outcomes = [0usize; 2];
    for cut in 0.. {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let s = OutputSet::begin(&out).unwrap();
        for f in old {
            crate::output::write_atomic(&s.dir().join(f), b"old").unwrap();
        }
        s.commit(Some(true)).unwrap();
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
        let s = OutputSet::begin(&out).unwrap();
        for f in new {
            crate::output::write_atomic(&s.dir().join(f), b"new").unwrap();
        }
        let staging = s.dir().to_path_buf();
        cut::LEFT.with(|c| c.set(Some(cut)));
        let done = s.commit(Some(true));
        cut::LEFT.with(|c| c.set(None));
        if done.is_ok() {
            assert!(whole(&out, &new, "new"), "uncut");
            assert!(cut > 3, "the commit has several steps");
            break;
        }
        // a cut before the journal: the TempDir removed the staging directory on drop, as
        // the next run would remove a staging directory without a journal
        if !staging.exists() {
            assert!(whole(&out, &old, "old"), "cut {cut} before the journal");
            outcomes[0] += 1;
            continue;
        }
        settle_where(&out, |_, _| true);
        assert!(whole(&out, &new, "new"), "cut {cut} after the journal");
        assert_eq!(staging_left(&out), 0, "cut {cut}");
        let m: Manifest =
            serde_json::from_str(&std::fs::read_to_string(out.join(MANIFEST)).unwrap()).unwrap();
        assert_eq!(m.files.len(), new.len());
        assert_eq!(
            std::fs::read_to_string(out.join("notes.txt")).unwrap(),
            "mine"
        );
        outcomes[1] += 1;
    }
    assert!(outcomes[0] >= 1 && outcomes[1] >= 5, "{outcomes:?}");
}

/// A journal planted in a staging directory is obeyed only for the set's own files inside the
/// folder.
#[test]
fn a_planted_journal_is_not_obeyed() {
    let dir = tempfile::tempdir().unwrap();
    let victim = dir.path().join("victim.txt");
    std::fs::write(&victim, "mine").unwrap();
    let out = dir.path().join("out");
    let staging = out.join(format!("{STAGING}host-1-abcdef"));
    std::fs::create_dir_all(&staging).unwrap();
    let j = serde_json::json!({
        "kind": "plan", "files": [], "remove": ["../victim.txt"], "check_passed": true
    });
    std::fs::write(staging.join(JOURNAL), j.to_string()).unwrap();
    settle_where(&out, |_, _| true);
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "mine");
    assert!(!staging.exists());
}

#[test]
fn each_kind_owns_only_its_names() {
    let sim = Kind::Simulation("sim.json".into());
    let grid = Kind::Grid("floor.asc".into());
    assert!(sim.owns("sim.json") && sim.owns("figures/sim-error.png"));
    assert!(!sim.owns("plan.json") && !sim.owns("figures/depth.png"));
    assert!(grid.owns("floor.asc") && grid.owns("floor.prj") && !grid.owns("other.prj"));
    assert!(!Kind::Grid("floor.tif".into()).owns("floor.prj"));
    assert!(Kind::Plan.owns("auv12.csv") && !Kind::Plan.owns("auv.csv"));
    assert!(Kind::Plan.owns("figures/metrics.svg") && !Kind::Plan.owns("figures/x.svg"));
    // shoal plan --fly: the plan's flight is part of its set
    assert!(Kind::Plan.owns("sim.json") && Kind::Plan.owns("figures/sim-tracks.svg"));
    assert!(!Kind::Plan.owns("other.json"));
    assert_eq!(sim.manifest(), None);
    assert_eq!(Kind::Plan.manifest(), Some(MANIFEST));
}
