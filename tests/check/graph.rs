//! The Step 2 / Step 3 families on hand-built plans: the builder gives every plan an honest
//! graph (A2U link = the AUV nearest the USV in Step 1's positions, A2A path in index order) and
//! link report (bands of ±5 m around the final lengths, clipped to [0, ρ·d_s], ρ the plan's
//! `acoustic.link_margin`; a link longer than ρ·d_s gets [ρ·d_s − d_t, ρ·d_s] and is listed in
//! `out_of_band`), all computed here. Each test breaks one thing and expects exactly its family
//! to fail.

use super::*;
use shoal::plan::{Band, Link, OutOfBand};

fn dist(p: [f64; 3], q: [f64; 3]) -> f64 {
    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt()
}

fn end(st: &Stage, who: Option<usize>, k: usize) -> [f64; 3] {
    match who {
        None => {
            let p = st.usv.position[k];
            [p[0], p[1], 0.0]
        }
        Some(n) => st.auvs[n].position[k],
    }
}

/// Length of `link` at step k in the final stage of window `w`.
fn length(plan: &Plan, w: usize, k: usize, link: Link) -> f64 {
    let st = &plan.windows[w].final_;
    dist(end(st, Some(link.a), k), end(st, link.b, k))
}

/// The honest Step 2 graph of every window (P3 by nearest in Step 1's positions; the A2A path
/// 0–1–2–…), then [`fill_links`].
pub(super) fn fill_graph(plan: &mut Plan) {
    let n = plan.scenario.team.auvs;
    for win in &mut plan.windows {
        let st = &win.step1;
        let steps = st.usv.position.len();
        win.graph.a2u = (0..steps)
            .map(|k| {
                let usv = end(st, None, k);
                (0..n)
                    .min_by(|&a, &b| {
                        dist(end(st, Some(a), k), usv).total_cmp(&dist(end(st, Some(b), k), usv))
                    })
                    .unwrap()
            })
            .collect();
        win.graph.a2a = (0..steps)
            .map(|_| (1..n).map(|i| [i - 1, i]).collect())
            .collect();
    }
    fill_links(plan);
}

/// The link report of every window from its graph and final positions.
pub(super) fn fill_links(plan: &mut Plan) {
    let a = &plan.scenario.acoustic;
    let (top, d_t) = (a.link_margin * a.sonar_range, a.band_tolerance);
    for w in 0..plan.windows.len() {
        let g = plan.windows[w].graph.clone();
        let (mut links, mut bands, mut out) = (vec![], vec![], vec![]);
        for k in 0..g.a2u.len() {
            let mut at_k = vec![Link {
                a: g.a2u[k],
                b: None,
            }];
            at_k.extend(g.a2a[k].iter().map(|e| Link {
                a: e[0],
                b: Some(e[1]),
            }));
            let mut bands_k = vec![];
            for &link in &at_k {
                let len = length(plan, w, k, link);
                let band = if len <= top {
                    Band {
                        lo: (len - 5.0).max(0.0),
                        hi: (len + 5.0).min(top),
                    }
                } else {
                    let band = Band {
                        lo: top - d_t,
                        hi: top,
                    };
                    if k > 0 {
                        out.push(OutOfBand {
                            k,
                            link,
                            length: len,
                            band,
                        });
                    }
                    band
                };
                bands_k.push(band);
            }
            links.push(at_k);
            bands.push(bands_k);
        }
        let report = &mut plan.windows[w].links;
        report.links = links;
        report.bands = bands;
        report.out_of_band = out;
        report.los_rounds = 1;
    }
}

/// Spec with a third AUV, 30 m north of the USV's track, doing what AUV 0 does.
fn spec3(windows: usize) -> Spec {
    let mut sp = spec(windows);
    sp.s.team.auvs = 3;
    sp.auv0.push([0.0, 30.0, -55.0]);
    for w in &mut sp.auv_u {
        let u = w[0].clone();
        w.push(u);
    }
    sp
}

