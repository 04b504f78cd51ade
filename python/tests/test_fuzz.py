# A bounded fuzz of the Python API (fixed seed, as tests/runtime/fuzz_test.cpp for C++): random
# forms and sizes of M, built-in and Python gradients (some of them wrong), states with odd
# entries, odd step sizes, spans, output times and intervals, through erkn.solve and the
# Integrator's mutating calls. Every call returns a finite, well-formed result or raises
# erkn.Error (a callback's own exception passes through unchanged); nothing else, no hang, and a
# refused Integrator call changes no state.
import math

import numpy as np
import pytest

import erkn

ODD = [np.nan, np.inf, -np.inf, 1e308, 5e-324, -1e300, 0.0]
METHODS = [m["name"] for m in erkn.methods()]


class UserError(Exception):
    """A callback's own exception: erkn must let it through unchanged."""


class Fuzzer:
    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)
        self.rate = 0.3

    def new_case(self):
        """Half the cases are clean (they reach the stepping), the rest odd here and there."""
        self.rate = 0.0 if self.rng.integers(2) else 0.3

    def odd(self, share=1.0):
        return self.rng.random() < self.rate * share

    def pick(self, options):
        return options[self.rng.integers(len(options))]

    def either(self, good, bad):
        return self.pick(bad) if self.odd() else self.pick(good)

    def value(self, lo=-2.0, hi=2.0):
        return self.pick(ODD) if self.odd(0.1) else self.rng.uniform(lo, hi)

    def vector(self, d):
        n = int(self.rng.integers(0, 5)) if self.odd(0.3) else d  # sometimes a wrong size
        return np.array([self.value() for _ in range(n)])

    def step_size(self):
        # (odd values are refused; ordinary ones keep every run below ~1e4 steps: no hang)
        odd = [0.0, -0.1, 1e-300, np.nan, np.inf, 1e300, "0.1", None]
        return self.pick(odd) if self.odd() else self.rng.uniform(1e-3, 0.3)

    def stiffness(self, d):
        kind = self.rng.integers(6)
        if kind == 0:
            return self.value(0, 50)
        if kind == 1:
            return np.abs(self.vector(d)) * 20
        if kind == 2:
            a = np.array([[self.value() for _ in range(d)] for _ in range(d)])
            return a if self.odd() else a @ a.T  # sometimes not symmetric
        col = np.zeros(d)
        col[0] = self.value(0, 40)
        if d > 1:
            col[1] = col[-1] = -abs(self.value(0, 10))
        if kind == 3:
            return erkn.circulant(col)
        return erkn.grid([(d, self.either([0.5, 1.0], [1e-200, -1.0, np.nan]), self.either(
            ["periodic", "dirichlet", "neumann"], ["wrap"]))])

    def gradient(self):
        """(grad, potential or None) of varying quality."""
        kind = int(self.rng.integers(5, 9)) if self.odd() else int(self.rng.integers(5))
        cubic = (lambda q: q**3, lambda q: 0.25 * float((q**4).sum()))
        if kind < 3:
            return self.either(["sine", "phi4", "duffing", "fpu"], ["nonsense"]), None
        if kind == 3:
            return cubic
        if kind == 4:

            def into(q, out):
                out[:] = q**3

            return into, cubic[1]
        if kind == 5:
            return (lambda q: np.zeros(q.size + 1)), None  # wrong shape
        if kind == 6:
            return (lambda q: np.full(q.size, np.nan)), None  # not finite

        if kind == 7:
            def raises(q):
                raise UserError("user gradient failed")

            return raises, None
        return cubic[0], (lambda q: "energy")  # a potential that is no float

    def times(self, t1):
        kind = int(self.rng.integers(2, 6)) if self.odd() else int(self.rng.integers(2))
        if kind == 0:
            return None
        if kind == 1:
            return np.sort(self.rng.uniform(0, abs(t1), 5))
        if kind == 2:
            return self.rng.uniform(-1, 1 + 2 * abs(t1), 4)  # unsorted, outside
        if kind == 3:
            return np.zeros((2, 2))
        if kind == 4:
            return []
        return [0.0, np.nan]


