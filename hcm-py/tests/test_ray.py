"""The Ray example of docs/python.md runs (a local Ray with two CPUs)."""

import re
import subprocess
import sys

import pytest


@pytest.mark.slow
def test_the_ray_example_runs(root):
    pytest.importorskip("ray")
    text = (root / "docs" / "python.md").read_text()
    example = next(b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "import ray" in b)
    done = subprocess.run([sys.executable, "-c", example], cwd=root, capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-3000:]
    assert done.stdout.strip()