const PATH: &str = "A2A Hamiltonian path";
const A2U: &str = "A2U link";
const BANDS: &str = "link bands within [0, ρ·d_s]";
const IN_BAND: &str = "links in band";
const CONNECTED: &str = "acoustic connectivity (range + line of sight)";
const CHAIN_LOS: &str = "planned chain line of sight";
const ALL: [&str; 6] = [PATH, A2U, BANDS, IN_BAND, CONNECTED, CHAIN_LOS];

#[test]
fn honest_graphs_pass_every_graph_family() {
    let floor = flat();
    for sp in [spec(2), spec3(2)] {
        let plan = build(&sp, &floor);
        let r = check_plan(&plan, &floor);
        assert!(r.passed(), "\n{}", r.table());
        for name in ALL {
            let f = r.family(name).unwrap();
            assert!(f.checked > 0, "{name} checked nothing");
        }
        let f = r.family(CONNECTED).unwrap();
        assert_eq!(f.checked, 2 * (K + 1));
        assert!(
            f.where_.contains("every AUV reaches the USV"),
            "{}",
            f.where_
        );
    }
}

#[test]
fn a_plan_without_step2_data_skips_the_graph_families() {
    let floor = flat();
    let mut plan = build(&spec(2), &floor);
    for win in &mut plan.windows {
        win.graph = Default::default();
        win.links = Default::default();
    }
    record_metrics(&mut plan, &floor); // no planned chain at any step: chain fraction 0
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());
    for name in ALL {
        let f = r.family(name).unwrap();
        assert_eq!(f.checked, 0, "{name}");
        assert_eq!(f.where_, "no Step 2 graph in this plan");
    }

    // one window with a graph, one without: malformed
    let mut p = build(&spec(2), &floor);
    p.windows[1].graph = Default::default();
    p.windows[1].links = Default::default();
    record_metrics(&mut p, &floor);
    let r = check_plan(&p, &floor);
    assert_fails_exactly(&r, &["structure"]);
    assert!(r.problems[0].contains("window 1 has no Step 2 graph"));

    // a graph without a link report: the link families cannot be checked
    let mut p = build(&spec(2), &floor);
    p.windows[0].links = Default::default();
    record_metrics(&mut p, &floor);
    let r = check_plan(&p, &floor);
    assert_fails_exactly(&r, &[IN_BAND, CHAIN_LOS]);
    assert!(r.family(IN_BAND).unwrap().where_.contains("no link report"));
}

#[test]
fn a_cycle_in_the_a2a_edges_fails_the_path_family_only() {
    let floor = flat();
    let mut plan = build(&spec3(1), &floor);
    plan.windows[0].graph.a2a[2] = vec![[0, 1], [1, 2], [0, 2]];
    fill_links(&mut plan); // the links follow the graph, so only the graph is wrong
    record_metrics(&mut plan, &floor); // and so do the recorded fractions
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &[PATH]);
    let f = r.family(PATH).unwrap();
    assert!(f.where_.contains("window 0, k = 2"), "{}", f.where_);
    assert!(f.where_.contains("closes a cycle"), "{}", f.where_);

    // a repeated edge, which leaves AUV 2 out
    let mut plan = build(&spec3(1), &floor);
    plan.windows[0].graph.a2a[3] = vec![[0, 1], [1, 0]];
    fill_links(&mut plan);
    record_metrics(&mut plan, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &[PATH]);
    let f = r.family(PATH).unwrap();
    assert!(f.where_.contains("repeated"), "{}", f.where_);
    assert!(f.where_.contains("unreachable"), "{}", f.where_);
}

#[test]
fn links_that_are_not_the_graph_fail_the_path_family_only() {
    let floor = flat();
    let mut plan = build(&spec3(1), &floor);
    // drop the A2A link 1–2 at k = 1 (and its band, so the report stays well formed)
    let l = &mut plan.windows[0].links;
    l.links[1].pop();
    l.bands[1].pop();
    record_metrics(&mut plan, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &[PATH]);
    let f = r.family(PATH).unwrap();
    assert!(f.where_.contains("k = 1"), "{}", f.where_);
    assert!(f.where_.contains("[1, 2] appears 0 times"), "{}", f.where_);
}

