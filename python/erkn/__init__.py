"""erkn: symplectic diagonal implicit ERKN integrators for q'' + M q = -grad U(q).

    sol = erkn.solve(M, grad, q0=q0, p0=p0, t_span=(0.0, 10.0), h=0.025, method="SERKN2s4",
                     t_eval=np.linspace(0, 10, 101))
    sol.t, sol.q, sol.p, sol.energy, sol.stats, sol.method
    sol = erkn.solve(M, grad, q0=q0, p0=p0, t_span=(0.0, 10.0), tol=1e-8)   # method, h chosen
    sol.choice["method"], sol.choice["h"], sol.choice["reason"]

Settings: options=erkn.Options(...) (every field of erkn::Options, validated on assignment), or
the shortcuts energy_tolerance= and check_stability=. Also: erkn.advise_step_size (the step-size
advisor), erkn.hessian_bounds_at / hessian_bounds_along, erkn.Ensemble (trajectories on threads).

M: a float (M = w2 I), a 1-D array (diagonal), a 2-D symmetric array (dense), or an
erkn.Stiffness (erkn.circulant(col), erkn.grid(axes, shift), ...).
grad: a built-in potential by name ("sine", "duffing", "fpu", "phi4"; parameters with
erkn.potential(name, **params)), evaluated in C++, a problem's erkn.System (erkn.problems:
fpu, henon_heiles, sine_gordon, duffing, stellar_orbits, klein_gordon, ...), or a callable: grad(q) returning grad U(q),
or grad(q, out) writing it into `out`. q (and out) are NumPy views of erkn's memory, valid only
during the call: copy q if you keep it.

Output at any time: t_eval may hold any times in t_span; a time between grid points t0 + n h is
the state of one step of the method itself, of the shorter size, from the grid point before it
(order of the method; the trajectory is the same with or without t_eval). t_span[1] off the grid
is reached by a last shorter step. See the README's "Python" section.
"""

import functools
import inspect
import numbers
import sys
import time

import numpy as np

from ._erkn import (Error, StepSizeAdvice, Stiffness, System, builtin_potentials, circulant,
                    dense, diagonal, grid, load_methods, methods, scalar, tableau,
                    trace_tolerance)
from . import _erkn

__version__ = "@PROJECT_VERSION@"
__all__ = ["Ensemble", "Error", "Integrator", "Options", "Solution", "StepSizeAdvice",
           "Stiffness", "advise_step_size", "circulant", "dense", "diagonal", "grid",
           "hessian_bounds_along", "hessian_bounds_at", "load_methods", "methods", "mode_energies",
           "potential", "problems", "scalar", "solve", "stability", "system", "tableau"]

# The method when none is named (and no tol= chooses one): of the methods that need grad U alone
# (plain kicks, unprocessed), the one closest to the cheapest over docs/accuracy.md's 24 cells
# (its per-method table, copied into the README: "Choosing a method").
_DEFAULT_METHOD = "SD9(10,6,4)"
_FLOAT64 = np.dtype(np.float64)  # (NumPy's one instance: arrays of doubles share it)


