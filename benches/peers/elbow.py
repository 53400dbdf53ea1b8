"""MuJoCo and PyBullet beside hcm on the real two-link elbow tosses
(benches/peers/README.md, "The elbow").

The elbow is two 0.1 × 0.05 × 0.05 m boxes of 0.37 kg joined by a hinge
(data/contactnets-elbow/). Each simulator reads the data set's URDF and models it as a
mechanism in reduced coordinates: elbow_1 a free base, elbow_2 on the revolute hinge.
Every peer starts each toss from the state hcm starts it from (the window start and the
per-link initial states of `hcm predict --scores`, which hcm assembles onto the hinge),
is sampled at the toss's recorded frame times, scored with hcm's metric (each link's
mean position error in % of its 0.1 m width and mean rotation error in °, the toss's
score their mean), and fitted with hcm's objective (the mean over training tosses of
position % + rotation °) on the tosses hcm's elbow fit sees: every `--fit-stride`th
even-numbered toss. The odd-numbered tosses are held out.
"""

import argparse
import csv
import json
import math
import os
import sys
import time
import xml.etree.ElementTree as ElementTree
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize
from scipy.stats import qmc

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import peers as cube  # noqa: E402  (the cube's helpers: rotations, fitting, summaries)
from peers import (  # noqa: E402
    Peer, conjugate, fitness, from_search, paired, quaternion_product, rotation_angles,
    rotation_matrix, search_box, summary, table_row, to_search, toss_number, versions,
)

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
URDF = os.path.join(ROOT, "data", "contactnets-elbow", "contactnets_elbow.urdf")
LINKS = ("elbow_1", "elbow_2")  # the base (free) and the child (on the hinge)
HINGE = "hinge_1_to_2"
MASS = 0.37  # kg, each link (the URDF's and the scenario's)
HALF = np.array([0.05, 0.025, 0.025])  # m, each link's half extents
WIDTH = 2 * float(HALF.max())  # m: hcm's width of a box, 2 × its largest half extent
# kg·m², each link: a uniform 0.1 × 0.05 × 0.05 m box, scenarios/elbow_toss.toml's values
# (the URDF's 6.167e-4 about each axis is a 0.1 m cube's, and is replaced).
INERTIA = np.array([1.5417e-4, 3.8542e-4, 3.8542e-4])
# hcm's hinge (scenarios/elbow_toss.toml): its point in each link's frame (centre of mass
# origin) and its axis in elbow_1's frame.
ANCHORS = (np.array([-0.035, 0.06, 0.0]), np.array([-0.035, 0.0, 0.0]))
AXIS = np.array([0.0, 1.0, 0.0])
GRAVITY = 9.81  # m/s²
FRAME = 0.0068  # s, the data's frame period (about 147 Hz)
SUBSTEPS = 10  # simulator steps per frame, as the cube's: timestep 0.68 ms
TIMESTEP = FRAME / SUBSTEPS
FAR_BELOW = -100.0  # m, where the table goes for the free-flight check


# ---------------------------------------------------------------- URDF


def read_urdf(path):
    """What the URDF says of the elbow, checked against hcm's scenario: each link's
    mass, box and centre of mass in its link frame, the hinge's origin and axis."""
    root = ElementTree.parse(path).getroot()
    links = {}
    for link in root.findall("link"):
        inertial = link.find("inertial")
        collision = link.find("collision")
        links[link.get("name")] = {
            "mass": float(inertial.find("mass").get("value")),
            "com": np.array([float(v) for v in inertial.find("origin").get("xyz").split()]),
            "box": np.array([float(v) for v in collision.find("geometry/box").get("size").split()]),
            "box_origin": np.array([float(v) for v in collision.find("origin").get("xyz").split()]),
            "rpy": [inertial.find("origin").get("rpy"), collision.find("origin").get("rpy")],
        }
    joint = root.find(f"joint[@name='{HINGE}']")
    origin = joint.find("origin")
    urdf = {
        "links": links, "joint_type": joint.get("type"),
        "parent": joint.find("parent").get("link"), "child": joint.find("child").get("link"),
        "joint_origin": np.array([float(v) for v in origin.get("xyz").split()]),
        "joint_rpy": [float(v) for v in origin.get("rpy").split()],
        "axis": np.array([float(v) for v in joint.find("axis").get("xyz").split()]),
    }
    check_urdf(urdf)
    return urdf


def check_urdf(urdf):
    """The URDF's elbow is hcm's: elbow_1's centre of mass at its frame's origin, the
    hinge at (−0.035, 0.06, 0) there about y; elbow_2's frame on the hinge, unturned
    (θ = 0 at aligned frames, hcm's convention), its centre 0.035 m along x, so that
    the hinge is at (−0.035, 0, 0) from elbow_2's centre (hcm's anchor); 0.37 kg boxes
    of 0.1 × 0.05 × 0.05 m centred on the centres of mass."""
    first, second = (urdf["links"][n] for n in LINKS)
    assert (urdf["parent"], urdf["child"]) == LINKS and urdf["joint_type"] == "continuous"
    assert urdf["joint_rpy"] == [0.0, 0.0, 0.0]
    assert all(rpy in ("0 0 0", None) for link in (first, second) for rpy in link["rpy"])
    assert np.array_equal(first["com"], [0, 0, 0])
    assert np.allclose(urdf["joint_origin"], ANCHORS[0], atol=1e-15)
    assert np.allclose(-second["com"], ANCHORS[1], atol=1e-15)
    assert np.array_equal(urdf["axis"], AXIS)
    for link in (first, second):
        assert link["mass"] == MASS
        assert np.allclose(link["box"], 2 * HALF, atol=1e-15)
        assert np.allclose(link["box_origin"], link["com"], atol=1e-15)


# ---------------------------------------------------------------- data


@dataclass
class ElbowToss:
    """One toss's window: both links' recorded frames and hcm's initial state at its
    start (elbow_1's pose and velocity, the hinge's angle and rate)."""

    run: str
    number: int
    times: np.ndarray  # s, the window's frame times
    positions: np.ndarray  # m, (2, n, 3): each link's centre of mass
    quaternions: np.ndarray  # (2, n, 4): (w, x, y, z), link → world
    starts: tuple  # per link: (p0, q0, v0, w0), hcm's (assembled) initial state
    p0: np.ndarray  # m, elbow_1's centre
    q0: np.ndarray  # (w, x, y, z), elbow_1 → world
    v0: np.ndarray  # m/s, world
    w0: np.ndarray  # rad/s, world
    angle: float  # rad, the hinge's angle θ
    rate: float  # rad/s, dθ/dt

    @property
    def frames(self):
        return len(self.times)

    @property
    def training(self):
        return self.number % 2 == 0


def read_tracks(path):
    """run → body → (times, positions, quaternions), in the file's run order."""
    rows = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            rows.setdefault(row["run"], {}).setdefault(row["body"], []).append(row)
    return {run: {body: cube.track_arrays(r) for body, r in bodies.items()}
            for run, bodies in rows.items()}


def read_scores(path):
    """run → body (elbow_1, elbow_2, all) → the row of an `hcm predict --scores` CSV of
    a mechanism (numbers as floats; the `all` row's empty cells as None)."""
    scores = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            parsed = {k: (v if k in ("run", "body", "initial_state") else
                          (float(v) if v != "" else None)) for k, v in row.items()}
            scores.setdefault(row["run"], {})[row["body"]] = parsed
    return scores


def state_of(row):
    pick = lambda *keys: np.array([row[k] for k in keys])
    return (pick("p0x", "p0y", "p0z"), pick("q0w", "q0x", "q0y", "q0z"),
            pick("v0x", "v0y", "v0z"), pick("w0x", "w0y", "w0z"))