#[test]
fn a_wrong_a2u_link_fails_the_a2u_family_only() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    let g = &mut plan.windows[0].graph;
    let right = g.a2u[2];
    g.a2u[2] = 1 - right;
    fill_links(&mut plan);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &[A2U]);
    let f = r.family(A2U).unwrap();
    assert!(
        f.where_
            .contains(&format!("k = 2, A2U link AUV {}", 1 - right)),
        "{}",
        f.where_
    );
    assert!(
        f.where_.contains(&format!("AUV {right} is nearer")),
        "{}",
        f.where_
    );
    // the margin is the difference of the two distances, in Step 1's positions
    let st = &plan.windows[0].step1;
    let usv = end(st, None, 2);
    let want = dist(end(st, Some(right), 2), usv) - dist(end(st, Some(1 - right), 2), usv);
    assert!((f.worst_margin - want).abs() < 1e-9, "{f:?} vs {want}");
    assert!(want < -1.0);
}

#[test]
fn a_link_out_of_band_fails_unless_it_is_reported() {
    let floor = flat();
    let mut plan = build(&spec(1), &floor);
    let link = plan.windows[0].links.links[3][1]; // the A2A link 0–1
    let len = length(&plan, 0, 3, link);
    let band = Band {
        lo: len + 10.0,
        hi: len + 20.0,
    };
    plan.windows[0].links.bands[3][1] = band;
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &[IN_BAND]);
    let f = r.family(IN_BAND).unwrap();
    assert!((f.worst_margin + 10.0).abs() < 1e-9, "{f:?}");
    assert!(
        f.where_.contains("k = 3, A2A link AUV 0–AUV 1"),
        "{}",
        f.where_
    );
    assert!(
        f.where_.contains("not listed in out_of_band"),
        "{}",
        f.where_
    );

    // reported: accepted
    let entry = OutOfBand {
        k: 3,
        link,
        length: len,
        band,
    };
    plan.windows[0].links.out_of_band.push(entry);
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());

    // reported with a wrong length, or at a step where it is not planned: not accepted
    for bad in [
        OutOfBand {
            length: len + 1e-3,
            ..entry
        },
        OutOfBand { k: 2, ..entry },
        OutOfBand {
            link: Link { a: 1, b: None },
            k: 2,
            ..entry
        },
    ] {
        let mut p = plan.clone();
        p.windows[0].links.out_of_band.push(bad);
        let r = check_plan(&p, &floor);
        assert_fails_exactly(&r, &[IN_BAND]);
        assert!(r
            .family(IN_BAND)
            .unwrap()
            .where_
            .contains("out_of_band entry"));
    }

    // k = 0 is the fixed start: its lengths need not be in band
    let mut plan = build(&spec(1), &floor);
    plan.windows[0].links.bands[0][1] = band;
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());
}

#[test]
fn a_band_beyond_d_s_fails_the_band_family_only() {
    let floor = flat();
    let d_s = spec(1).s.acoustic.sonar_range;
    for band in [
        Band {
            lo: 0.0,
            hi: d_s + 1e-6,
        },
        Band { lo: -1.0, hi: 60.0 },
        Band { lo: 60.0, hi: 0.0 },
    ] {
        let mut plan = build(&spec(1), &floor);
        // on the A2U link at k = 0 (whose length is not required in band)
        plan.windows[0].links.bands[0][0] = band;
        let r = check_plan(&plan, &floor);
        assert_fails_exactly(&r, &[BANDS]);
        assert!(r.family(BANDS).unwrap().where_.contains("k = 0"));
    }
}

