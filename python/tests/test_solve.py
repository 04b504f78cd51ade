# erkn.solve and erkn.Integrator: every form of M, every form of grad, output at any time,
# errors as erkn.Error with erkn's message.
import numpy as np
import pytest

import erkn

N = 16
DX = 2.0 / N


def sine_gordon_column():
    col = np.zeros(N)
    col[0], col[1], col[-1] = 2 / DX**2, -1 / DX**2, -1 / DX**2
    return col


def sine_gordon_initial():
    i = np.arange(1, N + 1)
    return np.full(N, np.pi), np.sqrt(N) * (0.01 + np.sin(2 * np.pi * i / N))


def test_every_form_of_the_same_M_gives_the_same_solution():
    col = sine_gordon_column()
    dense = np.array([np.roll(col, k) for k in range(N)])
    q0, p0 = sine_gordon_initial()
    forms = [erkn.circulant(col), dense, erkn.grid([(N, DX, "periodic")])]
    sols = [erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 1), h=0.05) for M in forms]
    for s in sols[1:]:
        assert np.abs(s.q - sols[0].q).max() < 1e-10
    # scalar and diagonal, against each other
    a = erkn.solve(4.0, "phi4", q0=[0.5, -0.3], p0=[0.1, 0.2], t_span=(0, 3), h=0.1)
    b = erkn.solve(np.array([4.0, 4.0]), "phi4", q0=[0.5, -0.3], p0=[0.1, 0.2], t_span=(0, 3), h=0.1)
    assert np.abs(a.q - b.q).max() < 1e-14
    assert a.q.shape == (31, 2) and a.t[0] == 0 and a.t[-1] == 3


def test_builtin_and_python_gradients_agree_in_both_calling_conventions(chain):
    M, q0, p0 = chain
    seen = []

    def grad(q):
        seen.append(q)
        assert not q.flags.writeable and not q.flags.owndata  # a view of erkn's memory
        return np.sin(q)

    def grad_into(q, out):
        out[:] = np.sin(q)

    kw = dict(q0=q0, p0=p0, t_span=(0, 2), h=0.05, method="SERKN3s4(1)")
    a = erkn.solve(M, "sine", **kw)
    b = erkn.solve(M, grad, potential=lambda q: -np.cos(q).sum(), **kw)
    c = erkn.solve(M, grad_into, **kw)
    assert np.abs(a.q - b.q).max() < 1e-13
    assert np.array_equal(b.q, c.q)
    assert np.abs(a.energy - b.energy).max() < 1e-12
    assert c.energy is None  # no potential given
    assert seen and a.stats["gradient_evaluations"] == b.stats["gradient_evaluations"]


def test_builtin_energies_wait_until_asked_for_and_equal_the_runs_own():
    # A built-in U: solve leaves the energies to the first access of sol.energy (the run does
    # not pay for them); they equal those the integrator computes at its outputs. A failed run's
    # partial solution has them too.
    M = erkn.circulant(np.array([2.0, -1.0, 0.0, -1.0]))
    q0, p0 = np.array([0.3, -0.2, 0.1, 0.4]), np.array([0.1, 0.0, -0.3, 0.2])
    sol = erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 2), h=0.05, method="Strang", every=8)
    assert sol._energy is erkn._LATER
    run = erkn.Integrator(M, "sine", q0=q0, p0=p0, h=0.05, method="Strang")
    t, q, p, energy, _, _ = run.run(2.0, every=8)
    assert np.array_equal(sol.t, t) and np.array_equal(sol.q, q)
    assert np.array_equal(sol.energy, energy) and sol.energy is sol.energy
    # Negative control: another run's energies differ.
    other = erkn.solve(M, "sine", q0=2 * q0, p0=p0, t_span=(0, 2), h=0.05, method="Strang",
                       every=8)
    assert np.abs(other.energy - energy).max() > 1e-3
    with pytest.raises(erkn.Error) as failure:
        erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 2), h=0.05, method="Strang",
                   energy_tolerance=1e-12)
    partial = failure.value.solution
    assert partial.energy.shape == partial.t.shape and np.isfinite(partial.energy).all()


