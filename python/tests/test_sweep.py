"""shoal.sweep: a study's table as a DataFrame, one row per run."""

import numpy as np
import pandas as pd
import pytest

import shoal

STUDY = {
    "set": {"horizon.steps": 4},
    "axes": {"seed": "1..2", "team.auvs": [2, 3]},
}


def test_a_study_dict_is_one_row_per_run_with_its_axes():
    table = shoal.sweep(STUDY)
    assert isinstance(table, pd.DataFrame)
    assert len(table) == 4
    assert table["run"].tolist() == [0, 1, 2, 3]
    assert table["seed"].tolist() == [1, 1, 2, 2]
    assert table["team.auvs"].tolist() == [2, 3, 2, 3]
    assert table["auvs"].tolist() == [2, 3, 2, 3]
    assert (table["status"] == "passed").all(), table[["status", "error"]]
    assert (table["error"] == "").all()
    assert (table["scenario"] == "study").all() and (table["method"] == "mpc").all()
    for col in ("run", "seed", "auvs", "out_of_band"):
        assert table[col].dtype == np.int64, col
    for col in ("wall_s", "energy", "explored_km2", "connected_fraction", "margin_floor_m"):
        assert table[col].dtype == np.float64, col
    assert (table["connected_fraction"] == 1.0).all()


def test_a_study_file_writes_its_table_in_out(tmp_path):
    study = tmp_path / "seeds.toml"
    study.write_text('[set]\n"horizon.steps" = 3\n"team.auvs" = 2\n[axes]\nseed = [5, 6]\n')
    out = tmp_path / "sweep"
    table = shoal.sweep(str(study), out=out)
    assert (out / "runs.csv").exists()
    assert table["seed"].tolist() == [5, 6]
    assert (table["scenario"] == "seeds").all()
    assert "team.auvs" not in table.columns  # a [set] key is no axis


def test_a_bad_run_fails_alone_and_a_bad_study_raises():
    table = shoal.sweep({"set": {"horizon.steps": 3}, "axes": {"team.auvs": [2, 0]}})
    assert table["status"].tolist() == ["passed", "failed"]
    assert "team.auvs = 0" in table["error"][1]
    assert np.isnan(table["energy"][1])
    with pytest.raises(shoal.ScenarioError, match='method = "simplex": allowed are'):
        shoal.sweep({"method": "simplex"})
    with pytest.raises(shoal.ScenarioError, match='unknown key "runs"'):
        shoal.sweep({"runs": 3})
    with pytest.raises(shoal.ScenarioError, match="cannot read"):
        shoal.sweep("no-such-study.toml")


def test_pandas_reads_the_parquet_table_as_the_csv_typed(tmp_path):
    # runs.parquet (written by the library's own Parquet writer) read by pandas/pyarrow: the
    # same rows and columns as runs.csv, integers int64, reals float64, a failed run's
    # measures and a passed run's empty error null.
    pytest.importorskip("pyarrow")
    study = {"set": {"horizon.steps": 3}, "axes": {"seed": [1, 2], "team.auvs": [2, 0]}}
    table = shoal.sweep(study, out=tmp_path)
    parquet = pd.read_parquet(tmp_path / "runs.parquet")
    assert list(parquet.columns) == list(table.columns)
    assert len(parquet) == len(table) == 4
    for col in ("run", "team.auvs", "auvs", "seed", "out_of_band", "samples_drawn"):
        assert parquet[col].dtype == np.int64, col
    for col in ("wall_s", "energy", "explored_km2", "margin_floor_m"):
        assert parquet[col].dtype == np.float64, col
    assert parquet["status"].tolist() == ["passed", "failed", "passed", "failed"]
    assert parquet["error"].isna().tolist() == [True, False, True, False]
    assert parquet["error"][1] == table["error"][1]
    assert parquet["energy"].isna().tolist() == [False, True, False, True]
    for col in ("energy", "explored_km2", "p2_objective", "margin_floor_m"):
        np.testing.assert_allclose(parquet[col].to_numpy(), table[col].to_numpy(), rtol=1e-15)
