//! One receding-horizon window on the default synthetic floor, K = 20, N = 5 and N = 7 (the
//! paper's two experiments): Step 1 (P2) alone, and the full window (Steps 1–3 with the
//! line-of-sight loop, as `shoal plan` runs it). Run: cargo bench --bench window.
//! Figures and machine in BENCHMARKS.md.

use criterion::{criterion_group, criterion_main, Criterion};
use shoal::planner::{initial_state, plan, scenario_floor, PlanInput};
use shoal::scenario::Scenario;
use shoal::team::TeamProblem;
use shoal::trajectory::Start;
use shoal::vehicle::{AuvModel, UsvModel};
use std::path::Path;

fn window(c: &mut Criterion) {
    let mut group = c.benchmark_group("window");
    group.sample_size(10);
    for n in [5usize, 7] {
        let mut s = Scenario::default();
        s.team.auvs = n;
        let (floor, source) = scenario_floor(&s, Path::new("")).expect("default floor");
        let auv = AuvModel::new(&s.auv, s.horizon.dt).expect("model");
        let usv = UsvModel {
            dt: s.horizon.dt,
            max_speed: s.usv.max_speed,
        };
        let keep_out = floor.keep_out();
        let init = initial_state(&s, &floor, &keep_out).expect("initial state");
        let start = Start {
            usv: init.usv,
            auvs: init.auvs,
        };
        group.bench_function(format!("step1/N={n},K=20"), |b| {
            b.iter(|| {
                let mut p2 = TeamProblem::new(&s, &floor, &keep_out, auv, usv, start.clone());
                shoal::step1::solve(&mut p2, None).expect("P2")
            })
        });
        let input = PlanInput {
            scenario: &s,
            floor: &floor,
            scenario_source: "bench".into(),
            overrides: vec![],
            seafloor_source: source,
        };
        group.bench_function(format!("steps1-3/N={n},K=20"), |b| {
            b.iter(|| plan(&input).expect("plan"))
        });
    }
    group.finish();
}

criterion_group!(benches, window);
criterion_main!(benches);
