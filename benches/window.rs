//! One receding-horizon window on the default synthetic floor, K = 20, N = 5 and N = 7 (the
//! paper's two experiments): Step 1 (P2) alone, and the full window (Steps 1–3 with the
//! line-of-sight loop, as `shoal plan` runs it). Run: cargo bench --bench window.
//! Figures and machine in BENCHMARKS.md.

mod common;

use criterion::{criterion_group, criterion_main, Criterion};

fn window(c: &mut Criterion) {
    let mut group = c.benchmark_group("window");
    group.sample_size(10);
    for n in [5usize, 7] {
        let b = common::setup(n);
        let s = &b.scenario;
        group.bench_function(format!("step1/N={n},K=20"), |bench| {
            bench.iter(|| {
                let mut p2 = b.problem();
                shoal::step1::solve(&mut p2, None, &mut |_| {}).expect("P2")
            })
        });
        let input = shoal::Provenance {
            scenario_source: "bench".into(),
            overrides: vec![],
            seafloor: b.source.clone(),
        };
        group.bench_function(format!("steps1-3/N={n},K=20"), |bench| {
            bench.iter(|| {
                shoal::Planner::new(s, &b.floor)
                    .provenance(input.clone())
                    .run()
                    .expect("plan")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, window);
criterion_main!(benches);
