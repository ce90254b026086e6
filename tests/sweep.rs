//! `shoal sweep`: a study run locally, in shards collected afterwards, resumed after an
//! interruption, and with runs that fail.

mod common;
use common::shoal;

use shoal::sweep::{self, Options, Shard, Study};
use std::path::Path;

/// A small study: 2 seeds × 2 team sizes, 6 steps.
const STUDY: &str =
    "[set]\n\"horizon.steps\" = 6\n[axes]\nseed = \"1..2\"\n\"team.auvs\" = [1, 2]\n";

fn study_in(dir: &Path, text: &str) -> Study {
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    Study::load(&path).unwrap()
}

/// The table's rows without the columns that are times (which differ run to run).
fn rows_without_times(path: &Path) -> Vec<Vec<String>> {
    let mut r = csv::Reader::from_path(path).unwrap();
    let header = r.headers().unwrap().clone();
    let keep: Vec<usize> = (0..header.len())
        .filter(|&i| header[i] != *"wall_s")
        .collect();
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            keep.iter().map(|&i| rec[i].to_string()).collect()
        })
        .collect()
}

#[test]
fn shards_collected_are_the_local_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let local = dir.path().join("local");
    let o = sweep::run(
        &study,
        &Options {
            out: local.clone(),
            shard: None,
            resume: false,
        },
        &|_| {},
    )
    .unwrap();
    assert_eq!((o.total, o.mine, o.passed), (4, 4, 4));
    let sharded = dir.path().join("sharded");
    for i in 0..3 {
        let opts = Options {
            out: sharded.clone(),
            shard: Some(Shard::new(i, 3).unwrap()),
            resume: false,
        };
        let o = sweep::run(&study, &opts, &|_| {}).unwrap();
        assert_eq!(o.mine, [2, 1, 1][i]);
    }
    let (table, rows) = sweep::collect(&sharded).unwrap();
    assert_eq!(rows, 4);
    let (a, b) = (
        rows_without_times(&sweep::table_path(&local)),
        rows_without_times(&table),
    );
    assert_eq!(a, b);
    // sorted by run, every swept key a column (seed is the row's own)
    assert_eq!(
        a.iter().map(|r| r[0].clone()).collect::<Vec<_>>(),
        ["0", "1", "2", "3"]
    );
    let header = csv::Reader::from_path(&table)
        .unwrap()
        .headers()
        .unwrap()
        .clone();
    assert_eq!(&header[0], "run");
    assert_eq!(&header[1], "team.auvs");
    assert_eq!(header.iter().filter(|h| *h == "seed").count(), 1);
}

#[test]
fn a_resumed_sweep_makes_only_the_runs_its_table_lacks() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let out = dir.path().join("out");
    let opts = Options {
        out: out.clone(),
        shard: None,
        resume: false,
    };
    sweep::run(&study, &opts, &|_| {}).unwrap();
    // an interrupted sweep: two rows, the second cut short
    let table = sweep::table_path(&out);
    let text = std::fs::read_to_string(&table).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let cut = format!("{}\n{}\n{}", lines[0], lines[3], &lines[1][..20]);
    std::fs::write(&table, cut).unwrap();
    let seen = std::sync::Mutex::new(Vec::new());
    let o = sweep::run(
        &study,
        &Options {
            resume: true,
            ..opts
        },
        &|d| seen.lock().unwrap().push(d.index),
    )
    .unwrap();
    assert_eq!(o.skipped, 1);
    let mut seen = seen.into_inner().unwrap();
    seen.sort();
    assert_eq!(seen, [0, 1, 3]);
    let rows = rows_without_times(&table);
    assert_eq!(rows.len(), 4, "{rows:?}");
    assert_eq!(
        rows.iter().map(|r| r[0].clone()).collect::<Vec<_>>(),
        ["0", "1", "2", "3"]
    );
}

#[test]
fn a_run_that_fails_records_why_and_the_sweep_goes_on() {
    let dir = tempfile::tempdir().unwrap();
    // team.auvs = 0 is not a team; the other run plans
    let study = study_in(
        dir.path(),
        "[set]\n\"horizon.steps\" = 6\n[axes]\n\"team.auvs\" = [0, 1]\n",
    );
    let out = dir.path().join("out");
    let o = sweep::run(
        &study,
        &Options {
            out: out.clone(),
            shard: None,
            resume: false,
        },
        &|_| {},
    )
    .unwrap();
    assert_eq!((o.failed, o.passed), (1, 1));
    let mut r = csv::Reader::from_path(sweep::table_path(&out)).unwrap();
    let header = r.headers().unwrap().clone();
    let status = header.iter().position(|h| h == "status").unwrap();
    let error = header.iter().position(|h| h == "error").unwrap();
    let recs: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
    assert_eq!(&recs[0][status], "failed");
    assert!(recs[0][error].contains("team.auvs"), "{}", &recs[0][error]);
    assert_eq!(&recs[1][status], "passed");
}