class Options(_erkn._Options):
    """erkn::Options (erkn/integrator.hpp), field by field:

        opts = erkn.Options(energy_tolerance=1e-8, max_theta=0.5)
        opts.tolerance = 1e-12   # checked on assignment by the C++ validation

    A value out of range, of the wrong type, or an unknown field raises erkn.Error naming the
    field, and the Options keep their previous values. Options.fields lists the fields."""

    __slots__ = ()
    fields = _erkn._Options._fields

    def __init__(self, **fields):
        super().__init__()
        for name, value in fields.items():
            setattr(self, name, value)

    def __setattr__(self, name, value):
        if name not in self.fields:
            raise Error(f"Options has no field '{name}'; its fields: " + ", ".join(self.fields))
        if isinstance(getattr(self, name), bool) and not isinstance(value, (bool, np.bool_)):
            raise Error(f"Options::{name} must be True or False; got {value!r}")
        try:
            super().__setattr__(name, value)
        except TypeError:
            kind = type(getattr(self, name)).__name__
            raise Error(f"Options::{name} must be a {kind}; got {value!r}") from None

    def asdict(self):
        return {name: getattr(self, name) for name in self.fields}

    def __eq__(self, other):
        return isinstance(other, _erkn._Options) and self.asdict() == Options._of(other).asdict()

    def __repr__(self):
        return "erkn.Options(" + ", ".join(f"{k}={v!r}" for k, v in self.asdict().items()) + ")"

    @staticmethod
    def _of(options, energy_tolerance=None, check_stability=None):
        """A new Options from None, an Options or a dict, with the shortcuts (the two fields
        solve and Integrator take as arguments) set where not None (the shared defaults for
        None and no shortcut: callers hand the result to C++, which copies it, and never change
        it)."""
        if options is None and energy_tolerance is None and check_stability is None:
            return _DEFAULT_OPTIONS
        if options is None:
            out = Options()
        elif isinstance(options, _erkn._Options):
            out = Options(**{name: getattr(options, name) for name in Options.fields})
        elif isinstance(options, dict):
            out = Options(**options)
        else:
            raise Error("options must be an erkn.Options or a dict of its fields; got "
                        + type(options).__name__)
        for name, value in (("energy_tolerance", energy_tolerance),
                            ("check_stability", check_stability)):
            if value is not None:
                setattr(out, name, value)
        return out


_DEFAULT_OPTIONS = Options()


class potential:
    """A built-in potential with parameters, e.g. erkn.potential("duffing", k=0.03)."""

    def __init__(self, name, **params):
        if name not in _builtin_names():
            raise Error(f"unknown built-in potential '{name}'; known: "
                        + ", ".join(sorted(_builtin_names())))
        self.name, self.params = name, {k: float(v) for k, v in params.items()}

    def __repr__(self):
        args = "".join(f", {k}={v!r}" for k, v in self.params.items())
        return f"erkn.potential({self.name!r}{args})"


@functools.cache
def _builtin_names():
    """The built-in potentials' names (fixed for the module's life; asked once)."""
    return frozenset(builtin_potentials())


def _stiffness(M):
    if isinstance(M, Stiffness):
        return M
    if type(M) is float:  # (the common scalar case, without np.isscalar's checks)
        return scalar(M)
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


def system(M, grad, d, potential=None, hessian=None, hessian_vector_product=None):
    """The erkn.System solve and Integrator build (for evaluating U, its gradient and Hessian)."""
    return _system(M, grad, d, potential, hessian, hessian_vector_product)


def _system(M, grad, d, potential_fn, hessian, hessian_vector_product=None):
    if isinstance(grad, (str, potential)):  # (a name: its defaults; C++ checks the name)
        if potential_fn is not None or hessian is not None or hessian_vector_product is not None:
            _stiffness(M)  # (a bad M is reported first, as with any grad)
            raise Error("a built-in potential brings its own potential and Hessian")
        params = {} if isinstance(grad, str) else grad.params
        name = grad if isinstance(grad, str) else grad.name
        # (kept for M a float or an erkn.Stiffness, both immutable: see _builtin_system)
        cached = type(M) is float or isinstance(M, Stiffness)
        return _erkn._builtin_system(M if cached else _stiffness(M), name, params, d, cached)
    M = _stiffness(M)
    if isinstance(grad, System):  # (a problem's: its U in C++, with this M)
        if potential_fn is not None or hessian is not None:
            raise Error("an erkn.System brings its own potential and Hessian")
        return _erkn._with_stiffness(grad, M, d)
    if not callable(grad):
        raise Error("grad must be a built-in potential's name, an erkn.potential, or a callable")
    if hessian_vector_product is not None and not callable(hessian_vector_product):
        raise Error("hessian_vector_product must be a callable (q, v) -> Hess U(q) v")
    return _erkn._python_system(M, grad, _writes_into(grad, "grad"), potential_fn, hessian,
                                hessian is not None and _writes_into(hessian, "hessian"),
                                hessian_vector_product, d)


def _state(x, name):
    if type(x) is np.ndarray and x.ndim == 1 and x.dtype is _FLOAT64:
        return x  # (the common case, as it is: C++ copies it, with its strides)
    a = np.ascontiguousarray(np.atleast_1d(np.asarray(x, dtype=float)))
    if a.ndim != 1:
        raise Error(f"{name} must be a 1-D array; got shape {a.shape}")
    return a


