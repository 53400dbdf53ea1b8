"""Scores of an ensemble forecast of a toss, as `hcm predict --members` scores one
(docs/real-data.md, "The path as a distribution"; hcm-host/src/replay/path_forecast.rs,
ensemble.rs, face.rs and numerics/scores.rs; tests/commands/members.rs scores hcm's
members file again the same way).

Per toss, over the window's recorded frames, M members each sampled at those frames:

- energy score of the centre, E‖X − y‖ − ½·E‖X − X′‖ with the plain 1/M² estimators
  (not the fair M/(M − 1) one), per frame; the toss's score is the mean over the frames,
  in % of the cube's width;
- the same with the rotation angle between two orientations, 2·atan2(|vec(qa⁻¹·qb)|,
  |w|), as the distance, in degrees;
- the CRPS of x, y and z (the energy score in one dimension), % of the width;
- per frame and coordinate x, y, z, whether the recorded coordinate lies inside the
  members' central band of each level (type-6 quantiles: the k-th smallest of M is the
  k/(M + 1) quantile, linearly interpolated, held within the members' range; bounds
  included); the counts are pooled over frames and coordinates (and, over tosses, over
  tosses);
- the final face: the face whose outward normal points most nearly down (along gravity)
  at the window's last frame, 0 +x, 1 −x, 2 +y, 3 −y, 4 +z, 5 −z; the members' share of
  each face gives the Brier score Σ_f (p_f − y_f)² and the add-½ log-likelihood
  ln((n_f + ½)/(M + 3)) of the recorded face.

The fair energy score (M/(M − 1) on the spread term), which hcm's diagnosis compares
spreads by, is the plain one less spread/(M − 1).
"""

import csv
import math

import numpy as np

from peers import SIDE, quaternion_product, conjugate

LEVELS = (0.5, 0.9)  # the bands hcm's --scores reports
FACES = 6
DOWN = np.array([0.0, 0.0, -9.81])  # the scenario's gravity, world frame


def unit(q):
    """Quaternions scaled to norm 1 (hcm's UnitQuaternion::from_quaternion)."""
    return q / np.linalg.norm(q, axis=-1, keepdims=True)


def angle(a, b):
    """Rotation angle (rad) of a⁻¹·b, broadcasting over leading axes (hcm's
    rotation_angle)."""
    d = quaternion_product(conjugate(a), b)
    return 2.0 * np.arctan2(np.linalg.norm(d[..., 1:], axis=-1), np.abs(d[..., 0]))


def energy_parts(pairwise, to_outcome):
    """Per frame: E d(X, y) and ½·E d(X, X′) with 1/M² (each unordered pair once over M²).

    pairwise: (M, M, n) distances between members; to_outcome: (M, n)."""
    m = to_outcome.shape[0]
    error = to_outcome.sum(axis=0) / m
    upper = np.triu_indices(m, 1)
    spread = pairwise[upper].sum(axis=0) / (m * m)
    return error, spread


def crps(sorted_members, outcome):
    """Per frame, the CRPS of the members (sorted along axis 0) for the outcome: the mean
    absolute error less Σ_k (2k − M + 1)·x₍ₖ₎ / M² (k from 0)."""
    m = sorted_members.shape[0]
    error = np.abs(sorted_members - outcome).sum(axis=0) / m
    weights = (2.0 * np.arange(m) - m + 1.0).reshape((m,) + (1,) * (sorted_members.ndim - 1))
    return error - (weights * sorted_members).sum(axis=0) / (m * m)


def band(sorted_members, level):
    """The central band of `level` of the members (sorted along axis 0): low, high."""
    m = sorted_members.shape[0]
    level = min(max(level, 0.0), 1.0)

    def quantile(q):
        h = min(max((m + 1) * q - 1.0, 0.0), m - 1.0)
        below, above = math.floor(h), math.ceil(h)
        return sorted_members[below] + (h - below) * (sorted_members[above] - sorted_members[below])

    return quantile(0.5 * (1.0 - level)), quantile(0.5 * (1.0 + level))


def face(q):
    """The face a box at orientation q (w, x, y, z, body → world) lies on: the one whose
    outward normal points most nearly along gravity (hcm's Face::facing)."""
    w, x, y, z = q / np.linalg.norm(q)
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
        [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
        [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)],
    ])
    local = rotation.T @ DOWN
    axis = int(np.argmax(np.abs(local)))  # the first of a tie, as nalgebra's iamax
    return 2 * axis + int(local[axis] < 0.0)