def check_solution(sol, t1, d):
    assert np.isfinite(sol.q).all() and np.isfinite(sol.p).all() and np.isfinite(sol.t).all()
    assert sol.q.shape == sol.p.shape == (sol.t.size, d)
    if sol.t.size:
        assert sol.t.min() >= -1e-12 and sol.t.max() <= t1 * (1 + 1e-12) + 1e-12
    repr(sol)


def attempt(call, counts):
    """call() -> its result, or None when refused with erkn.Error (or the callback's UserError)."""
    try:
        result = call()
    except erkn.Error:
        counts["refused"] += 1
        return None
    except TypeError as e:  # (pybind11's refusal of an argument of the wrong type, named)
        if "incompatible function arguments" not in str(e):
            raise
        counts["refused"] += 1
        return None
    except UserError:
        counts["passed through"] += 1
        return None
    counts["accepted"] += 1
    return result


def test_solve_fuzz():
    f, counts = Fuzzer(20261125), {"accepted": 0, "refused": 0, "passed through": 0}
    for n in range(400):
        f.new_case()
        d = int(f.rng.integers(1, 5)) * 2
        grad, potential = f.gradient()
        t1 = f.either([1.0, 0.37], [0.0, -1.0, np.nan])
        kw = dict(q0=f.vector(d), p0=f.vector(d), t_span=(0.0, t1), h=f.step_size(),
                  method=f.either(METHODS, ["RK4"]), t_eval=f.times(t1 if t1 == t1 else 1.0),
                  every=f.either([1, 3], [2.5, 0, 10**30]))
        sol = attempt(lambda: erkn.solve(f.stiffness(d), grad, potential=potential, **kw), counts)
        if sol is not None:
            check_solution(sol, t1, len(kw["q0"]))
    print(counts)
    assert sum(counts.values()) == 400
    assert counts["accepted"] > 40 and counts["refused"] > 100  # it reaches past the refusals


def snapshot(run):
    return run.q.copy(), run.p.copy(), run.t, run.h, run.statistics["steps"]


def same(a, b):
    return all(np.array_equal(x, y) for x, y in zip(a, b))


def test_integrator_fuzz_refusals_change_nothing():
    f, counts = Fuzzer(7), {"accepted": 0, "refused": 0, "passed through": 0}
    calls = 0
    while calls < 600:
        f.new_case()
        d = 4
        method = f.pick(METHODS)
        built = attempt(lambda: erkn.Integrator(f.stiffness(d), "phi4", q0=f.vector(d), p0=f.vector(d),
                                                h=f.step_size(), method=method), counts)
        calls += 1
        if built is None:
            continue
        run = built
        for _ in range(8):
            before, t = snapshot(run), run.t
            call = f.pick([
                lambda: run.step(int(f.pick([1, 2, -1]))),
                lambda: run.set_state(f.vector(d), f.vector(d), f.value(0, 10)),
                lambda: run.set_step_size(f.step_size()),
                lambda: run.state_at(t + f.pick([0.5, 2.0, -1.0, np.inf, np.nan]) * run.h),
                lambda: run.integrate(t + f.pick([0.3, 1.0, -1.0, np.nan])),
                lambda: run.run(t + 0.5, t_eval=f.times(t + 0.5), every=f.pick([1, 2.5, 0])),
            ])
            calls += 1
            refused_before = counts["refused"]
            result = attempt(call, counts)
            if counts["refused"] > refused_before:
                assert same(snapshot(run), before), "a refused call changed the state"
            assert np.isfinite(run.q).all() and np.isfinite(run.p).all() and math.isfinite(run.t)
            if isinstance(result, tuple) and len(result) == 2:  # state_at
                assert np.isfinite(result[0]).all() and same(snapshot(run), before)
    print(counts, calls)
    assert counts["accepted"] > 100 and counts["refused"] > 100