def axis_angle(axis, angle):
    """(w, x, y, z) of a turn by `angle` about the unit `axis`."""
    return np.concatenate([[math.cos(angle / 2)], math.sin(angle / 2) * np.asarray(axis)])


def hinge_state(first, second):
    """The hinge's angle and rate from the two links' states, as hcm reads them
    (scenario/joint.rs, replay/assembly.rs): θ = the turn of q1⁻¹·q2 about the axis
    (elbow_1's y), 0 at aligned frames, right-handed; dθ/dt = (ω2 − ω1)·(R1·axis)."""
    q1, q2 = first[1], second[1]
    u = np.array([1.0, 0.0, 0.0])  # perpendicular to the axis: θ's reference
    turned = rotation_matrix(quaternion_product(conjugate(q1), q2)) @ u
    angle = math.atan2(float(np.cross(u, turned) @ AXIS), float(u @ turned))
    rate = float((second[3] - first[3]) @ (rotation_matrix(q1) @ AXIS))
    return angle, rate


def child_state(p1, q1, v1, w1, angle, rate):
    """elbow_2's centre, orientation, velocity and angular velocity (world) from the
    base's state and the hinge's: the URDF's forward kinematics."""
    q2 = quaternion_product(q1, axis_angle(AXIS, angle))
    r1, r2 = rotation_matrix(q1) @ ANCHORS[0], rotation_matrix(q2) @ ANCHORS[1]
    w2 = w1 + rotation_matrix(q1) @ AXIS * rate
    return p1 + r1 - r2, q2, v1 + np.cross(w1, r1) - np.cross(w2, r2), w2


def window_toss(run, tracks, scores):
    """The toss's frames of both links from hcm's window start on, with hcm's initial
    state turned into the mechanism's coordinates."""
    rows = [scores[link] for link in LINKS]
    assert rows[0]["window_start"] == rows[1]["window_start"], run
    assert rows[0]["frames"] == rows[1]["frames"], run
    assert scores["all"]["frames"] == rows[0]["frames"] + rows[1]["frames"], run
    start_time = rows[0]["window_start"]
    times, positions, quaternions = None, [], []
    for link in LINKS:
        t, p, q = tracks[link]
        start = int(np.searchsorted(t, start_time - 1e-9))
        assert abs(t[start] - start_time) < 1e-9, run
        assert len(t) - start == int(rows[0]["frames"]), run
        assert np.allclose(np.diff(t[start:]), FRAME, atol=1e-9), f"{run}: uneven frames"
        assert times is None or np.array_equal(times, t[start:]), f"{run}: two clocks"
        times = t[start:]
        positions.append(p[start:])
        quaternions.append(q[start:])
    starts = tuple(state_of(row) for row in rows)
    angle, rate = hinge_state(*starts)
    p0, q0, v0, w0 = starts[0]
    return ElbowToss(run, toss_number(run), times, np.array(positions), np.array(quaternions),
                     starts, p0, q0, v0, w0, angle, rate)


def load_tosses(data, scores, first=None):
    """Every scored toss of `data` (the first `first` runs, as `hcm --first`)."""
    tracks = read_tracks(data)
    runs = list(tracks)[:first] if first else list(tracks)
    return [window_toss(r, tracks[r], scores[r]) for r in runs if r in scores]


# --------------------------------------------------------------- metric


def link_errors(positions, quaternions, measured_positions, measured_quaternions):
    """hcm's scores of one link: mean |p_pred − p| in % of its width, mean angle in °."""
    miss = np.linalg.norm(positions - measured_positions, axis=1)
    position = 100.0 * float(np.mean(miss)) / WIDTH
    rotation = math.degrees(float(np.mean(rotation_angles(quaternions, measured_quaternions))))
    return position, rotation


def toss_errors(toss, positions, quaternions):
    """hcm's scores of one toss: (position, rotation) of the toss (the links' means),
    then each link's (position, rotation)."""
    links = [link_errors(positions[i], quaternions[i], toss.positions[i], toss.quaternions[i])
             for i in range(len(LINKS))]
    position = sum(p for p, _ in links) / len(links)
    rotation = sum(r for _, r in links) / len(links)
    return (position, rotation, *links)


def failed(positions, quaternions):
    """A replay that blew up (a value not finite)."""
    return not (np.all(np.isfinite(positions)) and np.all(np.isfinite(quaternions)))


# Scores a failed replay gets (never seen in the runs reported): far off in both.
FAILED = (1e3, 180.0, (1e3, 180.0), (1e3, 180.0))


# --------------------------------------------------------------- MuJoCo


def mujoco_spec(urdf, k, b, mu, offset=0.0, inertia_scale=1.0, hinge_damping=0.0,
                hinge_friction=0.0, substeps=SUBSTEPS, cone="elliptic", free=True):
    """MuJoCo's elbow, read from the URDF by MuJoCo's own parser (MjSpec.from_file,
    which drops the visual geoms), then: elbow_1 on a free joint (the URDF's root is
    welded to the world otherwise); each link's inertia set explicitly to the uniform
    box's (× `inertia_scale`) about its URDF centre of mass, the URDF's 6.167e-4 cube
    inertia replaced; the links excluded from touching each other; each link's box
    given priority 1 (its friction, solref and solimp are the contact's, the plane's
    are not mixed in), condim 3 (sliding friction only), μ and solref = (−k, −b)
    (MuJoCo's direct form); the hinge's damping (N·m·s/rad) and frictionloss (N·m);
    a plane at z = offset; Euler, Newton, dense Jacobian, `cone` friction cone. `free`
    False leaves elbow_1 welded to the world (the hinge friction check's)."""
    import mujoco

    spec = mujoco.MjSpec.from_file(urdf)
    spec.option.timestep = FRAME / substeps
    spec.option.integrator = mujoco.mjtIntegrator.mjINT_EULER
    spec.option.cone = {"elliptic": mujoco.mjtCone.mjCONE_ELLIPTIC,
                        "pyramidal": mujoco.mjtCone.mjCONE_PYRAMIDAL}[cone]
    spec.option.solver = mujoco.mjtSolver.mjSOL_NEWTON
    spec.option.jacobian = mujoco.mjtJacobian.mjJAC_DENSE
    spec.option.gravity = [0.0, 0.0, -GRAVITY]
    if free:
        spec.body(LINKS[0]).add_freejoint()
    for name in LINKS:
        body = spec.body(name)
        body.explicitinertial = True
        body.mass = MASS
        body.fullinertia = [math.nan] * 6  # the URDF's (a full tensor) out, the diagonal in
        body.inertia = (INERTIA * inertia_scale).tolist()
        body.iquat = [1.0, 0.0, 0.0, 0.0]
    geoms = list(spec.geoms)
    assert len(geoms) == 2, "the URDF's collision boxes alone"
    for geom in geoms:
        geom.priority = 1
        geom.condim = 3
        geom.friction = [mu, 0.0, 0.0]
        geom.solref = [-k, -b]
    hinge = spec.joint(HINGE)
    hinge.damping[0] = hinge_damping  # MuJoCo 4's damping holds coefficients; [0] linear
    hinge.frictionloss = hinge_friction
    spec.add_exclude(bodyname1=LINKS[0], bodyname2=LINKS[1])
    spec.worldbody.add_geom(name="table", type=mujoco.mjtGeom.mjGEOM_PLANE, size=[0, 0, 1],
                            pos=[0.0, 0.0, offset], friction=[0.0, 0.0, 0.0])
    return spec


