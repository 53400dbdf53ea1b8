"""Domain randomisation of the peers, scored as ensembles the way hcm's forecast is
(benches/peers/README.md, "Randomised peers").

Each peer keeps the parameters `peers.py` fitted (peers.json) and draws, per member, one
of two families of run-to-run variation:

- contact scatter: each contact parameter it fits (k, b, μ; not the table offset) ×
  max(0.05, 1 + σ·ζ), ζ ~ N(0, 1) truncated to ±2.5, one σ for all (hcm's
  `contact_scatter`, a forecast member's draw);
- table tilt: the table turned by the rotation vector (σ·ζ₁, σ·ζ₂, 0) rad, ζ truncated
  to ±2.5 (hcm's `variation.fixed_tilt`).

Every member starts from hcm's start state for the toss (no start-state draw, no
tracker noise). Member m of toss t always draws the same ζ (a generator seeded with
(seed, toss number, m)), so every σ of a grid sees the same draws and the results do not
depend on the worker count or order. σ is chosen on the training tosses (even numbers)
by the mean fair energy score (position % + rotation °, M/(M − 1) on the spread term,
as hcm's diagnosis compares spreads) of small ensembles; the held-out tosses (odd
numbers) are then scored with `ensemble.py`, exactly as `hcm predict --members` scores
hcm's own ensemble, and paired per toss against it.

    python randomised.py split --data tosses.csv [--first N] --out DIR
    python randomised.py run --data … --scenario-scores … --peers peers.json \
        --hcm LABEL SCORES FACES [--hcm …] --hcm-members MEMBERS --out DIR
"""

import argparse
import csv
import json
import math
import multiprocessing
import os
import sys
import time

import numpy as np
from scipy import stats

import ensemble
import peers as P

FAMILIES = ("contact scatter", "table tilt")
SCATTERED = ("k", "b", "mu")  # the contact parameters each peer fits
TRUNCATION = 2.5  # |ζ| at most (hcm's Draw::Member)
LEAST_FACTOR = 0.05  # a scattered parameter keeps at least this share of its value
DEFAULT_PEERS = (
    "PyBullet fitted (k, b, μ)",
    "PyBullet fitted (k, b, μ, inertia scale)",
    "MuJoCo fitted (k, b, μ, table offset)",
    "MuJoCo fitted (k, b, μ, table offset, inertia scale)",
)


# ------------------------------------------------------------------ split


def split(args):
    """Writes the training (even toss numbers) and held-out (odd) runs of the first
    `--first` runs of --data, lines as they are, to OUT/training.csv and
    OUT/held_out.csv."""
    os.makedirs(args.out, exist_ok=True)
    runs, kept = [], set()
    with open(args.data, newline="") as f, \
            open(os.path.join(args.out, "training.csv"), "w", newline="") as even, \
            open(os.path.join(args.out, "held_out.csv"), "w", newline="") as odd:
        header = f.readline()
        even.write(header)
        odd.write(header)
        for line in f:
            run = line.split(",", 1)[0]
            if run not in kept:
                if args.first and len(runs) >= args.first:
                    continue
                kept.add(run)
                runs.append(run)
            (even if P.toss_number(run) % 2 == 0 else odd).write(line)
    held = sum(P.toss_number(r) % 2 for r in runs)
    print(f"split {len(runs)} runs: {len(runs) - held} training, {held} held out")


# ------------------------------------------------------------------ draws


def zeta(seed, number, member):
    """Member `member` of toss `number`: its five ζ (k, b, μ, tilt x, tilt y), truncated
    to ±2.5; the same at every σ and in every process."""
    z = np.random.default_rng([seed, number, member]).standard_normal(5)
    return np.clip(z, -TRUNCATION, TRUNCATION)


def member_params(fitted, family, sigma, z):
    """The peer's parameters for one member of `family` at `sigma` with draws `z`."""
    params = dict(fitted)
    if family == "contact scatter":
        for name, value in zip(SCATTERED, z[:3]):
            params[name] = params[name] * max(1.0 + sigma * float(value), LEAST_FACTOR)
    elif family == "table tilt":
        params["tilt"] = (sigma * float(z[3]), sigma * float(z[4]))
    return params


# ------------------------------------------------------------ simulation

_shared = {}  # the tosses and peers, handed to the workers when they fork
_mujoco = {}  # this process's compiled MuJoCo model of each peer


