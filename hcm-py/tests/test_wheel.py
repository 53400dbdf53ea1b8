"""A newcomer's install: a fresh virtual environment, `pip install ./hcm-py` (maturin
builds the release wheel), then the README's Python example from that environment, which
must print what the development build prints. Marked `slow`: the release build takes
minutes on 2 cores."""

import os
import re
import subprocess
import sys
import time
import venv

import pytest


@pytest.mark.slow
def test_pip_install_then_the_readme_example(root, tmp_path):
    environment = tmp_path / "venv"
    venv.EnvBuilder(with_pip=True).create(environment)
    python = environment / "bin" / "python"
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYO3_", "VIRTUAL_ENV", "CARGO_TARGET_DIR"))}
    env["CARGO_TARGET_DIR"] = str(tmp_path / "target")
    started = time.perf_counter()
    install = subprocess.run([str(python), "-m", "pip", "install", str(root / "hcm-py")],
                             cwd=tmp_path, env=env, capture_output=True, text=True)
    seconds = time.perf_counter() - started
    assert install.returncode == 0, install.stdout[-3000:] + install.stderr[-3000:]
    print(f"pip install ./hcm-py: {seconds:.0f} s")
    code = re.findall(r"```python\n(.*?)```", (root / "README.md").read_text(), re.S)[0]
    fresh = subprocess.run([str(python), "-c", code], cwd=root, env=env, capture_output=True, text=True)
    assert fresh.returncode == 0, fresh.stderr
    here = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True)
    assert here.returncode == 0, here.stderr
    # The release wheel computes what the development build does, figure for figure.
    assert fresh.stdout == here.stdout