def mujoco_model(urdf, params, substeps=SUBSTEPS, cone="elliptic"):
    return mujoco_spec(urdf, **params, substeps=substeps, cone=cone).compile()


def mujoco_set(mujoco, model, data, toss):
    """hcm's initial state in MuJoCo's coordinates: the free joint's qpos = (p, q) of
    elbow_1 (its body frame is its centre of mass), qvel = (v world, ω in elbow_1's
    frame); the hinge's qpos = θ, qvel = dθ/dt."""
    mujoco.mj_resetData(model, data)
    data.qpos[:] = np.concatenate([toss.p0, toss.q0, [toss.angle]])
    body_omega = rotation_matrix(toss.q0).T @ toss.w0
    data.qvel[:] = np.concatenate([toss.v0, body_omega, [toss.rate]])


def mujoco_pose(mujoco, model, data, bodies):
    """Each link's centre (xipos) and orientation (xquat) at the current qpos."""
    mujoco.mj_kinematics(model, data)
    return ([data.xipos[b].copy() for b in bodies], [data.xquat[b].copy() for b in bodies])


def mujoco_replay(urdf, params, tosses, substeps=SUBSTEPS):
    """MuJoCo's trajectory of each toss (both links), sampled at its frames."""
    import mujoco

    model = mujoco_model(urdf, params, substeps)
    data = mujoco.MjData(model)
    bodies = [model.body(n).id for n in LINKS]
    return [mujoco_toss(mujoco, model, data, bodies, t, substeps) for t in tosses]


def mujoco_toss(mujoco, model, data, bodies, toss, substeps):
    """One toss from hcm's start; every position NaN (a failed toss) if MuJoCo found the
    simulation unstable (a bad qpos, qvel or qacc: it then resets the state and goes
    on) or ran out of room for contacts or constraints."""
    mujoco_set(mujoco, model, data, toss)
    positions, quaternions = [], []
    for frame in range(toss.frames):
        if frame:
            mujoco.mj_step(model, data, nstep=substeps)
        p, q = mujoco_pose(mujoco, model, data, bodies)
        positions.append(p)
        quaternions.append(q)
    positions, quaternions = np.array(positions), np.array(quaternions)
    w = mujoco.mjtWarning
    failures = (w.mjWARN_BADQPOS, w.mjWARN_BADQVEL, w.mjWARN_BADQACC, w.mjWARN_CONTACTFULL,
                w.mjWARN_CNSTRFULL)
    if any(data.warning[f].number for f in failures):
        # MuJoCo resets an unstable simulation and carries on: the toss failed.
        positions[:] = np.nan
    # (frames, links, …) → (links, frames, …)
    return positions.swapaxes(0, 1), quaternions.swapaxes(0, 1)


# ------------------------------------------------------------- PyBullet


def bullet_world(p, c, urdf, k, b, mu, offset=0.0, inertia_scale=1.0, hinge_damping=0.0,
                 hinge_friction=0.0, fixed=False):
    """PyBullet's elbow: loadURDF (a multibody: elbow_1 the free base, elbow_2 link 0
    on the hinge; links of one multibody do not collide without URDF_USE_SELF_COLLISION),
    then set explicitly: each link's inertia the uniform box's (× `inertia_scale`),
    no velocity damping, μ the links' (the plane's 1), contact (2k, b/2) on each link
    and on the plane, which Bullet combines to (k, b) (stiffness in series, damping as
    a sum); the hinge's damping (N·m·s/rad) and its velocity motor (target 0, at most
    `hinge_friction` N·m: PyBullet's Coulomb joint friction; PyBullet's default motor
    would lock the hinge, so it is set to the friction, or to 0 without it); a plane at
    z = offset. `fixed` holds elbow_1 still (the hinge friction check's)."""
    plane = p.createMultiBody(0.0, p.createCollisionShape(p.GEOM_PLANE, physicsClientId=c),
                              basePosition=[0, 0, offset], physicsClientId=c)
    elbow = p.loadURDF(urdf, useFixedBase=fixed, physicsClientId=c)
    for link in (-1, 0):
        p.changeDynamics(elbow, link, localInertiaDiagonal=(INERTIA * inertia_scale).tolist(),
                         linearDamping=0.0, angularDamping=0.0, lateralFriction=mu,
                         contactStiffness=2 * k, contactDamping=b / 2, physicsClientId=c)
    p.changeDynamics(elbow, 0, jointDamping=hinge_damping, physicsClientId=c)
    p.setJointMotorControl2(elbow, 0, p.VELOCITY_CONTROL, targetVelocity=0.0,
                            force=hinge_friction, physicsClientId=c)
    p.changeDynamics(plane, -1, lateralFriction=1.0, contactStiffness=2 * k,
                     contactDamping=b / 2, physicsClientId=c)
    return elbow


def bullet_set(p, c, urdf, params, toss, substeps):
    """A fresh world with the elbow at hcm's initial state: the base (elbow_1's centre
    of mass: the URDF puts it at the link frame's origin) at (p, q) with (v, ω) in the
    world frame; the hinge at θ, dθ/dt."""
    p.resetSimulation(physicsClientId=c)
    p.setGravity(0, 0, -GRAVITY, physicsClientId=c)
    p.setTimeStep(FRAME / substeps, physicsClientId=c)
    elbow = bullet_world(p, c, urdf, **params)
    w, x, y, z = toss.q0
    p.resetBasePositionAndOrientation(elbow, toss.p0.tolist(), [x, y, z, w], physicsClientId=c)
    p.resetBaseVelocity(elbow, toss.v0.tolist(), toss.w0.tolist(), physicsClientId=c)
    p.resetJointState(elbow, 0, toss.angle, toss.rate, physicsClientId=c)
    return elbow


def bullet_pose(p, c, elbow):
    """Each link's centre of mass and orientation (w, x, y, z)."""
    base, (x, y, z, w) = p.getBasePositionAndOrientation(elbow, physicsClientId=c)
    state = p.getLinkState(elbow, 0, computeForwardKinematics=1, physicsClientId=c)
    x2, y2, z2, w2 = state[1]
    return [base, state[0]], [(w, x, y, z), (w2, x2, y2, z2)]


def bullet_replay(urdf, params, tosses, substeps=SUBSTEPS):
    """PyBullet's trajectory of each toss (both links), sampled at its frames; a fresh
    world each."""
    return [bullet_toss(urdf, params, t, substeps) for t in tosses]


def bullet_toss(urdf, params, toss, substeps):
    p, c = cube.bullet_client()
    elbow = bullet_set(p, c, urdf, params, toss, substeps)
    positions, quaternions = [], []
    for frame in range(toss.frames):
        if frame:
            for _ in range(substeps):
                p.stepSimulation(physicsClientId=c)
        position, quaternion = bullet_pose(p, c, elbow)
        positions.append(position)
        quaternions.append(quaternion)
    return np.array(positions).swapaxes(0, 1), np.array(quaternions).swapaxes(0, 1)


def replay(peer, params, tosses, substeps=SUBSTEPS):
    """The peer's trajectory of each toss with `params`, `substeps` steps a frame."""
    if peer.simulator == "mujoco":
        return mujoco_replay(_shared["urdf"], params, tosses, substeps)
    return bullet_replay(_shared["urdf"], params, tosses, substeps)


# ---------------------------------------------------------------- peers


MUJOCO_START = {"k": 3294.0, "b": 45.1}  # Acosta et al.'s MuJoCo k, b (the cube peers')
BULLET_START = {"k": 1784.0, "b": 27.2}  # their Bullet k, b
MU_START = 0.3  # the URDF's μ (the authors' simulator default; hcm's scenario's too)
CONTACT_BOX = {"b": (1.0, 1e3), "mu": (0.08, 0.5), "offset": (-0.004, 0.002),
               "inertia_scale": cube.INERTIA_BOX}  # the cube peers' boxes (--inertia-box)
