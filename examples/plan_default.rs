//! The library in three lines: plan the embedded default scenario (the paper's experiment,
//! Section V) over its synthetic floor, and check the plan independently.
//!
//! Run: cargo run --release --example plan_default

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scenario = shoal::Scenario::default();
    let floor = shoal::Seafloor::synthetic(&scenario.seafloor.synthetic, scenario.seed)?;
    let plan = shoal::Planner::new(&scenario, &floor)
        .on_progress(|p| {
            if let shoal::Progress::Step3 { window, stage, .. } = p {
                eprintln!(
                    "window {window}: step 3 {} after {} SCP iterations",
                    stage.status, stage.iterations
                );
            }
        })
        .run()?;

    let m = &plan.metrics;
    println!(
        "{} window(s), N = {} AUVs: input energy {:.3} (m/s²)², explored {:.3} km²",
        plan.windows.len(),
        scenario.team.auvs,
        m.input_energy,
        m.explored_area_km2
    );
    let report = shoal::check(&plan, &floor);
    if !report.passed() {
        return Err(format!("the plan fails its check:\n{}", report.table()).into());
    }
    println!("check: every constraint holds");
    Ok(())
}