#[test]
fn a_seamount_on_a_planned_link_fails_the_chain_line_of_sight_only() {
    let mut sp = spec(1);
    sp.s.acoustic.resolution = 1.0;
    // the midpoint of the A2A link at k = 2 (the floor does not change the rollout)
    let probe = build(&sp, &flat());
    let link = probe.windows[0].links.links[2][1];
    let st = &probe.windows[0].final_;
    let (a, b) = (end(st, Some(link.a), 2), end(st, link.b, 2));
    let mid = [
        (a[0] + b[0]) / 2.0,
        (a[1] + b[1]) / 2.0,
        (a[2] + b[2]) / 2.0,
    ];
    // a one-node peak at −30 m right under it; the AUVs' own paths stay ≥ 10 m away from it
    let d = 5.0;
    let floor = grid(mid[0] - 60.0 * d, mid[1] - 60.0 * d, d, 121, |x, y| {
        let peak = (x - mid[0]).abs() < 1e-6 && (y - mid[1]).abs() < 1e-6;
        Some(if peak { -30.0 } else { -100.0 })
    });
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    // both AUVs still reach the USV directly: the team stays connected
    assert_fails_exactly(&r, &[CHAIN_LOS]);
    let f = r.family(CHAIN_LOS).unwrap();
    assert!(
        f.where_.contains("k = 2, A2A link AUV 0–AUV 1"),
        "{}",
        f.where_
    );
    // the link passes 25 m below the peak; the 1 m samples straddle it, on its slopes
    assert!(
        f.worst_margin < -10.0 && f.worst_margin >= mid[2] + 30.0 - 1e-9,
        "{f:?}, link midpoint at z = {}",
        mid[2]
    );
}

#[test]
fn an_auv_out_of_range_of_everyone_fails_connectivity_only() {
    // δ = 100 s: the USV and AUV 0 stay put; AUV 1 runs 140 m west at 1.5 m/s, coasts, and
    // comes back. At k = 1 and 2 it is > 150 m from both (its planned links are then longer
    // than d_s and listed in out_of_band, honestly); at k = 0 and K it is near again.
    let floor = flat();
    let mut sp = spec(1);
    sp.s.auv.min_speed = 0.0; // AUVs held still: no cruise floor
    sp.s.horizon.dt = 100.0;
    let e = rates(&sp.s)[0];
    sp.usv_u[0] = vec![[0.0; 2]; K];
    sp.auv_u[0][0] = vec![[0.0; 3]; K];
    sp.auv_u[0][1] = vec![
        [-1.5 * e, 0.0, 0.0],
        [0.0; 3],
        [1.5 * e, 0.0, 0.0],
        [0.0; 3],
    ];
    let plan = build(&sp, &floor);
    let x1 = plan.windows[0].final_.auvs[1].position[1][0];
    assert!(x1 < -155.0, "{x1}");
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &[CONNECTED]);
    let f = r.family(CONNECTED).unwrap();
    assert_eq!(f.worst_margin, -1.0);
    assert!(
        f.where_
            .contains("window 0, k = 1, cut off from the USV: AUV 1"),
        "{}",
        f.where_
    );
    assert!(f.where_.contains("> d_s = 150 m"), "{}", f.where_);
    assert!(!plan.windows[0].links.out_of_band.is_empty());
}

#[test]
fn a_blocked_line_of_sight_cuts_an_auv_off() {
    // AUV 1 waits at the bottom of a pit: a square rim of nodes at −30 m, 10 m around it (the
    // floor elsewhere at −100 m, AUV 1 at −90 m). Every line from it to the USV or AUV 0 meets
    // the rim, although both are in range.
    let mut sp = spec(1);
    sp.s.auv.min_speed = 0.0; // AUVs held still: no cruise floor
    sp.s.acoustic.resolution = 1.0;
    sp.auv0[1] = [-20.0, -10.0, -90.0];
    sp.auv_u[0][1] = vec![[0.0; 3]; K];
    let (cx, cy) = (-20.0, -10.0);
    let floor = grid(cx - 300.0, cy - 300.0, 5.0, 121, |x, y| {
        let r = (x - cx).abs().max((y - cy).abs());
        Some(if (r - 10.0).abs() < 1e-6 {
            -30.0
        } else {
            -100.0
        })
    });
    let r = check_plan(&build(&sp, &floor), &floor);
    // the planned A2A link 0–1 is blocked too
    assert_fails_exactly(&r, &[CONNECTED, CHAIN_LOS]);
    let f = r.family(CONNECTED).unwrap();
    assert_eq!(f.worst_margin, -1.0);
    assert!(
        f.where_
            .contains("window 0, k = 0, cut off from the USV: AUV 1"),
        "{}",
        f.where_
    );
    assert!(f.where_.contains("no line of sight"), "{}", f.where_);
}

