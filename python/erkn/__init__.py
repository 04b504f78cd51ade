"""erkn: symplectic diagonal implicit ERKN integrators for q'' + M q = -grad U(q).

    sol = erkn.solve(M, grad, q0=q0, p0=p0, t_span=(0.0, 10.0), h=0.025, method="SERKN2s4",
                     t_eval=np.linspace(0, 10, 101))
    sol.t, sol.q, sol.p, sol.energy, sol.stats, sol.method

M: a float (M = w2 I), a 1-D array (diagonal), a 2-D symmetric array (dense), or an
erkn.Stiffness (erkn.circulant(col), erkn.grid(axes, shift), ...).
grad: a built-in potential by name ("sine", "duffing", "fpu", "phi4"; parameters with
erkn.potential(name, **params)), evaluated in C++, or a callable: grad(q) returning grad U(q),
or grad(q, out) writing it into `out`. q (and out) are NumPy views of erkn's memory, valid only
during the call: copy q if you keep it.

Output at any time: t_eval may hold any times in t_span; a time between grid points t0 + n h is
the state of one step of the method itself, of the shorter size, from the grid point before it
(order of the method; the trajectory is the same with or without t_eval). t_span[1] off the grid
is reached by a last shorter step. See the README's "Python" section.
"""

import inspect
import time

import numpy as np

from ._erkn import (Error, Stiffness, System, builtin_potentials, circulant, dense, diagonal,
                    grid, methods, scalar, tableau, trace_tolerance)
from . import _erkn

__version__ = "@PROJECT_VERSION@"
__all__ = ["Error", "Integrator", "Solution", "Stiffness", "circulant", "dense", "diagonal",
           "grid", "methods", "potential", "scalar", "solve", "stability", "system", "tableau"]


class potential:
    """A built-in potential with parameters, e.g. erkn.potential("duffing", k=0.03)."""

    def __init__(self, name, **params):
        if name not in builtin_potentials():
            raise Error(f"unknown built-in potential '{name}'; known: "
                        + ", ".join(sorted(builtin_potentials())))
        self.name, self.params = name, {k: float(v) for k, v in params.items()}

    def __repr__(self):
        args = "".join(f", {k}={v!r}" for k, v in self.params.items())
        return f"erkn.potential({self.name!r}{args})"


def _stiffness(M):
    if isinstance(M, Stiffness):
        return M
    if np.isscalar(M):
        return scalar(float(M))
    a = np.asarray(M, dtype=float)
    if a.ndim == 1:
        return diagonal(a)
    if a.ndim == 2:
        return dense(a)
    raise Error(f"M must be a float, a 1-D or 2-D array, or an erkn.Stiffness; got shape {a.shape}")


def _writes_into(f, name):
    """True for f(q, out), False for f(q) -> result (by the number of positional parameters)."""
    try:
        params = [p for p in inspect.signature(f).parameters.values()
                  if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD) and p.default is p.empty]
    except (TypeError, ValueError):  # (builtins without a signature: assume f(q))
        return False
    if len(params) not in (1, 2):
        raise Error(f"{name} must take (q) or (q, out); it takes {len(params)} arguments")
    return len(params) == 2


def system(M, grad, d, potential=None, hessian=None):
    """The erkn.System solve and Integrator build (for evaluating U, its gradient and Hessian)."""
    return _system(M, grad, d, potential, hessian)


def _system(M, grad, d, potential_fn, hessian):
    M = _stiffness(M)
    if isinstance(grad, str):
        grad = potential(grad)
    if isinstance(grad, potential):
        if potential_fn is not None or hessian is not None:
            raise Error("a built-in potential brings its own potential and Hessian")
        return _erkn._builtin_system(M, grad.name, grad.params, d)
    if not callable(grad):
        raise Error("grad must be a built-in potential's name, an erkn.potential, or a callable")
    return _erkn._python_system(M, grad, _writes_into(grad, "grad"), potential_fn, hessian,
                                hessian is not None and _writes_into(hessian, "hessian"), d)


def _state(x, name):
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(x, dtype=float)))
    if a.ndim != 1:
        raise Error(f"{name} must be a 1-D array; got shape {a.shape}")
    return a