def mujoco_member(peer, params):
    """The peer's model, compiled once with its fitted parameters, set to a member's k, b,
    μ and tilt in place (the cube's solref and friction, the table's orientation), and
    its data. MuJoCo places the world body's geoms among the model's constants
    (mj_resetData puts them back as compiled), so a member whose table turns
    differently has them set again by mj_setConst, as compiling does."""
    import mujoco

    if peer.name not in _mujoco:
        model = mujoco.MjModel.from_xml_string(P.mujoco_xml(**peer.fitted, cone=peer.world))
        table = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "table")
        _mujoco[peer.name] = [model, mujoco.MjData(model), table, 1 - table]
    entry = _mujoco[peer.name]
    model, data, table, cube = entry
    model.geom_solref[cube] = [-params["k"], -params["b"]]
    model.geom_friction[cube, 0] = params["mu"]
    turn = P.tilt_quaternion(params.get("tilt", (0.0, 0.0)))
    if not np.array_equal(model.geom_quat[table], turn):
        model.geom_quat[table] = turn
        mujoco.mj_setConst(model, data)
    return model, data


def simulate(peer, params, toss):
    """The peer's path of `toss` under `params` (a tilt included): positions (n, 3),
    quaternions (n, 4) and whether it failed (a MuJoCo instability warning, or a value
    not finite)."""
    if peer.simulator == "mujoco":
        import mujoco

        model, data = mujoco_member(peer, params)
        positions, quaternions = P.mujoco_toss(mujoco, model, data, toss, P.SUBSTEPS)
        unstable = data.warning[mujoco.mjtWarning.mjWARN_BADQACC].number > 0
    else:
        positions, quaternions = P.bullet_toss(params, toss, peer.world, P.SUBSTEPS)
        unstable = False
    failed = unstable or not (np.all(np.isfinite(positions)) and np.all(np.isfinite(quaternions)))
    return positions, quaternions, failed


def toss_ensemble(peer, family, sigma, members, toss, seed):
    """The members' scores on one toss (failed members left out and counted)."""
    if family == "replay" or sigma == 0.0:
        # Without spread every member is the replay: simulated once.
        positions, quaternions, failed = simulate(peer, dict(peer.fitted), toss)
        paths = [] if failed else [(positions, quaternions)] * members
        failures = members if failed else 0
    else:
        paths, failures = [], 0
        for m in range(members):
            params = member_params(peer.fitted, family, sigma, zeta(seed, toss.number, m))
            positions, quaternions, failed = simulate(peer, params, toss)
            if failed:
                failures += 1
            else:
                paths.append((positions, quaternions))
    assert paths, f"{peer.name}, {family} σ = {sigma}: every member of {toss.run} failed"
    s = ensemble.score_toss(toss.positions, toss.quaternions,
                            np.stack([p for p, _ in paths]), np.stack([q for _, q in paths]))
    s["failed"] = failures
    return s


def ensemble_chunk(job):
    """Worker: the ensemble scores of the tosses `indices` (peer, family, σ, members)."""
    name, family, sigma, members, indices, seed = job
    peer = _shared["peers"][name]
    return [toss_ensemble(peer, family, sigma, members, _shared["tosses"][i], seed)
            for i in indices]


class Pool:
    """Ensembles in a pool of forked workers; each toss's result depends on the toss
    alone, so the scores (in toss order) do not depend on the worker count."""

    def __init__(self, tosses, fitted_peers, workers):
        _shared["tosses"] = tosses
        _shared["peers"] = {p.name: p for p in fitted_peers}
        self.index = {t.run: i for i, t in enumerate(tosses)}
        self.workers = workers
        context = multiprocessing.get_context("fork")
        self.pool = context.Pool(workers) if workers > 1 else None

    def run(self, requests, seed):
        """requests: [(peer name, family, σ, members, tosses)] → per request, the per-toss
        scores in toss order. All requests go to the workers at once."""
        jobs, owners = [], []
        for r, (name, family, sigma, members, tosses) in enumerate(requests):
            indices = [self.index[t.run] for t in tosses]
            size = max(1, math.ceil(len(indices) / (2 * self.workers)))
            for i in range(0, len(indices), size):
                jobs.append((name, family, sigma, members, indices[i:i + size], seed))
                owners.append(r)
        mapped = (self.pool.map(ensemble_chunk, jobs, chunksize=1) if self.pool
                  else map(ensemble_chunk, jobs))
        out = [[] for _ in requests]
        for r, chunk in zip(owners, mapped):
            out[r].extend(chunk)
        return out

    def close(self):
        if self.pool:
            self.pool.close()
            self.pool.join()