#[test]
fn a_link_over_an_obstacle_cell_has_no_line_of_sight() {
    // AUV 0 waits at (20, 10), AUV 1 at (20, 60): their link runs along x = 20, through the
    // cells beside a NODATA node at (25, 35), where the floor along x = 20 is still −100 m
    let mut sp = spec(1);
    sp.s.auv.min_speed = 0.0; // AUVs held still: no cruise floor
    sp.auv0 = vec![[20.0, 10.0, -50.0], [20.0, 60.0, -60.0]];
    sp.auv_u[0] = vec![vec![[0.0; 3]; K]; 2];
    let floor = grid(-300.0, -300.0, 5.0, 121, |x, y| {
        ((x - 25.0).abs() > 1e-6 || (y - 35.0).abs() > 1e-6).then_some(-100.0)
    });
    let plan = build(&sp, &floor);
    let r = check_plan(&plan, &floor);
    // the planned link crosses the obstacle at every step, with clearance; once the USV is
    // east of x = 20, AUV 1's own line to it crosses too, and AUV 1 is cut off
    assert_fails_exactly(&r, &["no obstacle (NODATA/land)", CONNECTED]);
    let f = r.family("no obstacle (NODATA/land)").unwrap();
    assert!(
        f.where_
            .contains("window 0, k = 1, A2A link AUV 0–AUV 1: sample")
            && f.where_.contains("is over a NODATA cell"),
        "{}",
        f.where_
    );
    let f = r.family(CONNECTED).unwrap();
    assert!(
        f.where_.contains("cut off from the USV: AUV 1")
            && f.where_.contains("it crosses an obstacle cell"),
        "{}",
        f.where_
    );
    assert!(r.family(CHAIN_LOS).unwrap().worst_margin > 0.0);
}

#[test]
fn the_final_stage_is_the_plan() {
    let floor = flat();
    // Step 1 of window 0 took other inputs (slower AUVs) than the final stage: fine, as long as
    // the graph is built on Step 1's positions and window 1 starts from the final stage's end
    let mut sp = spec(2);
    sp.s.auv.min_speed = 0.0; // the slower AUVs stay below the spec's cruise floor
    let mut slow = spec(2);
    for u in slow.auv_u[0].iter_mut().flatten() {
        u[0] *= 0.5;
    }
    let mut plan = build(&sp, &floor);
    plan.windows[0].step1 = build(&slow, &floor).windows[0].step1.clone();
    fill_graph(&mut plan);
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());

    // the other way round, window 1 no longer starts where the executed plan ended
    let mut plan = build(&sp, &floor);
    plan.windows[0].final_ = build(&slow, &floor).windows[0].final_.clone();
    fill_graph(&mut plan);
    super::record_metrics(&mut plan, &floor);
    let r = check_plan(&plan, &floor);
    assert_fails_exactly(&r, &["window chain"]);
    let f = r.family("window chain").unwrap();
    assert!(f.where_.starts_with("window 1, k = 0"), "{}", f.where_);
}

