//! NODATA and land cells are obstacles that no path or acoustic link may cross (issue 5): the
//! planner keeps out of them over the default mission with a NODATA hole and an island in its
//! way, `check` verifies it, and a start next to an obstacle is refused with its position.

mod common;

use common::{plan_and_check, strips, tif};
use shoal::mission::scenario_floor;
use shoal::plan::{Plan, Stage};
use shoal::scenario::{self, Scenario};
use shoal::seafloor::{Crs, SampleType, Seafloor, TiffCompression};
use std::path::{Path, PathBuf};

/// A disc of nodes: centre x, centre y, radius, metres.
type Disc = (f64, f64, f64);

/// The default synthetic floor (what the default mission plans over) with NODATA nodes in the
/// `holes` and land nodes (+3 m) in the `islands`.
fn carved(holes: &[Disc], islands: &[Disc]) -> Seafloor {
    let s = Scenario::default();
    let f = Seafloor::synthetic(&s.seafloor.synthetic, s.seed).unwrap();
    let mut z = f.nodes().0.to_vec();
    let mut nodata = vec![false; z.len()];
    let within = |x: f64, y: f64, d: &Disc| (x - d.0).hypot(y - d.1) <= d.2;
    for j in 0..f.ny() {
        for i in 0..f.nx() {
            let (x, y) = (f.x0() + i as f64 * f.dx(), f.y0() + j as f64 * f.dy());
            let k = j * f.nx() + i;
            nodata[k] = holes.iter().any(|d| within(x, y, d));
            if islands.iter().any(|d| within(x, y, d)) {
                z[k] = 3.0;
            }
        }
    }
    Seafloor::from_nodes(f.lattice(), z, nodata).unwrap()
}

/// The default scenario over the grid file `floor`, plus `extra` overrides.
fn over(floor: &Path, extra: &[&str]) -> Scenario {
    let mut set = vec![format!("seafloor.file={:?}", floor.display().to_string())];
    set.extend(extra.iter().map(|s| s.to_string()));
    scenario::default_with(&set).expect("valid overrides")
}

/// Every waypoint, every 𝓛_r sample of every segment (USV and AUVs, both stages) and every
/// planned link of k = 1..=K is clear of obstacle cells, by the seafloor's own query.
fn assert_clear(p: &Plan, floor: &Seafloor) {
    let r = p.scenario.acoustic.resolution;
    let clear = |a: [f64; 3], b: [f64; 3], what: &str| {
        let hit = floor.segment_obstacle(a, b, r).unwrap();
        assert!(hit.is_none(), "{what} crosses an obstacle: {hit:?}");
    };
    let usv = |st: &Stage, k: usize| {
        let q = st.usv.position[k];
        [q[0], q[1], 0.0]
    };
    for (w, win) in p.windows.iter().enumerate() {
        for st in [&win.step1, &win.final_] {
            for k in 1..st.usv.position.len() {
                clear(
                    usv(st, k - 1),
                    usv(st, k),
                    &format!("window {w} USV k = {k}"),
                );
                for (n, a) in st.auvs.iter().enumerate() {
                    let (pa, pb) = (a.position[k - 1], a.position[k]);
                    clear(pa, pb, &format!("window {w} AUV {n} k = {k}"));
                }
            }
        }
        let st = &win.final_;
        for (k, links) in win.links.links.iter().enumerate().skip(1) {
            for l in links {
                let a = st.auvs[l.a].position[k];
                let b = l.b.map_or(usv(st, k), |j| st.auvs[j].position[k]);
                clear(a, b, &format!("window {w} link {l:?} k = {k}"));
            }
        }
    }
}

/// Whether the straight USV run of window `w`'s first guess (from the window's start, along
/// the direction of the previous window's last USV input, or along x for window 0, at full
/// speed) crosses an obstacle cell: the fixture puts an obstacle in the mission's way.
fn straight_run_blocked(p: &Plan, floor: &Seafloor, w: usize) -> bool {
    let s = &p.scenario;
    let start = p.windows[w].final_.usv.position[0];
    let heading = match w.checked_sub(1) {
        None => s.usv.initial_heading,
        Some(prev) => {
            let u = *p.windows[prev].final_.usv.input.last().unwrap();
            u[1].atan2(u[0])
        }
    };
    let run = s.usv.max_speed * s.horizon.steps as f64 * s.horizon.dt;
    let end = [
        start[0] + run * heading.cos(),
        start[1] + run * heading.sin(),
        0.0,
    ];
    let hit = floor.segment_obstacle([start[0], start[1], 0.0], end, s.acoustic.resolution);
    hit.unwrap().is_some()
}

/// x range [min, max] of window `w`'s final USV path.
fn usv_x_range(p: &Plan, w: usize) -> [f64; 2] {
    let xs = p.windows[w].final_.usv.position.iter().map(|q| q[0]);
    [
        xs.clone().fold(f64::INFINITY, f64::min),
        xs.fold(f64::NEG_INFINITY, f64::max),
    ]
}

/// Writes `f` as a projected GeoTIFF (float64, Deflate strips) into `dir`.
fn geotiff(dir: &Path, name: &str, f: &Seafloor) -> PathBuf {
    let crs = Crs::Projected {
        epsg: None,
        citation: None,
    };
    let (z, nodata) = f.nodes();
    let layout = strips(TiffCompression::Deflate);
    tif(
        dir,
        name,
        (&f.lattice(), z, nodata),
        &crs,
        SampleType::Float64,
        layout,
    )
}