# ----------------------------------------------------------------- checks


def field_edit_check(fitted_peers, tosses, seed):
    """MuJoCo members change the compiled model's fields in place; the same member
    compiled from its own XML (peers.mujoco_xml with the member's k, b, μ and tilt) must
    give the same path. Largest gaps (m, °) over a few tosses and members of each family."""
    worst = [0.0, 0.0]
    for peer in (p for p in fitted_peers if p.simulator == "mujoco"):
        for toss in tosses:
            for m in range(2):
                for family, sigma in (("contact scatter", 0.3), ("table tilt", 0.02)):
                    params = member_params(peer.fitted, family, sigma, zeta(seed, toss.number, m))
                    edited = simulate(peer, params, toss)[:2]
                    compiled = P.mujoco_replay(params, [toss], cone=peer.world)[0]
                    position, rotation = P.gap(edited, compiled)
                    worst = [max(worst[0], position), max(worst[1], rotation)]
    return {"position_gap_m": worst[0], "rotation_gap_deg": worst[1]}


# ---------------------------------------------------------------- summaries


def paired(a, b):
    """Per toss a − b: mean and the half-width of its 95 % interval, t(n − 1)·sd/√n."""
    d = np.asarray(a, dtype=float) - np.asarray(b, dtype=float)
    n = len(d)
    if n < 2:
        return {"mean": float(d.mean()) if n else float("nan"), "half_width_95": float("nan")}
    half = float(stats.t.ppf(0.975, n - 1) * d.std(ddof=1) / math.sqrt(n))
    return {"mean": float(d.mean()), "half_width_95": half}


def total(s):
    return s["position"] + s["rotation"]


def grid_values(text):
    return [float(v) for v in text.split(",") if v.strip()]


# ------------------------------------------------------------------ report


