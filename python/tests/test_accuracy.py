# erkn.solve(..., tol=): erkn chooses the method and h (erkn/accuracy.hpp); the achieved error
# lies within [tol/100, 3 tol]; a given method or h is kept; sol.choice says why.
import numpy as np
import pytest

import erkn

K = 0.03  # Duffing q'' + 100 q = k^2 (2 q^3 - q), q(0) = 0, q'(0) = 10: exact q = sn(10 t, k/10)


def duffing_reference(t_end):
    # sn by a fine run of the registry's highest-order explicit method, at h = 1/2000
    best = max((m for m in erkn.methods() if m["kind"] == "explicit"),
               key=lambda m: (m["order"], m["stages"]))
    return erkn.solve(100.0, erkn.potential("duffing", k=K), q0=[0.0], p0=[10.0],
                      t_span=(0, t_end), h=1 / 2000, method=best["name"]).q[-1]


@pytest.mark.parametrize("tol", [1e-5, 1e-8])
def test_tol_reaches_the_window_and_says_why(tol):
    ref = duffing_reference(10.0)
    sol = erkn.solve(100.0, erkn.potential("duffing", k=K), q0=[0.0], p0=[10.0],
                     t_span=(0, 10.0), tol=tol)
    error = np.abs(sol.q[-1] - ref).max()
    assert tol / 100 <= error <= 3 * tol, sol.choice["reason"]
    assert sol.choice["method"] == sol.method
    assert sol.choice["pilot_gradient_evaluations"] > 0 and sol.choice["reason"]
    assert [c["method"] for c in sol.choice["candidates"]][0] == sol.method or \
        any(c["piloted"] for c in sol.choice["candidates"])
    # negative control: the choice for 1000 tol takes a longer step and a larger error
    loose = erkn.solve(100.0, erkn.potential("duffing", k=K), q0=[0.0], p0=[10.0],
                       t_span=(0, 10.0), tol=1000 * tol)
    assert loose.choice["h"] > sol.choice["h"]
    assert np.abs(loose.q[-1] - ref).max() > error


def test_a_given_method_or_step_is_kept():
    kw = dict(q0=[0.0], p0=[10.0], t_span=(0, 10.0), tol=1e-6)
    name = next(m["name"] for m in erkn.methods() if m["kind"] == "explicit" and m["order"] == 4)
    assert erkn.solve(100.0, "duffing", method=name, **kw).method == name
    sol = erkn.solve(100.0, "duffing", h=0.01, **kw)
    assert sol.choice["h"] == 0.01 and np.isclose(sol.t[1] - sol.t[0], 0.01)


def test_without_tol_h_is_required_and_bad_tol_is_refused():
    kw = dict(q0=[0.0], p0=[10.0], t_span=(0, 1.0))
    with pytest.raises(erkn.Error, match="tol"):
        erkn.solve(100.0, "duffing", **kw)
    with pytest.raises(erkn.Error, match="tol"):
        erkn.solve(100.0, "duffing", tol=-1.0, **kw)
    with pytest.raises(erkn.Error, match="unknown method"):
        erkn.solve(100.0, "duffing", tol=1e-6, method="NoSuchMethod", **kw)


def test_methods_carry_the_error_constants():
    for m in erkn.methods():
        assert m["error_constant"] is None or m["error_constant"] > 0, m["name"]
        assert len(m["generalized_error_constant"]) == len(m["generalized_order"]), m["name"]