#[test]
fn the_shard_comes_from_slurm_or_kubernetes() {
    let env = |pairs: &'static [(&'static str, &'static str)]| {
        move |k: &str| pairs.iter().find(|p| p.0 == k).map(|p| p.1.to_string())
    };
    assert_eq!(Shard::from_env(env(&[])).unwrap(), None);
    assert_eq!(
        Shard::from_env(env(&[
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "4")
        ]))
        .unwrap(),
        Some(Shard { index: 3, count: 4 })
    );
    assert_eq!(
        Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "0"), ("SHOAL_SHARDS", "2")])).unwrap(),
        Some(Shard { index: 0, count: 2 })
    );
    assert!(Shard::from_env(env(&[
        ("SLURM_ARRAY_TASK_ID", "4"),
        ("SLURM_ARRAY_TASK_COUNT", "4")
    ]))
    .is_err());
    assert!(Shard::from_env(env(&[("JOB_COMPLETION_INDEX", "1")]))
        .unwrap_err()
        .contains("SHOAL_SHARDS"));
    assert_eq!(Shard::parse("1/3").unwrap(), Shard { index: 1, count: 3 });
    assert!(Shard::parse("3/3").is_err() && Shard::parse("x").is_err());
}

#[test]
fn cli_sweep_and_collect() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("study.toml"), STUDY).unwrap();
    let out = dir.path().join("out");
    let study = dir.path().join("study.toml");
    for shard in ["0/2", "1/2"] {
        let (code, stdout, stderr) = common::run(shoal().args([
            "sweep",
            study.to_str().unwrap(),
            "--shard",
            shard,
            "-q",
            "-o",
            out.to_str().unwrap(),
        ]));
        assert_eq!(code, 0, "{stdout}\n{stderr}");
        assert!(
            stdout.contains(&format!("(shard {shard}: 2 runs): 2 passed")),
            "{stdout}"
        );
    }
    let (code, stdout, _) = common::run(shoal().args(["sweep", "collect", out.to_str().unwrap()]));
    assert_eq!(code, 0);
    assert!(stdout.contains("runs.csv (4 runs)"), "{stdout}");
    // the shard from Slurm's environment
    let (code, stdout, _) = common::run(
        shoal()
            .args([
                "sweep",
                study.to_str().unwrap(),
                "-q",
                "-o",
                out.to_str().unwrap(),
            ])
            .env("SLURM_ARRAY_TASK_ID", "1")
            .env("SLURM_ARRAY_TASK_COUNT", "4"),
    );
    assert_eq!(code, 0);
    assert!(stdout.contains("(shard 1/4: 1 runs)"), "{stdout}");
    // a bad study names its file and key
    std::fs::write(&study, "[axes]\nseed = \"9..1\"\n").unwrap();
    let (code, _, stderr) = common::run(shoal().args(["sweep", study.to_str().unwrap()]));
    assert_eq!(code, 2);
    assert!(stderr.contains("study.toml: axes.\"seed\""), "{stderr}");
}

#[test]
fn a_simulated_study_records_each_plans_localization() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(
        dir.path(),
        "simulate = true\n[set]\n\"horizon.steps\" = 6\n[axes]\n\"team.auvs\" = [0, 2]\n",
    );
    let out = dir.path().join("out");
    let opts = Options {
        out: out.clone(),
        shard: None,
        resume: false,
    };
    sweep::run(&study, &opts, &|_| {}).unwrap();
    let mut r = csv::Reader::from_path(sweep::table_path(&out)).unwrap();
    let header = r.headers().unwrap().clone();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let recs: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
    // the failed run has no flight; the other was flown and localized by its chain
    assert_eq!(&recs[0][col("sim_status")], "no plan");
    assert_eq!(&recs[1][col("sim_status")], "flown");
    assert_eq!(&recs[1][col("sim_below_floor")], "0");
    let num = |name: &str| recs[1][col(name)].parse::<f64>().unwrap();
    assert!(num("sim_tracking_rms_m") < 5.0);
    assert!(num("sim_chain_end_m") < num("sim_dead_reckoning_end_m"));
    assert!(num("sim_all_links_end_m").is_finite());
}