def _real(x, name):
    """x as a float if it is a real number (int, float, NumPy real); else erkn.Error ("0.1",
    None and True are not step sizes or times)."""
    if type(x) is float:
        return x
    if isinstance(x, np.ndarray) and x.ndim == 0 and x.dtype.kind in "fiu":
        return float(x)
    if not isinstance(x, numbers.Real) or isinstance(x, (bool, np.bool_)):
        raise Error(f"{name} must be a real number; got {type(x).__name__} {x!r}")
    return float(x)


def _every(every):
    """The output interval as an int in [1, 2^53]; a float must be integral (2.5 is refused)."""
    if type(every) is int and 1 <= every <= 2**53:  # (the common case, as it is)
        return every
    try:
        n = int(every)
        integral = n == every
    except (TypeError, ValueError, OverflowError):
        integral = False
    if not integral or not 1 <= n <= 2**53:
        raise Error(f"every must be an integer in [1, 2^53] (steps between outputs); got {every!r}")
    return n


class Integrator(_erkn._Integrator):
    """Fixed-step integrator for users who drive the loop:

        run = erkn.Integrator(M, grad, q0=q0, p0=p0, h=0.01, method="SERKN2s4")
        run.step(); run.integrate(1.234, observer=lambda t, q, p: ..., every=10)
        q, p = run.state_at(run.t + 0.3 * run.h)

    integrate(t_end) reaches t_end exactly (off the grid by a last shorter step of the method
    with its own coefficients; the grid then restarts at t_end). state_at(t), t in [t, t + h],
    leaves the integrator unchanged."""

    def __init__(self, M, grad, *, q0, p0, h, method=_DEFAULT_METHOD, t0=0.0, potential=None,
                 hessian=None, options=None, energy_tolerance=None, check_stability=None,
                 hessian_vector_product=None):
        super().__init__(*_integrator_arguments(M, grad, q0, p0, h, method, t0, potential, hessian,
                                                options, energy_tolerance, check_stability,
                                                hessian_vector_product))

    @property
    def options(self):
        """A copy of the run's erkn.Options (fixed at construction)."""
        return Options._of(self._options)

    def run(self, t_end, t_eval=None, every=1, energy=True, events=None, progress=None):
        """(t, q, p, energy, events, stopped): the state at t_eval, or else at the start, every
        `every`-th step and t_end; with events (see erkn.solve), (t_events, q_events, p_events,
        statistics) and whether a terminal event stopped the run. progress: see erkn.solve."""
        return self._run(*_run_arguments(self.t, t_end, t_eval, every, energy, events, progress))


def _integrator_arguments(M, grad, q0, p0, h, method, t0, potential, hessian, options,
                          energy_tolerance, check_stability, hessian_vector_product):
    """Integrator's arguments (see there), checked, as the C++ constructor takes them."""
    q0, p0 = _state(q0, "q0"), _state(p0, "p0")
    options = Options._of(options, energy_tolerance=energy_tolerance,
                          check_stability=check_stability)
    system = _system(M, grad, q0.size, potential, hessian, hessian_vector_product)
    return method, system, _real(h, "h"), q0, p0, _real(t0, "t0"), options


def _run_arguments(t, t_end, t_eval, every, energy, events, progress):
    """Integrator.run's arguments (see there; t: the run's time), checked, as _run takes them."""
    t_end = _real(t_end, "t_end")
    return (t_end, t_eval, _every(every), bool(energy), _events(events),
            _progress(progress, t, t_end))


class _ProgressBar:
    """A one-line bar on stderr, drawn from the first call after `after` seconds."""

    def __init__(self, t0, t1, after):
        self.t0, self.t1, self.after, self.drawn = t0, t1, after, False
        self.start = time.monotonic()

    def __call__(self, t):
        if not self.drawn and time.monotonic() - self.start < self.after:
            return
        done = 1.0 if self.t1 == self.t0 else (t - self.t0) / (self.t1 - self.t0)
        bar = "#" * int(30 * done)
        sys.stderr.write(f"\rerkn: [{bar:<30}] {100 * done:5.1f} %  t = {t:.6g}")
        if done >= 1.0:
            sys.stderr.write("\n")
        sys.stderr.flush()
        self.drawn = True