def score_toss(recorded_positions, recorded_quaternions, positions, quaternions,
               width=SIDE, levels=LEVELS):
    """One toss's ensemble scores: recorded (n, 3) and (n, 4); members (M, n, 3) and
    (M, n, 4), each at the recorded frames. A dict of plain numbers."""
    positions = np.asarray(positions, dtype=float)
    quaternions = unit(np.asarray(quaternions, dtype=float))
    y = np.asarray(recorded_positions, dtype=float)
    r = unit(np.asarray(recorded_quaternions, dtype=float))
    m, n = positions.shape[:2]

    to_y = np.linalg.norm(positions - y, axis=-1)  # (M, n)
    between = np.linalg.norm(positions[:, None] - positions[None, :], axis=-1)  # (M, M, n)
    error, spread = energy_parts(between, to_y)
    turn_to_y = angle(quaternions, r[None])
    turn_between = angle(quaternions[:, None], quaternions[None, :])
    turn_error, turn_spread = energy_parts(turn_between, turn_to_y)

    percent = lambda total: 100.0 * total / n / width
    ordered = np.sort(positions, axis=0)  # (M, n, 3), per frame and coordinate
    inside = {}
    for level in levels:
        low, high = band(ordered, level)
        inside[level] = int(np.count_nonzero((low <= y) & (y <= high)))
    counts = [0] * FACES
    for q in quaternions[:, -1]:
        counts[face(q)] += 1
    return {
        "members": m,
        "frames": n,
        "position": percent(float(np.sum(error - spread))),
        "rotation": math.degrees(float(np.sum(turn_error - turn_spread))) / n,
        "spread": [percent(float(np.sum(spread))), math.degrees(float(np.sum(turn_spread))) / n],
        "crps": [percent(float(np.sum(crps(ordered[..., k], y[:, k])))) for k in range(3)],
        "inside": {str(level): inside[level] for level in levels},
        "scored": 3 * n,
        "face_counts": counts,
        "measured_face": face(r[-1]),
    }


def fair_score(s):
    """The toss's position + rotation energy score with the fair spread term, M/(M − 1)."""
    total = s["position"] + s["rotation"]
    if s["members"] < 2:
        return total
    return total - (s["spread"][0] + s["spread"][1]) / (s["members"] - 1)


def probabilities(s):
    m = max(sum(s["face_counts"]), 1)
    return [c / m for c in s["face_counts"]]


def brier(s):
    return float(sum((p - (f == s["measured_face"])) ** 2 for f, p in enumerate(probabilities(s))))


def log_likelihood(s):
    """ln p of the recorded face, add-½ estimate (n + ½)/(M + 3)."""
    return math.log((s["face_counts"][s["measured_face"]] + 0.5) / (sum(s["face_counts"]) + 3.0))


def most_probable(s):
    """The face most members reached (the lowest of a tie)."""
    return max(range(FACES), key=lambda f: (s["face_counts"][f], FACES - f))


def summary(scores, levels=LEVELS):
    """Over tosses: mean energy scores, mean CRPS, the pooled band shares, mean Brier and
    log-likelihood, tosses whose most probable face is the recorded one."""
    mean = lambda f: float(np.mean([f(s) for s in scores]))
    scored = sum(s["scored"] for s in scores)
    return {
        "tosses": len(scores),
        "energy_position": mean(lambda s: s["position"]),
        "energy_rotation": mean(lambda s: s["rotation"]),
        "fair_energy": mean(fair_score) if all("spread" in s for s in scores) else None,
        "crps": [mean(lambda s, k=k: s["crps"][k])
                 if all(s["crps"][k] is not None for s in scores) else None for k in range(3)],
        "inside": {str(level): sum(s["inside"][str(level)] for s in scores) / scored
                   for level in levels},
        "brier": mean(brier),
        "log_likelihood": mean(log_likelihood),
        "right_face": sum(most_probable(s) == s["measured_face"] for s in scores),
        "failed": sum(s.get("failed", 0) for s in scores),
    }


# ------------------------------------------------------- hcm's members file