HINGE_BOX = {"hinge_damping": (1e-6, 0.1), "hinge_friction": (1e-6, 0.3)}
HINGE_START = {"hinge_damping": 1e-6, "hinge_friction": 1e-6}  # the box's low end: ≈ none
STEPS = {**cube.LOG_STEPS, "offset": -0.001, "hinge_damping": 1.5, "hinge_friction": 1.5}


@dataclass
class ElbowPeer(Peer):
    """A peer of the elbow: `survey_dims`, the parameters its survey spreads (the
    others held at the start), and `after`, the peer whose fit it starts from."""

    survey_dims: tuple = ()
    after: str = ""
    hinge_off: list = field(default_factory=list)  # held-out scores, hinge terms set back


def peers(inertia_box=cube.INERTIA_BOX):
    """The peers in the table's order, each built on the one before it where `after`
    says so; the inertia scale boxed to `inertia_box`."""
    rows = []
    for simulator, label, start_kb, k_box in (
            ("mujoco", "MuJoCo (elliptic cone)", MUJOCO_START, (1e2, 2e5)),
            ("pybullet", "PyBullet", BULLET_START, (1e2, 1e5))):
        start = {**start_kb, "mu": MU_START, "offset": 0.0, "inertia_scale": 1.0}
        bounds = {"k": k_box, **CONTACT_BOX, "inertia_scale": tuple(inertia_box)}
        plain = f"{label} fitted (k, b, μ, table offset, inertia scale)"
        rows.append(ElbowPeer(
            plain, simulator, "elliptic" if simulator == "mujoco" else "fitted", start,
            bounds, ("k", "b", "mu", "inertia_scale"), STEPS,
            "starts from Acosta et al.'s cube k and b for this simulator, the URDF's μ 0.3, "
            "the table at z = 0 and the uniform-box inertia × 1; a free hinge",
            survey_dims=tuple(bounds)))
        hinge = ("damping, frictionloss" if simulator == "mujoco"
                 else "jointDamping, velocity motor")
        rows.append(ElbowPeer(
            f"{label} fitted (the same + hinge {hinge})", simulator,
            "elliptic" if simulator == "mujoco" else "fitted",
            {**start, **HINGE_START}, {**bounds, **HINGE_BOX},
            ("k", "b", "mu", "inertia_scale", "hinge_damping", "hinge_friction"), STEPS,
            "starts from the row above's fit with the hinge's damping and friction at "
            "the low end of their boxes (1e-6: none to speak of); its survey spreads "
            "the two hinge terms over their boxes, then Nelder–Mead moves all seven",
            survey_dims=tuple(HINGE_BOX), after=plain))
    return rows


# ------------------------------------------------------- parallel scoring

_shared = {"urdf": URDF}  # the tosses and the URDF, handed to the workers when they fork


def score_chunk(job):
    """Worker: hcm's scores of the tosses `indices` under `peer` with `params`."""
    peer, params, indices, substeps = job
    tosses = [_shared["tosses"][i] for i in indices]
    return [FAILED if failed(*r) else toss_errors(t, *r)
            for t, r in zip(tosses, replay(peer, params, tosses, substeps))]


class Scorer(cube.Scorer):
    """The cube's pool of workers (each toss from a fresh world: the scores, in toss
    order, do not depend on the worker count), scoring the elbow's tosses."""

    chunk = staticmethod(score_chunk)

    def __init__(self, tosses, workers, urdf):
        _shared["urdf"] = urdf
        super().__init__(tosses, workers)

    @staticmethod
    def share(tosses):
        _shared["tosses"] = tosses


# -------------------------------------------------------------- fitting


def survey_points(peer, count):
    """The start and `count` scrambled-Sobol points (seed 0) spreading the peer's
    `survey_dims` over their box, its other parameters held at the start. With every
    parameter spread these are peers.py's points."""
    x0 = to_search(peer, peer.start)
    box = np.array(search_box(peer))
    dims = [i for i, n in enumerate(peer.start) if n in peer.survey_dims]
    unit = qmc.Sobol(len(dims), scramble=True, seed=0).random(count) if count else []
    points = [x0]
    for u in unit:
        x = x0.copy()
        x[dims] = box[dims, 0] + u * (box[dims, 1] - box[dims, 0])
        points.append(x)
    return points


def fit(peer, scorer, training, survey, evaluations):
    """peers.py's fit (a survey, then Nelder–Mead from its best point: deterministic,
    on the training tosses), with the survey over `survey_dims`."""

    def objective(x):
        params = from_search(peer, x)
        scores = scorer.scores(peer, params, training)
        value = fitness([s[:2] for s in scores])
        peer.history.append({**params, "fitness": value,
                             "failed": sum(s == FAILED for s in scores)})
        return value

    surveyed = [(objective(x), i, x) for i, x in enumerate(survey_points(peer, survey))]
    x0 = min(surveyed, key=lambda s: s[:2])[2]
    simplex = [x0] + [x0 + peer.steps[n] * np.eye(len(x0))[i] for i, n in enumerate(peer.start)]
    result = minimize(objective, x0, method="Nelder-Mead", bounds=search_box(peer),
                      options={"initial_simplex": np.array(simplex), "maxfev": evaluations,
                               "xatol": 1e-3, "fatol": 1e-3})
    peer.fitted = from_search(peer, result.x)
    return result


def fit_and_score(peer, scorer, training, held_out, args):
    """Fits the peer, scores it held out, and again with half the timestep."""
    fit(peer, scorer, training, args.survey, args.evaluations)
    scores = scorer.scores(peer, peer.fitted, held_out)
    finer = scorer.scores(peer, peer.fitted, held_out, 2 * SUBSTEPS)
    peer.step_check = {"held_out_fitness": fitness([s[:2] for s in scores]),
                       "held_out_fitness_half_step": fitness([s[:2] for s in finer]),
                       "training_fitness": min(h["fitness"] for h in peer.history),
                       "failed_held_out": sum(s == FAILED for s in scores)}
    if peer.after:
        # The hinge terms' own share: the same fit with them set back to (almost) none.
        peer.hinge_off = scorer.scores(peer, {**peer.fitted, **HINGE_START}, held_out)
        peer.step_check["held_out_fitness_hinge_terms_off"] = fitness(
            [s[:2] for s in peer.hinge_off])
    return scores


# -------------------------------------------------------------- checks


def metric_check(tosses, predicted_csv, scores):
    """Rescore hcm's own predictions (both links) with this file's metric against
    hcm's scores: each link's row and the toss's `all` row. The largest absolute and
    relative differences."""
    tracks = read_tracks(predicted_csv)
    worst, relative = 0.0, 0.0
    for t in tosses:
        predicted = [tracks[t.run][link] for link in LINKS]
        assert all(np.allclose(p[0], t.times, atol=1e-9) for p in predicted), t.run
        errors = toss_errors(t, np.array([p[1] for p in predicted]),
                             np.array([p[2] for p in predicted]))
        rows = scores[t.run]
        pairs = [(errors[0], rows["all"]["position_error"]),
                 (errors[1], rows["all"]["rotation_error"])]
        for i, link in enumerate(LINKS):
            pairs += [(errors[2 + i][0], rows[link]["position_error"]),
                      (errors[2 + i][1], rows[link]["rotation_error"])]
        for mine, hcm in pairs:
            worst = max(worst, abs(mine - hcm))
            relative = max(relative, abs(mine - hcm) / abs(hcm))
    return {"max_abs": worst, "max_relative": relative, "tosses": len(tosses)}