def _progress(progress, t0, t1):
    """The callable the run calls between chunks: progress itself, a bar (True; None: a bar on
    a terminal once the run has lasted 2 s), or None (False)."""
    if progress is None:
        return _ProgressBar(t0, t1, 2.0) if _erkn._on_terminal() else None
    if progress is True:
        return _ProgressBar(t0, t1, 0.0)
    if progress is False:
        return None
    if not callable(progress):
        raise Error(f"progress must be a callable progress(t), True or False; got {progress!r}")
    return progress


def _events(events):
    """[(g, direction, terminal)] from event functions with SciPy's optional attributes
    (g.direction: its sign; g.terminal: True or False), or None."""
    if events is None:
        return None
    if callable(events):
        events = [events]
    out = []
    for k, g in enumerate(events):
        if not callable(g):
            raise Error(f"event {k} must be a callable g(t, q, p); got {type(g).__name__}")
        direction = _real(getattr(g, "direction", 0.0), f"event {k}'s direction")
        terminal = getattr(g, "terminal", False)
        if not isinstance(terminal, (bool, np.bool_)):
            raise Error(f"event {k}'s terminal must be True or False; got {terminal!r}")
        out.append((g, int(np.sign(direction)), bool(terminal)))
    return out


_LATER = object()  # (a Solution's energies: computed from its run when first asked for)


class Solution:
    """t (n,), q and p (n, d): row k is the state at t[k]; energy (n,) or None without a
    potential; stats: the integrator's counters and wall time; method: the method's name;
    choice: with tol=, how the method and h were chosen (a dict: method, h, estimated_error,
    reason, pilot_cpu_time, pilot_gradient_evaluations, candidates), else None.
    With events (SciPy's names): t_events[k] (n_k,), q_events[k], p_events[k] (n_k, d) and
    y_events[k] = [q, p] (n_k, 2d) at event k's zeros; stats["events"]: the work spent locating
    them; status 1 if a terminal event stopped the run, else 0."""

    # (Made by erkn.solve, in C++ (python/src/integrator.cpp: make_solution), which stores every
    # slot but __dict__ and __weakref__ directly: t, q, p, method, choice (None without tol),
    # status, the events (None without events, then set by _add_events), _energy (or _LATER:
    # computed on first access), _run (the integrator, in a capsule for _erkn's _run_statistics
    # and _run_energies) and _stats (None: statistics not read yet).)
    __slots__ = ("t", "q", "p", "method", "choice", "status", "t_events", "q_events", "p_events",
                 "y_events", "_energy", "_run", "_stats", "__dict__", "__weakref__")

    def _add_events(self, events):
        """The events' zeros: events = (t_events, q_events, p_events, their statistics)."""
        self.t_events, self.q_events, self.p_events, self.stats["events"] = events
        self.y_events = [np.hstack([q, p]) for q, p in zip(self.q_events, self.p_events)]

    @property
    def stats(self):
        """The run's counters and times (a dict; solve reads them from the run when first
        asked for, as building the dict costs about a microsecond)."""
        if self._stats is None:
            self._stats = _erkn._run_statistics(self._run)
        return self._stats

    @property
    def energy(self):
        """H at each output time, or None without a potential (a built-in potential's is
        computed on first access: solve does not pay for it unless it is looked at)."""
        if self._energy is _LATER:
            self._energy = _erkn._run_energies(self._run, self.q, self.p)
        return self._energy

    def __repr__(self):
        span = f" in [{self.t[0]:g}, {self.t[-1]:g}]" if self.t.size else ""
        return (f"erkn.Solution(method={self.method!r}, {self.t.size} times{span}, "
                f"d={self.q.shape[1]})")