def test_python_energies_are_computed_in_the_run_and_equal_the_integrators():
    # A Python U: the energies cannot wait (calling U later could fail where the run did not),
    # so solve's one C++ call computes them during the run; they equal Integrator.run's, and a
    # failed run's partial solution has them for the rows it kept.
    M = erkn.circulant(np.array([2.0, -1.0, 0.0, -1.0]))
    q0, p0 = np.array([0.3, -0.2, 0.1, 0.4]), np.array([0.1, 0.0, -0.3, 0.2])
    kw = dict(potential=lambda q: float(np.sum(1 - np.cos(q))), h=0.05, method="Strang")
    sol = erkn.solve(M, np.sin, q0=q0, p0=p0, t_span=(0, 2), every=8, **kw)
    assert isinstance(sol._energy, np.ndarray)
    run = erkn.Integrator(M, np.sin, q0=q0, p0=p0, **kw)
    t, q, _, energy, _, _ = run.run(2.0, every=8)
    assert np.array_equal(sol.t, t) and np.array_equal(sol.q, q)
    assert np.array_equal(sol.energy, energy)
    assert sol.method == "Strang" and sol.stats["steps"] == 40
    # Negative control: another run's energies differ.
    other = erkn.solve(M, np.sin, q0=2 * q0, p0=p0, t_span=(0, 2), every=8, **kw)
    assert np.abs(other.energy - energy).max() > 1e-3
    with pytest.raises(erkn.Error, match="energy monitor") as failure:
        erkn.solve(M, np.sin, q0=q0, p0=p0, t_span=(0, 2), energy_tolerance=1e-12, **kw)
    partial = failure.value.solution
    assert 0 < partial.t.size < 41 and partial.energy.shape == partial.t.shape
    kept = erkn.solve(M, np.sin, q0=q0, p0=p0, t_span=(0, partial.t[-1]), **kw)
    assert np.array_equal(partial.energy, kept.energy)


def test_output_arrays_outlive_the_solution_and_share_one_owner():
    # t, q, p and the energies view the run's output vectors (no copy), which one capsule owns:
    # the arrays stay valid and writable after the solution and its integrator are gone, and
    # writing into one leaves the others as they were.
    import gc

    M = erkn.circulant(np.array([2.0, -1.0, 0.0, -1.0]))
    q0, p0 = np.array([0.3, -0.2, 0.1, 0.4]), np.array([0.1, 0.0, -0.3, 0.2])
    kw = dict(q0=q0, p0=p0, t_span=(0, 2), h=0.05, method="Strang", every=4)
    sol = erkn.solve(M, "sine", **kw)
    t, q, p, energy = sol.t, sol.q, sol.p, sol.energy
    assert q.base is t.base and p.base is t.base and energy.base is not None
    assert q.shape == p.shape == (11, 4) and t.shape == energy.shape == (11,)
    assert all(a.flags.writeable and a.flags.c_contiguous for a in (t, q, p, energy))
    kept = [a.copy() for a in (t, q, p, energy)]
    del sol
    gc.collect()
    junk = [erkn.solve(M, "sine", **kw).q for _ in range(20)]  # (reuse any freed memory)
    assert all(np.array_equal(a, b) for a, b in zip((t, q, p, energy), kept))
    q[:] = 0.0
    assert np.array_equal(p, kept[2]) and np.array_equal(t, kept[0])
    # Negative control: the other runs' arrays are their own, not these.
    assert not np.shares_memory(junk[0], q) and np.array_equal(junk[0], kept[1])


def _explicit_methods():
    return [m["name"] for m in erkn.methods()
            if not np.diag(np.asarray(erkn.tableau(m["name"])["abar"])).any()]


def _builtin_callbacks(name, param):
    # A built-in's grad and Hess U v in NumPy, in the built-in's order of operations.
    if name == "duffing":
        c = -(param * param)
        return dict(grad=lambda q, out: np.multiply(c, 2 * (q * q * q) - q, out=out),
                    hessian_vector_product=lambda q, v: c * (6 * (q * q) - 1) * v)
    return dict(grad=lambda q, out: np.multiply(param, q * q * q, out=out),
                hessian_vector_product=lambda q, v: 3 * param * (q * q) * v)


