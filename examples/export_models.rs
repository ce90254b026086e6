//! Write the convex models of `cargo bench --bench model` as Clarabel JSON problem files, so
//! that other solvers can be measured on exactly the models the SCP solves
//! (`scripts/other_solvers.py`; BENCHMARKS.md, "The convex solve against the anchor and other solvers").
//!
//! For N = 5 and N = 20 on the default scenario (K = 20, seed 1), into DIR:
//! - `p2_N{n}.json`: P2 (Step 1) about the first guess;
//! - `p5_N{n}_a.json`: P5 (Step 3) about Step 1's plan, with Step 2's chain;
//! - `p5_N{n}_b.json`: the next P5 model, about the first one's candidate (same radius and
//!   penalty): two models of one SCP in a row, for a warm start from the first's solution.
//!
//! Run: cargo run --release --example export_models -- DIR [N=5,20] [K=20]
//!
//! `N=` the team sizes, `K=` the steps of the 2000 s window (δ = 2000 s / K). Prints each
//! model's size and its factorisation's (`TeamProblem::fill`).

#[path = "../benches/common/mod.rs"]
mod common;

use shoal::scp::ScpProblem;
use shoal::team::TeamProblem;
use std::path::{Path, PathBuf};

fn save(problem: &TeamProblem, path: PathBuf) {
    problem
        .save_model(&path)
        .expect("a model was solved")
        .unwrap_or_else(|e| panic!("{e}"));
    let fill = problem.fill().expect("a model was solved").expect("fill");
    eprintln!(
        "wrote {}: {} variables, KKT {} nonzeros, L {} nonzeros, {:.3e} multiply-adds",
        path.display(),
        problem.layout().variables(),
        fill.kkt_nonzeros,
        fill.factor_nonzeros,
        fill.multiply_adds
    );
}

fn main() {
    let usage = "usage: export_models DIR [N=5,20] [K=20] (DIR an existing directory)";
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dir = Path::new(args.first().expect(usage));
    let (mut teams, mut steps) = (vec![5usize, 20], 20usize);
    for arg in &args[1..] {
        match arg.split_once('=') {
            Some(("N", v)) => teams = v.split(',').map(|t| t.parse().expect(usage)).collect(),
            Some(("K", v)) => steps = v.parse().expect(usage),
            _ => panic!("{usage}"),
        }
    }
    let tag = |n: usize| {
        if steps == 20 {
            format!("N{n}")
        } else {
            format!("N{n}_K{steps}")
        }
    };
    for n in teams {
        let b = common::setup_steps(n, steps);
        let s = &b.scenario;
        let penalty = s.scp.penalty;

        let mut p2 = b.problem();
        let guess = p2.initial_guess(None);
        p2.solve_model(&guess, s.scp.trust_region, penalty)
            .expect("P2 model");
        save(&p2, dir.join(format!("p2_{}.json", tag(n))));

        let (step1, mut p5, radius) = common::step3(&b, &mut p2);
        let (candidate, _, _) = p5.solve_model(&step1, radius, penalty).expect("P5 model");
        save(&p5, dir.join(format!("p5_{}_a.json", tag(n))));
        p5.solve_model(&candidate, radius, penalty)
            .expect("P5 model");
        save(&p5, dir.join(format!("p5_{}_b.json", tag(n))));
    }
}
