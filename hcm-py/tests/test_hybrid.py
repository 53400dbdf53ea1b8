"""The hybrid model over many states in one call, through the core's f32 code."""

import os
import re
import subprocess
from pathlib import Path

import numpy as np
import pytest

import hcm

BLOBS = Path(__file__).resolve().parents[2] / "examples" / "blobs"


@pytest.fixture(scope="module")
def ball(root):
    scenario = hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml")
    return scenario.with_physics(BLOBS / "bouncing_ball.pm2.toml")


@pytest.fixture(scope="module", params=["f32", "int8"])
def model(request, ball):
    return hcm.HybridModel(ball, BLOBS / f"bouncing_ball.{request.param}.hcm")


def states(n=2000, seed=3):
    rng = np.random.default_rng(seed)
    depth = rng.uniform(-5e-6, 70e-6, n).astype(np.float32)
    rate = rng.uniform(-1.6, 1.6, n).astype(np.float32)
    approach = np.full(n, 1.4, dtype=np.float32)
    return depth, rate, approach


def test_one_call_is_the_loop_of_single_states(model):
    depth, rate, approach = states(300)
    batch = model.force(depth, rate, approach)
    for i in range(len(depth)):
        one = model.force(depth[i], rate[i], approach[i])
        assert one.force.tobytes() == batch.force[i].tobytes()
        assert bool(one.residual_used) == bool(batch.residual_used[i])


def test_the_physics_is_the_law_in_f32(model):
    depth, rate, approach = states()
    batch = model.force(depth, rate, approach)
    law = hcm.Law("lankarani_nikravesh", **dict(
        stiffness=6909559489.48986, exponent=1.4894618532836206, restitution=0.9289993736609472))
    physics = law.force(depth, rate, approach, dtype=np.float32).astype(np.float32)
    assert batch.physics.tobytes() == physics.tobytes()
    # Out of contact nothing; in contact and inside its envelope the residual corrects.
    out = depth <= 0
    assert np.all(batch.force[out] == 0) and not batch.residual_used[out].any()
    inside = batch.residual_used
    assert 0 < inside.sum() < len(depth)
    assert np.all(batch.force[~inside] == batch.physics[~inside])
    assert np.any(batch.force[inside] != batch.physics[inside])


def test_far_outside_the_envelope_the_residual_is_off(model):
    result = model.force([10e-6, 10e-6], [0.5, 0.5], [1.4, 40.0])
    assert not result.residual_used[1]
    assert result.force[1] == result.physics[1]


def test_nan_and_inf_in_no_exception_out(model):
    result = model.force([np.nan, np.inf, 1e-5], [0.0, 0.0, np.nan], [1.4, 1.4, 1.4])
    assert np.isnan(result.force[0]) and not result.residual_used.any()


def test_int8_and_f32_weights_agree_where_both_apply(ball):
    f32 = hcm.HybridModel(ball, BLOBS / "bouncing_ball.f32.hcm")
    int8 = hcm.HybridModel(ball, BLOBS / "bouncing_ball.int8.hcm")
    assert int8.int8 and not f32.int8
    depth, rate, approach = states()
    a, b = f32.force(depth, rate, approach), int8.force(depth, rate, approach)
    both = a.residual_used & b.residual_used
    correction = np.abs(a.force - a.physics)[both]
    assert np.max(np.abs(a.force - b.force)[both]) < 0.1 * np.max(correction)


def test_a_wrong_blob_is_refused(ball):
    with pytest.raises(hcm.HcmError, match="3-16-16-1"):
        hcm.HybridModel(ball, BLOBS / "peg_in_hole.f32.hcm")
    damaged = bytearray((BLOBS / "bouncing_ball.f32.hcm").read_bytes())
    damaged[len(damaged) // 2] ^= 0x10
    with pytest.raises(hcm.HcmError):
        hcm.HybridModel(ball, bytes(damaged))
    with pytest.raises(hcm.HcmError, match="1 contact"):
        hcm.HybridModel(ball, BLOBS / "bouncing_ball.f32.hcm", contact=3)


def static_library():
    """hcm-ffi's static library as the Rust build left it (`cargo test` builds it)."""
    target = Path(os.environ.get("CARGO_TARGET_DIR", BLOBS.parents[1] / "target"))
    for candidate in (target / "debug" / "deps" / "libhcm_ffi.a", target / "release" / "libhcm_ffi.a"):
        if candidate.exists():
            return candidate
    return None


@pytest.mark.skipif(static_library() is None, reason="hcm-ffi's static library is not built (cargo test builds it)")
def test_bit_for_bit_the_c_api_s(ball, tmp_path):
    """examples/c/ball_hcm.c, compiled against hcm-ffi, prints each state and the
    hybrid force as raw bits; the batch evaluation gives the same bits."""
    program = tmp_path / "ball_hcm"
    c = BLOBS.parents[0] / "c" / "ball_hcm.c"
    include = BLOBS.parents[1] / "hcm-ffi" / "include"
    subprocess.run(
        ["cc", "-std=c11", "-O2", f"-I{include}", "-o", str(program), str(c), str(static_library()),
         "-lpthread", "-ldl", "-lm"],
        check=True,
    )
    out = subprocess.run([str(program), str(BLOBS)], capture_output=True, text=True, check=True).stdout
    pattern = re.compile(
        r"hybrid weights=(\w+) depth=0x(\w+) rate=0x(\w+) approach_speed=0x(\w+) max_depth=0x\w+"
        r" force=0x(\w+) physics=0x(\w+) residual_used=(\d)"
    )
    bits = lambda h: np.array([int(h, 16)], dtype=np.uint32).view(np.float32)[0]
    models = {w: hcm.HybridModel(ball, BLOBS / f"bouncing_ball.{w}.hcm") for w in ("f32", "int8")}
    lines = pattern.findall(out)
    assert len(lines) >= 6
    for weights, d, r, a, force, physics, used in lines:
        result = models[weights].force(bits(d), bits(r), bits(a))
        assert result.force.tobytes() == np.float32(bits(force)).tobytes()
        assert result.physics.tobytes() == np.float32(bits(physics)).tobytes()
        assert bool(result.residual_used) == (used == "1")