@pytest.mark.parametrize("name,k", [("duffing", 0.5), ("phi4", 2.0)])
def test_builtins_at_small_d_give_a_python_gradients_states_bit_for_bit(name, k):
    # d <= 4 with scalar or diagonal M: the built-ins' explicit steps call their gradient
    # compiled in (problems::Potential::compiled_grad_u); the same arithmetic in NumPy through
    # the callback path gives the same bits, for every explicit method.
    def callbacks(param):
        return _builtin_callbacks(name, param)

    builtin = erkn.potential(name, **{"k" if name == "duffing" else "beta": k})
    moved = k * (1 + 2.0**-40)  # (negative control: the comparison sees this change)
    for d in range(1, 5):
        q0, p0 = np.linspace(0.4, 1.3, d), np.linspace(1.0, -0.5, d)
        for M in (9.0, np.linspace(4.0, 16.0, d)):
            for method in _explicit_methods():
                kw = dict(q0=q0, p0=p0, t_span=(0, 3.01), h=0.05, method=method, every=7)
                a = erkn.solve(M, builtin, **kw)
                b = erkn.solve(M, **callbacks(k), **kw)
                assert np.array_equal(a.q, b.q) and np.array_equal(a.p, b.p), (method, d, M)
                assert a.stats["gradient_evaluations"] == b.stats["gradient_evaluations"]
        c = erkn.solve(M, **callbacks(moved), **kw)
        assert not np.array_equal(a.q, c.q)


@pytest.mark.parametrize("name,k", [("duffing", 0.5), ("phi4", 2.0)])
def test_builtins_with_half_spectrum_bases_give_a_python_gradients_states_bit_for_bit(name, k):
    # Circulant M and a periodic grid (FFTW's half spectrum; without FFTW circulant M of N > 64):
    # the built-ins' gradients compiled into the explicit steps of that basis give the states of
    # the same arithmetic in NumPy through the callback path, for every explicit method.
    col = np.zeros(80)
    col[0], col[1], col[-1] = 6.0, -1.0, -1.0
    forms = [erkn.circulant(col), erkn.grid([(8, 0.5, "periodic"), (10, 0.4, "periodic")])]
    builtin = erkn.potential(name, **{"k" if name == "duffing" else "beta": k})
    for M in forms:
        q0, p0 = 0.3 * np.sin(np.linspace(0, 6, 80)), np.linspace(0.2, -0.4, 80)
        for method in _explicit_methods():
            kw = dict(q0=q0, p0=p0, t_span=(0, 0.51), h=0.05, method=method, every=4)
            a = erkn.solve(M, builtin, **kw)
            b = erkn.solve(M, **_builtin_callbacks(name, k), **kw)
            assert np.array_equal(a.q, b.q) and np.array_equal(a.p, b.p), (method, M)
        c = erkn.solve(M, **_builtin_callbacks(name, k * (1 + 2.0**-40)), **kw)
        assert not np.array_equal(a.q, c.q)  # (negative control: the comparison sees it)


def test_a_built_in_systems_cache_gives_the_uncached_solutions():
    # solve keeps a built-in's System for a float M or an erkn.Stiffness (erkn._builtin_system):
    # each key gives the System built for it, whatever was asked for before.
    kw = dict(q0=np.array([0.3, -0.2]), p0=np.array([1.0, 0.5]), t_span=(0, 2), h=0.05,
              method="SABA2")  # (with a name: solve's common call, in its C++ entry)
    M = erkn.diagonal(np.array([4.0, 9.0]))
    duffing = erkn.potential("duffing", k=0.5)
    runs = {}
    for rep in range(2):  # (the second time from the cache)
        for key, (m, grad) in {"float": (9.0, duffing), "other float": (4.0, duffing),
                               "Stiffness": (M, duffing), "name": (9.0, "duffing"),
                               "other k": (9.0, erkn.potential("duffing", k=0.25))}.items():
            sol = erkn.solve(m, grad, **kw)
            assert key not in runs or np.array_equal(runs[key], sol.q), key
            runs[key] = sol.q
    # The uncached forms of the same M give the same bits; every key its own solution.
    assert np.array_equal(erkn.solve(np.float64(9.0), duffing, **kw).q, runs["float"])
    assert np.array_equal(erkn.solve(np.array([4.0, 9.0]), duffing, **kw).q, runs["Stiffness"])
    qs = list(runs.values())
    assert all(not np.array_equal(a, b) for i, a in enumerate(qs) for b in qs[i + 1:])
    # A potential's parameters changed after a solve are those of the next one.
    duffing.params["k"] = 0.25
    assert np.array_equal(erkn.solve(9.0, duffing, **kw).q, runs["other k"])