#[test]
fn malformed_graphs_fail_the_structure_without_panicking() {
    let floor = flat();
    let plan = build(&spec3(2), &floor);
    type Break = fn(&mut Plan);
    let breaks: [Break; 12] = [
        |p| p.windows[0].graph.a2u[1] = 7,
        |p| p.windows[0].graph.a2u.truncate(2),
        |p| p.windows[1].graph.a2a[2] = vec![[0, 9], [1, 2]],
        |p| p.windows[1].graph.a2a.truncate(3),
        |p| p.windows[0].links.links[1].push(Link { a: 5, b: Some(8) }),
        |p| p.windows[0].links.links.truncate(3),
        |p| p.windows[0].links.bands[2].clear(),
        |p| p.windows[0].links.bands.clear(),
        |p| {
            p.windows[0].links.out_of_band.push(OutOfBand {
                k: 99,
                link: Link { a: 0, b: None },
                length: 1.0,
                band: Band { lo: 0.0, hi: 1.0 },
            })
        },
        |p| {
            p.windows[1].links.out_of_band.push(OutOfBand {
                k: 1,
                link: Link { a: 3, b: Some(0) },
                length: 1.0,
                band: Band { lo: 0.0, hi: 1.0 },
            })
        },
        |p| p.windows[1].final_.auvs.truncate(1),
        |p| p.scenario.team.auvs = usize::MAX,
    ];
    for (i, b) in breaks.iter().enumerate() {
        let mut p = plan.clone();
        b(&mut p);
        let r = check_plan(&p, &floor);
        assert!(
            failing(&r).contains(&"structure"),
            "break {i}\n{}",
            r.table()
        );
        let _ = r.table();
    }
    // NaN bands fail their families, never panic
    let mut p = plan.clone();
    p.windows[0].links.bands[2][0] = Band {
        lo: f64::NAN,
        hi: f64::NAN,
    };
    let r = check_plan(&p, &floor);
    assert_fails_exactly(&r, &[BANDS, IN_BAND]);
}

/// Spec with a third AUV 125 m north of the USV's track, doing what AUV 0 does: its A2A edge
/// to AUV 1 is within d_s = 150 m but beyond the default ρ·d_s = 120 m.
fn spec_far(windows: usize) -> Spec {
    let mut sp = spec3(windows);
    sp.auv0[2] = [0.0, 125.0, -55.0];
    sp
}

/// A plan must keep the margin it claims: its bands top at ρ·d_s (the plan's
/// `acoustic.link_margin`), and a link beyond its band is listed in `out_of_band`. Honest, the
/// far edge is listed and the plan passes; unlisted, or covered by a band raised to d_s, or
/// with the plan claiming a margin its bands exceed, exactly the family that owns it fails.
#[test]
fn a_link_beyond_its_margin_fails_unless_reported() {
    let floor = flat();
    let plan = build(&spec_far(1), &floor);
    let rho = plan.scenario.acoustic.link_margin;
    assert!(rho < 1.0, "the default plans links inside d_s");
    assert!(
        !plan.windows[0].links.out_of_band.is_empty(),
        "the far edge is beyond ρ·d_s"
    );
    let r = check_plan(&plan, &floor);
    assert!(r.passed(), "\n{}", r.table());

    // not listed in out_of_band: the link is beyond its band, unreported
    let mut p = plan.clone();
    p.windows[0].links.out_of_band.clear();
    let r = check_plan(&p, &floor);
    assert_fails_exactly(&r, &[IN_BAND]);
    assert!(
        r.family(IN_BAND).unwrap().where_.contains("not listed"),
        "{}",
        r.family(IN_BAND).unwrap().where_
    );

    // its band raised to d_s to cover it: the band is beyond the plan's margin
    let mut p = plan.clone();
    let d_s = p.scenario.acoustic.sonar_range;
    for o in std::mem::take(&mut p.windows[0].links.out_of_band) {
        let links = &p.windows[0].links.links[o.k];
        let i = links.iter().position(|l| *l == o.link).unwrap();
        p.windows[0].links.bands[o.k][i] = Band { lo: 0.0, hi: d_s };
    }
    let r = check_plan(&p, &floor);
    assert_fails_exactly(&r, &[BANDS]);
    assert!(
        r.family(BANDS).unwrap().where_.contains("link_margin"),
        "{}",
        r.family(BANDS).unwrap().where_
    );

    // the plan claims a tighter margin than its bands keep
    let mut p = build(&spec3(1), &floor);
    p.scenario.acoustic.link_margin = 0.2; // ρ·d_s = 30 m, the bands reach ≈ 50 m
    let r = check_plan(&p, &floor);
    assert_fails_exactly(&r, &[BANDS]);
}