class Integrator(_erkn._Integrator):
    """Fixed-step integrator for users who drive the loop:

        run = erkn.Integrator(M, grad, q0=q0, p0=p0, h=0.01, method="SERKN2s4")
        run.step(); run.integrate(1.234, observer=lambda t, q, p: ..., every=10)
        q, p = run.state_at(run.t + 0.3 * run.h)

    integrate(t_end) reaches t_end exactly (off the grid by a last shorter step of the method
    with its own coefficients; the grid then restarts at t_end). state_at(t), t in [t, t + h],
    leaves the integrator unchanged."""

    def __init__(self, M, grad, *, q0, p0, h, method="SERKN2s4", t0=0.0, potential=None,
                 hessian=None):
        q0, p0 = _state(q0, "q0"), _state(p0, "p0")
        super().__init__(method, _system(M, grad, q0.size, potential, hessian), float(h), q0, p0,
                         float(t0))

    def run(self, t_end, t_eval=None, every=1, energy=True):
        """(t, q, p, energy) at t_eval, or else at the start, every `every`-th step and t_end."""
        return self._run(float(t_end), t_eval, int(every), bool(energy))


class Solution:
    """t (n,), q and p (n, d): row k is the state at t[k]; energy (n,) or None without a
    potential; stats: the integrator's counters and wall time; method: the method's name."""

    def __init__(self, t, q, p, energy, stats, method):
        self.t, self.q, self.p, self.energy, self.stats, self.method = t, q, p, energy, stats, method

    def __repr__(self):
        return (f"erkn.Solution(method={self.method!r}, {self.t.size} times in "
                f"[{self.t[0]:g}, {self.t[-1]:g}], d={self.q.shape[1]})")


def solve(M, grad, *, q0, p0, t_span, h, method="SERKN2s4", t_eval=None, every=1,
          potential=None, hessian=None):
    """Integrates q'' + M q = -grad U(q) over t_span = (t0, t1) with step h.

    Output at t_eval (any ascending times in t_span), else at t0, every `every`-th step and
    t1. The energy H = p.p/2 + q.M q/2 + U(q) is reported when U is known (a built-in, or the
    `potential` callable); `hessian(q)` (or hessian(q, out)) helps the stage solver's Newton
    fallback. Raises erkn.Error with erkn's message on any bad input or failed step; an error
    (or an exception from a callback) during the run carries the output up to the last completed
    step as its `solution` attribute."""
    t0, t1 = (float(x) for x in t_span)
    run = Integrator(M, grad, q0=q0, p0=p0, h=h, method=method, t0=t0, potential=potential,
                     hessian=hessian)
    if t_eval is not None:
        t_eval = np.ascontiguousarray(t_eval, dtype=float)
    try:
        t, q, p, energy = run.run(t1, t_eval, every)
    except Exception as e:  # keep the output up to the last completed step
        e.solution = Solution(*run._partial, run.statistics, run.method)
        raise
    return Solution(t, q, p, energy, run.statistics, run.method)


def stability(name, V, z=0.0):
    """S(V, z) of the linear test equation y'' + w^2 y = -eps y (V = h^2 w^2, z = h^2 eps):
    V, z broadcast; returns {"S": (..., 2, 2), "trace", "det", "rho", "class"} with classes
    periodic / marginal / unstable / contractive / singular / pole (see erkn/stability.hpp)."""
    V, z = np.broadcast_arrays(np.asarray(V, dtype=float), np.asarray(z, dtype=float))
    S, classes = _erkn._stability(name, np.ascontiguousarray(V).ravel(),
                                  np.ascontiguousarray(z).ravel())
    S = S.reshape(V.shape + (2, 2))
    trace = S[..., 0, 0] + S[..., 1, 1]
    det = S[..., 0, 0] * S[..., 1, 1] - S[..., 0, 1] * S[..., 1, 0]
    with np.errstate(invalid="ignore"):
        rho = np.abs(np.linalg.eigvals(np.nan_to_num(S))).max(axis=-1)
    rho = np.where(np.isfinite(trace), rho, np.nan)
    return {"S": S, "trace": trace, "det": det, "rho": rho,
            "class": np.array(classes, dtype=object).reshape(V.shape)}