def test_the_common_call_gives_what_its_arguments_in_other_forms_give(monkeypatch):
    # solve's common call (a built-in's name, M a float or an erkn.Stiffness, float64 arrays,
    # Python numbers) runs in erkn.solve's C++ entry, without the Python solve's checks; the
    # same values in other forms take the checked path (erkn._solve_checked): the same bits,
    # counts, errors and partial output of a failed run.
    taken = []

    def spy(*args, **kw):
        taken.append("checked")
        return original(*args, **kw)

    original = erkn._solve_checked
    monkeypatch.setattr(erkn, "_solve_checked", spy)

    def solve(M, grad, **kw):  # (and whether the checked path took the call)
        taken.clear()
        return erkn.solve(M, grad, **kw), bool(taken)

    q0, p0 = np.array([0.3, -0.2]), np.array([1.0, 0.5])
    common = dict(q0=q0, p0=p0, t_span=(0, 2.0), h=0.05, every=3)
    other = dict(q0=list(q0), p0=p0.tolist(), t_span=np.array([0, 2.0]), h=np.float64(0.05),
                 every=3.0)
    for M in (9.0, erkn.diagonal(np.array([4.0, 9.0]))):
        for method in [m["name"] for m in erkn.methods()]:
            (a, checked_a), (b, checked_b) = (solve(M, "duffing", method=method, **kw)
                                              for kw in (common, other))
            assert (checked_a, checked_b) == (False, True), method
            for x, y in ((a.t, b.t), (a.q, b.q), (a.p, b.p), (a.energy, b.energy)):
                assert np.array_equal(x, y), (M, method)
            assert a.stats["gradient_evaluations"] == b.stats["gradient_evaluations"]
            assert a.method == b.method == method and a.status == b.status == 0
    c = erkn.solve(9.0, "duffing", method=method, **dict(common, h=0.05 * (1 + 2.0**-40)))
    assert not np.array_equal(a.q, c.q)  # (negative control: the comparison sees it)
    for bad in (dict(h=-0.1), dict(method="nope"), dict(grad="cosh"), dict(M=float("nan")),
                dict(p0=np.zeros(3)), dict(t_span=(0, 1e30)), dict(every=0),
                dict(q0=np.array([30.0, 0.0]), h=0.5, t_span=(0, 100.0))):  # (a run that blows up)
        refusals = []
        for kw, form in ((common, lambda x: x), (other, _other_form)):
            args = {**kw, "M": 9.0 - 8 * ("q0" in bad), "grad": "duffing" if "q0" in bad
                    else "sine", **{k: form(v) for k, v in bad.items()}}
            taken.clear()
            with pytest.raises(ValueError) as refused:
                erkn.solve(args.pop("M"), args.pop("grad"), **args)
            partial = getattr(refused.value, "solution", None)
            refusals.append((type(refused.value), str(refused.value), bool(taken),
                             None if partial is None else (partial.t.tolist(), partial.q.tolist())))
        assert refusals[0][:2] == refusals[1][:2] and refusals[0][0] is erkn.Error, bad
        assert refusals[0][3] == refusals[1][3], bad  # (the output up to the failed step)
        assert (refusals[0][2], refusals[1][2]) == ("every" in bad, True), bad
    assert len(refusals[0][3][0]) > 1  # (the blow-up: steps were taken and kept)
    # A keyword solve does not have: Python's TypeError in both forms.
    for kw in (common, other):
        with pytest.raises(TypeError, match="unexpected keyword argument 'tolerance'"):
            erkn.solve(9.0, "duffing", tolerance=None, **kw)


