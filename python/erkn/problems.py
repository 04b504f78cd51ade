"""The test problems, one line each, with what erkn.solve needs:

    import erkn
    fpu = erkn.problems.fpu()                       # m = 3 stiff springs, omega = 50
    sol = fpu.solve(h=0.01, method="ABA864")        # t_span = fpu.t_span unless given
    I = fpu.invariants(sol.q, sol.p)                # {"H": (n,), "I_1": ..., "I": ...}
    # or: erkn.solve(fpu.M, fpu.grad, q0=fpu.q0, p0=fpu.p0, t_span=fpu.t_span, h=0.01)

Each is the C++ problems library's definition (problems/: the same M, U, initial data and
invariants the tests, benchmarks and experiments use): `grad` is an erkn.System whose gradient,
potential and Hessian run in C++ (without the GIL), `M` an erkn.Stiffness. The coordinate layout
of each is in its constructor's documentation and in docs/python.md.
"""

import numpy as np

from . import _erkn
from ._erkn import Error


class Problem:
    """key, title; M (erkn.Stiffness); grad (erkn.System: U, its gradient and Hessian in C++;
    erkn.solve and erkn.Integrator take it as grad); q0, p0; t_span (the span errors are measured
    over); invariant_names (H first), exact_invariant[name] (False: an adiabatic invariant,
    conserved up to small oscillations only); layout (where each coordinate is)."""

    def __init__(self, problem, layout):
        self._problem = problem
        self.key, self.title, self.layout = problem.key, problem.title, layout
        self.M, self.grad = problem.M, problem.system
        self.q0, self.p0 = problem.q0, problem.p0
        self.t_span = (0.0, problem.t_error)
        self.exact_invariant = dict(problem.exact_invariants)
        self.invariant_names = [name for name, _ in problem.exact_invariants]

    @property
    def dim(self):
        return self.q0.size

    def invariants(self, q, p):
        """{name: value} at the state (q, p), or {name: (n,) array} over the rows of (n, d)
        arrays (e.g. sol.q, sol.p)."""
        q, p = np.asarray(q, dtype=float), np.asarray(p, dtype=float)
        rows = self._problem.invariants(np.atleast_2d(q), np.atleast_2d(p))
        return {k: float(v[0]) for k, v in rows.items()} if q.ndim == 1 else rows

    @property
    def has_exact(self):
        return self._problem.has_exact

    def exact(self, t):
        """The exact q at the times t ((n, d) for an array, (d,) for a float); erkn.Error if the
        problem has none (only Duffing has: sn)."""
        rows = self._problem.exact(np.atleast_1d(np.asarray(t, dtype=float)))
        return rows[0] if np.ndim(t) == 0 else rows

    def solve(self, **kwargs):
        """erkn.solve(M, grad, q0=q0, p0=p0, t_span=t_span, **kwargs)."""
        from . import solve
        kwargs.setdefault("t_span", self.t_span)
        return solve(self.M, self.grad, q0=self.q0, p0=self.p0, **kwargs)

    def __repr__(self):
        return f"erkn.problems.{self.key}({self.title!r}, d={self.dim})"


def fpu(m=3, omega=50.0):
    """Fermi-Pasta-Ulam chain (Hairer-Lubich-Wanner I.5.1), d = 2m: q = (x0_1..x0_m, x1_1..x1_m),
    the soft springs' midpoints' coordinates x0 first (M = 0 there), the stiff springs'
    elongations x1 second (M = omega^2 there): M = diag(0, omega^2). U = 1/4 sum_i u_i^4 with
    u_0 = x0_1 - x1_1, u_i = x0_{i+1} - x1_{i+1} - x0_i - x1_i, u_m = x0_m + x1_m. Standard data:
    x0_1 = 1, x0_1' = 1, x1_1 = 1/omega, x1_1' = 1, all else 0; t_span (0, 10). Invariants: H;
    the stiff springs' energies I_j = (x1_j'^2 + omega^2 x1_j^2)/2 and I = sum_j I_j (adiabatic:
    I stays within O(1/omega) of I(0) over long times while energy flows between the I_j)."""
    return Problem(_erkn._fpu(int(m), float(omega)),
                   f"q[:{m}] = x0 (soft, M = 0), q[{m}:] = x1 (stiff elongations, M = omega^2)")


def henon_heiles(energy=0.13):
    """Henon-Heiles: H = |p|^2/2 + |q|^2/2 + q1^2 q2 - q2^3/3 (M = I, U = q1^2 q2 - q2^3/3), d = 2,
    from q = (0, 0.1), p = (p1, 0) with p1 > 0 set by the energy (in (0.005, 1/6): below the
    escape energy); t_span (0, 20). Invariant: H."""
    return Problem(_erkn._henon_heiles(float(energy)), "q = (x, y), p = (x', y')")


def sine_gordon(n=32, kappa=1.0):
    """The paper's problem 1: u_tt = u_xx - kappa sin u, periodic on [-1, 1] with n points
    x_i = -1 + i dx (i = 1..n, dx = 2/n), M = circulant(-1, 2, -1)/dx^2, U = -kappa sum cos u_i;
    u(0) = pi, u_t(0) = sqrt(n) (0.01 + sin(2 pi i/n)); t_span (0, 10). Invariant: H."""
    return Problem(_erkn._sine_gordon(int(n), float(kappa)), "q[i-1] = u(x_i), i = 1..n")


def duffing(k=0.03):
    """The paper's problem 2: q'' + 100 q = k^2 (2 q^3 - q), d = 1, q(0) = 0, q'(0) = 10; exact
    q = sn(10 t, k/10) (Jacobi sn, modulus k/10: .exact(t)); t_span (0, 10). Invariant: H."""
    return Problem(_erkn._duffing(float(k)), "q = (q,)")


def stellar_orbits(eps=1e-3):
    """The paper's problem 3: q1'' + 4 q1 = eps q2^2, q2'' + q2 = 2 eps q1 q2 (M = diag(4, 1),
    U = -eps q1 q2^2), q(0) = (1, 1), q'(0) = 0; t_span (0, 10). Invariant: H."""
    return Problem(_erkn._stellar_orbits(float(eps)), "q = (q1, q2)")


def klein_gordon(n=15, dims=1):
    """Klein-Gordon / phi^4 u_tt = Lap u - u - u^3 on [0, 1]^dims (dims = 1, 2, 3), Dirichlet, n
    interior points per axis (x = (i+1)/(n+1)): M = -Lap_h + 1 (an erkn.grid), U = sum u^4/4;
    u0 = 2 prod sin(pi x_a) + exp(-100 |x - c|^2), c = (0.3, 0.4, 0.5)[:dims], u_t(0) = 0;
    t_span (0, 1). Invariant: H. (dims = 3 is the experiments' 3-D grid scene.)"""
    return Problem(_erkn._klein_gordon(int(n), int(dims)),
                   "q[(i*n + j)*n + k] = u at grid point (i, j, k): row-major, last axis fastest")


def sine_gordon_2d(n=32):
    """2-D sine-Gordon u_tt = Lap u - sin u, periodic on [-6, 6)^2 with n x n points (x along
    the first axis, row-major), u0 = 2.5 exp(-(x^2 + y^2)), u_t(0) = 0; t_span (0, 1).
    Invariant: H."""
    return Problem(_erkn._sine_gordon_2d(int(n)), "q[i*n + j] = u(x_i, y_j)")


__all__ = ["Problem", "duffing", "fpu", "henon_heiles", "klein_gordon", "sine_gordon",
           "sine_gordon_2d", "stellar_orbits"]
