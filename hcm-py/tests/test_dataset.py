"""Data sets from arrays and CSV: one reader, one set of checks."""

import numpy as np
import pytest

import hcm


def test_arrays_round_trip_through_the_reader(root):
    data = hcm.simulate(hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml"))
    again = hcm.Dataset.from_arrays(data.columns)
    assert again.to_csv() == data.to_csv()


def test_a_channel_left_out_is_not_sampled():
    data = hcm.Dataset.from_arrays(
        {"run": "r1", "body": "ball", "time": [0.0, 0.1, 0.2], "px": 0.0, "py": 0.0, "pz": [0.3, 0.2, 0.1]}
    )
    assert np.isnan(data["fz"]).all() and list(data["pz"]) == [0.3, 0.2, 0.1]
    with pytest.raises(hcm.HcmError, match=r"<arrays>, line 2, column `px`.*filled whole"):
        hcm.Dataset.from_arrays({"run": "r1", "body": "ball", "time": [0.0], "pz": [0.3]})
    text = data.to_csv().splitlines()
    assert text[0].startswith("run,body,time,px") and len(text) == 4


def test_a_bad_row_is_named_by_its_line():
    with pytest.raises(hcm.HcmError, match=r"<arrays>, line 4"):
        hcm.Dataset.from_arrays(
            {"run": "r1", "body": "ball", "time": [0.0, 0.1, 0.1], "px": 0, "py": 0, "pz": [0.3, 0.2, 0.1]}
        )
    with pytest.raises(hcm.HcmError, match="unknown column"):
        hcm.Dataset.from_arrays({"run": "r", "body": "b", "time": [0.0], "force": [1.0]})


def test_to_pandas_when_installed(root):
    pandas = pytest.importorskip("pandas")
    data = hcm.simulate(hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml"))
    frame = data.to_pandas()
    assert isinstance(frame, pandas.DataFrame) and list(frame.columns) == list(hcm.dataset.COLUMNS)