# A reload of erkn runs its __init__ again, which makes a new erkn.solve (a C++ entry): each
# entry has its own doc string, and every entry, the one the user held before too, solves into
# the reloaded module's Solution class, on the common call's path and the checked one. In a fresh
# interpreter, so this process's erkn stays as imported.
RELOAD_SCRIPT = """
import importlib, inspect, erkn, numpy as np
first_solve, first_solution = erkn.solve, erkn.Solution
doc = "solve" + str(inspect.signature(erkn._solve_checked)) + "\\n--\\n\\n" + erkn._solve_checked.__doc__
other = erkn._erkn._solve_entry(erkn._solve_checked, vars(erkn), doc + "!")
assert other.__doc__ == erkn._solve_checked.__doc__ + "!", "a second entry's own doc"
assert first_solve.__doc__ == erkn._solve_checked.__doc__, "the first entry's doc kept"
importlib.reload(erkn)
assert erkn.solve is not first_solve and erkn.Solution is not first_solution  # (control)
assert erkn.solve.__doc__ == erkn._solve_checked.__doc__
assert inspect.signature(erkn.solve) == inspect.signature(erkn._solve_checked)
common = dict(q0=np.array([0.3]), p0=np.array([1.0]), t_span=(0, 1.0), h=0.1)
checked = dict(common, q0=[0.3], p0=[1.0])  # (a list: the checked path)
sols = [f(9.0, "duffing", **kw) for f in (erkn.solve, first_solve) for kw in (common, checked)]
assert all(type(s) is erkn.Solution for s in sols), "the reloaded module's class"
assert all((s.q == sols[0].q).all() for s in sols)
print("ok")
"""


def test_a_reload_of_erkn_makes_a_solve_with_its_own_doc_into_the_new_solution_class():
    import os
    import subprocess
    import sys
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    run = subprocess.run([sys.executable, "-c", RELOAD_SCRIPT], capture_output=True, text=True,
                         env=env)
    assert run.returncode == 0 and run.stdout == "ok\n", run.stderr


def _other_form(x):
    """x in a form solve's common call does not take (the same value)."""
    if isinstance(x, float):
        return np.float64(x)
    if isinstance(x, (int, str)):
        return x  # (the other arguments' forms decide; messages quote ints and names)
    return x.tolist() if isinstance(x, np.ndarray) else np.array(x)


@pytest.mark.parametrize("name,d,params", [("sine", 3, {}), ("duffing", 3, {"k": 0.3}),
                                           ("phi4", 3, {"beta": 2.0}), ("fpu", 6, {})])
def test_builtin_gradient_and_hessian_are_derivatives_of_the_potential(name, d, params):
    s = erkn.system(0.0, erkn.potential(name, **params), d)
    q = np.linspace(-0.7, 0.9, d)
    eps = 1e-6
    fd = np.array([(s.potential(q + eps * e) - s.potential(q - eps * e)) / (2 * eps)
                   for e in np.eye(d)])
    assert np.abs(s.gradient(q) - fd).max() < 1e-8
    fdH = np.array([(s.gradient(q + eps * e) - s.gradient(q - eps * e)) / (2 * eps)
                    for e in np.eye(d)])
    assert np.abs(s.hessian(q) - fdH).max() < 1e-7
    # Negative control: a wrong gradient fails the same check.
    assert np.abs(2 * s.gradient(q) - fd).max() > 1e-3


def test_fpu_with_stiff_springs_conserves_energy():
    m, omega = 3, 50.0
    M = np.r_[np.zeros(m), np.full(m, omega**2)]
    q0 = np.r_[1.0, 0, 0, 1 / omega, 0, 0]
    p0 = np.r_[1.0, 0, 0, 1.0, 0, 0]
    sol = erkn.solve(M, "fpu", q0=q0, p0=p0, t_span=(0, 20), h=0.03)  # h omega = 1.5
    assert np.abs(sol.energy - sol.energy[0]).max() < 1e-3 * sol.energy[0]


def test_output_at_any_time_keeps_the_trajectory_and_has_the_method_order(chain):
    M, q0, p0 = chain
    t_eval = np.array([0.0, 0.123, 0.5, 1.0, 1.377])
    kw = dict(q0=q0, p0=p0, t_span=(0, 1.4), method="SERKN2s4")
    a = erkn.solve(M, "sine", h=0.1, t_eval=t_eval, **kw)
    b = erkn.solve(M, "sine", h=0.1, **kw)
    assert np.array_equal(a.t, t_eval)
    assert np.abs(a.q[3] - b.q[10]).max() < 1e-14  # t = 1.0 is grid point 10
    ref = erkn.solve(M, "sine", h=0.1 / 64, t_eval=t_eval, **kw).q
    errs = [np.abs(erkn.solve(M, "sine", h=0.1 / k, t_eval=t_eval, **kw).q - ref).max()
            for k in (1, 2, 4)]
    orders = np.log2(np.array(errs[:-1]) / np.array(errs[1:]))
    assert np.all(np.abs(orders - 4) < 0.3), orders


