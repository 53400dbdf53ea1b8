"""CPU time per rollout: hcm, MuJoCo and PyBullet replaying the same tosses
(benches/peers/README.md, "Time per rollout").

One run, one thread each: every toss of `--scores` (an `hcm predict --scores` file: the
window and the initial state hcm starts each toss from) is replayed once by each
simulator from that state, over the same window, sampled at the toss's frames, with the
parameters each was fitted to (peers.json of a full run; hcm's `--physics` file, or the
scenario's own). The time is the process's CPU time (time.process_time for the peers,
around each rollout; for hcm its whole `hcm predict` process on one thread, reading the
data and writing the predictions included, divided by the tosses).

    benches/peers/.venv/bin/python benches/peers/timing.py --hcm target/release/hcm \
        --scores OUT/hcm_scenario_scores.csv --peers benches/peers/full-run/peers.json
"""

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import peers  # noqa: E402  (the rollouts themselves: the same code the fits run)

SCENARIO = "scenarios/cube_toss.toml"
DATA = "data/contactnets-cube/tosses.csv"
# One peer of each simulator, the table's closest to hcm's setup: Coulomb's cone
# (MuJoCo's elliptic) and hcm's inertia, each with its fitted contact parameters.
TIMED = {
    "MuJoCo": "MuJoCo fitted (k, b, μ, table offset)",
    "PyBullet": "PyBullet fitted (k, b, μ)",
}


def hcm_seconds(hcm, physics, count):
    """CPU seconds of one `hcm predict` of every toss on one thread, per toss, and the
    median simulation time per toss it prints (wall, one thread)."""
    with tempfile.TemporaryDirectory() as folder:
        command = [hcm, "predict", "--scenario", SCENARIO, "--data", DATA,
                   "--out", os.path.join(folder, "predicted.csv")]
        if physics:
            command += ["--physics", physics]
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        printed = subprocess.run(command, check=True, capture_output=True, text=True,
                                 env={**os.environ, "RAYON_NUM_THREADS": "1"}).stdout
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    median = float(printed.split("median ")[1].split(" ms")[0]) / 1e3
    return cpu / count, median


def peer_seconds(peer, params, tosses):
    """CPU seconds of each toss's rollout by `peer` (one process, one thread)."""
    seconds = []
    for toss in tosses:
        started = time.process_time()
        peers.replay(peer, params, [toss])
        seconds.append(time.process_time() - started)
    return np.array(seconds)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--hcm", required=True, help="the hcm binary")
    parser.add_argument("--scores", required=True, help="`hcm predict --scores` CSV")
    parser.add_argument("--peers", required=True, help="peers.json of a full run")
    parser.add_argument("--physics", help="hcm's physics file (default: the scenario's)")
    parser.add_argument("--out", help="write the timings as JSON here")
    args = parser.parse_args()
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    tosses = peers.load_tosses(DATA, peers.read_scores(args.scores))
    with open(args.peers) as f:
        fitted = json.load(f)["peers"]
    table = {p.name: p for p in peers.peers()}
    per_toss, median = hcm_seconds(args.hcm, args.physics, len(tosses))
    rows = {"hcm": {"mean_ms": 1e3 * per_toss, "median_ms": 1e3 * median}}
    for simulator, name in TIMED.items():
        seconds = peer_seconds(table[name], fitted[name]["fitted"], tosses)
        rows[simulator] = {"peer": name, "mean_ms": 1e3 * seconds.mean(),
                           "median_ms": 1e3 * float(np.median(seconds))}
    frames = sum(t.frames for t in tosses)
    print(f"{len(tosses)} tosses, {frames} frames, one thread each; CPU time per rollout:")
    print("| simulator | mean (ms) | median (ms) | mean ÷ hcm's |")
    print("|---|---|---|---|")
    for simulator, row in rows.items():
        ratio = row["mean_ms"] / rows["hcm"]["mean_ms"]
        row["ratio_to_hcm"] = ratio
        print(f"| {simulator} | {row['mean_ms']:.2f} | {row['median_ms']:.2f} | {ratio:.2f} |")
    if args.out:
        # Beside the target, then renamed: never a half-written file.
        folder = os.path.dirname(os.path.abspath(args.out))
        with tempfile.NamedTemporaryFile("w", dir=folder, delete=False) as f:
            json.dump({"tosses": len(tosses), "frames": frames, "rows": rows}, f, indent=1)
        os.replace(f.name, args.out)


if __name__ == "__main__":
    main()
