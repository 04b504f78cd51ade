import numpy as np
import pytest


@pytest.fixture
def chain():
    """A small nonlinear system: d = 4, dense non-diagonal M, sine nonlinearity."""
    rng = np.random.default_rng(1)
    A = rng.standard_normal((4, 4))
    M = A @ A.T + np.eye(4)
    q0 = np.array([0.3, -0.2, 0.5, 0.1])
    p0 = np.array([0.1, 0.4, -0.3, 0.2])
    return M, q0, p0
