//! The size of one interior-point iteration's factorisation for any Clarabel JSON problem
//! file: shoal's models (`export_models`) and the anchor (`scripts/anchor_lcvx.py`)
//! measured by the same rule (`shoal::conic::fill`: QDLDL's symbolic analysis under its AMD
//! ordering, as Clarabel factorises the KKT matrix), so that they compare per variable.
//!
//! Run: cargo run --release --example model_fill -- FILE.json [FILE.json ...]
//!
//! Prints per file: variables n, rows m, rows per variable, nonzeros of the KKT matrix and of
//! L, multiply-adds of one numeric factorisation, and multiply-adds per variable.

use clarabel::algebra::CscMatrix;
use clarabel::solver::SupportedConeT;
use serde::Deserialize;
use std::collections::BTreeMap;

/// A matrix as Clarabel's JSON problem file holds it (compressed sparse columns).
#[derive(Deserialize)]
struct Csc {
    m: usize,
    n: usize,
    colptr: Vec<usize>,
    rowval: Vec<usize>,
    nzval: Vec<f64>,
}

/// The parts of the file the fill needs.
#[derive(Deserialize)]
#[allow(non_snake_case)]
struct Problem {
    P: Csc,
    A: Csc,
    cones: Vec<BTreeMap<String, usize>>,
}

fn matrix(c: Csc) -> CscMatrix<f64> {
    CscMatrix::new(c.m, c.n, c.colptr, c.rowval, c.nzval)
}

fn main() {
    let files: Vec<String> = std::env::args().skip(1).collect();
    if files.is_empty() {
        eprintln!("usage: model_fill FILE.json [FILE.json ...] (Clarabel JSON problem files)");
        std::process::exit(2);
    }
    println!("file n m rows_per_variable kkt_nonzeros l_nonzeros multiply_adds per_variable");
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let problem: Problem =
            serde_json::from_str(&text).unwrap_or_else(|e| panic!("{path}: {e}"));
        let cones: Vec<SupportedConeT<f64>> = problem
            .cones
            .iter()
            .flat_map(|c| c.iter())
            .map(|(kind, &d)| match kind.as_str() {
                "ZeroConeT" => SupportedConeT::ZeroConeT(d),
                "NonnegativeConeT" => SupportedConeT::NonnegativeConeT(d),
                "SecondOrderConeT" => SupportedConeT::SecondOrderConeT(d),
                other => panic!("{path}: cone {other} is not one shoal's fill counts"),
            })
            .collect();
        let (p, a) = (matrix(problem.P), matrix(problem.A));
        let f = shoal::conic::fill(&p, &a, &cones).unwrap_or_else(|e| panic!("{path}: {e}"));
        println!(
            "{path} {} {} {:.2} {} {} {:.3e} {:.0}",
            p.n,
            a.m,
            a.m as f64 / p.n as f64,
            f.kkt_nonzeros,
            f.factor_nonzeros,
            f.multiply_adds,
            f.multiply_adds / p.n as f64
        );
    }
}
