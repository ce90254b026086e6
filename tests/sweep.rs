//! `shoal sweep`: a study run locally, in shards collected afterwards, resumed after an
//! interruption, and with runs that fail.

mod common;
use common::shoal;

use parquet::basic::{LogicalType, Repetition, Type as Physical};
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::record::Field;
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

/// Run every run of `study` on this machine into `out` (no shard, not resumed).
fn run_local(study: &Study, out: &Path) -> sweep::Outcome {
    let opts = Options {
        out: out.to_path_buf(),
        shard: None,
        resume: false,
    };
    sweep::run(study, &opts, &|_| {}).unwrap()
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

/// A Parquet column: its name, physical and logical types and repetition.
type ParquetColumn = (String, Physical, Option<LogicalType>, Repetition);

/// The Parquet table beside CSV table `csv`, checked to hold the CSV's columns in order and its
/// values (a null where the CSV has an empty cell or NaN): its columns and rows.
fn parquet_matches_csv(csv: &Path) -> (Vec<ParquetColumn>, Vec<Vec<Field>>) {
    let file = std::fs::File::open(csv.with_extension("parquet")).unwrap();
    let reader = SerializedFileReader::new(file).unwrap();
    let meta = reader.metadata().file_metadata();
    let columns: Vec<ParquetColumn> = meta
        .schema_descr()
        .columns()
        .iter()
        .map(|c| {
            let t = c.self_type();
            (
                c.name().to_string(),
                c.physical_type(),
                c.logical_type_ref().cloned(),
                t.get_basic_info().repetition(),
            )
        })
        .collect();
    let kv = meta.key_value_metadata().cloned().unwrap_or_default();
    assert!(kv.iter().any(|k| k.key == "shoal.version"), "{kv:?}");
    let rows: Vec<Vec<Field>> = reader
        .get_row_iter(None)
        .unwrap()
        .map(|r| {
            r.unwrap()
                .get_column_iter()
                .map(|(_, f)| f.clone())
                .collect()
        })
        .collect();
    let mut r = csv::Reader::from_path(csv).unwrap();
    let header = r.headers().unwrap().clone();
    assert_eq!(
        columns.iter().map(|c| c.0.as_str()).collect::<Vec<_>>(),
        header.iter().collect::<Vec<_>>()
    );
    let recs: Vec<csv::StringRecord> = r.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), recs.len());
    for (row, rec) in rows.iter().zip(&recs) {
        for ((field, cell), col) in row.iter().zip(rec.iter()).zip(&header) {
            let same = match field {
                Field::Null => cell.is_empty() || cell == "NaN",
                Field::Long(i) => cell.parse::<i64>() == Ok(*i),
                Field::Double(x) => cell.parse::<f64>() == Ok(*x),
                Field::Str(s) => s == cell,
                Field::Bool(b) => cell == b.to_string(),
                _ => false,
            };
            assert!(same, "column {col}: Parquet {field:?}, CSV \"{cell}\"");
        }
    }
    (columns, rows)
}

/// The Parquet type of `name` among `columns`: physical, whether a UTF8 string, optional.
fn parquet_type(columns: &[ParquetColumn], name: &str) -> (Physical, bool, bool) {
    let c = columns.iter().find(|c| c.0 == name).unwrap();
    (
        c.1,
        c.2 == Some(LogicalType::String),
        c.3 == Repetition::OPTIONAL,
    )
}

#[test]
fn the_table_is_also_written_as_typed_parquet() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(
        dir.path(),
        "[set]\n\"horizon.steps\" = 6\n[axes]\n\"team.auvs\" = [0, 1]\n\
         \"auv.max_speed\" = [1.5, 2]\n",
    );
    let out = dir.path().join("out");
    let o = run_local(&study, &out);
    assert_eq!(o.parquet, Some(sweep::parquet_path(&out)));
    let (columns, rows) = parquet_matches_csv(&sweep::table_path(&out));
    assert_eq!(rows.len(), 4);
    let (int, real, text) = (
        (Physical::INT64, false, true),
        (Physical::DOUBLE, false, true),
        (Physical::BYTE_ARRAY, true, true),
    );
    for (name, want) in [
        ("run", int),
        ("team.auvs", int),
        ("auv.max_speed", real),
        ("scenario", text),
        ("auvs", int),
        ("seed", int),
        ("status", text),
        ("error", text),
        ("wall_s", real),
        ("explored_km2", real),
        ("out_of_band", int),
        ("margin_c1_5_m", real),
        ("samples_drawn", int),
    ] {
        assert_eq!(parquet_type(&columns, name), want, "{name}");
    }
    // a run that failed: its error a string, its measures nulls
    let col = |name: &str| columns.iter().position(|c| c.0 == name).unwrap();
    let failed = &rows[0];
    assert_eq!(failed[col("status")], Field::Str("failed".into()));
    assert!(matches!(&failed[col("error")], Field::Str(e) if e.contains("team.auvs")));
    assert_eq!(failed[col("explored_km2")], Field::Null);
    assert_eq!(failed[col("p2_objective")], Field::Null);
    assert_eq!(failed[col("auv.max_speed")], Field::Double(1.5));
    // a run that passed: no error (a null), its measures numbers
    let passed = &rows[2];
    assert_eq!(passed[col("status")], Field::Str("passed".into()));
    assert_eq!(passed[col("error")], Field::Null);
    assert!(matches!(passed[col("explored_km2")], Field::Double(x) if x > 0.0));
    assert_eq!(passed[col("team.auvs")], Field::Long(1));
}

