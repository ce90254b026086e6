//! Malformed plans: structure failures, never a panic.

use super::*;

#[test]
fn truncated_arrays_fail_the_structure_without_panicking() {
    let floor = flat();
    let plan = build(&spec(2), &floor);
    let r = |p: &Plan| {
        let r = check_plan(p, &floor);
        assert!(failing(&r).contains(&"structure"), "\n{}", r.table());
        r
    };

    let mut p = plan.clone();
    p.windows[1].final_.auvs[0].position.pop();
    let rep = r(&p);
    assert!(
        rep.problems[0].contains("window 1, AUV 0: 4 positions, expected 5"),
        "{:?}",
        rep.problems
    );

    let mut p = plan.clone();
    p.windows[0].final_.usv.input.truncate(1);
    r(&p);

    let mut p = plan.clone();
    p.windows[0].final_.auvs.pop();
    r(&p);

    let mut p = plan.clone();
    p.windows.pop();
    r(&p);

    let mut p = plan.clone();
    p.windows.clear();
    r(&p);

    let mut p = plan.clone();
    p.initial.auvs.clear();
    r(&p);

    let mut p = plan.clone();
    p.scenario.horizon.steps = 0;
    r(&p);

    // a corrupt K neither overflows nor makes the checker walk a huge range
    let mut p = plan.clone();
    p.scenario.horizon.steps = usize::MAX;
    r(&p);

    let mut p = plan.clone();
    p.format = "shoal-plan/0".into();
    r(&p);
}

/// Every array of the plan cut to every shorter length, one at a time: never a panic, always a
/// structure failure.
#[test]
fn no_truncation_of_any_array_panics() {
    let floor = flat();
    let plan = build(&spec(2), &floor);
    type Cut = fn(&mut Plan, usize, usize, usize) -> usize;
    // (window, auv, new length) → original length
    let cuts: [Cut; 16] = [
        |p, w, _, l| cut(&mut p.windows[w].final_.usv.position, l),
        |p, w, _, l| cut(&mut p.windows[w].final_.usv.input, l),
        |p, w, n, l| cut(&mut p.windows[w].final_.auvs[n].position, l),
        |p, w, n, l| cut(&mut p.windows[w].final_.auvs[n].velocity, l),
        |p, w, n, l| cut(&mut p.windows[w].final_.auvs[n].input, l),
        |p, w, n, l| cut(&mut p.windows[w].final_.auvs[n].surge_speed, l),
        |p, w, n, l| cut(&mut p.windows[w].final_.auvs[n].heading, l),
        |p, w, _, l| cut(&mut p.windows[w].final_.auvs, l),
        |p, w, _, l| cut(&mut p.windows[w].step1.usv.position, l),
        |p, w, _, l| cut(&mut p.windows[w].step1.usv.input, l),
        |p, w, n, l| cut(&mut p.windows[w].step1.auvs[n].position, l),
        |p, w, n, l| cut(&mut p.windows[w].step1.auvs[n].velocity, l),
        |p, w, n, l| cut(&mut p.windows[w].step1.auvs[n].input, l),
        |p, w, n, l| cut(&mut p.windows[w].step1.auvs[n].surge_speed, l),
        |p, w, n, l| cut(&mut p.windows[w].step1.auvs[n].heading, l),
        |p, w, _, l| cut(&mut p.windows[w].step1.auvs, l),
    ];
    fn cut<T>(v: &mut Vec<T>, len: usize) -> usize {
        let was = v.len();
        v.truncate(len);
        was
    }
    let mut cases = 0;
    for c in cuts {
        for w in 0..2 {
            for n in 0..2 {
                for len in 0..=K {
                    let mut p = plan.clone();
                    let was = c(&mut p, w, n, len);
                    if len >= was {
                        continue;
                    }
                    let r = check_plan(&p, &floor);
                    assert!(failing(&r).contains(&"structure"), "\n{}", r.table());
                    let _ = r.table();
                    cases += 1;
                }
            }
        }
    }
    assert!(cases > 200);
}

#[test]
fn non_finite_numbers_fail_without_panicking() {
    let floor = flat();
    let plan = build(&spec(2), &floor);
    for value in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300] {
        for (w, n, k) in [(0, 0, 0), (0, 1, 2), (1, 0, K)] {
            let mut p = plan.clone();
            p.windows[w].final_.auvs[n].position[k][0] = value;
            p.windows[w].final_.auvs[n].velocity[k][1] = value;
            let r = check_plan(&p, &floor);
            assert!(!r.passed(), "\n{}", r.table());
            if !value.is_finite() {
                assert!(failing(&r).contains(&"structure"));
            }
            let _ = r.table();
        }
        let mut p = plan.clone();
        p.scenario.horizon.dt = value;
        p.scenario.acoustic.resolution = value;
        assert!(!check_plan(&p, &floor).passed());
    }
    let mut p = plan.clone();
    p.scenario.acoustic.resolution = 0.0;
    assert!(failing(&check_plan(&p, &floor)).contains(&"structure"));
    let mut p = plan;
    p.scenario.auv.mass = 0.0;
    p.scenario.auv.added_mass_surge = 0.0;
    assert!(failing(&check_plan(&p, &floor)).contains(&"model record"));
}
