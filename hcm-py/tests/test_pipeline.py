"""The paper's method from Python — PM1, PM2, diagnosis, residual, HCM — against the
`hcm` commands on the same inputs: the same bytes and figures where the arithmetic is
the same (every figure but the wall-clock times)."""

import json

import numpy as np
import pytest

import hcm

RUNS = 40  # PM1's runs: enough for S1 and S2 and a diagnosis, small for CI


def without_times(value):
    """`value` with every `seconds` entry removed (wall-clock time differs by run)."""
    if isinstance(value, dict):
        return {k: without_times(v) for k, v in value.items() if k != "seconds"}
    if isinstance(value, list):
        return [without_times(v) for v in value]
    return value


def toml_without_times(text):
    return [line for line in text.splitlines() if not line.startswith(("#", "seconds"))]


@pytest.fixture(scope="module")
def files(cli, root, tmp_path_factory):
    """The CLI's pipeline on the ball: generate, identify, train, export, evaluate."""
    out = tmp_path_factory.mktemp("cli")
    ball = root / "scenarios" / "bouncing_ball.toml"
    s = ["--scenario", ball]
    cli.ok("generate", *s, "--runs", RUNS, "--seed", 1, "--out", out / "pm1.csv")
    cli.ok("identify", *s, "--data", out / "pm1.s1.csv", "--law", "lankarani_nikravesh", "--out", out / "pm2.toml")
    pm2 = ["--physics", out / "pm2.toml"]
    cli.ok("train", *s, *pm2, "--data", out / "pm1.s1.csv", "--epochs", 30, "--int8-epochs", 2, "--out", out / "residual.json")
    for weights in ("f32", "int8"):
        cli.ok("export", "--residual", out / "residual.json", "--weights", weights, "--out", out / f"residual.{weights}.bin")
    evaluation = cli.ok("evaluate", *s, *pm2, "--data", out / "pm1.s2.csv", "--residual", out / "residual.f32.bin", "--json")
    (out / "evaluation.json").write_text(evaluation)
    cli.ok("diagnose", *s, *pm2, "--data", out / "pm1.s1.csv", "--out", out / "diagnosis")
    return out


@pytest.fixture(scope="module")
def ball(root):
    return hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml")


@pytest.fixture(scope="module")
def s1(files):
    return hcm.Dataset.read_csv(files / "pm1.s1.csv")


@pytest.fixture(scope="module")
def pm2(ball, s1):
    return hcm.identify(ball, s1, law="lankarani_nikravesh")


def test_generate_writes_the_cli_s_bytes(files, ball):
    pm1 = hcm.generate(ball, runs=RUNS, seed=1)
    assert pm1.runs.to_csv() == (files / "pm1.csv").read_text()
    assert pm1.s1.to_csv() == (files / "pm1.s1.csv").read_text()
    assert pm1.s2.to_csv() == (files / "pm1.s2.csv").read_text()
    assert len(pm1.s1.runs) + len(pm1.s2.runs) == RUNS


def test_identify_fits_the_cli_s_law(files, pm2):
    cli = hcm.Physics.read(files / "pm2.toml")
    assert pm2.law == cli.law == "lankarani_nikravesh"
    assert pm2.parameters == cli.parameters  # bit for bit
    assert without_times(pm2.fit) == without_times(cli.fit)
    assert toml_without_times(pm2.to_toml()) == toml_without_times((files / "pm2.toml").read_text())
    assert set(pm2.standard_errors) <= set(pm2.parameters) and all(
        0 < e < abs(pm2.parameters[k]) for k, e in pm2.standard_errors.items()
    )


def test_train_and_export_give_the_cli_s_blobs(files, ball, pm2, s1):
    residual = hcm.train(ball, pm2, s1, epochs=30, int8_epochs=2)
    assert residual.to_json() == json.loads((files / "residual.json").read_text())
    for weights in ("f32", "int8"):
        assert residual.blob(weights) == (files / f"residual.{weights}.bin").read_bytes()
    report = residual.report
    assert report["rows"] > 0 and report["epochs"] <= 30 and report["train_rms"] > 0


def test_evaluate_gives_the_cli_s_table(files, ball, pm2):
    s2 = hcm.Dataset.read_csv(files / "pm1.s2.csv")
    blob = (files / "residual.f32.bin").read_bytes()
    tables = hcm.evaluate(ball, pm2, s2, residual=blob)
    assert tables == json.loads((files / "evaluation.json").read_text())
    assert [m["model"] for m in tables[0]["models"]] == ["PM2", "HCM"]


def test_diagnose_gives_the_cli_s_answer_and_files(files, ball, pm2, s1, tmp_path):
    diagnosis = hcm.diagnose(ball, pm2, s1, out=tmp_path / "diagnosis")
    cli = files / "diagnosis"
    assert without_times(diagnosis.contents) == without_times(json.loads((cli / "diagnosis.json").read_text()))
    assert diagnosis.report == (cli / "report.md").read_text()
    for name in sorted(p.name for p in cli.iterdir()):
        if name.endswith(".toml"):
            assert toml_without_times((tmp_path / "diagnosis" / name).read_text()) == toml_without_times((cli / name).read_text())
        else:
            assert (tmp_path / "diagnosis" / name).read_bytes() == (cli / name).read_bytes(), name
    assert diagnosis.answer and isinstance(diagnosis.causes, list)
    assert toml_without_times(diagnosis.extended.to_toml()) == toml_without_times((cli / "extended.toml").read_text())


def test_the_hcm_through_the_core_is_the_exported_model(files, ball, pm2):
    blob = (files / "residual.f32.bin").read_bytes()
    model = hcm.HybridModel(ball.with_physics(pm2), blob)
    depth = np.linspace(1e-6, 50e-6, 50, dtype=np.float32)
    result = model.force(depth, np.float32(0.5), np.float32(1.4))
    from_file = hcm.HybridModel(ball.with_physics(files / "pm2.toml"), blob).force(depth, np.float32(0.5), np.float32(1.4))
    assert result.force.tobytes() == from_file.force.tobytes()
    assert result.residual_used.any()
