"""The power study from Python: the rows and table ``hcm power`` writes, whole or as
chunks mapped separately and joined, and its refusals in the command's words."""

import pickle

import pytest

import hcm

BALL = "scenarios/bouncing_ball.toml"
OPTIONS = dict(runs=4, seeds=2, levels=[0.03], effects=["viscous_damping", "force_offset"])
FLAGS = ["--runs", "4", "--seeds", "2", "--levels", "0.03", "--effects", "viscous_damping,force_offset"]


@pytest.fixture(scope="module")
def by_cli(cli, root, tmp_path_factory):
    out = tmp_path_factory.mktemp("power") / "power.csv"
    cli.ok("power", "--scenario", BALL, *FLAGS, "--out", out)
    return out.read_text(), out.with_suffix(".md").read_text()


def test_one_call_writes_what_the_command_writes(root, by_cli, monkeypatch):
    monkeypatch.chdir(root)
    result = hcm.power(hcm.Scenario.load(BALL), **OPTIONS)
    assert (result.csv, result.table) == by_cli
    columns = result.columns
    assert list(columns["effect"]) == ["viscous_damping"] * 2 + ["force_offset"] * 2 + ["none"] * 2
    assert columns["exact"].all() and not columns["wrong"].any()
    named = columns["truth"] == columns["truth"]  # the hidden ones (truth not NaN)
    assert ((columns["low"] <= columns["truth"]) & (columns["truth"] <= columns["high"]))[named].all()


def test_chunks_mapped_apart_then_joined_are_the_whole_study(root, by_cli, monkeypatch):
    monkeypatch.chdir(root)
    study = hcm.PowerStudy(hcm.Scenario.load(BALL), **OPTIONS)
    assert len(study) == 6
    # As a Ray or Dask worker receives it: pickled, rebuilt from its options.
    parts = [pickle.loads(pickle.dumps(study)).rows(a, b) for a, b in study.chunks(4)]
    assert tuple(study.join(parts)) == by_cli
    with pytest.raises(hcm.HcmError, match="part 1: data set 3 where 1 comes next"):
        study.join([parts[0], parts[2], parts[3]])  # chunks (0, 1), (1, 3), (3, 4), (4, 6)
    with pytest.raises(hcm.HcmError, match="a part is missing"):
        study.join(parts[:2])
    other = hcm.PowerStudy(hcm.Scenario.load(BALL), **{**OPTIONS, "seed": 2})
    with pytest.raises(hcm.HcmError, match="it is not a shard of this study"):
        other.join(parts)


@pytest.mark.parametrize(
    "flags, options",
    [
        (["--levels", "0.01,2"], dict(levels=[0.01, 2])),
        (["--effects", "coulomb_friction"], dict(effects=["coulomb_friction"])),
        (["--seeds", "0"], dict(seeds=0)),
        (["--base", "other"], dict(base="other")),
    ],
    ids=["a strength outside (0, 1]", "an effect the 1D diagnosis does not name", "no seed",
         "an unknown base"],
)
def test_refusals_carry_the_command_s_message(cli, root, tmp_path, monkeypatch, flags, options):
    expected = cli.refusal("power", "--scenario", BALL, *flags, "--out", tmp_path / "p.csv")
    expected = expected.removesuffix("\n\nFor more information, try '--help'.")
    monkeypatch.chdir(root)
    with pytest.raises(hcm.HcmError) as raised:
        hcm.PowerStudy(hcm.Scenario.load(BALL), **options)
    assert str(raised.value) == expected