def solve(M, grad, *, q0, p0, t_span, h=None, method=None, tol=None, t_eval=None, every=1,
          potential=None, hessian=None, options=None, energy_tolerance=None,
          check_stability=None, pilot_fraction=1.0 / 32, safety=1.0, events=None,
          progress=None, hessian_vector_product=None):
    """Integrates q'' + M q = -grad U(q) over t_span = (t0, t1) with step h, or to a tolerance.

    tol: the requested global error (max norm of q's error at t1). With tol, method "auto"
    (the default then) and h None, erkn chooses both (erkn/accuracy.hpp: the methods' certified
    orders and error constants, a short pilot on this problem with h and h/2 over
    pilot_fraction of t_span, the advisor on M's spectrum) and aims at safety * tol; a given
    method or h is kept. sol.choice says what was chosen and why. Without tol, h is required
    and method defaults to "SD9(10,6,4)" (README, "Choosing a method").

    Output at t_eval (any ascending times in t_span), else at t0, every `every`-th step and
    t1. The energy H = p.p/2 + q.M q/2 + U(q) is reported when U is known (a built-in, or the
    `potential` callable); `hessian(q)` (or hessian(q, out)) helps the stage solver's Newton
    fallback. Methods with modified kicks (a non-empty "modified" in erkn.methods()) need
    `hessian_vector_product(q, v)` -> Hess U(q) v (or `hessian`); the built-ins have it.
    options: an erkn.Options (or a dict of its fields); energy_tolerance= and
    check_stability= set those fields.

    events: event functions g(t, q, p) -> float (or one), as SciPy's solve_ivp takes them, with
    the optional attributes g.terminal (stop at the first zero) and g.direction (> 0: zeros
    where g rises only, < 0: falls only). Their zeros are located after every step on the
    method's own shorter step from the step's start (to the method's order; erkn/events.hpp):
    sol.t_events, sol.q_events, sol.p_events, sol.y_events.

    Long runs: Ctrl-C (KeyboardInterrupt) stops the run within ~0.1 s, keeping the output up to
    the last step in the exception's `solution`, whose last row is the last state (also with
    t_eval: after the output times reached). progress: a callable progress(t), called about
    every 0.05 s of stepping and at the end; True draws a bar on stderr; None (the default)
    draws it only on a terminal and once the run has lasted 2 s; False never. Raises erkn.Error with erkn's message on any bad input
    or failed step; an error (or an exception from a callback) during the run carries the
    output up to the last completed step as its `solution` attribute."""
    holder = []  # (the integrator, once built: a failed run's output is kept there)
    choice = None
    try:
        t0, t1 = _span(t_span)
        if tol is not None and (method in (None, "auto") or h is None):
            choice = _choice(M, grad, q0, p0, t0, t1, h, method, tol, potential, hessian,
                             options, energy_tolerance, check_stability, pilot_fraction,
                             safety, hessian_vector_product)
            method, h = choice["method"], choice["h"]
        elif h is None or method == "auto":
            raise Error("solve: give h (and a method), or tol= to let erkn choose them")
        if t_eval is not None:
            t_eval = np.ascontiguousarray(t_eval, dtype=float)
        return _erkn._construct_and_run(
            holder, *_integrator_arguments(M, grad, q0, p0, h, method or _DEFAULT_METHOD, t0,
                                           potential, hessian, options, energy_tolerance,
                                           check_stability, hessian_vector_product),
            *_run_arguments(t0, t1, t_eval, every, True, events, progress), choice)
    except BaseException as e:  # keep the output up to the last completed step (if one began)
        _attach_partial(holder, choice, e)
        raise


def _attach_partial(holder, choice, e):
    """e.solution: the output of the run in holder (if one was built) up to its last completed
    step (solve's; erkn.solve's entry calls it too)."""
    solution = _erkn._partial_solution(holder[0], choice) if holder else None
    if solution is not None:
        e.solution = solution


# erkn.solve: _erkn's entry (python/src/integrator.cpp: solve_entry), which runs solve's common
# call (a built-in potential's name, M a float or an erkn.Stiffness, float64 1-D q0 and p0,
# Python numbers, a method's name, the other arguments left out or None) in C++ as it comes, and
# hands any other form, with its arguments as given, to the Python solve above (_solve_checked),
# which checks and converts each: one set of checks, the same messages. Its text signature and
# docstring are the Python solve's.
_solve_checked = solve
solve = _erkn._solve_entry(
    _solve_checked, globals(),
    "solve" + str(inspect.signature(_solve_checked)) + "\n--\n\n" + _solve_checked.__doc__)


def _span(t_span):
    """(t0, t1) from solve's t_span, checked."""
    if len(t_span) != 2:
        raise Error(f"t_span must be (t0, t1); got {t_span!r}")
    t0, t1 = t_span
    return _real(t0, "t_span"), _real(t1, "t_span")