#[test]
fn shards_collected_are_the_local_sweep() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let local = dir.path().join("local");
    let o = run_local(&study, &local);
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
    // collect writes the typed copy too, its axis typed from its column as the study would
    let (local_cols, _) = parquet_matches_csv(&sweep::table_path(&local));
    let (collected_cols, rows) = parquet_matches_csv(&table);
    assert_eq!(rows.len(), 4);
    assert_eq!(local_cols, collected_cols);
    assert_eq!(
        parquet_type(&collected_cols, "team.auvs"),
        (Physical::INT64, false, true)
    );
    // a shard's table stays CSV only
    assert!(!sharded.join("shard-0-of-3.parquet").exists());
}

#[test]
fn a_resumed_sweep_makes_only_the_runs_its_table_lacks() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let out = dir.path().join("out");
    run_local(&study, &out);
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
            out: out.clone(),
            shard: None,
            resume: true,
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
    let o = run_local(&study, &out);
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
    assert!(stdout.contains("runs.parquet"), "{stdout}");
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
    run_local(&study, &out);
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
    // how the flown team kept its links and distances
    for share in ["sim_planned_links_received", "sim_linked_fraction"] {
        assert!((0.0..=1.0).contains(&num(share)), "{share}");
    }
    assert!(num("sim_min_separation_m") > 0.0);
    let below_eps = recs[1][col("sim_below_clearance")]
        .parse::<usize>()
        .unwrap();
    assert!(below_eps >= recs[1][col("sim_below_floor")].parse::<usize>().unwrap());
    // typed: the failed run's counts of the flight are nulls, not "NaN"
    let (columns, rows) = parquet_matches_csv(&sweep::table_path(&out));
    let at = |name: &str| columns.iter().position(|c| c.0 == name).unwrap();
    assert_eq!(
        parquet_type(&columns, "sim_below_floor"),
        (Physical::INT64, false, true)
    );
    assert_eq!(rows[0][at("sim_below_floor")], Field::Null);
    assert_eq!(
        parquet_type(&columns, "sim_below_clearance"),
        (Physical::INT64, false, true)
    );
    assert_eq!(rows[1][at("sim_below_floor")], Field::Long(0));
    assert_eq!(rows[0][at("sim_status")], Field::Str("no plan".into()));
}

/// The texts of an SVG figure.
fn svg_texts(path: &Path) -> Vec<String> {
    let svg = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&svg).unwrap();
    doc.descendants()
        .filter(|n| n.has_tag_name("text"))
        .map(|n| n.text().unwrap_or("").trim().to_string())
        .collect()
}

#[test]
fn cli_sweep_plot_draws_each_measure_against_each_swept_key() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    // 3 seeds × 3 team sizes; team.auvs = 0 makes no plan
    std::fs::write(
        &study,
        "[set]\n\"horizon.steps\" = 6\n[axes]\nseed = \"1..3\"\n\"team.auvs\" = [0, 1, 2]\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let (code, _, stderr) = common::run(shoal().args([
        "sweep",
        study.to_str().unwrap(),
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(code, 0, "{stderr}");
    let (code, stdout, stderr) =
        common::run(shoal().args(["sweep", "plot", out.to_str().unwrap()]));
    assert_eq!(code, 0, "{stderr}");
    assert!(stdout.contains("sweep-team.auvs.svg"), "{stdout}");
    assert!(out.join("sweep-team.auvs.png").exists());
    let texts = svg_texts(&out.join("sweep-team.auvs.svg"));
    // one panel per usual measure the table has (no simulation: no sim_* panel)
    let titles: Vec<&String> = texts
        .iter()
        .filter(|t| {
            [
                "wall_s:",
                "p2_objective:",
                "explored_km2:",
                "mean_height_m:",
                "chain_fraction:",
                "passed_fraction:",
            ]
            .iter()
            .any(|m| t.starts_with(m))
        })
        .collect();
    assert_eq!(titles.len(), 6, "{texts:?}");
    assert!(!texts.iter().any(|t| t.starts_with("sim_")), "{texts:?}");
    // one line: no other swept key but the seed
    assert!(!texts.iter().any(|t| t.contains(" = ")), "{texts:?}");
    let caption = texts
        .iter()
        .find(|t| t.starts_with("9 runs in runs.csv"))
        .unwrap();
    assert!(caption.contains("3 made no plan"), "{caption}");
    assert!(texts.iter().any(|t| t.contains("quartiles")), "{texts:?}");

    // against the seed, chosen measures: one line per team size
    let figs = dir.path().join("figs");
    let (code, _, stderr) = common::run(shoal().args([
        "sweep",
        "plot",
        sweep::table_path(&out).to_str().unwrap(),
        "-o",
        figs.to_str().unwrap(),
        "--x",
        "seed",
        "--y",
        "explored_km2",
        "energy",
    ]));
    assert_eq!(code, 0, "{stderr}");
    let texts = svg_texts(&figs.join("sweep-seed.svg"));
    let lines = texts
        .iter()
        .filter(|t| t.starts_with("team.auvs = ") && t.ends_with("(3 runs)"))
        .count();
    assert_eq!(lines, 3, "{texts:?}");
    assert!(texts.iter().any(|t| t.starts_with("energy")), "{texts:?}");
    assert!(!texts.iter().any(|t| t.starts_with("wall_s")), "{texts:?}");

    // an unknown measure or key is named, with the table and what is allowed
    let (code, _, stderr) =
        common::run(shoal().args(["sweep", "plot", out.to_str().unwrap(), "--y", "explored_m2"]));
    assert_eq!(code, 2);
    for want in [
        "runs.csv",
        "\"explored_m2\"",
        "allowed: ",
        "explored_km2",
        "passed_fraction",
    ] {
        assert!(stderr.contains(want), "{want}: {stderr}");
    }
    let (code, _, stderr) =
        common::run(shoal().args(["sweep", "plot", out.to_str().unwrap(), "--x", "team"]));
    assert_eq!(code, 2);
    assert!(
        stderr.contains("--x \"team\"") && stderr.contains("allowed: team.auvs, seed"),
        "{stderr}"
    );
}