def quaternion_angle(a, b):
    return math.degrees(float(rotation_angles(np.array([a]), np.array([b]))[0]))


def initial_state_check(tosses, urdf):
    """hcm's elbow_2 start against the one the hinge's θ and dθ/dt give: by this
    file's forward kinematics, and as MuJoCo and PyBullet place it (their own
    kinematics, after setting the base and the hinge). The largest gaps in position
    (m), orientation (°), velocity (m/s) and angular velocity (rad/s); also elbow_1's
    as each simulator reads it back."""
    import mujoco

    model = mujoco_model(urdf, {"k": 1e3, "b": 20.0, "mu": 0.3})
    data = mujoco.MjData(model)
    ids = [model.body(n).id for n in LINKS]
    p, c = cube.bullet_client()
    gaps = {name: np.zeros(4) for name in ("forward kinematics", "MuJoCo", "PyBullet")}
    for t in tosses:
        placed = {"forward kinematics": [t.starts[0], child_state(t.p0, t.q0, t.v0, t.w0,
                                                                  t.angle, t.rate)]}
        mujoco_set(mujoco, model, data, t)
        mujoco.mj_forward(model, data)
        placed["MuJoCo"] = []
        for b in ids:
            velocity = np.zeros(6)
            mujoco.mj_objectVelocity(model, data, mujoco.mjtObj.mjOBJ_BODY, b, velocity, 0)
            placed["MuJoCo"].append((data.xipos[b].copy(), data.xquat[b].copy(),
                                     velocity[3:], velocity[:3]))
        elbow = bullet_set(p, c, urdf, {"k": 1e3, "b": 20.0, "mu": 0.3}, t, SUBSTEPS)
        (base_p, base_q), (base_v, base_w) = (
            p.getBasePositionAndOrientation(elbow, physicsClientId=c),
            p.getBaseVelocity(elbow, physicsClientId=c))
        link = p.getLinkState(elbow, 0, computeLinkVelocity=1, computeForwardKinematics=1,
                              physicsClientId=c)
        wxyz = lambda q: np.array([q[3], q[0], q[1], q[2]])
        placed["PyBullet"] = [
            (np.array(base_p), wxyz(base_q), np.array(base_v), np.array(base_w)),
            (np.array(link[0]), wxyz(link[1]), np.array(link[6]), np.array(link[7]))]
        for name, states in placed.items():
            for mine, hcm in zip(states, t.starts):
                gap = [np.linalg.norm(mine[0] - hcm[0]), quaternion_angle(mine[1], hcm[1]),
                       np.linalg.norm(mine[2] - hcm[2]), np.linalg.norm(mine[3] - hcm[3])]
                gaps[name] = np.maximum(gaps[name], gap)
    keys = ("position_m", "orientation_deg", "velocity_m_s", "angular_velocity_rad_s")
    angles = np.degrees([t.angle for t in tosses])
    return {"tosses": len(tosses),
            "hinge_angle_deg_range": [float(angles.min()), float(angles.max())],
            **{name: dict(zip(keys, map(float, g))) for name, g in gaps.items()}}


CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]) * HALF


def lowest_corner(position, quaternion):
    """The height (m) of a link's lowest corner at a pose."""
    return float(np.min(position[2] + (rotation_matrix(quaternion) @ CORNERS.T)[2]))


def free_flight_checks(tosses, hcm_predicted, urdf):
    """Each peer (its start parameters) with the table far below: the two links' centre
    of mass against the exact parabola from hcm's start less semi-implicit Euler's lag
    ½·g·dt·t, over each window, at the timestep and at half of it (the mechanism's
    centre also carries Euler's first-order error of the links' turning, which halves
    with the step); MuJoCo against PyBullet over the window (the same free mechanism);
    and, with the table in place, each peer's first window frames (up to 3) before a
    corner of either link comes below the table in hcm's prediction, against hcm's
    own prediction."""
    tracks = read_tracks(hcm_predicted)
    report, flights = {}, {}
    for peer in peers():
        if peer.after:
            continue
        lifted = {**peer.start, "offset": FAR_BELOW}
        near = replay(peer, peer.start, tosses)
        parabola = {}
        for substeps in (SUBSTEPS, 2 * SUBSTEPS):
            flown = replay(peer, lifted, tosses, substeps)
            if substeps == SUBSTEPS:
                flights[peer.simulator] = flown
            lag = 0.5 * GRAVITY * FRAME / substeps
            gaps = [0.0]
            for (positions, _), t in zip(flown, tosses):
                s = t.times - t.times[0]
                centre0 = sum(st[0] for st in t.starts) / 2  # equal masses
                velocity0 = sum(st[2] for st in t.starts) / 2
                drop = 0.5 * GRAVITY * s * s + lag * s
                exact = centre0 + np.outer(s, velocity0) - np.outer(drop, [0, 0, 1])
                gaps.append(float(np.max(np.linalg.norm(positions.mean(axis=0) - exact,
                                                        axis=1))))
            parabola[substeps] = max(gaps)
        first, compared = [(0.0, 0.0)], 0
        for (near_p, near_q), t in zip(near, tosses):
            hcm = [tracks[t.run][link] for link in LINKS]
            clear = 0
            while clear < 3 and all(lowest_corner(h[1][clear], h[2][clear]) > 0.0 for h in hcm):
                clear += 1
            compared += clear > 1
            for i, h in enumerate(hcm):
                first.append(cube.gap((near_p[i][:clear], near_q[i][:clear]),
                                      (h[1][:clear], h[2][:clear])) if clear else (0.0, 0.0))
        report[peer.name] = {
            "tosses": len(tosses),
            "free_flight_centre_less_euler_lag_gap_m": parabola[SUBSTEPS],
            "free_flight_centre_less_euler_lag_gap_m_half_step": parabola[2 * SUBSTEPS],
            "first_frames_vs_hcm_tosses": compared,
            "first_frames_vs_hcm_position_gap_m": max(g[0] for g in first),
            "first_frames_vs_hcm_rotation_gap_deg": max(g[1] for g in first)}
    between = [cube.gap((a[0][i], a[1][i]), (b[0][i], b[1][i]))
               for a, b in zip(flights["mujoco"], flights["pybullet"]) for i in range(2)]
    report["free flight, MuJoCo vs PyBullet"] = {
        "tosses": len(tosses), "position_gap_m": max(g[0] for g in between),
        "rotation_gap_deg": max(g[1] for g in between),
        "longest_window_s": float(max(t.times[-1] - t.times[0] for t in tosses))}
    return report


