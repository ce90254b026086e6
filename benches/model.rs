//! One convex model of the SCP, solved once: P2's (Step 1) about the first guess and P5's
//! (Step 3) about Step 1's plan, on the default synthetic floor, K = 20, N = 5 and N = 20.
//! Each measured call updates the solver's data and solves (the symbolic factorisation is kept,
//! as in every SCP iteration after the first). Run: cargo bench --bench model.
//!
//! Before measuring, each model's factorisation size is printed (`conic::fill`: nonzeros of the
//! KKT matrix and of L, multiply-adds per factorisation): the fill is what an interior-point
//! iteration costs.
//!
//! A window needs at least one solve of each model, so these medians are a lower bound on a
//! window's time with Clarabel (BENCHMARKS.md, "One window against team size").

mod common;

use criterion::{criterion_group, criterion_main, Criterion};
use shoal::scp::ScpProblem;
use shoal::team::TeamProblem;
use shoal::trajectory::Trajectory;

/// Solve `problem`'s model about `reference` once (building the solver), say how big it is and
/// how many interior-point iterations it took, then measure further solves.
fn measure(
    group: &mut criterion::BenchmarkGroup<criterion::measurement::WallTime>,
    name: &str,
    problem: &mut TeamProblem,
    reference: &Trajectory,
    radius: f64,
    penalty: f64,
) {
    let (_, _, first) = problem
        .solve_model(reference, radius, penalty)
        .expect("model");
    let fill = problem.fill().expect("solved once").expect("fill");
    eprintln!(
        "{name}: {} variables, {} interior-point iterations, {:?}; KKT {} nonzeros, L {} \
         nonzeros, {:.2e} multiply-adds per factorisation",
        problem.layout().variables(),
        first.iterations,
        first.status,
        fill.kkt_nonzeros,
        fill.factor_nonzeros,
        fill.multiply_adds
    );
    group.bench_function(name, |b| {
        b.iter(|| {
            problem
                .solve_model(reference, radius, penalty)
                .expect("model")
        })
    });
}

fn model(c: &mut Criterion) {
    let mut group = c.benchmark_group("model");
    group.sample_size(10);
    for n in [5usize, 20] {
        let b = common::setup(n);
        let s = &b.scenario;
        let penalty = s.scp.penalty;

        let mut p2 = b.problem();
        let guess = p2.initial_guess(None);
        let name = format!("p2/N={n},K=20");
        measure(
            &mut group,
            &name,
            &mut p2,
            &guess,
            s.scp.trust_region,
            penalty,
        );

        let (step1, mut p5, radius) = common::step3(&b, &mut p2);
        let name = format!("p5/N={n},K=20");
        measure(&mut group, &name, &mut p5, &step1, radius, penalty);
    }
    group.finish();
}

criterion_group!(benches, model);
criterion_main!(benches);
