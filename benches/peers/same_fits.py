"""Whether two runs of peers.py (two OUT folders, e.g. one whole and one `--shards N`)
fitted the same peers to the same values and scores: their peers.json compared whole but
for the measured times (every `timings_s`, the randomised stage's too) and the worker count,
and their peers.md line by line but for the times printed in it (each fit's, the stages',
the command line's).

    python benches/peers/same_fits.py OUT_A OUT_B
"""

import json
import re
import sys


def timeless(value):
    """`value` without its measured times and worker counts, at any depth."""
    if isinstance(value, dict):
        return {k: timeless(v) for k, v in value.items() if k not in ("timings_s", "workers")}
    if isinstance(value, list):
        return [timeless(v) for v in value]
    return value


def report(folder):
    with open(f"{folder}/peers.json") as f:
        return timeless(json.load(f))


def page(folder):
    with open(f"{folder}/peers.md") as f:
        # "(7 evaluations, 2 s; …": the fit's wall time; the stages' and the command's.
        return [re.sub(r"evaluations, \d+ s;", "evaluations, … s;", line) for line in f
                if not line.startswith(("Stage wall times:", "Command:"))]


def main(a, b):
    one, other = report(a), report(b)
    differ = [k for k in sorted(set(one) | set(other)) if one.get(k) != other.get(k)]
    if differ:
        sys.exit(f"peers.json differs in {', '.join(differ)}")
    lines = [(x, y) for x, y in zip(page(a), page(b)) if x != y]
    if lines or len(page(a)) != len(page(b)):
        sys.exit(f"peers.md differs: {lines[:1] or 'in length'}")
    print(f"{a} and {b}: the same fits, values and scores (times aside)")


if __name__ == "__main__":
    main(*sys.argv[1:3])
