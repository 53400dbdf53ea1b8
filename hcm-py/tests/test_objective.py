"""The fit's objective for optimisers outside hcm: the GA's fitness, batched."""

import pickle

import numpy as np
import pytest

import hcm


@pytest.fixture(scope="module")
def ball(root):
    return hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml")


@pytest.fixture(scope="module")
def s1(ball):
    return hcm.generate(ball, runs=12, seed=1).s1


@pytest.fixture(scope="module")
def objective(ball, s1):
    return hcm.Objective(ball, s1, "lankarani_nikravesh")


def test_parameters_and_bounds_are_the_scenario_s(objective):
    # scenarios/bouncing_ball.toml, [identify.bounds.lankarani_nikravesh].
    assert objective.parameters == ["stiffness", "exponent", "restitution"]
    np.testing.assert_array_equal(objective.bounds, [[1e9, 1e10], [1.0, 2.0], [0.7, 1.0]])


def test_the_fitness_is_the_fit_s_curve_rms(ball, s1, objective):
    pm2 = hcm.identify(ball, s1, law="lankarani_nikravesh")
    at = np.array([pm2.parameters[p] for p in objective.parameters])
    assert objective.fitness(at) == pm2.fit["curve_rms"]
    worse = objective.fitness(at * np.array([1.3, 1.0, 0.9]))
    assert worse > pm2.fit["curve_rms"]


def test_a_batch_is_the_same_however_it_is_split(objective):
    low, high = objective.bounds.T
    candidates = np.random.default_rng(7).uniform(low, high, size=(24, 3))
    whole = objective.fitness(candidates)
    assert whole.shape == (24,) and np.all(np.isfinite(whole))
    chunks = np.concatenate([objective.fitness(c) for c in np.array_split(candidates, 5)])
    assert whole.tobytes() == chunks.tobytes()
    one_by_one = np.array([objective(c) for c in candidates])
    assert whole.tobytes() == one_by_one.tobytes()


def test_wrong_candidates_are_refused(objective):
    with pytest.raises(hcm.HcmError, match="free parameters are 3: stiffness, exponent, restitution"):
        objective.fitness(np.ones((2, 4)))


def test_scenarios_and_data_pickle_for_workers(ball, s1):
    again = pickle.loads(pickle.dumps(ball.with_set({"body.ball.velocity": [0.0, 0.0, -1.5]})))
    assert hcm.simulate(again).to_csv() == hcm.simulate(ball.with_set({"body.ball.velocity": [0.0, 0.0, -1.5]})).to_csv()
    data = pickle.loads(pickle.dumps(s1))
    assert data.to_csv() == s1.to_csv() and data.name == s1.name
    objective = hcm.Objective(again, data, "lankarani_nikravesh")
    assert objective.parameters == ["stiffness", "exponent", "restitution"]