def hinge_friction_check(urdf, damping=1e-3, friction=1e-3):
    """elbow_1 held still, no gravity, the hinge turning at 1 rad/s: with the hinge's
    damping alone its rate after 0.1 s against exp(−c·t/I) (I = the link's inertia
    about the hinge: I_yy + m·0.035²); with its friction alone the rate after 0.1 s
    against 1 − τ·t/I and the time it stops against I/τ."""
    import mujoco

    inertia = INERTIA[1] + MASS * float(ANCHORS[1] @ ANCHORS[1])
    frames = 147  # 1.0 s
    report = {"inertia_about_hinge": inertia,
              "viscous_exact_at_0.1s": math.exp(-damping / inertia * 0.1),
              "coulomb_exact_at_0.1s": 1 - friction / inertia * 0.1,
              "coulomb_exact_stop_s": inertia / friction}
    for name, params in (("viscous", {"hinge_damping": damping}),
                         ("coulomb", {"hinge_friction": friction})):
        contact = {"k": 1e3, "b": 20.0, "mu": 0.3, "offset": FAR_BELOW, **params}
        # MuJoCo: elbow_1 left welded to the world, as the URDF has it; no gravity.
        spec = mujoco_spec(urdf, **contact, free=False)
        spec.option.gravity = [0, 0, 0]
        model = spec.compile()
        data = mujoco.MjData(model)
        data.qvel[0] = 1.0
        rates = []
        for _ in range(frames * SUBSTEPS):
            mujoco.mj_step(model, data)
            rates.append(float(data.qvel[0]))
        report[f"MuJoCo {name}"] = stopping(rates)
        p, c = cube.bullet_client()
        p.resetSimulation(physicsClientId=c)
        p.setGravity(0, 0, 0, physicsClientId=c)
        p.setTimeStep(TIMESTEP, physicsClientId=c)
        elbow = bullet_world(p, c, urdf, **contact, fixed=True)
        p.resetJointState(elbow, 0, 0.0, 1.0, physicsClientId=c)
        rates = []
        for _ in range(frames * SUBSTEPS):
            p.stepSimulation(physicsClientId=c)
            rates.append(p.getJointState(elbow, 0, physicsClientId=c)[1])
        report[f"PyBullet {name}"] = stopping(rates)
    return report


def stopping(rates):
    """The rate after 0.1 s and the first time it is below 1e-6 rad/s."""
    rates = np.asarray(rates)
    step = round(0.1 / TIMESTEP) - 1
    stopped = np.flatnonzero(np.abs(rates) < 1e-6)
    return {"rate_at_0.1s": float(rates[step]),
            "stops_s": float((stopped[0] + 1) * TIMESTEP) if len(stopped) else None}


# ------------------------------------------------------------- summaries


def mujoco_setup(urdf):
    """What MuJoCo compiled from the URDF: masses, inertias, centres, the hinge and a
    resting contact's friction and solref."""
    import mujoco

    params = {"k": 3294.0, "b": 45.1, "mu": 0.3, "hinge_damping": 1e-3, "hinge_friction": 2e-3}
    spec = mujoco_spec(urdf, **params)
    model = spec.compile()
    data = mujoco.MjData(model)
    data.qpos[:] = [0, 0, 0.025 - 1e-4, 1, 0, 0, 0, 0]
    mujoco.mj_forward(model, data)
    ids = [model.body(n).id for n in LINKS]
    contact = data.contact[0]
    return {"params": params, "xml": spec.to_xml(),
            "mass": [float(model.body_mass[b]) for b in ids],
            "inertia": [model.body_inertia[b].tolist() for b in ids],
            "centre_in_body": [model.body_ipos[b].tolist() for b in ids],
            "body_pos": [model.body_pos[b].tolist() for b in ids],
            "hinge_axis": model.jnt_axis[1].tolist(), "hinge_damping": model.dof_damping[6],
            "hinge_frictionloss": model.dof_frictionloss[6],
            "excluded_body_pairs": int(model.nexclude),
            "timestep": float(model.opt.timestep), "contacts_flat_on_table": int(data.ncon),
            "contact_friction": contact.friction[:2].tolist(),
            "contact_solref": contact.solref.tolist(), "contact_solimp": contact.solimp.tolist()}


def bullet_setup(urdf):
    """What PyBullet holds (getDynamicsInfo, getJointInfo) for the elbow and the table
    of a world with k = 1000, b = 20, μ = 0.3, hinge damping 1e-3, friction 2e-3."""
    p, c = cube.bullet_client()
    p.resetSimulation(physicsClientId=c)
    params = {"k": 1000.0, "b": 20.0, "mu": 0.3, "hinge_damping": 1e-3, "hinge_friction": 2e-3}
    elbow = bullet_world(p, c, urdf, **params)
    named = lambda i: {"mass": i[0], "lateral_friction": i[1], "inertia": list(i[2]),
                       "inertial_position": list(i[3]), "contact_damping": i[8],
                       "contact_stiffness": i[9]}
    joint = p.getJointInfo(elbow, 0, physicsClientId=c)
    return {"params": params,
            "elbow_1": named(p.getDynamicsInfo(elbow, -1, physicsClientId=c)),
            "elbow_2": named(p.getDynamicsInfo(elbow, 0, physicsClientId=c)),
            "table": named(p.getDynamicsInfo(0, -1, physicsClientId=c)),
            # getJointInfo's damping is the URDF's: changeDynamics's jointDamping is not
            # reported back (hinge_friction_check measures it).
            "hinge": {"type": joint[2], "urdf_damping": joint[6], "axis": list(joint[13]),
                      "parent_frame_position": list(joint[14])}}


def hcm_physics_summary(path):
    import tomllib

    if not path or not os.path.exists(path):
        return {}
    with open(path, "rb") as f:
        physics = tomllib.load(f)
    contact = physics["contact"][0]
    return {"law": contact["law"], "parameters": contact["parameters"],
            "friction": contact.get("friction", {}), "sets": physics.get("sets", [])}


def table_rows(held_out, fitted_hcm, scenario, fitted_peers, rows):
    """(model, per-toss (position, rotation, link 1, link 2)) in the table's order."""
    def hcm(scores, prefix=""):
        return [tuple([scores[t.run]["all"][prefix + "position_error"],
                       scores[t.run]["all"][prefix + "rotation_error"]]
                      + [(scores[t.run][link][prefix + "position_error"],
                          scores[t.run][link][prefix + "rotation_error"]) for link in LINKS])
                for t in held_out]
    table = [("hcm fitted", hcm(fitted_hcm)), ("hcm, scenario not fitted", hcm(scenario))]
    return (table + [(p.name, rows[p.name]) for p in fitted_peers]
            + [("frozen pose", hcm(scenario, "frozen_"))])


def hinge_gains(table, fitted_peers):
    """Each peer with the hinge's friction against the same simulator without it, paired
    per held-out toss: (row with it, row without it, paired Δ(position + rotation)
    against that row, and against its own fit with the hinge terms set back to 1e-6)."""
    scores = {name: [s[:2] for s in rows] for name, rows in table}
    return [(p.name, p.after, paired(scores[p.name], scores[p.after]),
             paired(scores[p.name], [s[:2] for s in p.hinge_off]))
            for p in fitted_peers if p.after]


def markdown(table, held_out, gains, context):
    """peers.md: the table, each link's means, and what they rest on."""
    reference = [s[:2] for s in table[0][1]]
    lines = [
        f"# hcm beside MuJoCo and PyBullet: the elbow tosses ({len(held_out)} held out)",
        "",
        "| model | position error (% of 0.1 m, mean of the links): mean ± std | median | "
        "rotation error (°, mean of the links): mean ± std | median | paired vs hcm "
        "fitted: Δ(position + rotation) ± 95 % |",
        "|---|---|---|---|---|---|",
    ]
    lines += [table_row(name, [s[:2] for s in scores], reference) for name, scores in table]
    lines += ["", "The hinge's friction, paired per held-out toss: Δ(position + rotation) of "
              "the row with it minus the row without it, ± 95 % (negative: it helps); then "
              "minus its own fit with the two hinge terms set back to 1e-6 (the hinge terms "
              "alone, the contact fit kept):", ""]
    lines += [f"- {name}: {d['mean']:+.2f} ± {d['half_width_95']:.2f}; the hinge terms alone "
              f"{off['mean']:+.2f} ± {off['half_width_95']:.2f}" for name, _, d, off in gains]
    lines += ["", "Each link's own means on the held-out tosses (position % of 0.1 m, "
              "rotation °):", "",
              "| model | elbow_1 position | elbow_1 rotation | elbow_2 position | "
              "elbow_2 rotation |", "|---|---|---|---|---|"]
    for name, scores in table:
        means = [np.mean([s[2 + i][j] for s in scores]) for i in range(2) for j in range(2)]
        lines.append(f"| {name} | " + " | ".join(f"{m:.2f}" for m in means) + " |")
    return "\n".join(lines + [""] + context) + "\n"


