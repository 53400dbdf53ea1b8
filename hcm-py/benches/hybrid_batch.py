"""Time per hybrid-model evaluation from Python: one call over N states against one
call per state, on the bouncing ball's shipped HCM (examples/blobs). Compare the batch
figure with Criterion's `per_contact_f32/hcm_f32` (benches/residual_evaluation.rs):

    python hcm-py/benches/hybrid_batch.py            # from the repository's root

A measurement, not a test: it prints, it asserts nothing about speed.
"""

import statistics
import sys
import time
from pathlib import Path

import numpy as np

import hcm

ROOT = Path(__file__).resolve().parents[2]
N = 1_000_000
LOOP = 20_000


def best_of(repeats, work):
    times = []
    for _ in range(repeats):
        started = time.perf_counter()
        work()
        times.append(time.perf_counter() - started)
    return min(times), statistics.median(times)


def main():
    ball = hcm.Scenario.load(ROOT / "scenarios" / "bouncing_ball.toml")
    pm2 = ball.with_physics(ROOT / "examples" / "blobs" / "bouncing_ball.pm2.toml")
    model = hcm.HybridModel(pm2, ROOT / "examples" / "blobs" / "bouncing_ball.f32.hcm")
    rng = np.random.default_rng(1)
    # Inside the residual's envelope, as Criterion's state (10 µm, 1 m/s, 1.4 m/s) is.
    depth = rng.uniform(5e-6, 40e-6, N).astype(np.float32)
    rate = rng.uniform(-1.0, 1.0, N).astype(np.float32)
    approach = np.full(N, 1.4, dtype=np.float32)
    used = model.force(depth, rate, approach).residual_used.mean()
    best, median = best_of(7, lambda: model.force(depth, rate, approach))
    print(f"one call, {N:,} states ({used:.1%} with the residual): "
          f"{best / N * 1e9:.1f} ns per state (best of 7; median {median / N * 1e9:.1f} ns)")
    d, r, a = (float(x) for x in (depth[0], rate[0], approach[0]))
    loop_best, loop_median = best_of(3, lambda: [model.force(d, r, a) for _ in range(LOOP)])
    print(f"one call per state, {LOOP:,} calls: {loop_best / LOOP * 1e9:.0f} ns per state "
          f"(best of 3; median {loop_median / LOOP * 1e9:.0f} ns)")
    print(f"the loop costs {loop_best / LOOP / (best / N):.0f}× the batch per state")
    print(f"python {sys.version.split()[0]}, numpy {np.__version__}, hcm {hcm.__version__}")


if __name__ == "__main__":
    main()
