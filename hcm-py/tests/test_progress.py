"""Long work from Python: progress to a callback, Python's lock released, Ctrl-C and a
failing callback stop it."""

import os
import signal
import threading
import time

import pytest

import hcm


@pytest.fixture(scope="module")
def ball(root):
    return hcm.Scenario.load(root / "scenarios" / "bouncing_ball.toml")


def test_progress_reaches_the_callback(ball):
    seen = []
    hcm.generate(ball, runs=12, seed=1, progress=lambda stage, done, total: seen.append((stage, done, total)))
    stages = {stage for stage, _, _ in seen}
    assert stages == {"1/5 generate"}
    assert seen[-1][1] == seen[-1][2] == 12
    assert all(0 <= d <= t for _, d, t in seen)


def test_an_exception_in_the_callback_stops_the_work(ball):
    calls = []

    def progress(stage, done, total):
        calls.append(done)
        if done >= 3:
            raise RuntimeError("enough")

    with pytest.raises(RuntimeError, match="enough"):
        hcm.generate(ball, runs=400, seed=1, progress=progress)
    assert max(calls) < 400


def test_ctrl_c_stops_the_work(ball):
    # Python's own Ctrl-C handler, installed even where the test runner was started
    # with SIGINT ignored (a background job of a non-interactive shell, as in .ci/run).
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    done = []
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            hcm.generate(ball, runs=5000, seed=1, progress=lambda s, d, t: done.append(d))
    finally:
        timer.join()
        signal.signal(signal.SIGINT, previous)
    assert done and max(done) < 5000


def test_the_lock_is_released_while_it_works(ball):
    ticks = []
    stop = threading.Event()

    def count():
        while not stop.is_set():
            ticks.append(1)
            time.sleep(0.001)

    counter = threading.Thread(target=count)
    counter.start()
    before = len(ticks)
    hcm.generate(ball, runs=60, seed=1)
    during = len(ticks) - before
    stop.set()
    counter.join()
    assert during > 5