#[test]
fn a_table_swept_over_seeds_only_is_plotted_against_the_seed() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(
        dir.path(),
        "[set]\n\"horizon.steps\" = 6\n\"team.auvs\" = 1\n[axes]\nseed = \"1..2\"\n",
    );
    let out = dir.path().join("out");
    run_local(&study, &out);
    let files = shoal::figures::write_sweep(&out, None, None, &[]).unwrap();
    assert_eq!(
        files,
        [out.join("sweep-seed.png"), out.join("sweep-seed.svg")]
    );
    let texts = svg_texts(&files[1]);
    assert!(texts.iter().any(|t| t == "seed"), "the x axis: {texts:?}");
    assert!(texts
        .iter()
        .any(|t| t.contains("median of the runs at each seed")));
    // a study without axes has nothing to plot against
    let one = dir.path().join("one");
    let study = study_in(
        dir.path(),
        "[set]\n\"horizon.steps\" = 6\n\"team.auvs\" = 1\n",
    );
    run_local(&study, &one);
    let e = shoal::figures::write_sweep(&one, None, None, &[])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("runs.csv") && e.contains("nothing to plot against"),
        "{e}"
    );
}

#[test]
fn collect_refuses_a_missing_shard_and_shards_of_another_split() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let out = dir.path().join("sharded");
    let shard = |i, n| {
        let opts = Options {
            out: out.clone(),
            shard: Some(Shard::new(i, n).unwrap()),
            resume: false,
        };
        sweep::run(&study, &opts, &|_| {}).unwrap();
    };
    // task 1 of 3 never ran: collecting would silently lose its runs
    shard(0, 3);
    shard(2, 3);
    let e = sweep::collect(&out).unwrap_err().to_string();
    assert!(
        e.contains("1 of 3 shard tables missing (shard-1-of-3.csv)"),
        "{e}"
    );
    // an earlier sweep's split left in the directory
    shard(1, 3);
    shard(0, 2);
    let e = sweep::collect(&out).unwrap_err().to_string();
    assert!(e.contains("shard tables of 2 splits (of-2, of-3)"), "{e}");
    std::fs::remove_file(out.join("shard-0-of-2.csv")).unwrap();
    assert_eq!(sweep::collect(&out).unwrap().1, 4);
}

#[test]
fn shards_partition_the_runs_evenly_whatever_the_axes() {
    // every run in exactly one shard, shard sizes within one of each other; totals 0 and 1
    // and more shards than runs included
    for total in [0, 1, 2, 7, 12, 200, 1001] {
        for count in [1, 2, 3, 4, 8, 13] {
            let mut seen = vec![0; total];
            let sizes: Vec<usize> = (0..count)
                .map(|i| {
                    let runs = Shard::new(i, count).unwrap().runs(total);
                    assert!(runs.windows(2).all(|w| w[0] < w[1]), "ascending");
                    runs.iter().for_each(|&r| seen[r] += 1);
                    runs.len()
                })
                .collect();
            assert!(
                seen.iter().all(|&n| n == 1),
                "{total} runs in {count} shards"
            );
            let (lo, hi) = (sizes.iter().min(), sizes.iter().max());
            assert!(hi.unwrap() - lo.unwrap() <= 1, "{sizes:?}");
        }
    }
    // regression: dealt in their own order (every N-th run), the 200-run benchmark study
    // (seed × team.auvs = [1, 3, 5, 8]) gave one of two shards every N = 3 and N = 8 run.
    // Each shard now has about half of each team size.
    for i in 0..2 {
        let runs = Shard::new(i, 2).unwrap().runs(200);
        for n in 0..4 {
            let of_n = runs.iter().filter(|&&r| r % 4 == n).count();
            assert!(
                (15..=35).contains(&of_n),
                "shard {i}: {of_n} runs of team size #{n}"
            );
        }
    }
}