def read_members(path):
    """Run → (times (n,), positions (M, n, 3), quaternions (M, n, 4)) of a members file
    (`hcm predict --members --out`: the measured-data columns and `member` last)."""
    rows = {}
    with open(path, newline="") as f:
        reader = csv.reader(f)
        header = next(reader)
        at = {name: i for i, name in enumerate(header)}
        keys = [at[k] for k in ("time", "px", "py", "pz", "qw", "qx", "qy", "qz")]
        run, member = at["run"], at["member"]
        for row in reader:
            per_run = rows.setdefault(row[run], {})
            per_run.setdefault(int(row[member]), []).append([float(row[i]) for i in keys])
    out = {}
    for name, members in rows.items():
        arrays = [np.array(members[k]) for k in sorted(members)]
        stacked = np.stack(arrays)  # (M, n, 8)
        times = stacked[0, :, 0]
        assert np.all(np.abs(stacked[:, :, 0] - times) < 1e-9), f"{name}: members' frames differ"
        out[name] = (times, stacked[:, :, 1:4], stacked[:, :, 4:8])
    return out


def read_faces(path):
    """Run → the row of an `hcm predict --faces` file."""
    with open(path, newline="") as f:
        return {row["run"]: row for row in csv.DictReader(f)}


FACE_NAMES = ["+x", "-x", "+y", "-y", "+z", "-z"]

SCORE_COLUMNS = {  # --scores column → this module's value
    "energy_position": lambda s: s["position"],
    "energy_rotation": lambda s: s["rotation"],
    "crps_x": lambda s: s["crps"][0],
    "crps_y": lambda s: s["crps"][1],
    "crps_z": lambda s: s["crps"][2],
    "inside_50": lambda s: s["inside"]["0.5"] / s["scored"],
    "inside_90": lambda s: s["inside"]["0.9"] / s["scored"],
    "members": lambda s: s["members"],
}


def rescore_hcm(members_path, scores, faces, tosses):
    """hcm's members file scored again here: per toss, this module's scores of the
    members against the recorded frames of `tosses`, and the largest gap to what hcm's
    --scores (`scores`: run → row) and --faces (`faces`: run → row) report, per column.
    Returns (per-toss scores, gaps)."""
    members = read_members(members_path)
    gaps = {name: 0.0 for name in SCORE_COLUMNS}
    gaps.update({"brier": 0.0, "measured_face_mismatches": 0, "face_probability": 0.0})
    rescored = {}
    for t in tosses:
        times, positions, quaternions = members[t.run]
        assert len(times) == t.frames and np.allclose(times, t.times, atol=1e-9), t.run
        s = score_toss(t.positions, t.quaternions, positions, quaternions)
        rescored[t.run] = s
        row = scores[t.run]
        for name, value in SCORE_COLUMNS.items():
            gaps[name] = max(gaps[name], abs(value(s) - float(row[name])))
        if faces is not None:
            f = faces[t.run]
            gaps["brier"] = max(gaps["brier"], abs(brier(s) - float(f["brier"])))
            gaps["measured_face_mismatches"] += FACE_NAMES[s["measured_face"]] != f["measured"]
            for k, p in enumerate(probabilities(s)):
                gaps["face_probability"] = max(gaps["face_probability"],
                                               abs(p - float(f["p" + FACE_NAMES[k]])))
    return rescored, gaps


def hcm_ensemble_scores(scores, faces, tosses, levels=LEVELS):
    """Per toss, hcm's own reported ensemble scores in this module's form (bands as counts
    of 3·frames; faces from the --faces file's probabilities × members)."""
    out = {}
    for t in tosses:
        row = scores[t.run]
        m = int(float(row["members"]))
        n = int(float(row["frames"]))
        s = {
            "members": m, "frames": n,
            "position": float(row["energy_position"]),
            "rotation": float(row["energy_rotation"]),
            "crps": [float(row[f"crps_{k}"]) for k in "xyz"],
            "inside": {str(level): round(float(row[f"inside_{round(100 * level)}"]) * 3 * n)
                       for level in levels},
            "scored": 3 * n,
            "failed": int(float(row["failed"])),
        }
        if faces is not None:
            f = faces[t.run]
            members = int(f["members"])
            s["face_counts"] = [round(float(f["p" + name]) * members) for name in FACE_NAMES]
            s["measured_face"] = FACE_NAMES.index(f["measured"])
        out[t.run] = s
    return out