def _choice(M, grad, q0, p0, t0, t1, h, method, tol, potential, hessian, options,
            energy_tolerance, check_stability, pilot_fraction, safety, hessian_vector_product):
    """solve's method and h chosen for tol (see solve): choose_method_and_step's dict."""
    q0, p0 = _state(q0, "q0"), _state(p0, "p0")
    opts = Options._of(options, energy_tolerance=energy_tolerance,
                       check_stability=check_stability)
    return _erkn._choose(_system(M, grad, q0.size, potential, hessian, hessian_vector_product),
                         q0, p0, t0, t1, _real(tol, "tol"), method or "auto", float(h or 0.0),
                         float(pilot_fraction), float(safety), opts)


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


def hessian_bounds_at(M, grad, q, hessian=None):
    """(lo, hi): the extreme eigenvalues of U's Hessian at q (from `hessian`, a built-in's, or
    finite differences of grad: d gradient evaluations, d <= 2000)."""
    q = _state(q, "q")
    return _erkn._hessian_bounds_at(_system(M, grad, q.size, None, hessian), q)


def hessian_bounds_along(method, M, grad, *, h, q0, p0, steps, hessian=None):
    """(lo, hi) over q0 and each of `steps` steps of `method` with step h from (q0, p0): the
    range at q0 alone can be far too narrow (FPU: hi = 12.5 at q0, 22.4 by t = 100)."""
    q0, p0 = _state(q0, "q0"), _state(p0, "p0")
    return _erkn._hessian_bounds_along(method, _system(M, grad, q0.size, None, hessian), float(h),
                                       q0, p0, int(steps))


def mode_energies(M, q, p):
    """The state's 1/2|p|^2 + 1/2 q'Mq at each eigenvalue of M (M.eigenvalues order): the
    excitation a resonance needs (erkn/advisor.hpp)."""
    return _erkn.mode_energies(_stiffness(M), _state(q, "q"), _state(p, "p"))


# AdvisorOptions fields only the trial run reads (erkn/advisor.hpp, "Severity").
_TRIAL_OPTIONS = ("steps", "energy_tolerance", "trial_steps", "trial_margin", "explained_margin",
                  "saturated_margin", "extended_trial_steps", "ambiguity")


def advise_step_size(method, M, h, grad=None, *, q0=None, p0=None, hessian_steps=0,
                     hessian_bounds=None, potential=None, hessian=None, **advisor_options):
    """The step sizes near h the stability analysis warns against for `method` on
    q'' + M q = -grad U(q), and the nearest one it does not (erkn/advisor.hpp; `erkn advise`).

    With the problem -- grad, q0 and p0 (and no hessian_bounds or hessian_steps) -- the verdict is
    `erkn advise --problem`'s: the linear model at q0 judged by a trial run of the problem itself
    (the first min(trial_steps, steps) steps at h; its energy error extrapolated to a run of
    `steps` steps, default 1e5, is held against energy_tolerance / saturated_margin where it has
    stopped growing, else energy_tolerance / explained_margin where the linear model finds a
    resonance or an unstable band at h, else energy_tolerance / trial_margin; a trial whose
    prediction comes within a factor `ambiguity` of its limit goes on to extended_trial_steps; a
    quiet mode growing exponentially to take over within the run flags h too; U
    from the built-in potential, a problem's System or `potential`, else 1/2|p|^2 + 1/2 q'Mq's
    growth).
    Otherwise the linear model alone, with the bounds (lo, hi) on U's Hessian: hessian_bounds if
    given; else, with grad, at q0 or along `hessian_steps` steps from (q0, p0); else (0, 0). With
    q0 and p0 a resonance is flagged only at eigenvalues the state excites (erkn.mode_energies).
    advisor_options: potential_degree, pole_margin, trace_tolerance, z_samples, max_change,
    search_step, min_excitation, and for the trial steps, energy_tolerance, trial_steps (0: no
    trial), trial_margin, explained_margin, saturated_margin, extended_trial_steps, ambiguity.
    Returns an erkn.StepSizeAdvice: safe, findings, equation (the
    differential equation's own growth: information), notes (linear findings the trial clears),
    trial, suggested_h, hessian, report."""
    options = _erkn._AdvisorOptions()
    for name, value in advisor_options.items():
        if not hasattr(options, name) or name.startswith("_"):
            raise Error(f"advise_step_size has no option '{name}'")
        setattr(options, name, value)
    problem = (grad is not None and q0 is not None and p0 is not None and hessian_bounds is None
               and hessian_steps == 0)
    trial_options = sorted(set(advisor_options) & set(_TRIAL_OPTIONS))
    trial_options += ["potential"] if potential is not None else []
    if trial_options and not problem:
        raise Error("advise_step_size: " + ", ".join(trial_options) + " set the trial run, which "
                    "needs the problem: grad, q0 and p0, without hessian_bounds or hessian_steps")
    if problem:
        q0, p0 = _state(q0, "q0"), _state(p0, "p0")
        return _erkn._advise_problem(method, _system(M, grad, q0.size, potential, hessian),
                                     float(h), q0, p0, options)
    if hessian_bounds is None and grad is not None:
        if q0 is None:
            raise Error("advise_step_size: grad needs q0 (the state the Hessian is bounded at)")
        hessian_bounds = (hessian_bounds_at(M, grad, q0, hessian) if hessian_steps == 0 else
                          hessian_bounds_along(method, M, grad, h=h, q0=q0, p0=p0,
                                               steps=hessian_steps, hessian=hessian))
    lo, hi = (0.0, 0.0) if hessian_bounds is None else (float(x) for x in hessian_bounds)
    stiffness = _stiffness(M)
    energy = np.zeros(0)
    if q0 is not None and p0 is not None:
        energy = mode_energies(stiffness, q0, p0)
    return _erkn._advise(method, stiffness.eigenvalues, float(h), lo, hi, options, energy)


