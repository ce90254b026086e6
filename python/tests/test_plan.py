"""shoal.plan and the Plan object: shapes, values against the plan file, determinism, floors
given as arrays, scenarios given as dictionaries and files."""

import json
import threading
import time

import numpy as np
import pytest

import shoal
from conftest import SMALL, sloped_floor


def test_the_default_plan_passes_its_check(default_plan):
    report = default_plan.check()
    assert report.passed, report.table
    assert report.violations == []
    assert len(report.families) > 20
    assert all(f.passed for f in report.families)
    assert "PASS: every constraint family holds" in report.table
    floor = next(f for f in report.families if f.name.startswith("C2_2"))
    assert floor.checked > 0 and floor.worst_margin >= -floor.tolerance and floor.unit == "m"
    default_plan.check(strict=True)  # does not raise


def test_shapes_and_dtypes_follow_the_scenario(default_plan):
    p = default_plan
    steps = p.windows * 20 + 1
    assert (p.auvs, p.windows, p.dt, p.seed, p.method) == (5, 1, 100.0, 1, "mpc")
    assert p.positions.shape == (steps, 5, 3) and p.positions.dtype == np.float64
    assert p.velocities.shape == (steps, 5, 3)
    assert p.inputs.shape == (steps - 1, 5, 3)
    assert p.usv_positions.shape == (steps, 2)
    assert p.usv_inputs.shape == (steps - 1, 2)
    assert p.times.shape == (steps,) and np.allclose(np.diff(p.times), 100.0)
    assert p.window.shape == (steps,) and p.window.dtype == np.int64
    assert p.links.shape == (steps, 5, 2) and p.links.dtype == np.int64
    for a in (p.positions, p.velocities, p.inputs, p.usv_positions, p.usv_inputs):
        assert np.isfinite(a).all()
    assert (p.positions[..., 2] < 0).all(), "AUVs are under water"


def test_links_are_the_a2u_link_then_a_chain_over_every_auv(default_plan):
    links = default_plan.links
    n = default_plan.auvs
    assert (links[:, 0, 1] == -1).all(), "row 0 is the link to the USV"
    assert ((links[:, 0, 0] >= 0) & (links[:, 0, 0] < n)).all()
    for edges in links[:, 1:, :]:
        assert (edges[:, 0] < edges[:, 1]).all()
        assert set(edges.ravel()) == set(range(n)), "the chain reaches every AUV"


def test_metrics_are_the_plan_files(default_plan):
    m = default_plan.metrics
    for key in ("input_energy", "explored_area_km2", "mean_height", "min_height",
                "connected_fraction", "chain_fraction", "max_heading_rate"):
        assert isinstance(m[key], float), key
    assert m["connected_fraction"] == 1.0
    assert m["explored_area_km2"] > 0
    assert json.loads(default_plan.to_json())["metrics"] == m
    assert len(default_plan.window_metrics) == default_plan.windows


def test_arrays_are_the_plan_json_final_stage(default_plan):
    doc = json.loads(default_plan.to_json())
    assert doc["format"] == "shoal-plan/5"
    final = doc["windows"][0]["final"]
    for n, auv in enumerate(final["auvs"]):
        np.testing.assert_array_equal(default_plan.positions[:, n, :], auv["position"])
        np.testing.assert_array_equal(default_plan.velocities[:, n, :], auv["velocity"])
        np.testing.assert_array_equal(default_plan.inputs[:, n, :], auv["input"])
    np.testing.assert_array_equal(default_plan.usv_positions, final["usv"]["position"])
    np.testing.assert_array_equal(default_plan.usv_inputs, final["usv"]["input"])
    first = doc["windows"][0]["links"]["links"][3]
    assert [[l["a"], -1 if l["b"] is None else l["b"]] for l in first] == \
        default_plan.links[3].tolist()


def test_windows_are_stitched_without_repeating_their_first_step():
    p = shoal.plan(SMALL, overrides={"windows": 2})
    doc = json.loads(p.to_json())
    assert p.positions.shape == (2 * 6 + 1, 3, 3)
    assert p.window.tolist() == [0] * 7 + [1] * 6
    np.testing.assert_array_equal(p.times, 100.0 * np.arange(13))
    second = np.array([a["position"] for a in doc["windows"][1]["final"]["auvs"]])
    np.testing.assert_array_equal(p.positions[6:, :, :], second.transpose(1, 0, 2))
    assert p.check().passed


