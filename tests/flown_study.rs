//! A flown study as a regression test: plans of five AUVs over a few seeds, each flown by the
//! 6-DoF REMUS 100 under its tracking controller (`simulate = true`), must keep every AUV
//! above the floor, also in a current of 0.3 m/s along the first course. Without the
//! planner's flight envelope seeds 4, 8 and 10 asked for level flight at 0.6–1.2 m/s through
//! the water, where the vehicle cannot hold its depth, and sank (123, 409 and 29 samples below
//! the floor); without the current in the plan every flight in 0.3 m/s sank.

use shoal::sweep::{self, Options, Study};

#[test]
fn regression_flown_plans_sank_below_the_floor_at_low_speed() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("study.toml");
    std::fs::write(
        &path,
        "simulate = true\n[set]\n\"team.auvs\" = 5\n[axes]\nseed = [1, 2, 3, 4, 8, 10]\n\
         \"current.velocity\" = [[0.0, 0.1], [0.3, 0.0]]\n",
    )
    .unwrap();
    let study = Study::load(&path).unwrap();
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
    for rec in r.records() {
        let rec = rec.unwrap();
        let seed = &rec[col("seed")];
        assert_eq!(&rec[col("sim_status")], "flown", "seed {seed}");
        assert_eq!(
            &rec[col("sim_below_floor")],
            "0",
            "seed {seed}: flown samples below the floor"
        );
    }
}