/// Regression: `seed = "0..1000000000000"` made every run in memory first and aborted on the
/// allocation. A study's size is now computed from its axes' ends and refused above
/// `MAX_RUNS`, before anything is made.
#[test]
fn regression_a_huge_seed_range_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("study.toml");
    std::fs::write(&path, "[axes]\nseed = \"0..1000000000000\"\n").unwrap();
    let e = Study::load(&path).unwrap_err().to_string();
    assert!(
        e.contains("study.toml: axes: seed (1 000 000 000 001 values) make 1 000 000 000 001 runs")
            && e.contains("a study has at most 1 000 000 runs"),
        "{e}"
    );
    assert_eq!(sweep::MAX_RUNS, 1_000_000);
    // the CLI says so at once, exit code 2
    let (code, _, stderr) = common::run(shoal().args(["sweep", path.to_str().unwrap()]));
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("1 000 000 000 001 runs"), "{stderr}");
    // at the limit a study is taken, and never made into a list of runs
    std::fs::write(&path, "[axes]\nseed = \"1..1000\"\nx = \"1..1000\"\n").unwrap();
    let s = Study::load(&path).unwrap();
    assert_eq!(s.total(), Ok(1_000_000));
    assert_eq!(s.run(999_999).values, ["1000", "1000"]);
    assert_eq!(s.run(1_000).values, ["2", "1"]);
}

/// Regression: a full 64-bit range panicked ("capacity overflow"); it has 2^64 values, more
/// than a 64-bit count holds, and is refused saying so.
#[test]
fn regression_a_full_64_bit_range_is_refused_not_a_panic() {
    let e = Study::parse(
        "[axes]\nseed = \"-9223372036854775808..9223372036854775807\"\n",
        Path::new("s.toml"),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("18 446 744 073 709 551 616 runs (more than a 64-bit count holds)"),
        "{e}"
    );
    // the ends of a range may be any 64-bit numbers; a small range near them is taken
    let s = Study::parse(
        "[axes]\nseed = \"9223372036854775806..9223372036854775807\"\n",
        Path::new("s.toml"),
    )
    .unwrap();
    assert_eq!(s.run(1).values, ["9223372036854775807"]);
}

