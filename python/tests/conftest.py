import os
import pathlib
import threading
import time

import numpy as np
import pytest

# The source tree: ctest sets ERKN_SOURCE_DIR; run by hand (pytest python/tests) it is the
# checkout this file lies in.
SOURCE_DIR = pathlib.Path(os.environ.get("ERKN_SOURCE_DIR", pathlib.Path(__file__).parents[2]))


@pytest.fixture
def chain():
    """A small nonlinear system: d = 4, dense non-diagonal M, sine nonlinearity."""
    rng = np.random.default_rng(1)
    A = rng.standard_normal((4, 4))
    M = A @ A.T + np.eye(4)
    q0 = np.array([0.3, -0.2, 0.5, 0.1])
    p0 = np.array([0.1, 0.4, -0.3, 0.2])
    return M, q0, p0


def _longest_stall(work):
    """(The longest time this thread waited for the GIL while `work` ran in another, the seconds
    `work` takes alone.) Python runs here only while `work` does not hold the GIL. (The clock
    starts before the thread: a worker holding the GIL from its start stalls start() itself.)"""
    start = time.perf_counter()
    work()
    alone = time.perf_counter() - start
    worker = threading.Thread(target=work)
    last, gap = time.perf_counter(), 0.0
    worker.start()
    while worker.is_alive():
        now = time.perf_counter()
        gap, last = max(gap, now - last), now
    worker.join()
    return gap, alone


@pytest.fixture
def longest_stall():
    """_longest_stall: whether a call releases the GIL while it runs."""
    return _longest_stall
