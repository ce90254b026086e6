//! Issue 13's sweep: scenarios drawn from the whole space users set (AUV and USV speed
//! 0.2–3 m/s, N 1–25, K 2–40, δ 10–200 s, d_s 60–400 m, 1–4 windows, seeds, synthetic floors),
//! each planned and, when a plan comes back, checked. One CSV row per draw on stdout: the
//! draw, the outcome (`plan`, `error`, or `FAIL` for a plan that fails its check), the stages
//! of a plan that did not converge ("w1 step3 max_iterations") and the error's text or the
//! plan's warnings; the counts on stderr at the end.
//!
//! Run: cargo run --release --example feasible_sweep -- DRAWS [FIRST_DRAW]
//! (draw i uses seed i of the generator, so two processes can split a sweep by FIRST_DRAW).
//! `-- show I` prints draw I's scenario as TOML instead, for `shoal plan I.toml`.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use shoal::{mission, Planner, Scenario};

/// A scenario from the space of the sweep, from draw `i`.
fn draw(i: u64) -> Scenario {
    let mut r = ChaCha8Rng::seed_from_u64(i);
    let mut s = Scenario {
        seed: r.gen_range(1..1_000_000),
        windows: r.gen_range(1..=4),
        ..Scenario::default()
    };
    s.auv.max_speed = r.gen_range(0.2..3.0);
    s.usv.max_speed = r.gen_range(0.2..3.0);
    s.team.auvs = r.gen_range(1..=25);
    s.horizon.steps = r.gen_range(2..=40);
    s.horizon.dt = r.gen_range(10.0..200.0);
    let ds: f64 = r.gen_range(60.0..400.0);
    s.acoustic.sonar_range = ds;
    s.acoustic.band_tolerance = 0.2 * ds;
    s.acoustic.max_range = s.acoustic.max_range.max(2.0 * ds);
    let f = &mut s.seafloor.synthetic;
    f.seamounts = r.gen_range(0..=60);
    f.valleys = r.gen_range(0..=30);
    s
}

fn main() {
    let raw: Vec<String> = std::env::args().skip(1).collect();
    if raw.first().map(String::as_str) == Some("show") {
        let i = raw
            .get(1)
            .and_then(|a| a.parse().ok())
            .expect("show I: I is an integer");
        print!(
            "{}",
            toml::to_string(&draw(i)).expect("a scenario serialises")
        );
        return;
    }
    let args: Vec<u64> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("DRAWS [FIRST_DRAW] are integers"))
        .collect();
    let draws = args.first().copied().unwrap_or(100);
    let first = args.get(1).copied().unwrap_or(0);
    println!(
        "draw,seed,auv_speed,usv_speed,auvs,steps,dt,ds,windows,outcome,seconds,unconverged,detail"
    );
    let (mut plans, mut errors, mut fails) = (0, 0, 0);
    for i in first..first + draws {
        let s = draw(i);
        let clock = std::time::Instant::now();
        // the stages that did not converge, "w1 step3 max_iterations"
        let mut unconverged = Vec::new();
        let outcome = match mission::scenario_floor(&s, std::path::Path::new(".")) {
            Err(e) => ("error", e.to_string()),
            Ok((floor, _)) => match Planner::new(&s, &floor).run() {
                Err(e) => ("error", e.to_string()),
                Ok(p) => {
                    for w in &p.windows {
                        for (step, st) in [("step1", &w.step1), ("step3", &w.final_)] {
                            if st.status != "converged" {
                                unconverged.push(format!("w{} {step} {}", w.index, st.status));
                            }
                        }
                    }
                    let r = shoal::check(&p, &floor);
                    if r.passed() {
                        ("plan", p.warnings.join(" | "))
                    } else {
                        let failing: Vec<&str> = r.failures().iter().map(|f| f.name).collect();
                        ("FAIL", failing.join(" | "))
                    }
                }
            },
        };
        match outcome.0 {
            "plan" => plans += 1,
            "error" => errors += 1,
            _ => fails += 1,
        }
        println!(
            "{i},{},{:.3},{:.3},{},{},{:.1},{:.1},{},{},{:.2},\"{}\",\"{}\"",
            s.seed,
            s.auv.max_speed,
            s.usv.max_speed,
            s.team.auvs,
            s.horizon.steps,
            s.horizon.dt,
            s.acoustic.sonar_range,
            s.windows,
            outcome.0,
            clock.elapsed().as_secs_f64(),
            unconverged.join(" | "),
            outcome.1.replace('"', "'")
        );
    }
    eprintln!("{draws} draws: {plans} plans that pass their check, {errors} errors, {fails} plans that fail it");
}
