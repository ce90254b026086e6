fn main() -> anyhow::Result<()> {
    let s = shoal::scenario::Scenario::default();
    let (nx, ny, c) = (481usize, 481usize, 25.0);
    let mut z = vec![0.0; nx * ny];
    let bumps = [(300.0, 100.0, 40.0, 200.0), (800.0, -300.0, 35.0, 300.0), (-400.0, 500.0, -30.0, 400.0), (1500.0, 200.0, 40.0, 250.0)];
    for j in 0..ny { for i in 0..nx {
        let x = -6000.0 + i as f64 * c; let y = -6000.0 + j as f64 * c;
        let mut v = -100.0 - 0.002 * x + 0.001 * y;
        for (bx, by, h, r) in bumps { v += h * (-((x - bx).powi(2) + (y - by).powi(2)) / (2.0 * r * r)).exp(); }
        z[j * nx + i] = v.max(-140.0).min(-50.0);
    }}
    let floor = shoal::seafloor::Seafloor::from_nodes(nx, ny, -6000.0, -6000.0, c, c, z, vec![false; nx * ny])?;
    let input = shoal::planner::PlanInput {
        scenario: &s,
        floor: &floor,
        scenario_source: "embedded default".into(),
        overrides: vec![],
        seafloor_source: ("synthetic".into(), None),
    };
    let t = std::time::Instant::now();
    let plan = shoal::planner::plan(&input)?;
    let st = &plan.windows[0].step1;
    for it in &st.scp {
        eprintln!("{:8.1} {:14.4} {:14.4} {:12.4e} {:8.3} {} {:.2e} {} {:.4}", it.trust_region, it.merit_before, it.merit_after, it.predicted, it.ratio, it.accepted, it.violation, it.solver_status, it.solver_time_s);
    }
    eprintln!("{} iters {:?} {:.3}s", st.status, st.objective, t.elapsed().as_secs_f64());
    shoal::output::write_plan(&plan, std::path::Path::new("plan.json"))?;
    Ok(())
}
