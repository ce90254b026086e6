//! Step 1 (P2) for one window on the default synthetic floor, N = 5 and N = 7, K = 20.
//! Run: cargo bench --bench step1. Figures and machine in BENCHMARKS.md.

use criterion::{criterion_group, criterion_main, Criterion};
use shoal::planner::{plan, scenario_floor, PlanInput};
use shoal::scenario::Scenario;
use std::path::Path;

fn step1(c: &mut Criterion) {
    let mut group = c.benchmark_group("step1_window");
    group.sample_size(10);
    for n in [5usize, 7] {
        let mut s = Scenario::default();
        s.team.auvs = n;
        let (floor, source) = scenario_floor(&s, Path::new("")).expect("default floor");
        let input = PlanInput {
            scenario: &s,
            floor: &floor,
            scenario_source: "bench".into(),
            overrides: vec![],
            seafloor_source: source,
        };
        group.bench_function(format!("N={n},K=20"), |b| {
            b.iter(|| plan(&input).expect("plan"))
        });
    }
    group.finish();
}

criterion_group!(benches, step1);
criterion_main!(benches);