def markdown(rows, grids, checks, args, timings, held_out, training):
    width = lambda v, d=3: "—" if v is None else f"{v:.{d}f}"
    crps = lambda v: width(v, 2)
    reference = rows[0]
    lines = [
        f"## Randomised peers: ensembles on {len(held_out)} held-out tosses",
        "",
        f"Each peer with the parameters `peers.py` fitted, its members drawn per toss from "
        f"one family (σ fitted on the {len(training)} training tosses by the mean fair "
        f"energy score of {args.train_members} members), every member from hcm's start "
        f"state; {args.members} members per held-out toss, scored as `hcm predict "
        f"--members` scores hcm's ensemble (`ensemble.py`). Δ: per toss, the model's "
        f"(position + rotation) energy score, or Brier score, minus {reference['model']}'s; "
        "mean ± t-based 95 % half-width (negative: better than hcm's ensemble).",
        "",
        "| model | σ | energy score: position (%) | rotation (°) | Δ(position + rotation) vs hcm's "
        "ensemble ± 95 % | CRPS x | y | z (%) | inside 50 % band | inside 90 % band | face Brier "
        "| Δ Brier ± 95 % | right face |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        s = r["summary"]
        sigma = r.get("sigma_label", "")
        d, db = r["paired_vs_reference"], r.get("brier_vs_reference")
        brier_delta = (f"{db['mean']:+.4f} ± {db['half_width_95']:.4f}" if db else "—")
        lines.append(
            f"| {r['model']} | {sigma} | {s['energy_position']:.2f} | {s['energy_rotation']:.2f} | "
            f"{d['mean']:+.2f} ± {d['half_width_95']:.2f} | {crps(s['crps'][0])} | "
            f"{crps(s['crps'][1])} | {crps(s['crps'][2])} | {width(s['inside']['0.5'])} | "
            f"{width(s['inside']['0.9'])} | {width(s.get('brier'), 4)} | {brier_delta} | "
            f"{s.get('right_face', '—')} |")
    lines += ["", "σ fitted on the training tosses (mean fair energy score, position % + "
              f"rotation °, of {args.train_members} members; the same draws at every σ):", ""]
    for (name, family), g in grids.items():
        unit_ = " rad" if family == "table tilt" else ""
        shown = ", ".join(f"{v['sigma']:g}: {v['fair_energy']:.3f}" for v in g["grid"])
        edge = " (the grid's upper end)" if g["sigma"] == max(v["sigma"] for v in g["grid"]) else ""
        lines.append(f"- {name}, {family}: σ = {g['sigma']:g}{unit_}{edge}; σ{unit_ and ' (rad)'}: "
                     f"score {shown}")
    lines += ["", "Each ensemble against the same peer's single replay (energy score, position + "
              "rotation, paired per toss, ± 95 %):", ""]
    for r in rows:
        if "paired_vs_own_replay" in r:
            g = r["paired_vs_own_replay"]
            lines.append(f"- {r['model']}: {g['mean']:+.2f} ± {g['half_width_95']:.2f}")
    v = checks["scorer"]
    lines += [
        "",
        f"Checks: this scorer rescoring hcm's own members file ({checks['scorer_members']} "
        f"members a toss) differs from what hcm reported per toss by at most "
        f"{max(v[k] for k in ensemble.SCORE_COLUMNS):.1e} (energy scores, CRPS, band shares; "
        f"face Brier {v['brier']:.1e}, face probabilities {v['face_probability']:.1e}, "
        f"recorded face different on {v['measured_face_mismatches']} tosses); over tosses: "
        + ", ".join(f"{k} {a:.4f} (hcm {b:.4f})" for k, (a, b) in checks["scorer_summary"].items())
        + ".",
    ]
    if "field_edit" in checks:
        f = checks["field_edit"]
        lines.append(f"MuJoCo members set in the compiled model against the same members "
                     f"compiled from XML: {f['position_gap_m']:.1e} m, "
                     f"{f['rotation_gap_deg']:.1e}°.")
    if "replay_vs_deterministic" in checks:
        lines.append(f"Each peer's one-member replay against its held-out scores in "
                     f"peers.json: at most {checks['replay_vs_deterministic']:.1e} apart "
                     "(the same start states and parameters).")
    lines.append(f"Failed members (left out): {checks['failed']}.")
    lines += ["", "Stage wall times: " + ", ".join(f"{k} {v:.0f} s" for k, v in timings.items())
              + f" ({args.workers} workers)."]
    return "\n".join(lines) + "\n"


# -------------------------------------------------------------------- run


def load_peers(path, names):
    with open(path) as f:
        fitted = json.load(f)["peers"]
    chosen = []
    for peer in P.peers():
        if peer.name in names:
            peer.fitted = dict(fitted[peer.name]["fitted"])
            chosen.append(peer)
    missing = set(names) - {p.name for p in chosen}
    assert not missing, f"not in {path}: {missing}"
    return chosen


def run(args):
    clock = time.perf_counter()
    timings = {}
    scenario = P.read_scores(args.scenario_scores)
    tosses = P.load_tosses(args.data, scenario, args.first)
    training = [t for t in tosses if t.training]
    held_out = [t for t in tosses if not t.training]
    print(f"{len(training)} training tosses, {len(held_out)} held out", flush=True)

    hcm = []  # (label, per-toss scores by run, replay scores by run)
    for label, scores_path, faces_path in args.hcm:
        scores = P.read_scores(scores_path)
        faces = ensemble.read_faces(faces_path)
        for t in held_out:
            row = scores[t.run]
            assert abs(row["window_start"] - scenario[t.run]["window_start"]) < 1e-9 and \
                row["frames"] == scenario[t.run]["frames"], f"{label}: {t.run}'s window differs"
        hcm.append((label, ensemble.hcm_ensemble_scores(scores, faces, held_out), scores, faces))

    fitted_peers = load_peers(args.peers, args.peer)
    pool = Pool(tosses, fitted_peers, args.workers)  # forks before PyBullet opens here

    # The scorer against hcm's own members file.
    start = time.perf_counter()
    checks = {}
    label, reported, scores, faces = hcm[0]
    rescored, gaps = ensemble.rescore_hcm(args.hcm_members, scores, faces, held_out)
    mine = ensemble.summary([rescored[t.run] for t in held_out])
    theirs = ensemble.summary([reported[t.run] for t in held_out])
    checks["scorer"] = gaps
    checks["scorer_members"] = int(reported[held_out[0].run]["members"])
    checks["scorer_summary"] = {
        "energy position": (mine["energy_position"], theirs["energy_position"]),
        "energy rotation": (mine["energy_rotation"], theirs["energy_rotation"]),
        "inside 50 %": (mine["inside"]["0.5"], theirs["inside"]["0.5"]),
        "inside 90 %": (mine["inside"]["0.9"], theirs["inside"]["0.9"]),
        "face Brier": (mine["brier"], theirs["brier"]),
    }
    print(f"scorer check: {gaps}; {checks['scorer_summary']}", flush=True)
    assert max(gaps[k] for k in ensemble.SCORE_COLUMNS) < 1e-9 and gaps["brier"] < 1e-9 \
        and gaps["measured_face_mismatches"] == 0, "the scorer does not reproduce hcm's"
    if any(p.simulator == "mujoco" for p in fitted_peers):
        checks["field_edit"] = field_edit_check(fitted_peers, held_out[:3], args.seed)
        print(f"field-edit check: {checks['field_edit']}", flush=True)
    timings["checks"] = time.perf_counter() - start

    # σ on the training tosses.
    start = time.perf_counter()
    grid_of = {"contact scatter": args.scatter_grid, "table tilt": args.tilt_grid}
    requests = [(p.name, family, sigma, args.train_members, training)
                for p in fitted_peers for family in FAMILIES for sigma in grid_of[family]]
    results = pool.run(requests, args.seed)
    grids = {}
    for (name, family, sigma, _, _), per_toss in zip(requests, results):
        s = ensemble.summary(per_toss)
        entry = grids.setdefault((name, family), {"grid": []})
        entry["grid"].append({"sigma": sigma, "fair_energy": s["fair_energy"],
                              "energy_position": s["energy_position"],
                              "energy_rotation": s["energy_rotation"],
                              "inside": s["inside"], "brier": s["brier"], "failed": s["failed"]})
    for key, g in grids.items():
        best = min(g["grid"], key=lambda v: v["fair_energy"])  # the first of a tie
        g["sigma"] = best["sigma"]
        print(f"{key[0]}, {key[1]}: σ = {best['sigma']:g} "
              f"({[round(v['fair_energy'], 3) for v in g['grid']]})", flush=True)
    timings["σ on the training tosses"] = time.perf_counter() - start

    # The held-out ensembles and each peer's one-member replay.
    start = time.perf_counter()
    requests = []
    for p in fitted_peers:
        requests.append((p.name, "replay", 0.0, 1, held_out))
        requests += [(p.name, family, grids[(p.name, family)]["sigma"], args.members, held_out)
                     for family in FAMILIES]
    results = pool.run(requests, args.seed)
    pool.close()
    timings["held-out ensembles"] = time.perf_counter() - start

    # The rows, paired per toss against hcm's reference ensemble.
    ref_label, ref, ref_scores, ref_faces = hcm[0]
    ref_total = [total(ref[t.run]) for t in held_out]
    ref_brier = [ensemble.brier(ref[t.run]) for t in held_out]

    def row(model, per_toss, sigma_label="", extra=None):
        per_toss = list(per_toss)
        summary = ensemble.summary(per_toss)
        r = {"model": model, "sigma_label": sigma_label, "summary": summary,
             "paired_vs_reference": paired([total(s) for s in per_toss], ref_total),
             "brier_vs_reference": paired([ensemble.brier(s) for s in per_toss], ref_brier),
             "scores": {t.run: s for t, s in zip(held_out, per_toss)}}
        r.update(extra or {})
        return r

    rows = []
    for label, reported, scores, faces in hcm:
        rows.append(row(f"hcm: {label}", [reported[t.run] for t in held_out], "",
                        {"members": reported[held_out[0].run]["members"]}))
    replay = [{"members": 1, "frames": int(ref_scores[t.run]["frames"]),
               "position": ref_scores[t.run]["position_error"],
               "rotation": ref_scores[t.run]["rotation_error"],
               "crps": [None] * 3, "inside": {"0.5": 0, "0.9": 0},
               "scored": 3 * int(ref_scores[t.run]["frames"]),
               "face_counts": [int(ensemble.FACE_NAMES[k] == ref_faces[t.run]["replay"])
                               for k in range(ensemble.FACES)],
               "measured_face": ensemble.FACE_NAMES.index(ref_faces[t.run]["measured"])}
              for t in held_out]
    rows.append(row("hcm: the same physics, single replay", replay, "—"))
    deterministic = {}
    if args.deterministic:
        with open(args.deterministic) as f:
            deterministic = json.load(f).get("scores", {})
    worst_replay = 0.0
    replays = {}
    for i, p in enumerate(fitted_peers):
        replay_scores, *ensembles = results[3 * i: 3 * i + 3]
        replays[p.name] = replay_scores
        rows.append(row(f"{p.name}: single replay", replay_scores, "—"))
        if p.name in deterministic:
            for t, s in zip(held_out, replay_scores):
                d = deterministic[p.name].get(t.run)
                if d:
                    worst_replay = max(worst_replay, abs(s["position"] - d["position_error"]),
                                       abs(s["rotation"] - d["rotation_error"]))
            checks["replay_vs_deterministic"] = worst_replay
        for family, per_toss in zip(FAMILIES, ensembles):
            sigma = grids[(p.name, family)]["sigma"]
            gain = paired([total(s) for s in per_toss], [total(s) for s in replay_scores])
            rows.append(row(f"{p.name}, {family}", per_toss,
                            f"{sigma:g} rad" if family == "table tilt" else f"{sigma:g}",
                            {"family": family, "sigma": sigma, "members": args.members,
                             "paired_vs_own_replay": gain}))
    checks["failed"] = sum(r["summary"]["failed"] for r in rows)
    timings["randomised.py total"] = time.perf_counter() - clock

    text = markdown(rows, grids, checks, args, timings, held_out, training)
    report = {
        "held_out": [t.run for t in held_out], "training": [t.run for t in training],
        "members": args.members, "train_members": args.train_members, "seed": args.seed,
        "scatter_grid": args.scatter_grid, "tilt_grid": args.tilt_grid,
        "workers": args.workers, "first": args.first,
        "rows": rows,
        "grids": [{"peer": k[0], "family": k[1], **v} for k, v in grids.items()],
        "checks": checks, "timings_s": timings, "versions": P.versions(),
    }
    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "randomised.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "randomised.json"), "w") as f:
        json.dump(report, f, indent=1)
    if args.merge:
        with open(os.path.join(args.out, "peers.md"), "a") as f:
            f.write("\n" + text)
        path = os.path.join(args.out, "peers.json")
        with open(path) as f:
            merged = json.load(f)
        merged["randomised"] = report
        with open(path, "w") as f:
            json.dump(merged, f, indent=1)
    print(text)


def arguments():
    a = argparse.ArgumentParser(description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = a.add_subparsers(dest="command", required=True)
    s = sub.add_parser("split", help="write the training and held-out runs of --data")
    s.add_argument("--data", required=True)
    s.add_argument("--first", type=int)
    s.add_argument("--out", required=True)
    r = sub.add_parser("run", help="fit σ on the training tosses, score the held-out ones")
    r.add_argument("--data", required=True, help="tosses CSV (hcm's measured-data format)")
    r.add_argument("--scenario-scores", required=True,
                   help="`hcm predict --scores` of the shipped scenario: windows, start states")
    r.add_argument("--peers", required=True, help="peers.json with each peer's fit")
    r.add_argument("--peer", action="append", help="a peer to randomise (by its name in "
                   "peers.json; repeatable; default: the four k, b, μ peers)")
    r.add_argument("--hcm", nargs=3, action="append", required=True,
                   metavar=("LABEL", "SCORES", "FACES"),
                   help="an hcm ensemble on the held-out tosses: its `--scores` and `--faces` "
                   "files; the first is the reference every row is paired with")
    r.add_argument("--hcm-members", required=True,
                   help="the first --hcm ensemble's members file, scored again here")
    r.add_argument("--deterministic", help="peers.json whose held-out scores the one-member "
                   "replays must give back (default: --peers)")
    r.add_argument("--out", required=True)
    r.add_argument("--first", type=int, help="use only the first N runs (as hcm --first)")
    r.add_argument("--members", type=int, default=32, help="members per held-out toss")
    r.add_argument("--train-members", type=int, default=8,
                   help="members per training toss when fitting σ")
    r.add_argument("--scatter-grid", type=grid_values,
                   default=grid_values("0,0.05,0.1,0.2,0.3,0.4"))
    r.add_argument("--tilt-grid", type=grid_values,
                   default=grid_values("0,0.006,0.012,0.018,0.024,0.03"), help="rad")
    r.add_argument("--seed", type=int, default=1)
    r.add_argument("--workers", type=int, default=os.cpu_count())
    r.add_argument("--merge", action="store_true",
                   help="also append the table to OUT/peers.md and the results to OUT/peers.json")
    args = a.parse_args()
    if args.command == "run":
        args.peer = args.peer or list(DEFAULT_PEERS)
        args.deterministic = args.deterministic or args.peers
    return args


def main():
    args = arguments()
    if args.command == "split":
        split(args)
    else:
        run(args)


if __name__ == "__main__":
    sys.exit(main())
