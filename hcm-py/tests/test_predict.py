"""Recorded tosses from Python: `hcm predict`'s trajectories and scores, byte for byte."""

import csv
import io

import numpy as np
import pytest

import hcm


@pytest.fixture(scope="module")
def cube(root):
    scenario = hcm.Scenario.load(root / "scenarios" / "cube_toss.toml")
    return scenario.with_physics(root / "docs" / "results" / "cube-toss" / "physics.toml")


def test_predict_is_the_cli_s(cli, root, cube, tmp_path):
    tosses = root / "data" / "contactnets-cube" / "tosses.csv"
    cli.ok(
        "predict", "--scenario", root / "scenarios" / "cube_toss.toml",
        "--physics", root / "docs" / "results" / "cube-toss" / "physics.toml",
        "--data", tosses, "--first", 6, "--out", tmp_path / "cli.csv", "--scores", tmp_path / "cli_scores.csv",
    )
    seen = []
    prediction = hcm.predict(cube, hcm.Dataset.read_csv(tosses), first=6,
                             progress=lambda stage, done, total: seen.append((stage, done, total)))
    assert prediction.data.to_csv() == (tmp_path / "cli.csv").read_text()
    prediction.write_scores(tmp_path / "py_scores.csv")
    assert (tmp_path / "py_scores.csv").read_bytes() == (tmp_path / "cli_scores.csv").read_bytes()
    scores = prediction.scores
    rows = list(csv.DictReader(io.StringIO((tmp_path / "cli_scores.csv").read_text())))
    assert list(scores["run"]) == [r["run"] for r in rows]
    assert np.all(scores["position_error"] < scores["frozen_position_error"])
    mean = prediction.summary["position_error"][0]
    assert mean == pytest.approx(scores["position_error"].mean(), rel=1e-12)
    assert seen[-1][1:] == (6, 6) and seen[0][0] == "predict"


def test_tosses_without_poses_are_refused(cube):
    empty = hcm.Dataset.from_arrays({"run": "t", "body": "cube", "time": [0.0, 0.1], "fz": [0.0, 1.0], "fx": 0.0, "fy": 0.0})
    with pytest.raises(hcm.HcmError):
        hcm.predict(cube, empty)