def test_same_seed_same_plan_other_seed_other_plan():
    a = shoal.plan(SMALL, seed=7)
    b = shoal.plan(SMALL, seed=7)
    c = shoal.plan(SMALL, seed=8)
    assert a.seed == b.seed == 7 and c.seed == 8
    for name in ("positions", "velocities", "inputs", "usv_positions", "links"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    assert not np.array_equal(a.positions, c.positions)


def test_a_dict_scenario_and_its_overrides_set_the_team_size(small_plan):
    assert small_plan.positions.shape[1] == 3
    assert shoal.plan(SMALL, overrides={"team.auvs": 2}).positions.shape[1] == 2
    assert shoal.plan({**SMALL, "team.auvs": 4}).positions.shape[1] == 4
    assert shoal.plan(SMALL, overrides=["team.auvs=2"]).auvs == 2
    assert small_plan.scenario["team"]["auvs"] == 3
    again = shoal.plan(small_plan.scenario)
    np.testing.assert_array_equal(again.positions, small_plan.positions)


def test_a_scenario_file_is_read_with_its_path(tmp_path):
    text = shoal.default_scenario_toml()
    assert "[team]" in text
    path = tmp_path / "mission.toml"
    path.write_text("seed = 4\n[team]\nauvs = 2\n[horizon]\nsteps = 5\n")
    p = shoal.plan(str(path))
    assert (p.auvs, p.seed, p.positions.shape[0]) == (2, 4, 6)
    assert json.loads(p.to_json())["scenario_source"] == str(path)
    assert shoal.plan(path).auvs == 2  # a pathlib.Path too


def bilinear(z, lattice, x, y):
    x0, y0, d = lattice["x0"], lattice["y0"], lattice["dx"]
    fi, fj = (x - x0) / d, (y - y0) / d
    i, j = np.floor(fi).astype(int), np.floor(fj).astype(int)
    u, v = fi - i, fj - j
    return ((1 - u) * (1 - v) * z[j, i] + u * (1 - v) * z[j, i + 1]
            + (1 - u) * v * z[j + 1, i] + u * v * z[j + 1, i + 1])


def test_a_numpy_floor_keeps_the_auvs_above_it():
    z, lattice = sloped_floor()
    p = shoal.plan(SMALL, z, lattice=lattice)
    report = p.check()
    assert report.passed, report.table
    pos = p.positions.reshape(-1, 3)
    floor = bilinear(z, lattice, pos[:, 0], pos[:, 1])
    clearance = p.scenario["auv"]["floor_clearance"]
    assert (pos[:, 2] >= floor + clearance - 1e-3).all()
    x, y, zz = p.seafloor()
    np.testing.assert_array_equal(zz, z)
    assert x[0] == lattice["x0"] and y[1] - y[0] == lattice["dx"]
    record = p.seafloor_record
    assert (record["source"], record["path"], record["format"]) == ("file", None, "array")
    assert (record["nx"], record["ny"]) == (z.shape[1], z.shape[0])


def test_a_lattice_can_be_a_tuple_or_a_lattice_and_ints_are_heights():
    z, lat = sloped_floor(spacing=100.0)
    a = shoal.plan(SMALL, z.round().astype(np.int32), lattice=(lat["x0"], lat["y0"], 100.0))
    b = shoal.plan(SMALL, z.round(), lattice=shoal.Lattice(lat["x0"], lat["y0"], 100.0, 100.0))
    np.testing.assert_array_equal(a.positions, b.positions)


def test_a_grid_file_is_a_seafloor(tmp_path):
    z, lat = sloped_floor(spacing=100.0)
    path = tmp_path / "slope.asc"
    header = (f"ncols {z.shape[1]}\nnrows {z.shape[0]}\nxllcenter {lat['x0']}\n"
              f"yllcenter {lat['y0']}\ncellsize 100\nnodata_value -99999\n")
    rows = "\n".join(" ".join(f"{v:.3f}" for v in row) for row in z[::-1])  # north first
    path.write_text(header + rows + "\n")
    p = shoal.plan(SMALL, str(path))
    assert p.seafloor_record["path"] == str(path.resolve())
    assert p.check().passed
    again = shoal.Plan.from_json(p.to_json())  # the file the plan names
    np.testing.assert_array_equal(again.positions, p.positions)


def test_from_json_reads_the_plan_back_with_its_floor(small_plan):
    back = shoal.Plan.from_json(small_plan.to_json())
    np.testing.assert_array_equal(back.positions, small_plan.positions)
    assert back.metrics == small_plan.metrics
    assert back.check().passed
    assert back.to_json() == small_plan.to_json()


def test_from_json_over_an_array_floor():
    z, lattice = sloped_floor(spacing=100.0)
    p = shoal.plan(SMALL, z, lattice=lattice)
    with pytest.raises(shoal.SeafloorError, match="give the floor explicitly"):
        shoal.Plan.from_json(p.to_json())
    back = shoal.Plan.from_json(p.to_json(), z, lattice=lattice)
    assert back.check().passed
    with pytest.raises(shoal.SeafloorError, match="not the floor the plan was made on"):
        shoal.Plan.from_json(p.to_json(), z - 1.0, lattice=lattice)


# The paper's vehicle, which the sampling baseline plans for: no depth rating to speak of, no
# angle limit, no cruise floor, no separation, still water, links up to d_s.
PAPER_VEHICLE = {
    "auv": {"max_depth": 1000.0, "max_flight_path_angle": 1.57, "min_speed": 0.0,
            "min_separation": 0.0},
    "current": {"velocity": [0.0, 0.0]},
    "acoustic": {"link_margin": 1.0},
}


def test_the_rrt_like_baseline_plans_too():
    p = shoal.plan({**SMALL, **PAPER_VEHICLE, "horizon": {"steps": 3}}, method="rrt-like")
    assert p.method == "rrt-like"
    assert p.positions.shape == (4, 3, 3)
    assert p.check().passed


def test_planning_releases_the_gil():
    done = {}

    def work():
        done["plan"] = shoal.plan("default")

    thread = threading.Thread(target=work)
    ticks = 0
    start = time.perf_counter()
    thread.start()
    while thread.is_alive():
        ticks += 1
        time.sleep(0.001)
    elapsed = time.perf_counter() - start
    thread.join()
    assert done["plan"].auvs == 5
    # with the GIL held by the planner this loop could not run until the plan was made
    # (about one tick per millisecond; at least one per 10 ms on a loaded machine)
    assert ticks > 10 and ticks >= elapsed / 0.01, (ticks, elapsed)
