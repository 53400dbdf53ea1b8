"""Scenarios and the simulator from Python: the same bytes as `hcm simulate`."""

import numpy as np
import pytest

import hcm


@pytest.mark.parametrize("override", [None, "contact.0.parameters.damping=500"])
def test_simulate_is_the_cli_s_trajectory(cli, root, tmp_path, override):
    path = root / "scenarios" / "bouncing_ball.toml"
    sets = [] if override is None else [override]
    out = tmp_path / "trajectory.csv"
    cli.ok("simulate", "--scenario", path, *[f"--set={s}" for s in sets], "--out", out)
    data = hcm.simulate(hcm.Scenario.load(path, set=sets))
    assert data.to_csv() == out.read_text()
    assert hcm.Dataset.read_csv(out).to_csv() == out.read_text()


def test_a_scenario_from_text_is_the_file(root):
    path = root / "scenarios" / "bouncing_ball.toml"
    from_file = hcm.simulate(hcm.Scenario.load(path))
    from_text = hcm.simulate(hcm.Scenario.from_toml(path.read_text(), name=path))
    assert from_text.to_csv() == from_file.to_csv()


def test_with_set_changes_the_run(root):
    scenario = hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml")
    base = hcm.simulate(scenario)
    faster = hcm.simulate(scenario.with_set({"body.ball.velocity": [0.0, 0.0, -2.0]}))
    # A faster drop presses harder: the peak contact force rises.
    assert faster["fz"].max() > base["fz"].max() > 0
    assert scenario.contacts == [("ball", "ground", "variable_stiffness")]


def test_columns_are_arrays_in_si_units(root):
    data = hcm.simulate(hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml"))
    assert data.runs == ["0"]
    assert set(data.columns) == set(hcm.dataset.COLUMNS)
    time = data["time"]
    ball = data["body"] == "ball"
    assert np.all(np.diff(time[ball]) > 0)
    assert data["fz"].dtype == np.float64 and len(data) == len(time)
    with pytest.raises(KeyError, match="the columns are"):
        data["force"]
