"""Bad input raises a ShoalError subclass carrying shoal's own message (the source, the key,
what is allowed); nothing reaches the user as a Rust panic."""

import numpy as np
import pytest

import shoal
from conftest import SMALL, sloped_floor


def test_every_error_is_a_shoal_error():
    for e in (shoal.ScenarioError, shoal.SeafloorError, shoal.PlanningError,
              shoal.InfeasibleError, shoal.SolverError, shoal.PlanFileError,
              shoal.SweepError, shoal.CheckFailed):
        assert issubclass(e, shoal.ShoalError) and issubclass(e, Exception)
    assert issubclass(shoal.InfeasibleError, shoal.PlanningError)
    assert issubclass(shoal.SolverError, shoal.PlanningError)


def test_an_unknown_key_names_the_key_and_what_is_allowed():
    with pytest.raises(shoal.ScenarioError) as e:
        shoal.plan({"team": {"auv": 3}})
    msg = str(e.value)
    assert msg.startswith("scenario dict: unknown key team.auv;"), msg
    assert "auvs" in msg and "line" not in msg


def test_a_value_out_of_range_says_what_is_allowed():
    with pytest.raises(shoal.ScenarioError, match=r"scenario dict: team\.auvs = 0: .*1 to 64"):
        shoal.plan({"team": {"auvs": 0}})
    with pytest.raises(shoal.ScenarioError, match=r"--set team\.auvs=100: team\.auvs = 100"):
        shoal.plan("default", overrides={"team.auvs": 100})
    with pytest.raises(shoal.ScenarioError, match=r"horizon\.dt: expected a number, found string \"fast\""):
        shoal.plan({"horizon": {"dt": "fast"}})


def test_a_bad_override_and_method_are_scenario_errors():
    with pytest.raises(shoal.ScenarioError, match=r"--set team\.auvs: "):
        shoal.plan("default", overrides=["team.auvs"])
    with pytest.raises(shoal.ScenarioError, match='method .simplex.: allowed are "mpc"'):
        shoal.plan("default", method="simplex")
    with pytest.raises(shoal.ScenarioError, match="expected \"default\", a path or a dictionary"):
        shoal.plan(42)


def test_scenario_files_name_the_file_and_the_line(tmp_path):
    missing = tmp_path / "nope.toml"
    with pytest.raises(shoal.ScenarioError, match="nope.toml: cannot read the scenario file"):
        shoal.plan(str(missing))
    bad = tmp_path / "bad.toml"
    bad.write_text("seed = 1\n[team]\nauvs = -3\n")
    with pytest.raises(shoal.ScenarioError, match=r"bad\.toml line 3: team\.auvs"):
        shoal.plan(bad)
    broken = tmp_path / "broken.toml"
    broken.write_text("seed = = 1\n")
    with pytest.raises(shoal.ScenarioError, match=r"broken\.toml line 1, column"):
        shoal.plan(broken)


def test_seafloor_errors(tmp_path):
    z, lattice = sloped_floor(spacing=100.0)
    with pytest.raises(shoal.SeafloorError, match="needs its lattice"):
        shoal.plan(SMALL, z)
    with pytest.raises(shoal.SeafloorError, match="must be 2-D"):
        shoal.plan(SMALL, z[0], lattice=lattice)
    with pytest.raises(shoal.SeafloorError, match="dx = -100: expected a positive number"):
        shoal.plan(SMALL, z, lattice={**lattice, "dx": -100.0})
    with pytest.raises(shoal.SeafloorError, match="every node is NODATA"):
        shoal.plan(SMALL, np.full((4, 4), np.nan), lattice=(0, 0, 10))
    with pytest.raises(shoal.SeafloorError, match="missing dx"):
        shoal.plan(SMALL, z, lattice={"x0": 0, "y0": 0})
    with pytest.raises(shoal.SeafloorError, match="nope.asc"):
        shoal.plan(SMALL, str(tmp_path / "nope.asc"))


def test_a_floor_away_from_the_mission_is_refused_with_the_reason():
    # 2 km × 2 km, 10 km east of the origin where the team starts
    z = np.full((21, 21), -100.0)
    with pytest.raises(shoal.InfeasibleError) as e:
        shoal.plan(SMALL, z, lattice=(10_000.0, 0.0, 100.0))
    msg = str(e.value)
    assert msg.startswith("the start of window 0 is infeasible: the USV at (0.0, 0.0) is "
                          "outside the seafloor"), msg
    assert "give [initial] positions inside the grid" in msg


def test_an_infeasible_start_is_an_infeasible_error():
    scenario = {**SMALL, "initial": {"usv": [0.0, 0.0],
                                     "auvs": [[0.0, 0.0, -5000.0], [10.0, 0.0, -60.0],
                                              [0.0, 10.0, -60.0]]}}
    with pytest.raises(shoal.InfeasibleError, match=r"the start of window 0 is infeasible: AUV 0 "
                       r"is 5000\.0 m from the USV, beyond the sonar range d_s = 150 m \(C1_6"):
        shoal.plan(scenario)


def test_a_bad_plan_text_is_a_plan_file_error():
    with pytest.raises(shoal.PlanFileError, match="not a shoal plan"):
        shoal.Plan.from_json("{")
    with pytest.raises(shoal.PlanFileError, match='format "shoal-plan/1" is not "shoal-plan/5"'):
        shoal.Plan.from_json('{"format": "shoal-plan/1"}')


def test_a_failing_check_raises_in_strict_mode(small_plan):
    import json

    doc = json.loads(small_plan.to_json())
    doc["windows"][0]["final"]["auvs"][0]["position"][2][2] -= 500.0  # into the floor
    tampered = shoal.Plan.from_json(json.dumps(doc))
    report = tampered.check()
    assert not report.passed
    names = [f.name for f in report.violations]
    assert any(n.startswith("C2_2") for n in names), names
    worst = next(f for f in report.violations if f.name.startswith("C2_2"))
    assert worst.worst_margin < -400 and "AUV 0" in worst.where
    with pytest.raises(shoal.CheckFailed) as e:
        tampered.check(strict=True)
    assert e.value.report.violations and "FAIL" in str(e.value)