def context_lines(args, split, fitted_peers, timings, checks):
    metric, start, flights, hinge = checks
    training_all, fit_tosses, held_out = split
    lines = [
        f"Held out: the {len(held_out)} odd-numbered tosses"
        f"{f' of the first {args.first} runs' if args.first else ''}. Fitted on every "
        f"{args.fit_stride}th even-numbered toss in data order ({len(fit_tosses)} of "
        f"{len(training_all)}: the tosses hcm's elbow fit sees), with hcm's objective "
        "(mean position error % + mean rotation error °, each the mean of the two links'). "
        "Every model starts from hcm's window-start state (the per-link rows of `hcm "
        "predict --scores`, assembled onto the hinge by hcm) and is sampled at the "
        "recorded frames. Paired: per held-out toss, (position + rotation error) of the "
        "model minus hcm fitted's; mean ± 1.96·sd/√n (negative: better than hcm fitted).",
        "",
        f"Both peers read `{os.path.relpath(args.urdf, ROOT)}` with their own URDF reader "
        "(MuJoCo's MjSpec, PyBullet's loadURDF): elbow_1 a free base, elbow_2 on the "
        "revolute hinge; each link's inertia set to the uniform box's "
        f"{INERTIA.tolist()} kg·m² (× the inertia scale), replacing the URDF's 6.167e-4; "
        f"links not colliding with each other; timestep {TIMESTEP * 1e3:.2f} ms ({SUBSTEPS} "
        "steps a 6.8 ms frame). MuJoCo: elliptic cone, Euler, Newton, dense Jacobian, "
        "default solimp, the hinge's damping and frictionloss (default solreffriction); "
        "PyBullet: DIRECT, default solver, no velocity damping, the hinge's jointDamping "
        "and a velocity motor (target 0, max force = the friction torque; 0 without it). "
        f"Each fit: the start and {args.survey} scrambled-Sobol points (seed 0), then "
        f"Nelder–Mead (scipy) from the best, at most {args.evaluations} evaluations; in log "
        "k, b, μ, inertia scale and hinge terms, the offset in m; the inertia scale boxed "
        f"to {args.inertia_box[0]:g}–{args.inertia_box[1]:g}.",
        "",
    ]
    hcm = hcm_physics_summary(args.hcm_physics)
    if hcm:
        law = ", ".join(f"{k} = {v:.4g}" for k, v in hcm["parameters"].items())
        friction = ", ".join(f"{k} = {v:.4g}" for k, v in hcm["friction"].items())
        lines.append(f"- hcm fitted ({os.path.relpath(args.hcm_physics, ROOT)}): "
                     f"{hcm['law']} {law}; {friction}; {'; '.join(hcm['sets'])}.")
    for peer in fitted_peers:
        shown = ", ".join(f"{k} = {v:.4g}" for k, v in peer.fitted.items())
        lines.append(f"- {peer.name}: {shown} ({len(peer.history)} evaluations, "
                     f"{timings[peer.name]:.0f} s; training fitness "
                     f"{peer.history[0]['fitness']:.2f} at the start → "
                     f"{peer.step_check['training_fitness']:.2f}; held-out fitness "
                     f"{peer.step_check['held_out_fitness']:.2f}, with half the timestep "
                     f"{peer.step_check['held_out_fitness_half_step']:.2f}). {peer.note}.")
    lines += [
        "",
        f"Checks. Metric: this script's metric rescoring hcm's own predictions "
        f"(`--scenario-predicted`, both links, {metric['tosses']} tosses) differs from "
        f"hcm's scores (each link's rows and the `all` rows) by at most "
        f"{metric['max_abs']:.1e} ({metric['max_relative']:.1e} relative).",
        f"Initial state ({start['tosses']} tosses, hinge angles "
        f"{start['hinge_angle_deg_range'][0]:.1f}° to {start['hinge_angle_deg_range'][1]:.1f}°): "
        "elbow_2's start as the hinge's θ and dθ/dt place it against hcm's elbow_2 row "
        "(position m, orientation °, velocity m/s, angular velocity rad/s, largest gaps; "
        "elbow_1's included as each simulator reads it back):",
    ]
    for name in ("forward kinematics", "MuJoCo", "PyBullet"):
        g = start[name]
        lines.append(f"- {name}: {g['position_m']:.1e} m, {g['orientation_deg']:.1e}°, "
                     f"{g['velocity_m_s']:.1e} m/s, {g['angular_velocity_rad_s']:.1e} rad/s")
    lines += ["", "Free flight (table at z = −100 m, start parameters): the two links' centre "
              "of mass against the exact parabola less Euler's lag ½·g·dt·t, at the timestep "
              "and at half of it (Euler's first-order error of the links' turning); the "
              "first window frames (up to 3) before a corner of either link is below the "
              "table in hcm's prediction, table in place, against hcm's prediction:"]
    for name, c in flights.items():
        if "position_gap_m" in c:
            lines.append(f"- {name}: {c['position_gap_m']:.1e} m, {c['rotation_gap_deg']:.1e}° "
                         f"over windows of up to {c['longest_window_s']:.2f} s "
                         f"({c['tosses']} tosses)")
        else:
            centre = c["free_flight_centre_less_euler_lag_gap_m"]
            finer = c["free_flight_centre_less_euler_lag_gap_m_half_step"]
            lines.append(f"- {name}: centre {centre:.1e} m, with half the step {finer:.1e} m "
                         f"({c['tosses']} tosses); first frames vs hcm "
                         f"{c['first_frames_vs_hcm_position_gap_m']:.1e} m, "
                         f"{c['first_frames_vs_hcm_rotation_gap_deg']:.1e}° "
                         f"({c['first_frames_vs_hcm_tosses']} tosses with 2 or 3 such frames)")
    lines += ["", f"Hinge friction (elbow_1 held, no gravity, the hinge at 1 rad/s, I = "
              f"{hinge['inertia_about_hinge']:.4e} kg·m² about it): damping 1e-3 N·m·s/rad "
              f"leaves {hinge['viscous_exact_at_0.1s']:.4f} rad/s after 0.1 s exactly; "
              f"friction 1e-3 N·m {hinge['coulomb_exact_at_0.1s']:.4f} rad/s, stopping at "
              f"{hinge['coulomb_exact_stop_s']:.3f} s:"]
    for name in ("MuJoCo viscous", "PyBullet viscous", "MuJoCo coulomb", "PyBullet coulomb"):
        h = hinge[name]
        stop = f", stops at {h['stops_s']:.3f} s" if h["stops_s"] is not None else ""
        lines.append(f"- {name}: {h['rate_at_0.1s']:.4f} rad/s after 0.1 s{stop}")
    return lines


# ------------------------------------------------------------------ main


