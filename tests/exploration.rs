//! Issue 14: bigger teams explore more, long missions explore new ground, and a plan that
//! does neither says why. Every plan here also passes `shoal check`.

use shoal::check::check_plan;
use shoal::linearise::nearest_on_track;
use shoal::mission::scenario_floor;
use shoal::plan::Plan;
use shoal::scenario::{AwayFrom, Scenario, W8Scaling, WeightScaling};
use shoal::seafloor::Seafloor;

fn plan(s: &Scenario) -> (Plan, Seafloor) {
    let (floor, _) = scenario_floor(s, std::path::Path::new("")).unwrap();
    let p = shoal::Planner::new(s, &floor).run().unwrap();
    let r = check_plan(&p, &floor);
    assert!(r.passed(), "{}", r.table());
    (p, floor)
}

/// Start-to-end distance of the USV in window `w`, metres.
fn usv_moved(p: &Plan, w: usize) -> f64 {
    let u = &p.windows[w].final_.usv.position;
    let (a, b) = (u[0], u[u.len() - 1]);
    (b[0] - a[0]).hypot(b[1] - a[1])
}

fn team(n: usize) -> Scenario {
    let mut s = Scenario::default();
    s.team.auvs = n;
    s
}

/// Regression (issue 14): with the paper's sums as weights, the team's input energy grew with
/// N and OF1_8 did not, so the weights that suit 5 AUVs stopped a bigger team (seed 1: the USV
/// moved 2992 m with 5 AUVs, 730 m with 10; explored 0.685 and 0.292 km²). Weighed per AUV,
/// 10 AUVs go as far as 5 and sweep more floor.
#[test]
fn regression_a_team_of_ten_moves_as_far_as_five_and_explores_more() {
    let (five, _) = plan(&team(5));
    let (ten, _) = plan(&team(10));
    let reach = 20.0 * 100.0 * 1.5; // K·δ at the USV's limit
    assert!(
        usv_moved(&five, 0) > 0.95 * reach,
        "{}",
        usv_moved(&five, 0)
    );
    assert!(usv_moved(&ten, 0) > 0.95 * reach, "{}", usv_moved(&ten, 0));
    let (a5, a10) = (
        five.metrics.explored_area_km2,
        ten.metrics.explored_area_km2,
    );
    assert!(a10 > 1.3 * a5, "N = 5: {a5} km², N = 10: {a10} km²");
    assert!(five.warnings.is_empty() && ten.warnings.is_empty());
}

/// Regression (issue 13's sweep, draw 1002: 9 AUVs of 0.51 m/s, 12 steps of 31 s): per m²,
/// OF1_8 paid a distance 17× less against the input energy it costs than on the paper's
/// window of 20 steps of 100 s, and the USV ended 11 m from its start (13 of 37 draws had a
/// window whose team barely moved). With `weights.w8_scaling = "energy"` the trade is the
/// paper's window's, and the team makes its way: the same scenario with 3 AUVs went 235 m
/// (94 m per m²), the whole 186 m its AUVs can go, and swept 0.023 km² (0.011), before the
/// separation, the links' margin and the current in the plan.
#[test]
fn regression_a_short_window_of_slow_auvs_barely_moved() {
    let mut s = team(3);
    s.seed = 430134;
    s.horizon.steps = 12;
    s.horizon.dt = 31.0;
    s.auv.max_speed = 0.5;
    s.auv.min_speed = 0.0; // slow AUVs: no cruise floor
    assert_eq!(s.weights.w8_scaling, W8Scaling::Energy);
    let reach = s.reach();
    assert!((reach - 186.0).abs() < 1e-9, "{reach}");
    let (scaled, _) = plan(&s);
    s.weights.w8_scaling = W8Scaling::None;
    let (per_m2, _) = plan(&s);
    // the team goes its reach with OF1_8 weighed against the energy (184 m, 0.99 of it), and
    // no less far nor over less ground than with OF1_8 per m² (with the separation, the
    // links' margin and the current planned in, per m² now goes 184 m too; 0.6 of the reach
    // or less before them)
    let (a, b) = (usv_moved(&scaled, 0), usv_moved(&per_m2, 0));
    assert!(a > 0.9 * reach, "{a}");
    assert!(a >= b - 1.0, "{a} against {b}");
    assert!(
        scaled.metrics.explored_area_km2 >= 0.95 * per_m2.metrics.explored_area_km2,
        "{} against {}",
        scaled.metrics.explored_area_km2,
        per_m2.metrics.explored_area_km2
    );
}

