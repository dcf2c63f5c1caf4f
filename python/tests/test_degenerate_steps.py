"""Degenerate steps from Python: the collision budget's error, Ctrl-C during a long detect, and the memory of the
arrays of a large answer (the process's own counters, Linux /proc)."""

import os
import signal
import threading

import numpy as np
import pytest

import clothcd


def collapsing_grid(n):
    """A flat n x n grid and its end positions: every vertex at the centroid."""
    vertices, faces = clothcd.make_grid(n, n)
    return faces, vertices, np.repeat(vertices.mean(axis=0, keepdims=True), len(vertices), axis=0)


def status_bytes(field):
    with open("/proc/self/status") as status:
        for line in status:
            if line.startswith(field + ":"):
                return int(line.split()[1]) * 1024
    raise LookupError(field)


def test_budget_raises_a_runtime_error_and_the_detector_recovers():
    faces, x0, point = collapsing_grid(20)
    detector = clothcd.CollisionDetector(faces, len(x0), max_collisions=1000)
    with pytest.raises(clothcd.CollisionBudgetExceeded, match="max_collisions = 1000"):
        detector.detect(x0, point)
    assert issubclass(clothcd.CollisionBudgetExceeded, RuntimeError)
    lowered = x0 - [0.0, 0.01, 0.0]
    assert len(detector.detect(x0, lowered).kind) == 0
    with pytest.raises(ValueError):
        clothcd.CollisionDetector(faces, len(x0), max_collisions=0)


def test_ctrl_c_interrupts_a_long_detect():
    faces, x0, point = collapsing_grid(40)  # 15.6 million collisions: many seconds without the interrupt
    # Were Ctrl-C not honoured, the budget would end the call (CollisionBudgetExceeded, not KeyboardInterrupt).
    detector = clothcd.CollisionDetector(faces, len(x0), max_collisions=3_000_000)
    timer = threading.Timer(0.3, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            detector.detect(x0, point)
    finally:
        timer.cancel()
    lowered = x0 - [0.0, 0.01, 0.0]
    assert len(detector.detect(x0, lowered).kind) == 0


def test_a_large_answer_takes_at_most_200_bytes_per_collision():
    faces, x0, point = collapsing_grid(20)
    detector = clothcd.CollisionDetector(faces, len(x0))
    with open("/proc/self/clear_refs", "w") as clear_refs:
        clear_refs.write("5")
    before = status_bytes("VmRSS")
    found = detector.detect(x0, point)
    peak = status_bytes("VmHWM") - before
    count = len(found.kind)
    assert count > 500_000
    assert peak <= 200 * count + (32 << 20)
