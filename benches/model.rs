//! One convex model of the SCP, solved once: P2's (Step 1) about the first guess and P5's
//! (Step 3) about Step 1's plan, on the default synthetic floor, K = 20, N = 5 and N = 20.
//! Each measured call updates the solver's data and solves (the symbolic factorisation is kept,
//! as in every SCP iteration after the first). Run: cargo bench --bench model.
//!
//! A window needs at least one solve of each model, so these medians are a lower bound on a
//! window's time with Clarabel (BENCHMARKS.md, "What one convex solve costs").

use criterion::{criterion_group, criterion_main, Criterion};
use shoal::planner::{initial_state, scenario_floor};
use shoal::scenario::Scenario;
use shoal::scp::ScpProblem;
use shoal::step3::LinkSet;
use shoal::team::TeamProblem;
use shoal::trajectory::Start;
use shoal::vehicle::{AuvModel, UsvModel};
use std::path::Path;

fn model(c: &mut Criterion) {
    let mut group = c.benchmark_group("model");
    group.sample_size(10);
    for n in [5usize, 20] {
        let mut s = Scenario::default();
        s.team.auvs = n;
        let (floor, _) = scenario_floor(&s, Path::new("")).expect("default floor");
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
        let penalty = s.scp.penalty;

        let mut p2 = TeamProblem::new(&s, &floor, &keep_out, auv, usv, start.clone());
        let guess = p2.initial_guess(None);
        let radius = s.scp.trust_region;
        let (_, _, first) = p2.solve_model(&guess, radius, penalty).expect("P2 model");
        eprintln!(
            "P2 model, N = {n}: {} variables, {} interior-point iterations, {:?}",
            p2.layout().variables(),
            first.iterations,
            first.status
        );
        group.bench_function(format!("p2/N={n},K=20"), |b| {
            b.iter(|| p2.solve_model(&guess, radius, penalty).expect("P2 model"))
        });

        let step1 = shoal::step1::solve(&mut p2, None).expect("P2").iterate;
        let graph = shoal::step2::solve(&step1, &floor, s.acoustic.resolution);
        let links = LinkSet::from_graph(&graph, s.acoustic.sonar_range, s.acoustic.band_tolerance);
        let mut p5 = TeamProblem::new(&s, &floor, &keep_out, auv, usv, start).with_links(links);
        let radius = s.acoustic.band_tolerance.min(s.scp.trust_region);
        let (_, _, first) = p5.solve_model(&step1, radius, penalty).expect("P5 model");
        eprintln!(
            "P5 model, N = {n}: {} variables, {} interior-point iterations, {:?}",
            p5.layout().variables(),
            first.iterations,
            first.status
        );
        group.bench_function(format!("p5/N={n},K=20"), |b| {
            b.iter(|| p5.solve_model(&step1, radius, penalty).expect("P5 model"))
        });
    }
    group.finish();
}

criterion_group!(benches, model);
criterion_main!(benches);