/// On the paper's window (K = 20 steps of δ = 100 s) w8 weighs OF1_8 per m² under either
/// scaling, so the default plan is the paper's weighting.
#[test]
fn the_paper_window_weighs_of1_8_per_square_metre() {
    let s = Scenario::default();
    assert_eq!(s.w8(), s.weights.w8);
    let mut short = s.clone();
    short.horizon.dt = 50.0;
    assert_eq!(short.w8(), 4.0 * s.weights.w8);
}

/// A team whose energy outweighs OF1_8 barely moves, and the plan says so, naming the weights
/// to change (here the paper's P5 with its sums and OF1_8 per m², with w1 = 10⁷ per (m/s²)²;
/// with 10⁶ the lanes chain's spread reward alone moves the USV 207 m, past the warning's
/// 10 %, and so does the lanes term, which spreads the team across the track).
#[test]
fn a_team_that_barely_moves_is_told_which_weight_to_change() {
    let mut s = team(3);
    s.horizon.steps = 10;
    s.weights.scaling = WeightScaling::Sum;
    s.weights.w8_scaling = W8Scaling::None;
    s.weights.w1 = 1e7;
    s.weights.w_lanes = 0.0;
    // a vehicle that can stop (with the REMUS cruise floor no team barely moves)
    s.auv.min_speed = 0.0;
    let (p, _) = plan(&s);
    assert!(usv_moved(&p, 0) < 0.1 * 10.0 * 100.0 * 1.5);
    let w = p.warnings.join("\n");
    assert!(
        w.contains("window 0: the team barely moves")
            && w.contains("weights.w1 = 10000000")
            && w.contains("weights.w8 = 0.001")
            && w.contains("weights.scaling = \"sum\"")
            && w.contains("weights.w8_scaling = \"none\""),
        "{w}"
    );
}

/// Regression (issue 14): OF1_8 measured from each window's own start let a long mission
/// head back over water it had seen once the grid's edge turned it, without a warning. Measured
/// from the USV's track (the default), the third window of a mission on an 8 km grid, turned
/// by the east edge in the second, ends more than 2 km from anywhere the USV has been, sweeps
/// almost nothing twice, and the plan names the edge.
#[test]
fn regression_a_long_mission_heads_for_new_ground_and_names_the_grid_edge() {
    let mut s = team(3);
    s.windows = 3;
    s.seafloor.synthetic.size = [8000.0, 8000.0];
    assert_eq!(s.usv.away_from, AwayFrom::Track);
    let (p, _) = plan(&s);
    let earlier: Vec<[f64; 2]> = p.windows[..2]
        .iter()
        .flat_map(|w| w.final_.usv.position.iter().copied())
        .collect();
    let end = *p.windows[2].final_.usv.position.last().unwrap();
    let c = nearest_on_track(end, &earlier);
    let new_ground = (end[0] - c[0]).hypot(end[1] - c[1]);
    assert!(new_ground > 2000.0, "{new_ground} m from the earlier track");
    let m = &p.metrics;
    assert!(m.revisited_area_km2 < 0.05 * m.explored_area_km2, "{m:?}");
    let w = p.warnings.join("\n");
    // (window 1's east edge; with the cruise floor the team turns before it, from the
    // terminal margin's room, and window 2 names the north edge it then meets)
    assert!(
        w.contains("the grid's edge stops the team") && w.contains(" edge ("),
        "{w}"
    );
}