def test_end_off_the_grid_and_every_k_steps(chain):
    M, q0, p0 = chain
    sol = erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0.5, 1.55), h=0.1, every=3)
    assert sol.t == pytest.approx([0.5, 0.8, 1.1, 1.4, 1.55])
    assert sol.t[-1] == 1.55
    assert sol.stats["steps"] == 11


def test_integrator_drives_the_loop(chain):
    M, q0, p0 = chain
    run = erkn.Integrator(M, "sine", q0=q0, p0=p0, h=0.1, method="SERKN2s4")
    run.step(3)
    assert run.t == pytest.approx(0.3)
    q, p = run.state_at(0.35)
    assert run.t == pytest.approx(0.3)
    times = []
    run.integrate(0.35, observer=lambda t, q, p: times.append(t))
    assert times == [0.35] and np.abs(run.q - q).max() < 1e-14
    st = run.statistics
    assert st["steps"] == 4 and st["gradient_evaluations"] > 0
    seen = {}
    run.integrate(1.0, observer=lambda t, q, p: seen.setdefault(t, q), times=[0.5, 0.777, 1.0])
    assert sorted(seen) == [0.5, 0.777, 1.0] and np.array_equal(seen[1.0], run.q)
    q_before = run.q
    q_before[:] = 7  # a copy: the integrator is not affected
    assert not np.any(run.q == 7)


def test_errors_carry_erkns_message(chain):
    M, q0, p0 = chain
    kw = dict(q0=q0, p0=p0, t_span=(0, 1))
    with pytest.raises(erkn.Error, match="step size h must be finite and > 0"):
        erkn.solve(M, "sine", h=-0.1, **kw)
    with pytest.raises(ValueError, match="unknown method"):
        erkn.solve(M, "sine", h=0.1, method="nope", **kw)
    with pytest.raises(erkn.Error, match="not symmetric|symmetric"):
        erkn.solve(M + np.triu(np.ones((4, 4)), 1), "sine", h=0.1, **kw)
    with pytest.raises(erkn.Error, match=r"grad\(q\) must return a float array of shape \(4,\)"):
        erkn.solve(M, lambda q: np.zeros(3), h=0.1, **kw)
    with pytest.raises(erkn.Error, match="unknown built-in potential"):
        erkn.solve(M, "cosh", h=0.1, **kw)
    with pytest.raises(erkn.Error, match="step-count limit"):
        erkn.solve(M, "sine", h=0.1, q0=q0, p0=p0, t_span=(0, 1e30))
    with pytest.raises(erkn.Error, match="not ascending"):
        erkn.solve(M, "sine", h=0.1, t_eval=[0.5, 0.2], **kw)


def test_a_python_exception_in_grad_propagates_and_leaves_the_state(chain):
    M, q0, p0 = chain
    calls = []

    def grad(q):
        calls.append(1)
        if len(calls) > 20:
            raise ZeroDivisionError("from grad")
        return np.sin(q)

    run = erkn.Integrator(M, grad, q0=q0, p0=p0, h=0.1)
    with pytest.raises(ZeroDivisionError, match="from grad"):
        run.integrate(10.0)
    t, q = run.t, run.q
    assert 0 < t < 10
    calls.clear()
    run.step()
    assert run.t == pytest.approx(t + 0.1) and not np.array_equal(run.q, q)


def test_a_failed_solve_keeps_the_output_before_the_failure(chain):
    M, q0, p0 = chain
    calls = []

    def grad(q):
        calls.append(1)
        if len(calls) > 200:
            raise ArithmeticError("gave up")
        return np.sin(q)

    with pytest.raises(ArithmeticError, match="gave up") as failure:
        erkn.solve(M, grad, q0=q0, p0=p0, t_span=(0, 100), h=0.1)
    sol = failure.value.solution
    full = erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 100), h=0.1)
    n = sol.t.size
    assert 2 < n < full.t.size and sol.q.shape == (n, 4)
    assert np.array_equal(sol.t, full.t[:n])
    assert np.abs(sol.q - full.q[:n]).max() < 1e-12