/// The default mission over two windows with a NODATA hole on window 0's course and an
/// island on window 1's (GeoTIFFs, projected): the team goes past both, and the plan passes
/// its check.
#[test]
fn the_default_mission_goes_around_a_nodata_hole_and_an_island() {
    let dir = tempfile::tempdir().unwrap();
    let hole = (1500.0, 20.0, 100.0);
    // the mission round the hole alone, to find window 1's course: the island goes 1.5 km
    // along it (two windows, so that window 0 ends with the terminal margin as it does below)
    let path = geotiff(dir.path(), "hole.tif", &carved(&[hole], &[]));
    let (first, _) = plan_and_check(&over(&path, &["windows=2"])).expect("round the hole");
    let w0 = &first.windows[0].final_.usv;
    let (end, u) = (w0.position[20], w0.input[19]);
    let heading = u[1].atan2(u[0]);
    let island = (
        end[0] + 1500.0 * heading.cos(),
        end[1] + 1500.0 * heading.sin(),
        150.0,
    );
    let f = carved(&[hole], &[island]);
    let path = geotiff(dir.path(), "obstacles.tif", &f);
    let (p, floor) = plan_and_check(&over(&path, &["windows=2"])).expect("plan around");
    assert_eq!(floor.fingerprint(), f.fingerprint());
    assert_eq!(p.windows[0].final_.usv.position, w0.position);
    assert_clear(&p, &floor);
    for (w, obstacle) in [(0, hole), (1, island)] {
        // the straight run would cross it, and the planned USV passes it without crossing
        assert!(straight_run_blocked(&p, &floor, w), "window {w}");
        let [lo, hi] = usv_x_range(&p, w);
        assert!(
            lo < obstacle.0 - obstacle.2 && hi > obstacle.0 + obstacle.2,
            "window {w}: the USV (x from {lo:.0} to {hi:.0}) did not get past the obstacle \
             at x = {:.0}",
            obstacle.0
        );
    }
    for w in &p.windows {
        assert_eq!(w.metrics.connected_fraction, 1.0);
    }
}

/// The bug of issue 5: a plan over a floor with a NODATA hole on its course flew through the
/// hole (the USV had no constraint at all, and an AUV could sit over a cell with one NODATA
/// corner above the interpolated floor), and `shoal check` failed it. The same mission over
/// one window, the grid as ESRI ASCII.
#[test]
fn regression_plan_crossed_a_nodata_hole() {
    let dir = tempfile::tempdir().unwrap();
    let f = carved(&[(1500.0, 0.0, 60.0)], &[]);
    let path = dir.path().join("hole.asc");
    f.write_esri_ascii(&path).unwrap();
    let (p, floor) = plan_and_check(&over(&path, &[])).expect("plan around the hole");
    assert!(straight_run_blocked(&p, &floor, 0));
    assert_clear(&p, &floor);
}

/// A start outside every obstacle cell but where the keep-out field (one cell of margin) keeps
/// the vehicles out is refused with the position and the reason; a start on land too.
#[test]
fn a_start_next_to_an_obstacle_is_refused_with_its_position() {
    let dir = tempfile::tempdir().unwrap();
    // land nodes within 60 m of (400, 0): obstacle cells reach x = 475 on y = 0, and the
    // field rises over the next cell, x from 475 to 500
    let f = carved(&[], &[(400.0, 0.0, 60.0)]);
    let path = dir.path().join("island.asc");
    f.write_esri_ascii(&path).unwrap();
    let (floor, _) = scenario_floor(&over(&path, &[]), Path::new("")).unwrap();
    let field = floor.keep_out();
    let at = |x: f64| {
        (
            field.elevation(x, 0.0).unwrap(),
            floor.elevation(x, 0.0).unwrap(),
        )
    };
    assert!(floor.is_obstacle(474.0, 0.0).unwrap() && !floor.is_obstacle(475.0, 0.0).unwrap());
    assert!(
        at(476.0).0 > 0.0 && at(490.0).0 < 0.0,
        "{:?} {:?}",
        at(476.0),
        at(490.0)
    );
    let refused = |usv: [f64; 2], auv: [f64; 3]| {
        let mut s = over(&path, &["team.auvs=1"]);
        s.initial = Some(scenario::Initial {
            usv,
            auvs: vec![auv],
        });
        match plan_and_check(&s) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("planned from {usv:?}, {auv:?}"),
        }
    };
    let m = refused([476.0, 0.0], [560.0, 0.0, -40.0]);
    assert!(
        m.contains(
            "the start of window 0 is infeasible: the USV at (476.0, 0.0) is next to an \
             obstacle cell"
        ),
        "{m}"
    );
    // an AUV ε above the floor but not above the field
    let (top, bottom) = at(481.0);
    let z = (top + 4.0).round();
    assert!(z > bottom + 5.0, "{top} {bottom}");
    let m = refused([560.0, 0.0], [481.0, 0.0, z]);
    assert!(
        m.contains(&format!(
            "AUV 0 at (481.0, 0.0, {z:.1}) is next to an obstacle cell"
        )),
        "{m}"
    );
    let m = refused([400.0, 0.0], [560.0, 0.0, -40.0]);
    assert!(m.contains("the USV at (400.0, 0.0) is on land"), "{m}");
}