/// Each AUV's mean cross-track offset from the USV over steps 5..=K of window 0 (positive to
/// the left of the USV's course from start to end), sorted.
fn cross_track_offsets(p: &Plan) -> Vec<f64> {
    let w = &p.windows[0].final_;
    let u = &w.usv.position;
    let (a, b) = (u[0], u[u.len() - 1]);
    let len = (b[0] - a[0]).hypot(b[1] - a[1]);
    let left = [-(b[1] - a[1]) / len, (b[0] - a[0]) / len];
    let mut offsets: Vec<f64> = w
        .auvs
        .iter()
        .map(|auv| {
            let steps = 5..auv.position.len();
            let n = steps.len() as f64;
            steps
                .map(|k| {
                    let (q, c) = (auv.position[k], u[k]);
                    left[0] * (q[0] - c[0]) + left[1] * (q[1] - c[1])
                })
                .sum::<f64>()
                / n
        })
        .collect();
    offsets.sort_by(f64::total_cmp);
    offsets
}

/// Regression (seventeenth session): with OF1_5 alone (a sum of squared distances) a team of 15
/// gathered at the corridor's two edges: 7 of 14 neighbouring AUVs (seed 1) within 25 m of each
/// other across the track, sweeping the same strip, and gaps of up to 141 m unswept between
/// others (1.453 km²). The lanes term prices a lane neighbour closer than a swath across the
/// track: the team spreads into lanes and sweeps more (2.066 km²).
#[test]
fn regression_fifteen_auvs_sweep_lanes_rather_than_the_corridor_edges() {
    let mut s = team(15);
    let (lanes, _) = plan(&s);
    s.weights.w_lanes = 0.0;
    let (edges, _) = plan(&s);
    let close = |p: &Plan| {
        cross_track_offsets(p)
            .windows(2)
            .filter(|w| w[1] - w[0] < 0.5 * s.auv.swath_width)
            .count()
    };
    assert!(close(&edges) >= 5, "{:?}", cross_track_offsets(&edges));
    // (3 of 14 with the REMUS envelope, seed 1: pairs at 16, 19 and 25 m, each other gap
    // 28–63 m; 1 before it)
    assert!(close(&lanes) <= 3, "{:?}", cross_track_offsets(&lanes));
    let (a_lanes, a_edges) = (
        lanes.metrics.explored_area_km2,
        edges.metrics.explored_area_km2,
    );
    // (1.21× with the REMUS envelope, seed 1: 1.589 against 1.311 km²; 1.42× before it)
    assert!(
        a_lanes > 1.15 * a_edges,
        "with lanes {a_lanes} km², without {a_edges} km²"
    );
}

/// Each AUV's mean height above the floor over k = 1..=K of window 0, metres.
fn mean_heights(p: &Plan, floor: &Seafloor) -> Vec<f64> {
    p.windows[0]
        .final_
        .auvs
        .iter()
        .map(|auv| {
            let h: Vec<f64> = auv.position[1..]
                .iter()
                .map(|q| q[2] - floor.elevation(q[0], q[1]).unwrap())
                .collect();
            h.iter().sum::<f64>() / h.len() as f64
        })
        .collect()
}

/// Regression (eighteenth session): C1_5 bounds the 3-D range to the USV at the surface, so
/// an AUV gains width across the track by climbing, and the lanes term priced only the gaps:
/// of 15 AUVs (seed 1) five flew on average 17–51 m above the floor, where a 50 m swath sees
/// nothing, and the team's mean height was 15.9 m. The term now prices the height above the
/// survey altitude at the gaps' own weight: every AUV stays on average within it.
#[test]
fn regression_the_lanes_term_lifted_the_outer_auvs_off_the_floor() {
    let s = team(15);
    let (p, floor) = plan(&s);
    let heights = mean_heights(&p, &floor);
    assert!(
        heights.iter().all(|&h| h <= s.auv.survey_altitude),
        "{heights:?}"
    );
    assert!(p.metrics.mean_height < 10.0, "{}", p.metrics.mean_height);
}