/// Regression: four axes of 65 536 values each made 2^64 runs, which wrapped to 0: "0 of 0
/// runs", exit 0. The product is now checked.
#[test]
fn regression_axes_whose_product_overflows_are_refused() {
    let four = "[axes]\na = \"1..65536\"\nb = \"1..65536\"\nc = \"1..65536\"\nd = \"1..65536\"\n";
    let e = Study::parse(four, Path::new("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(
            "axes: 4 axes of 65 536 values make 18 446 744 073 709 551 616 runs (more than a \
             64-bit count holds); a study has at most 1 000 000 runs"
        ),
        "{e}"
    );
    // past even 128 bits
    let many: String = (0..9)
        .map(|i| format!("a{i} = \"0..100000000000000\"\n"))
        .collect();
    let e = Study::parse(&format!("[axes]\n{many}"), Path::new("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("make more than 340 282 366"), "{e}");
    // axes of different sizes are each named
    let sizes: Vec<String> = (1..=501).map(|n| n.to_string()).collect();
    let text = format!(
        "[axes]\nseed = \"1..2000\"\n\"team.auvs\" = [{}]\n",
        sizes.join(", ")
    );
    let e = Study::parse(&text, Path::new("s.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("axes: seed (2 000 values) × team.auvs (501 values) make 1 002 000 runs"),
        "{e}"
    );
}

/// Make `study` in `n` shards into `out`.
fn run_shards(study: &Study, out: &Path, n: usize) {
    for i in 0..n {
        let opts = Options {
            out: out.to_path_buf(),
            shard: Some(Shard::new(i, n).unwrap()),
            resume: false,
        };
        sweep::run(study, &opts, &|_| {}).unwrap();
    }
}

/// Rewrite the lines of `path` (without their line ends) by `f`, each ended by "\n".
fn edit_lines(path: &Path, f: impl FnOnce(&mut Vec<String>)) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    f(&mut lines);
    let mut out = lines.join("\n");
    out.push('\n');
    std::fs::write(path, out).unwrap();
}

/// Set field `col` of CSV line `line` (no quoted commas in the small study's rows).
fn set_field(line: &str, col: usize, value: &str) -> String {
    let mut fields: Vec<&str> = line.split(',').collect();
    fields[col] = value;
    fields.join(",")
}

/// Regression: `shoal sweep collect` dropped damaged rows and empty shard tables and exited 0
/// without a word. Each damage below now either refuses the collect (exit code 2, nothing
/// written) naming the file and the line or the runs missing, or, when nothing is lost, gives
/// the whole table.
#[test]
fn regression_collect_loses_nothing_silently() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let good = dir.path().join("good");
    run_shards(&study, &good, 2);
    let header: Vec<String> = std::fs::read_to_string(good.join("shard-0-of-2.csv"))
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .split(',')
        .map(String::from)
        .collect();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (wall, auvs, status) = (col("wall_s"), col("team.auvs"), col("status"));
    // another study's shard 1, for its record
    let other = dir.path().join("other");
    let reference = {
        let whole = dir.path().join("whole");
        copy_dir(&good, &whole);
        let (table, rows) = sweep::collect(&whole).unwrap();
        assert_eq!(rows, 4);
        rows_without_times(&table)
    };

    type Damage = Box<dyn Fn(&Path)>;
    let s0 = |d: &Path| d.join("shard-0-of-2.csv");
    let s1 = |d: &Path| d.join("shard-1-of-2.csv");
    // (what, damage, None: the whole table; Some(needles): refused, stderr holding each)
    let cases: Vec<(&str, Damage, Option<Vec<&str>>)> = vec![
        (
            "a truncated last line",
            Box::new(move |d| {
                let text = std::fs::read_to_string(s1(d)).unwrap();
                std::fs::write(s1(d), &text[..text.len() - 30]).unwrap();
            }),
            Some(vec!["shard-1-of-2.csv line 3: cut short"]),
        ),
        (
            "a last line cut in its last field (as many fields as the header)",
            Box::new(move |d| {
                let text = std::fs::read_to_string(s1(d)).unwrap();
                std::fs::write(s1(d), &text[..text.len() - 2]).unwrap();
            }),
            Some(vec!["shard-1-of-2.csv line 3: cut short"]),
        ),
        (
            "a row with too few fields",
            Box::new(move |d| {
                edit_lines(&s0(d), |l| {
                    let cut = l[1].rfind(',').unwrap();
                    l[1].truncate(cut);
                })
            }),
            Some(vec![
                "shard-0-of-2.csv line 2: 25 fields, the header has 26",
                "1 of its 2 runs missing",
            ]),
        ),
        (
            "a row with too many fields",
            Box::new(move |d| edit_lines(&s0(d), |l| l[2].push_str(",7"))),
            Some(vec![
                "shard-0-of-2.csv line 3: 27 fields, the header has 26",
            ]),
        ),
        (
            "a stray line of text",
            Box::new(move |d| edit_lines(&s0(d), |l| l.insert(2, "oops".into()))),
            Some(vec!["shard-0-of-2.csv line 3: 1 field, the header has 26"]),
        ),
        (
            "a run index that is not a number",
            Box::new(move |d| edit_lines(&s0(d), |l| l[1] = set_field(&l[1], 0, "two"))),
            Some(vec![
                "shard-0-of-2.csv line 2: run \"two\" is not a whole number",
            ]),
        ),
        (
            "a run twice in one shard, with other values",
            Box::new(move |d| {
                edit_lines(&s0(d), |l| {
                    let again = set_field(&l[1], wall, "99.5");
                    l.push(again);
                })
            }),
            Some(vec![
                "shard-0-of-2.csv line 4: run",
                "again (first on line 2), with other values",
            ]),
        ),
        (
            "a run in two shards",
            Box::new(move |d| {
                let row = std::fs::read_to_string(s0(d))
                    .unwrap()
                    .lines()
                    .nth(1)
                    .unwrap()
                    .to_string();
                edit_lines(&s1(d), |l| l.push(row));
            }),
            Some(vec![
                "shard-1-of-2.csv line 4: run",
                "is not one of shard 1/2's runs",
            ]),
        ),
        (
            "a shard with only its header",
            Box::new(move |d| edit_lines(&s1(d), |l| l.truncate(1))),
            Some(vec!["shard-1-of-2.csv: 2 of its 2 runs missing"]),
        ),
        (
            "a zero-byte shard",
            Box::new(move |d| std::fs::write(s1(d), "").unwrap()),
            Some(vec![
                "shard-1-of-2.csv: empty file",
                "shard-1-of-2.csv: 2 of its 2 runs missing",
            ]),
        ),
        (
            "a shard whose header differs",
            Box::new(move |d| edit_lines(&s0(d), |l| l[0] = l[0].replace("wall_s", "wall"))),
            Some(vec![
                "shard-0-of-2.csv line 1: its columns are not its study's",
                "\"wall\"",
            ]),
        ),
        (
            "a run beyond the study",
            Box::new(move |d| {
                edit_lines(&s0(d), |l| {
                    let row = set_field(&l[1], 0, "99");
                    l.push(row);
                })
            }),
            Some(vec![
                "shard-0-of-2.csv line 4: run 99 is beyond the study's 4 runs",
            ]),
        ),
        (
            "a row whose swept value is not its run's",
            Box::new(move |d| {
                edit_lines(&s0(d), |l| {
                    let v = if l[1].split(',').nth(auvs) == Some("1") {
                        "2"
                    } else {
                        "1"
                    };
                    l[1] = set_field(&l[1], auvs, v);
                })
            }),
            Some(vec!["shard-0-of-2.csv line 2: run", "has team.auvs ="]),
        ),
        (
            "a status that is none",
            Box::new(move |d| edit_lines(&s0(d), |l| l[1] = set_field(&l[1], status, "ok"))),
            Some(vec![
                "shard-0-of-2.csv line 2: status \"ok\" is not passed, violated or failed",
            ]),
        ),
        (
            "a number that is not one",
            Box::new(move |d| edit_lines(&s0(d), |l| l[2] = set_field(&l[2], wall, "fast"))),
            Some(vec![
                "shard-0-of-2.csv line 3: column wall_s = \"fast\" is not a number",
            ]),
        ),
        (
            "a row deleted",
            Box::new(move |d| edit_lines(&s0(d), |l| drop(l.remove(2)))),
            Some(vec!["shard-0-of-2.csv: 1 of its 2 runs missing (run "]),
        ),
        (
            "a row that is not UTF-8",
            Box::new(move |d| {
                let mut bytes = std::fs::read(s0(d)).unwrap();
                let at = bytes.iter().position(|&b| b == b'\n').unwrap() + 3;
                bytes[at] = 0xff;
                std::fs::write(s0(d), bytes).unwrap();
            }),
            Some(vec!["shard-0-of-2.csv line 2: not UTF-8 text"]),
        ),
        (
            "a shard without its study record",
            Box::new(move |d| std::fs::remove_file(d.join("shard-0-of-2.study.json")).unwrap()),
            Some(vec![
                "shard-0-of-2.csv: no study record beside it",
                "shard-0-of-2.study.json is missing",
            ]),
        ),
        (
            "a shard of another study",
            Box::new({
                let other = other.clone();
                move |d| {
                    for f in ["shard-1-of-2.csv", "shard-1-of-2.study.json"] {
                        std::fs::copy(other.join(f), d.join(f)).unwrap();
                    }
                }
            }),
            Some(vec![
                "shard-1-of-2.csv was made by another study than",
                "axes.seed differs: \"1..2\" then, \"1..3\" now",
            ]),
        ),
        (
            "the same row twice",
            Box::new(move |d| {
                edit_lines(&s0(d), |l| {
                    let again = l[1].clone();
                    l.push(again);
                })
            }),
            None,
        ),
        (
            "rows out of order, with CRLF line ends",
            Box::new(move |d| {
                edit_lines(&s0(d), |l| l.swap(1, 2));
                let text = std::fs::read_to_string(s0(d)).unwrap();
                std::fs::write(s0(d), text.replace('\n', "\r\n")).unwrap();
            }),
            None,
        ),
    ];
    // the other study's shards, for the case that takes one
    let o = study_in(
        &{
            let d = dir.path().join("o");
            std::fs::create_dir_all(&d).unwrap();
            d
        },
        "[set]\n\"horizon.steps\" = 6\n[axes]\nseed = \"1..3\"\n\"team.auvs\" = [1, 2]\n",
    );
    let opts = Options {
        out: other.clone(),
        shard: Some(Shard::new(1, 2).unwrap()),
        resume: false,
    };
    sweep::run(&o, &opts, &|_| {}).unwrap();

    for (i, (what, damage, want)) in cases.iter().enumerate() {
        let d = dir.path().join(format!("case-{i}"));
        copy_dir(&good, &d);
        damage(&d);
        let (code, stdout, stderr) =
            common::run(shoal().args(["sweep", "collect", d.to_str().unwrap()]));
        match want {
            None => {
                assert_eq!(code, 0, "{what}: {stderr}");
                assert!(stdout.contains("(4 runs)"), "{what}: {stdout}");
                assert_eq!(
                    rows_without_times(&sweep::table_path(&d)),
                    reference,
                    "{what}"
                );
            }
            Some(needles) => {
                assert_eq!(code, 2, "{what}: {stdout}\n{stderr}");
                assert!(stderr.contains("nothing written"), "{what}: {stderr}");
                for n in needles {
                    assert!(stderr.contains(n), "{what}: wanted \"{n}\" in\n{stderr}");
                }
                assert!(!sweep::table_path(&d).exists(), "{what}: runs.csv written");
                assert!(!sweep::parquet_path(&d).exists(), "{what}");
            }
        }
    }
}

/// Copy the files of directory `from` into a new directory `to`.
fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap().flatten() {
        if e.path().is_file() {
            std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
        }
    }
}