class EnsembleResult:
    """Row i belongs to trajectory i: q, p (n, d) and t (n,) at t_end, or after the last
    completed step of a trajectory that failed; errors[i] ("" when it reached t_end), ok (n,)
    and statistics[i] (its counters and times)."""

    def __init__(self, results):
        self.q = np.array([r["q"] for r in results])
        self.p = np.array([r["p"] for r in results])
        self.t = np.array([r["t"] for r in results])
        self.errors = [r["error"] for r in results]
        self.ok = np.array([not e for e in self.errors], dtype=bool)
        self.statistics = [r["statistics"] for r in results]


class Ensemble:
    """Trajectories of one method and step size, run on threads (erkn/ensemble.hpp):

        ens = erkn.Ensemble(M, "fpu", q0=Q0, p0=P0, h=0.01)   # Q0, P0: (n, d)
        res = ens.integrate(100.0, threads=4)                  # res.q (n, d), res.ok, res.errors

    One M and grad for all, or systems=[erkn.system(M_i, grad_i, d), ...] one per trajectory.
    Each trajectory runs on one thread with its own Integrator, so its result equals a serial
    run bit for bit. Built-in potentials run without the GIL; Python callables take it per
    call (correct, but those trajectories take turns). A failing trajectory does not stop the
    others: its error and its last completed state are in the result."""

    def __init__(self, M=None, grad=None, *, q0, p0, h, method=_DEFAULT_METHOD, options=None,
                 systems=None, potential=None, hessian=None, hessian_vector_product=None):
        q0 = np.atleast_2d(np.asarray(q0, dtype=float))
        p0 = np.atleast_2d(np.asarray(p0, dtype=float))
        if q0.ndim != 2 or q0.shape != p0.shape:
            raise Error(f"q0 and p0 must be arrays of the same shape (n, d); got {q0.shape} "
                        f"and {p0.shape}")
        if (systems is None) == (grad is None):
            raise Error("give either M and grad, or systems (one per trajectory)")
        if systems is None:
            systems = [_system(M, grad, q0.shape[1], potential, hessian, hessian_vector_product)]
        self._ensemble = _erkn._Ensemble(method, float(h), list(systems), q0, p0,
                                         Options._of(options))

    @property
    def size(self):
        return self._ensemble.size

    def integrate(self, t_end, threads=0):
        """Every trajectory from t = 0 to t_end on `threads` threads (0: one per core)."""
        return EnsembleResult(self._ensemble._integrate(float(t_end), int(threads)))


from . import problems  # noqa: E402  (erkn.problems: uses solve above)