def arguments(argv=None):
    a = argparse.ArgumentParser(description=__doc__)
    a.add_argument("--data", required=True, help="the elbow's tosses CSV (hcm's format)")
    a.add_argument("--scenario-scores", required=True,
                   help="`hcm predict --scores` of the shipped scenario: windows, initial states")
    a.add_argument("--scenario-predicted", required=True,
                   help="`hcm predict --out` of the shipped scenario (for the checks)")
    a.add_argument("--fitted-scores", required=True,
                   help="`hcm predict --scores` with hcm's fitted physics")
    a.add_argument("--hcm-physics",
                   help="hcm's fitted physics file, shown in peers.md (run.sh --elbow: "
                   "docs/results/elbow-toss/physics.toml)")
    a.add_argument("--out", required=True, help="output folder (peers.md, peers.json)")
    a.add_argument("--first", type=int, help="use only the first N runs (as hcm --first)")
    a.add_argument("--fit-stride", type=int, default=4,
                   help="fit on every Nth training toss in data order (hcm's elbow fit: 4)")
    a.add_argument("--urdf", default=URDF, help="the elbow's URDF")
    a.add_argument("--survey", type=int, default=32,
                   help="quasi-random points of each peer's box tried before Nelder–Mead")
    a.add_argument("--evaluations", type=int, default=120,
                   help="objective evaluations of each Nelder–Mead polish")
    a.add_argument("--inertia-box", type=float, nargs=2, default=list(cube.INERTIA_BOX),
                   metavar=("LOW", "HIGH"), help="the inertia scale's box (the cube peers': "
                   "0.5 2.5)")
    a.add_argument("--workers", type=int, default=os.cpu_count())
    a.add_argument("--check-tosses", type=int, default=40,
                   help="held-out tosses the free-flight check uses")
    args = a.parse_args(argv)
    args.urdf = os.path.abspath(args.urdf)
    return args


def same_start(a, b):
    keys = ("window_start", "p0x", "p0y", "p0z", "q0w", "q0x", "q0y", "q0z",
            "v0x", "v0y", "v0z", "w0x", "w0y", "w0z")
    return all(abs(a[k] - b[k]) < 1e-12 for k in keys)


def split_tosses(args):
    """hcm's tosses (windows and starts from the scenario's scores), split even/odd,
    the training part strided as hcm's elbow fit strides it."""
    scenario = read_scores(args.scenario_scores)
    fitted_hcm = read_scores(args.fitted_scores)
    tosses = load_tosses(args.data, scenario, args.first)
    assert all(same_start(scenario[t.run][link], fitted_hcm[t.run][link])
               for t in tosses for link in LINKS), "hcm's fitted run started from other states"
    training = [t for t in tosses if t.training]
    held_out = [t for t in tosses if not t.training]
    fit_tosses = training[::args.fit_stride]
    print(f"{len(training)} training tosses ({len(fit_tosses)} fitted on: every "
          f"{args.fit_stride}th), {len(held_out)} held out", flush=True)
    return scenario, fitted_hcm, tosses, (training, fit_tosses, held_out)


def run_checks(args, tosses, held_out, scenario):
    metric = metric_check(tosses, args.scenario_predicted, scenario)
    print(f"metric check: {metric}", flush=True)
    assert metric["max_relative"] < 1e-9, "the metric does not reproduce hcm's"
    start = initial_state_check(tosses, args.urdf)
    print(f"initial-state check: {start}", flush=True)
    assert start["forward kinematics"]["position_m"] < 1e-6, "the hinge angle misplaces elbow_2"
    flights = free_flight_checks(held_out[:args.check_tosses], args.scenario_predicted,
                                 args.urdf)
    for name, c in flights.items():
        print(f"free-flight check, {name}: {c}", flush=True)
    hinge = hinge_friction_check(args.urdf)
    print(f"hinge friction check: {hinge}", flush=True)
    return metric, start, flights, hinge


def per_toss(held_out, scores):
    return {t.run: {"position_error": s[0], "rotation_error": s[1],
                    **{f"{link}_{k}": s[2 + i][j] for i, link in enumerate(LINKS)
                       for j, k in enumerate(("position_error", "rotation_error"))}}
            for t, s in zip(held_out, scores)}


def json_report(args, split, table, fitted_peers, checks, timings):
    training, fit_tosses, held_out = split
    metric, start, flights, hinge = checks
    reference = [s[:2] for s in table[0][1]]
    return {
        "held_out": [t.run for t in held_out], "fitted_on": [t.run for t in fit_tosses],
        "training": [t.run for t in training], "fit_stride": args.fit_stride,
        "scores": {name: per_toss(held_out, scores) for name, scores in table},
        "summaries": {name: {"position_error": summary([s[0] for s in scores]),
                             "rotation_error": summary([s[1] for s in scores]),
                             "paired_vs_hcm_fitted": paired([s[:2] for s in scores], reference),
                             **{f"{link}_{k}_mean": float(np.mean([s[2 + i][j] for s in scores]))
                                for i, link in enumerate(LINKS)
                                for j, k in enumerate(("position_error", "rotation_error"))}}
                      for name, scores in table},
        "peers": {p.name: {"simulator": p.simulator, "start": p.start, "bounds": p.bounds,
                           "survey_dims": list(p.survey_dims), "starts_from": p.after,
                           "fitted": p.fitted, "note": p.note, "step_check": p.step_check,
                           "history": p.history,
                           **({"held_out_hinge_terms_off": per_toss(held_out, p.hinge_off)}
                              if p.after else {})} for p in fitted_peers},
        "timestep_s": TIMESTEP, "substeps_per_frame": SUBSTEPS, "frame_s": FRAME,
        "width_m": WIDTH, "inertia": INERTIA.tolist(), "urdf": os.path.relpath(args.urdf, ROOT),
        "survey_points": args.survey, "max_evaluations": args.evaluations,
        "inertia_box": list(args.inertia_box), "workers": args.workers, "first": args.first,
        "metric_check": metric, "initial_state_check": start, "free_flight_checks": flights,
        "hinge_friction_check": hinge, "hcm_physics": hcm_physics_summary(args.hcm_physics),
        "setups": {"mujoco": mujoco_setup(args.urdf), "pybullet": bullet_setup(args.urdf)},
        "versions": versions(), "timings_s": timings,
    }


def main(argv=None):
    args = arguments(argv)
    clock = time.perf_counter()
    read_urdf(args.urdf)
    scenario, fitted_hcm, tosses, split = split_tosses(args)
    training, fit_tosses, held_out = split
    scorer = Scorer(tosses, args.workers, args.urdf)  # forks before PyBullet is opened here
    started = time.perf_counter()
    checks = run_checks(args, tosses, held_out, scenario)
    timings = {"checks": time.perf_counter() - started}

    fitted_peers, rows = peers(args.inertia_box), {}
    for peer in fitted_peers:
        start = time.perf_counter()
        if peer.after:
            before = next(p for p in fitted_peers if p.name == peer.after)
            peer.start = {**before.fitted, **HINGE_START}
        rows[peer.name] = fit_and_score(peer, scorer, fit_tosses, held_out, args)
        timings[peer.name] = time.perf_counter() - start
        print(f"{peer.name}: {peer.fitted} in {timings[peer.name]:.0f} s, "
              f"{peer.step_check}", flush=True)
    scorer.close()
    table = table_rows(held_out, fitted_hcm, scenario, fitted_peers, rows)
    timings["elbow.py total"] = time.perf_counter() - clock

    os.makedirs(args.out, exist_ok=True)
    gains = hinge_gains(table, fitted_peers)
    text = markdown(table, held_out, gains,
                    context_lines(args, split, fitted_peers, timings, checks))
    with open(os.path.join(args.out, "peers.md"), "w") as f:
        f.write(text)
    with open(os.path.join(args.out, "peers.json"), "w") as f:
        report = json_report(args, split, table, fitted_peers, checks, timings)
        report["hinge_friction_gain_paired"] = {
            name: {"without": without, **d, "hinge_terms_alone": off}
            for name, without, d, off in gains}
        json.dump(report, f, indent=1, default=float)
    print(text)


if __name__ == "__main__":
    sys.exit(main())