/// Regression: `--resume` after the study's values changed kept the old study's rows, exit 0.
/// Each table has its study's record beside it, and a resume of another study is refused,
/// naming what differs.
#[test]
fn regression_a_resume_after_the_study_changed_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("base.toml"), "[horizon]\nsteps = 6\n").unwrap();
    let text = "scenario = \"base.toml\"\n[axes]\nseed = \"1..2\"\n";
    let study = study_in(dir.path(), text);
    let out = dir.path().join("out");
    run_local(&study, &out);
    let table = sweep::table_path(&out);
    let record = out.join("runs.study.json");
    assert!(record.exists());
    let before = std::fs::read(&table).unwrap();
    let resume = |study: &Study| {
        let opts = Options {
            out: out.clone(),
            shard: None,
            resume: true,
        };
        sweep::run(study, &opts, &|_| {})
    };
    // the same study resumes: nothing to make
    assert_eq!(resume(&study).unwrap().skipped, 2);
    // another range of seeds
    let changed = study_in(dir.path(), &text.replace("1..2", "1..3"));
    let e = resume(&changed).unwrap_err().to_string();
    assert_eq!(
        e,
        format!(
            "{} was made by another study (axes.seed differs: \"1..2\" then, \"1..3\" now); use \
             another -o or delete it",
            table.display()
        )
    );
    // the base scenario's text
    std::fs::write(dir.path().join("base.toml"), "[horizon]\nsteps = 7\n").unwrap();
    let e = resume(&study).unwrap_err().to_string();
    assert!(
        e.contains("the base scenario's text (SHA-256) differs"),
        "{e}"
    );
    std::fs::write(dir.path().join("base.toml"), "[horizon]\nsteps = 6\n").unwrap();
    // another method, a [set], simulate
    let e = resume(&study_in(
        dir.path(),
        &format!("method = \"rrt-like\"\n{text}"),
    ))
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("method differs: \"mpc\" then, \"rrt-like\" now"),
        "{e}"
    );
    // the table was left as it was
    assert_eq!(std::fs::read(&table).unwrap(), before);
    // a table without its record is not taken either
    std::fs::remove_file(&record).unwrap();
    let e = resume(&study).unwrap_err().to_string();
    assert!(e.contains("it has no study record"), "{e}");
    // the CLI: exit code 2, the same message
    let study_file = dir.path().join("study.toml");
    std::fs::write(&study_file, text.replace("1..2", "1..3")).unwrap();
    run_local(&study, &out); // afresh, with its record
    let (code, _, stderr) = common::run(shoal().args([
        "sweep",
        study_file.to_str().unwrap(),
        "-q",
        "--resume",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("was made by another study (axes.seed differs"),
        "{stderr}"
    );
    // without --resume the table is made afresh for the new study
    let o = run_local(&study_in(dir.path(), &text.replace("1..2", "1..3")), &out);
    assert_eq!((o.total, o.rows, o.complete), (3, 3, true));
}

/// Regression: a sweep whose base scenario could not be read ran every run, each failing, and
/// exited 0. The study's scenario is made once before any run and refused with its error.
#[test]
fn regression_a_sweep_whose_base_scenario_cannot_be_read_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    for (text, want) in [
        (
            "scenario = \"nope.toml\"\n[axes]\nseed = \"1..2\"\n",
            "nope.toml: cannot read the scenario file",
        ),
        (
            "scenario = \"bad.toml\"\n[axes]\nseed = \"1..2\"\n",
            "bad.toml line 2: unknown key horizon.stepz",
        ),
        (
            "[set]\n\"horizon.steps\" = 0\n[axes]\nseed = \"1..2\"\n",
            "horizon.steps = 0",
        ),
        ("[axes]\n\"team.auv\" = [1, 2]\n", "unknown key team.auv"),
    ] {
        std::fs::write(dir.path().join("bad.toml"), "[horizon]\nstepz = 6\n").unwrap();
        let study = study_in(dir.path(), text);
        let e = sweep::run(
            &study,
            &Options {
                out: out.clone(),
                shard: None,
                resume: false,
            },
            &|_| panic!("no run is made"),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("study.toml: its scenario cannot be made, so no run could: ")
                && e.contains(want),
            "{text}: {e}"
        );
        assert!(!sweep::table_path(&out).exists(), "{text}");
    }
    // the CLI: exit code 2
    std::fs::write(
        dir.path().join("study.toml"),
        "scenario = \"nope.toml\"\n[axes]\nseed = \"1..2\"\n",
    )
    .unwrap();
    let (code, _, stderr) = common::run(shoal().args([
        "sweep",
        dir.path().join("study.toml").to_str().unwrap(),
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(code, 2, "{stderr}");
    assert!(
        stderr.contains("nope.toml: cannot read the scenario file"),
        "{stderr}"
    );
}

/// A sweep whose every run failed exits with code 1 and says so with the first run's error;
/// one in which some runs failed is a sweep that ran (exit code 0).
#[test]
fn regression_a_sweep_whose_every_run_failed_exits_1() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    let out = dir.path().join("out");
    std::fs::write(&study, "[axes]\n\"team.auvs\" = [0, 65]\n").unwrap();
    let (code, stdout, stderr) = common::run(shoal().args([
        "sweep",
        study.to_str().unwrap(),
        "-q",
        "-o",
        out.to_str().unwrap(),
    ]));
    assert_eq!(code, 1, "{stdout}\n{stderr}");
    assert!(
        stdout.contains("0 passed, 0 violated, 2 failed"),
        "{stdout}"
    );
    assert!(
        stderr.contains("every run of") && stderr.contains("failed (no plan), e.g. run 0: "),
        "{stderr}"
    );
    assert!(stderr.contains("team.auvs = 0"), "{stderr}");
}

/// A sweep cancelled (Ctrl-C) starts no new run: the table holds the runs that finished,
/// sorted, has no typed copy while incomplete, and `--resume` makes the rest.
#[test]
fn an_interrupted_sweep_keeps_its_finished_runs_and_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(
        dir.path(),
        "[set]\n\"horizon.steps\" = 6\n\"team.auvs\" = 1\n[axes]\nseed = \"1..6\"\n",
    );
    let out = dir.path().join("out");
    let cancel = std::sync::atomic::AtomicBool::new(false);
    let opts = Options {
        out: out.clone(),
        shard: None,
        resume: false,
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let o = pool
        .install(|| {
            sweep::run_until(
                &study,
                &opts,
                &|_| cancel.store(true, std::sync::atomic::Ordering::SeqCst),
                &cancel,
            )
        })
        .unwrap();
    assert!(o.interrupted && !o.complete, "{o:?}");
    assert_eq!((o.rows, o.passed, o.parquet.clone()), (1, 1, None));
    assert_eq!(rows_without_times(&sweep::table_path(&out)).len(), 1);
    assert!(!sweep::parquet_path(&out).exists());
    let o = sweep::run(
        &study,
        &Options {
            resume: true,
            ..opts
        },
        &|_| {},
    )
    .unwrap();
    assert_eq!(
        (o.skipped, o.rows, o.complete, o.interrupted),
        (1, 6, true, false)
    );
    assert!(sweep::parquet_path(&out).exists());
}

/// `--resume` drops the rows of its table it cannot take (named, by line) and makes their runs
/// again.
#[test]
fn a_resume_makes_the_runs_of_damaged_rows_again() {
    let dir = tempfile::tempdir().unwrap();
    let study = study_in(dir.path(), STUDY);
    let out = dir.path().join("out");
    run_local(&study, &out);
    let table = sweep::table_path(&out);
    edit_lines(&table, |l| {
        let cut = l[2].rfind(',').unwrap();
        l[2].truncate(cut);
    });
    let o = sweep::run(
        &study,
        &Options {
            out: out.clone(),
            shard: None,
            resume: true,
        },
        &|_| {},
    )
    .unwrap();
    assert_eq!((o.skipped, o.passed, o.rows), (3, 1, 4));
    assert_eq!(o.notes.len(), 1, "{:?}", o.notes);
    assert!(
        o.notes[0].contains("runs.csv line 3: 25 fields, the header has 26"),
        "{:?}",
        o.notes
    );
    assert_eq!(rows_without_times(&table).len(), 4);
}

/// Ctrl-C in `shoal sweep`: no new run starts, the table keeps the finished runs (sorted), the
/// sweep says how many and how to make the rest, exit code 130.
#[cfg(unix)]
#[test]
fn an_interrupted_sweep_says_what_it_kept() {
    let dir = tempfile::tempdir().unwrap();
    let study = dir.path().join("study.toml");
    std::fs::write(
        &study,
        "[set]\n\"horizon.steps\" = 6\n\"team.auvs\" = 1\n[axes]\nseed = \"1..400\"\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let child = shoal()
        .args([
            "sweep",
            study.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // wait for a finished row
    let table = sweep::table_path(&out);
    let clock = std::time::Instant::now();
    while std::fs::read_to_string(&table).map_or(0, |t| t.lines().count()) < 2 {
        assert!(clock.elapsed().as_secs() < 120, "no run finished");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // SAFETY: sending a signal to our own child process
    assert_eq!(
        unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) },
        0
    );
    let done = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&done.stderr);
    assert_eq!(done.status.code(), Some(130), "{stderr}");
    let rows = rows_without_times(&table);
    assert!(!rows.is_empty() && rows.len() < 400, "{}", rows.len());
    assert!(
        stderr.contains(&format!(
            "wrote {} with the {} finished runs of its 400 (incomplete; `shoal sweep",
            table.display(),
            rows.len()
        )) && stderr.contains("--resume` makes the rest"),
        "{stderr}"
    );
    let runs: Vec<usize> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    assert!(runs.windows(2).all(|w| w[0] < w[1]), "sorted: {runs:?}");
}

/// Every shard's runs dealt in one pass are each shard's own.
#[test]
fn dealing_every_shard_at_once_gives_each_shards_runs() {
    for (count, total) in [(1, 0), (3, 10), (4, 1001), (7, 5)] {
        let dealt = Shard::deal(count, total);
        for (i, runs) in dealt.iter().enumerate() {
            assert_eq!(runs, &Shard::new(i, count).unwrap().runs(total));
        }
    }
}
