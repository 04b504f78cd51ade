import os
import pathlib

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
