# Inputs at the edges (issue 21), each refused with an erkn.Error that names it, or handled as
# documented. Every test here failed before its fix (a silent zero force, a truncated interval, a
# TypeError hiding erkn's message, an IndexError, an anonymous cast error).
import numpy as np
import pytest

import erkn

Q0, P0 = np.array([0.3, -0.2]), np.array([0.1, 0.4])


def test_grad_that_rebinds_out_is_refused():
    def rebinds(q, out):
        out = q**3  # noqa: F841 (the mistake under test: `out` is a new array, erkn's is unwritten)

    with pytest.raises(erkn.Error, match=r"grad\(q, out\) left entry 0 of out NaN"):
        erkn.solve(4.0, rebinds, q0=Q0, p0=P0, t_span=(0, 1), h=0.1)

    def writes(q, out):  # negative control: written in place
        out[:] = q**3

    sol = erkn.solve(4.0, writes, q0=Q0, p0=P0, t_span=(0, 1), h=0.1)
    ref = erkn.solve(4.0, lambda q: q**3, q0=Q0, p0=P0, t_span=(0, 1), h=0.1)
    assert np.array_equal(sol.q, ref.q)


def test_hessian_that_rebinds_out_is_refused():
    def hessian(q, out):
        out = np.diag(3 * q**2)  # noqa: F841

    system = erkn.system(4.0, lambda q: q**3, 2, hessian=hessian)
    with pytest.raises(erkn.Error, match=r"hessian\(q, out\) left entry 0"):
        system.hessian(Q0)


@pytest.mark.parametrize("every", [2.5, 0, -1, 10**30, "2", None, float("nan")])
def test_every_must_be_a_whole_number_of_steps(every):
    with pytest.raises(erkn.Error, match="every must be an integer"):
        erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1, every=every)


def test_every_accepts_integral_values():
    a = erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1, every=2)
    b = erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1, every=2.0)
    c = erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1, every=np.int64(2))
    assert np.array_equal(a.t, b.t) and np.array_equal(a.t, c.t) and a.t.size == 6


def test_wrong_t_eval_raises_erkns_error_not_a_type_error():
    with pytest.raises(erkn.Error, match="t_eval must be a 1-D array") as info:
        erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1, t_eval=np.zeros((2, 2)))
    assert not hasattr(info.value, "solution")  # (no step was taken: nothing to keep)


def test_a_failed_run_carries_its_own_partial_output():
    run = erkn.Integrator(4.0, "phi4", q0=Q0, p0=P0, h=0.1)
    with pytest.raises(erkn.Error):
        run.run(1.0, t_eval=[0.5, 0.2])  # not ascending
    with pytest.raises(erkn.Error):
        run.run(1.0, t_eval=np.zeros((2, 2)))
    assert run._partial is None  # (the first failure's output is not the second's)


def test_solution_repr_with_no_times():
    sol = erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1, t_eval=[])
    assert sol.t.size == 0 and sol.q.shape == (0, 2)
    assert repr(sol) == f"erkn.Solution(method={erkn._DEFAULT_METHOD!r}, 0 times, d=2)"  # default
    full = erkn.solve(4.0, "phi4", q0=Q0, p0=P0, t_span=(0, 1), h=0.1)
    assert "11 times in [0, 1]" in repr(full)


@pytest.mark.parametrize("value", ["1.5", None, [1.0, 2.0], 1j, object()])
def test_potential_returning_a_non_float_names_the_callback(value):
    with pytest.raises(erkn.Error, match=r"potential\(q\) must return a float"):
        erkn.solve(4.0, lambda q: q**3, potential=lambda q: value, q0=Q0, p0=P0, t_span=(0, 1),
                   h=0.1)


def test_potential_may_return_a_numpy_scalar():
    sol = erkn.solve(4.0, lambda q: q**3, potential=lambda q: np.float64(0.25) * (q**4).sum(),
                     q0=Q0, p0=P0, t_span=(0, 1), h=0.1)
    assert np.isfinite(sol.energy).all()


def test_grid_with_overflowing_eigenvalues_or_too_many_unknowns_is_refused():
    with pytest.raises(erkn.Error, match="spacing 1e-200"):
        erkn.grid([(8, 1e-200, "periodic")])
    with pytest.raises(erkn.Error, match="1000000000000 unknowns"):
        erkn.grid([(10**6, 1.0, "periodic"), (10**6, 1.0, "periodic")])


def test_state_at_infinity_is_refused():
    run = erkn.Integrator(4.0, "phi4", q0=Q0, p0=P0, h=0.1)
    run.step()
    q = run.q
    for t in (np.inf, -np.inf, np.nan):
        with pytest.raises(erkn.Error, match="not finite"):
            run.state_at(t)
    assert np.array_equal(run.q, q) and run.t == pytest.approx(0.1)
