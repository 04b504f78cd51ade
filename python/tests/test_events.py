# Events (erkn.solve(events=...)): zeros of g(t, q, p) located on the method's own shorter step,
# with SciPy's direction and terminal; crossing times converge at the method's order.
import math

import numpy as np
import pytest

import erkn

# Duffing q'' + 100 q = k^2 (2 q^3 - q), q(0) = 0, q'(0) = 10: q = sn(10 t, k/10) exactly, so q
# rises through 0 at 10 t = 4 K j and falls at 10 t = 2 K + 4 K j (K: the quarter period). A
# large k makes the nonlinear part, and so the methods' errors, visible.
K_DUFFING = 5.0


def quarter_period(modulus):
    """K(modulus) = pi / (2 agm(1, sqrt(1 - modulus^2)))."""
    a, b = 1.0, math.sqrt(1 - modulus * modulus)
    while abs(a - b) > 1e-16 * a:
        a, b = (a + b) / 2, math.sqrt(a * b)
    return math.pi / (2 * a)


def duffing(h, method, events, t1=3.0, **kw):
    return erkn.solve(100.0, erkn.potential("duffing", k=K_DUFFING), q0=[0.0], p0=[10.0],
                      t_span=(0, t1), h=h, method=method, events=events, **kw)


def q_zero(direction=0, terminal=False):
    def g(t, q, p):
        return q[0]
    g.direction, g.terminal = direction, terminal
    return g


def exact_zeros(direction, t1=3.0):
    K = quarter_period(K_DUFFING / 10)
    first = {1: 4 * K, -1: 2 * K}[direction]
    return np.arange(first, 10 * t1, 4 * K) / 10


def methods_by_order():
    """The first method of each (kind, certified order) of the registry, ERKN and explicit
    alike: the property tested is the order, not a name."""
    chosen = {}
    for m in erkn.methods():
        if m["kind"] != "rkn":
            chosen.setdefault((m["kind"], m["order"]), m)
    return sorted(chosen.values(), key=lambda m: (m["order"], m["kind"]))


def henon_heiles_grad(q, out):
    out[0] = 2 * q[0] * q[1]
    out[1] = q[0] ** 2 - q[1] ** 2


def henon_heiles_hessian_vector_product(q, v):
    """Hess U(q) v for U = x^2 y - y^3 / 3 (for the methods with modified kicks)."""
    return np.array([2 * q[1] * v[0] + 2 * q[0] * v[1], 2 * q[0] * v[0] - 2 * q[1] * v[1]])


def henon_heiles_crossings(method, h, t1=30.0):
    """Times where q1 rises through 0 (a Poincare section) from q = (0, 0.1), H = 0.13."""
    y0 = 0.1
    p1 = math.sqrt(2 * (0.13 - (y0 * y0 / 2 - y0**3 / 3)))
    return erkn.solve(1.0, henon_heiles_grad, q0=[0.0, y0], p0=[p1, 0.0], t_span=(0, t1), h=h,
                      method=method, events=[q_zero(+1)],
                      hessian_vector_product=henon_heiles_hessian_vector_product).t_events[0]


def test_direction_selects_rising_or_falling_zeros_and_zero_takes_both():
    method = methods_by_order()[-1]["name"]
    rising = duffing(0.01, method, [q_zero(+1)]).t_events[0]
    falling = duffing(0.01, method, [q_zero(-1)]).t_events[0]
    both = duffing(0.01, method, [q_zero(0)]).t_events[0]
    assert len(rising) == len(exact_zeros(1)) and len(falling) == len(exact_zeros(-1))
    assert np.abs(rising - exact_zeros(1)).max() < 1e-3
    assert np.abs(falling - exact_zeros(-1)).max() < 1e-3
    assert np.array_equal(np.sort(np.concatenate([rising, falling])), both)
    # negative control: the rising zeros are not the falling ones
    assert np.abs(rising[:3] - exact_zeros(-1)[:3]).min() > 0.05


@pytest.fixture(scope="module")
def crossings_reference():
    best = max((m for m in erkn.methods() if m["kind"] == "explicit"), key=lambda m: m["order"])
    return henon_heiles_crossings(best["name"], 0.005)


