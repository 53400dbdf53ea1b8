"""The laws from Python: the catalogue is `hcm laws`', a force is `hcm force`'s."""

import re

import numpy as np
import pytest

import hcm


def test_the_catalogue_is_the_cli_s(cli):
    listed = cli.ok("laws")
    names = [law.name for law in hcm.laws()]
    assert len(names) >= 6
    for law in hcm.laws():
        assert law.name in listed
        for parameter in law.parameters:
            assert parameter.name in listed and parameter.unit


@pytest.mark.parametrize(
    "name, parameters, states",
    [
        ("hertz", {"stiffness": 6.86e9, "exponent": 1.5}, [(10e-6, 0.0, 1.0), (37e-6, 0.0, 1.0)]),
        (
            "lankarani_nikravesh",
            {"stiffness": 6.9e9, "exponent": 1.49, "restitution": 0.93},
            [(12e-6, 0.8, 1.4), (40e-6, -0.6, 1.4), (3e-6, 1.39, 1.4)],
        ),
    ],
)
def test_force_is_the_cli_s(cli, name, parameters, states):
    law = hcm.Law(name, **parameters)
    depth, rate, approach = map(np.array, zip(*states))
    f64 = law.force(depth, rate, approach)
    f32 = law.force(depth, rate, approach, dtype=np.float32)
    for i, (d, r, a) in enumerate(states):
        sets = [f"--set={k}={v!r}" for k, v in parameters.items()]
        out = cli.ok("force", "--law", name, *sets, f"--depth={d!r}", f"--rate={r!r}", f"--approach-speed={a!r}")
        printed = re.search(r"f_n = (\S+) N \(f64\), (\S+) N \(f32\)", out)
        assert printed, out
        # The same 7 significant digits (Rust writes `2.169322e2`, Python `2.169322e+02`).
        assert float(f"{f64[i]:.6e}") == float(printed.group(1))
        assert float(f"{f32[i]:.6e}") == float(printed.group(2))


def test_force_broadcasts_and_is_zero_out_of_contact():
    law = hcm.Law("hertz", stiffness=1e9, exponent=1.5)
    depth = np.linspace(-1e-5, 1e-5, 21).reshape(3, 7)
    force = law.force(depth, 0.0)
    assert force.shape == (3, 7)
    assert np.all(force[depth <= 0] == 0.0)
    np.testing.assert_allclose(force[depth > 0], 1e9 * depth[depth > 0] ** 1.5, rtol=1e-12)
    assert law.parameters == {"stiffness": 1e9, "exponent": 1.5}


def test_nan_in_gives_nan_out():
    law = hcm.Law("hertz", stiffness=1e9, exponent=1.5)
    force = law.force([np.nan, 1e-5], 0.0)
    assert np.isnan(force[0]) and force[1] > 0
