"""The README's Python example runs and prints the figures the `hcm` commands print
for the same inputs."""

import json
import re
import subprocess
import sys

import pytest


def readme_example(root):
    text = (root / "README.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1, "the README holds one Python example"
    return blocks[0]


@pytest.fixture(scope="module")
def printed(root):
    code = readme_example(root)
    assert 12 <= len(code.strip().splitlines()) <= 25
    done = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return done.stdout.splitlines()


def test_the_example_prints_the_cli_s_figures(printed, cli, root, tmp_path):
    ball = ["--scenario", root / "scenarios" / "bouncing_ball.toml"]
    cli.ok("generate", *ball, "--runs", 40, "--seed", 1, "--out", tmp_path / "pm1.csv")
    s1, s2 = tmp_path / "pm1.s1.csv", tmp_path / "pm1.s2.csv"
    identified = cli.ok("identify", *ball, "--data", s1, "--law", "lankarani_nikravesh", "--out", tmp_path / "pm2.toml")
    pm2 = ["--physics", tmp_path / "pm2.toml"]
    diagnosed = cli.ok("diagnose", *ball, *pm2, "--data", s1, "--out", tmp_path / "diagnosis")
    cli.ok("train", *ball, *pm2, "--data", s1, "--out", tmp_path / "residual.json")
    cli.ok("export", "--residual", tmp_path / "residual.json", "--out", tmp_path / "residual.bin")
    tables = json.loads(cli.ok("evaluate", *ball, *pm2, "--data", s2, "--residual", tmp_path / "residual.bin", "--json"))

    # PM2: `hcm identify` prints `  name  value  ± error (1σ)` per parameter.
    fitted = {name: value for name, value, _ in re.findall(r"^  (\w+)\s+(\S+)(?:  ± (\S+) \(1σ\))?", identified, re.M)}
    parameters = 0
    for line in printed:
        match = re.match(r"PM2 (\w+) = (\S+) ± (\S+)", line)
        if match:
            parameters += 1
            name, value, _ = match.groups()
            assert float(value) == float(fitted[name]), line
            errors = re.search(rf"^  {name}\s+\S+  ± (\S+)", identified, re.M)
            if errors:
                assert float(match.group(3)) == float(errors.group(1)), line
    assert parameters == 3

    # The diagnosis's answer is the command's.
    answer = next(line for line in printed if line.startswith("Answer:"))
    assert f"**{answer}**" in diagnosed

    # The Eq 20 errors of PM2 and the HCM on S2, as `hcm evaluate --json` gives them.
    for row in tables[0]["models"]:
        # The CLI's JSON lists the keys alphabetically; the example in the table's order.
        order = ("max_force", "impulse", "energy_loss", "duration")
        errors = ", ".join(f"{k} {100 * row['errors'][k]:.2f} %" for k in order)
        assert f"{row['model']} on S2 (Eq 20): {errors}" in printed

    # PM2's force at the last state, in f32, as `hcm force` prints it.
    law = re.search(r"law = \"(\w+)\"", (tmp_path / "pm2.toml").read_text()).group(1)
    values = dict(re.findall(r"^(\w+) = (\S+)$", (tmp_path / "pm2.toml").read_text(), re.M))
    sets = [f"--set={k}={values[k]}" for k in ("stiffness", "exponent", "restitution")]
    forced = cli.ok("force", "--law", law, *sets, "--depth", "4e-5", "--rate", "-0.5", "--approach-speed", "1.4")
    f32 = re.search(r"(\S+) N \(f32\)", forced).group(1)
    last = re.search(r"HCM (\S+) N, PM2 (\S+) N$", printed[-1])
    assert float(last.group(2)) == float(f32)
    # The residual corrects the force where it was trained.
    assert last.group(1) != last.group(2)