@pytest.mark.parametrize("m", methods_by_order(), ids=lambda m: m["name"])
def test_crossing_times_converge_at_the_methods_order(m, crossings_reference):
    # Henon-Heiles (not Duffing, where every symmetric method of order 3 shows order 4): h
    # halves from 0.4 until the error is below 1e-10 with three points above the reference's
    # round-off (1e-12); the slope of the last three is the measured order.
    hs, errors = [], []
    for k in range(9):
        h = 0.4 * 2.0**-k
        t = henon_heiles_crossings(m["name"], h)
        assert len(t) == len(crossings_reference), f"h = {h}: {t}"
        hs.append(h)
        errors.append(np.abs(t - crossings_reference).max())
        usable = [e for e in errors if e > 1e-12]
        if errors[-1] < 1e-10 and len(usable) >= 3:
            break
    usable = [(h, e) for h, e in zip(hs, errors) if e > 1e-12][-3:]
    slope = np.polyfit(*np.log(np.array(usable).T), 1)[0]
    assert abs(slope - m["order"]) <= 0.3, f"{m['name']}: slope {slope:.2f}, errors {errors}"


def test_located_state_is_the_methods_own_and_the_trajectory_is_unchanged():
    method = methods_by_order()[-1]["name"]
    plain = duffing(0.05, method, None)
    sol = duffing(0.05, method, [q_zero(+1), q_zero(-1)])
    assert np.array_equal(plain.q, sol.q) and np.array_equal(plain.t, sol.t)
    assert np.abs(np.concatenate(sol.q_events)).max() < 1e-12  # g = q[0] = 0 there
    assert sol.status == 0 and sol.stats["events"]["gradient_evaluations"] > 0
    assert sol.y_events[0].shape == (len(sol.t_events[0]), 2)
    # the state at an event is the run's own: a step of the method from the last grid point
    t_e = sol.t_events[0][0]
    run = erkn.Integrator(100.0, erkn.potential("duffing", k=K_DUFFING), q0=[0.0], p0=[10.0],
                          h=0.05, method=method)
    run.step(int(t_e // 0.05))
    q, p = run.state_at(t_e)
    assert np.array_equal(q, sol.q_events[0][0]) and np.array_equal(p, sol.p_events[0][0])


def test_a_terminal_event_stops_the_run_at_its_time_and_state():
    method = methods_by_order()[-1]["name"]
    sol = duffing(0.01, method, [q_zero(-1, terminal=True), q_zero(+1)])
    first_fall = exact_zeros(-1)[0]
    assert sol.status == 1 and abs(sol.t[-1] - first_fall) < 1e-6
    assert sol.t[-1] == sol.t_events[0][0] and len(sol.t_events[0]) == 1
    assert np.array_equal(sol.q[-1], sol.q_events[0][0])
    assert len(sol.t_events[1]) == 0  # (the first rising zero comes later)
    # with t_eval: only the times up to the event are output
    t_eval = np.linspace(0, 3, 31)
    cut = duffing(0.01, method, [q_zero(-1, terminal=True)], t_eval=t_eval)
    assert cut.status == 1 and np.array_equal(cut.t, t_eval[t_eval <= first_fall])
    # negative control: without terminal the run reaches t1
    assert duffing(0.01, method, [q_zero(-1)]).t[-1] == 3.0


def test_bad_events_are_refused_naming_the_event():
    method = methods_by_order()[-1]["name"]
    with pytest.raises(erkn.Error, match="event 1 must be a callable"):
        duffing(0.01, method, [q_zero(), 3.0])
    with pytest.raises(erkn.Error, match="event 0: g.*real number; got str"):
        duffing(0.01, method, [lambda t, q, p: "x"])
    g = q_zero()
    g.terminal = "yes"
    with pytest.raises(erkn.Error, match="event 0's terminal"):
        duffing(0.01, method, [g])


def test_an_exception_in_g_keeps_the_output_and_events_so_far():
    method = methods_by_order()[-1]["name"]

    def g(t, q, p):
        if t > 1.0:
            raise RuntimeError("stop here")
        return q[0]

    with pytest.raises(RuntimeError, match="stop here") as info:
        duffing(0.01, method, [g])
    sol = info.value.solution
    assert 0.98 <= sol.t[-1] <= 1.0 and len(sol.t_events[0]) == len(exact_zeros(1, 1.0)) + len(
        exact_zeros(-1, 1.0))
