# erkn.advise_step_size, erkn.hessian_bounds_at / hessian_bounds_along and erkn.Ensemble: the
# C++ advisor and ensemble reached from Python, checked against direct runs.

import numpy as np
import pytest

import erkn


def method_with_pole():
    m = next(m for m in erkn.methods() if m["poles"])
    return m["name"], m["poles"][0]


def test_advice_flags_a_pole_and_its_suggestion_is_safe():
    name, pole = method_with_pole()
    lam = np.array([1.0, 9.0])
    h = np.sqrt(pole / lam[1])  # h^2 lambda_2 on the pole
    advice = erkn.advise_step_size(name, lam, h)
    assert not advice.safe and advice.method == name and advice.h == h
    assert [f["hazard"] for f in advice.findings] == ["pole"]
    assert advice.findings[0]["index"] == 1 and advice.findings[0]["lambda"] == 9.0
    assert "pole" in advice.report and np.isfinite(advice.suggested_h)
    assert erkn.advise_step_size(name, lam, advice.suggested_h).safe
    # Negative control: a small h is safe, and the report says so.
    small = erkn.advise_step_size(name, lam, 0.1 * h)
    assert small.safe and small.findings == []


def fpu(m=3, omega=50.0):
    M = np.r_[np.zeros(m), np.full(m, omega**2)]
    q0 = np.r_[1.0, 0, 0, 1 / omega, 0, 0]
    p0 = np.r_[1.0, 0, 0, 1.0, 0, 0]
    return M, q0, p0


def test_hessian_bounds_along_a_run_contain_those_at_the_start():
    M, q0, p0 = fpu()
    name = erkn.methods()[0]["name"]
    at = erkn.hessian_bounds_at(M, "fpu", q0)
    assert erkn.hessian_bounds_along(name, M, "fpu", h=0.01, q0=q0, p0=p0, steps=0) == at
    along = erkn.hessian_bounds_along(name, M, "fpu", h=0.01, q0=q0, p0=p0, steps=500)
    assert along[0] <= at[0] and along[1] > at[1]
    # A Python gradient (finite differences) gives the built-in's bounds.
    s = erkn.system(M, "fpu", 6)
    fd = erkn.hessian_bounds_at(M, lambda q: s.gradient(q), q0)
    assert fd == pytest.approx(at, abs=1e-5)
    # advise_step_size takes the same bounds from grad and q0 (and along `hessian_steps`).
    assert erkn.advise_step_size(name, M, 0.01, "fpu", q0=q0).hessian == at
    assert erkn.advise_step_size(name, M, 0.01, "fpu", q0=q0, p0=p0,
                                 hessian_steps=500).hessian == along


def sine_gordon(n=32):
    dx = 2.0 / n
    col = np.zeros(n)
    col[0], col[1], col[-1] = 2 / dx**2, -1 / dx**2, -1 / dx**2
    q0 = np.full(n, np.pi)
    p0 = np.sqrt(n) * (0.01 + np.sin(2 * np.pi * np.arange(1, n + 1) / n))
    return erkn.circulant(col), q0, p0


def test_the_equations_own_growth_is_information_not_a_finding():
    # The sine-Gordon example of docs/python.md: at u = pi, M + Hessian has lambda + kappa = 0 - 1 < 0.
    M, q0, p0 = sine_gordon()
    for h in (0.025, 0.1):
        advice = erkn.advise_step_size("SERKN2s4", M, h, "sine", q0=q0, p0=p0)
        assert advice.safe and advice.findings == []
        assert [e["hazard"] for e in advice.equation] == ["the equation grows"]
        assert advice.equation[0]["lambda"] == 0 and advice.equation[0]["rate"] == pytest.approx(1)
        assert "differential equation itself grows" in advice.report
    # Negative control: a bounded Hessian range reports no growth.
    assert erkn.advise_step_size("SERKN2s4", M, 0.1, hessian_bounds=(0, 1)).equation == []


def test_mode_energies_sum_to_the_linear_energy_and_gate_resonances():
    M, q0, p0 = sine_gordon()
    e = erkn.mode_energies(M, q0, p0)
    dense = M.to_dense(32)
    assert e.shape == (17,) and e.sum() == pytest.approx(0.5 * p0 @ p0 + 0.5 * q0 @ dense @ q0)
    with pytest.raises(erkn.Error, match="mode_energies"):
        erkn.mode_energies(M, q0[:5], p0[:5])
    # FPU at h omega = pi: the stiff modes hold energy, so the resonance is flagged with the
    # state; an unexcited copy (p0 and q0 without the stiff part) is not flagged for resonance.
    Mf, qf, pf = fpu()
    h = np.pi / 50
    assert not erkn.advise_step_size("SERKN2s4", Mf, h, hessian_bounds=(0, 12),
                                     q0=qf, p0=pf).safe
    slow_q, slow_p = qf.copy(), pf.copy()
    slow_q[3:], slow_p[3:] = 0, 0
    quiet = erkn.advise_step_size("SERKN2s4", Mf, h, hessian_bounds=(0, 12), q0=slow_q, p0=slow_p)
    assert all(f["hazard"] != "resonance" for f in quiet.findings)


TRIAL = 2048  # steps of the trial, and of the whole run it judges
# The default margins (AdvisorOptions), read from the binding: energy_tolerance 0.5 over them.
TRIAL_MARGIN = erkn._erkn._AdvisorOptions().trial_margin
EXPLAINED_MARGIN = erkn._erkn._AdvisorOptions().explained_margin
SATURATED_MARGIN = erkn._erkn._AdvisorOptions().saturated_margin


def whole_run_error(problem, method, h):
    """The largest |H_n - H_0| / H_0 over TRIAL steps of the run without the blow-up guard (FPU:
    U(q0) >= 0, so H_0 is the trial's scale); inf when a step fails or H is not finite."""
    try:
        sol = erkn.solve(problem.M, problem.grad, q0=problem.q0, p0=problem.p0,
                         t_span=(0, TRIAL * h), h=h, method=method,
                         options={"blowup_guard": False})
    except erkn.Error:
        return np.inf
    error = np.abs(sol.energy - sol.energy[0]) / sol.energy[0]
    return error.max() if np.all(np.isfinite(error)) else np.inf


def advise_fpu(problem, method, h, **options):
    return erkn.advise_step_size(method, problem.M, h, problem.grad, q0=problem.q0,
                                 p0=problem.p0, max_change=0, **options)


def test_the_trial_run_flags_exactly_the_runs_beyond_the_limit():
    # With the problem, erkn.advise_step_size judges h by a trial run (erkn advise --problem's
    # C++ call). When the trial is the whole run (steps = trial_steps) it flags h exactly when
    # the run's own energy error reaches the trial's limit: energy_tolerance / saturated_margin
    # where the error has stopped growing (less than 1.5-fold over the trial's last 15/16),
    # else energy_tolerance / explained_margin where the linear model finds a resonance or an
    # unstable band ("explained"), else energy_tolerance / trial_margin: every method of the registry on FPU (omega = 50) at
    # h omega = 0.999 pi, where some blow up and some stay clean (both occur). Negative controls:
    # the linear model alone (trial_steps = 0) flags runs that stay clean; at h omega = 0.1 no
    # method is flagged.
    fpu = erkn.problems.fpu()
    h = 0.999 * np.pi / 50
    flagged = clean = linear_false_alarms = 0
    for m in erkn.methods():
        name = m["name"]
        advice = advise_fpu(fpu, name, h, steps=TRIAL, trial_steps=TRIAL)
        error = whole_run_error(fpu, name, h)
        trial = advice.trial
        linear = advise_fpu(fpu, name, h, trial_steps=0)
        explained = any(f["hazard"] != "pole" for f in linear.findings)
        saturated = trial["failure"] == "" and 0 < trial["error"] <= 1.5 * trial["early"]
        margin = (SATURATED_MARGIN if saturated else
                  EXPLAINED_MARGIN if explained else TRIAL_MARGIN)
        assert trial["saturated"] == saturated, (name, trial)
        assert trial["steps"] <= TRIAL and trial["horizon"] == TRIAL
        assert trial["explained"] == explained and trial["limit"] == 0.5 / margin, (name, trial)
        assert trial["flagged"] == (error >= trial["limit"]), (name, error, trial)
        if trial["flagged"]:
            assert not advice.safe
        else:  # (the linear model's findings are notes now; poles always flag)
            assert all(f["hazard"] == "pole" for f in advice.findings), (name, advice.report)
        flagged += trial["flagged"]
        clean += not trial["flagged"]
        assert linear.trial is None and linear.notes == []
        linear_false_alarms += not linear.safe and error < trial["limit"]
    assert flagged > 0 and clean > 0
    assert linear_false_alarms > 0
    for m in erkn.methods():
        calm = advise_fpu(fpu, m["name"], 0.1 / 50, steps=TRIAL, trial_steps=TRIAL)
        assert calm.safe and not calm.trial["flagged"], (m["name"], calm.report)


def test_trial_options_need_the_problem():
    M, q0, p0 = fpu()
    name = erkn.methods()[0]["name"]
    with pytest.raises(erkn.Error, match="trial_steps set the trial run"):
        erkn.advise_step_size(name, M, 0.01, "fpu", q0=q0, trial_steps=100)  # (no p0)
    with pytest.raises(erkn.Error, match="steps set the trial run"):
        erkn.advise_step_size(name, M, 0.01, "fpu", q0=q0, p0=p0, hessian_steps=5, steps=10)
    with pytest.raises(erkn.Error, match="potential set the trial run"):
        erkn.advise_step_size(name, M, 0.01, hessian_bounds=(0, 1), potential=lambda q: 0.0)
    with pytest.raises(erkn.Error, match="trial_steps"):
        erkn.advise_step_size(name, M, 0.01, "fpu", q0=q0, p0=p0, trial_steps=-1)


def test_advisor_refusals_name_the_problem():
    name, _ = method_with_pole()
    with pytest.raises(erkn.Error, match="no option 'degree'"):
        erkn.advise_step_size(name, 1.0, 0.1, degree=3)
    with pytest.raises(erkn.Error, match="needs q0"):
        erkn.advise_step_size(name, 1.0, 0.1, "sine")
    with pytest.raises(erkn.Error):
        erkn.advise_step_size(name, 1.0, -0.1)
    with pytest.raises(erkn.Error, match="steps"):
        erkn.hessian_bounds_along(name, 1.0, "sine", h=0.1, q0=[0.1], p0=[0.0], steps=-1)


def initial_data(n, d, seed=3):
    rng = np.random.default_rng(seed)
    return 0.5 * rng.standard_normal((n, d)), 0.5 * rng.standard_normal((n, d))


def test_ensemble_on_threads_equals_serial_runs_bit_for_bit(chain):
    M = chain[0]
    Q0, P0 = initial_data(7, 4)
    method = erkn.methods()[0]["name"]
    ens = erkn.Ensemble(M, "sine", q0=Q0, p0=P0, h=0.05, method=method)
    res = ens.integrate(3.0, threads=3)
    assert ens.size == 7 and res.ok.all() and np.all(res.t == 3.0)
    for i in range(7):
        run = erkn.Integrator(M, "sine", q0=Q0[i], p0=P0[i], h=0.05, method=method)
        run.integrate(3.0)
        assert np.array_equal(res.q[i], run.q) and np.array_equal(res.p[i], run.p)
        assert res.statistics[i]["steps"] == run.statistics["steps"]
    # Python gradients, called from the worker threads under the GIL, give the same states.
    py = erkn.Ensemble(M, lambda q: np.sin(q), q0=Q0, p0=P0, h=0.05, method=method)
    assert np.abs(py.integrate(3.0, threads=3).q - res.q).max() < 1e-13


def test_ensemble_failures_stay_with_their_trajectory(chain):
    M = chain[0]
    Q0, P0 = initial_data(4, 4)

    def fails(q):
        raise ZeroDivisionError("trajectory two")

    systems = [erkn.system(M, np.sin if i != 2 else fails, 4) for i in range(4)]
    res = erkn.Ensemble(systems=systems, q0=Q0, p0=P0, h=0.05).integrate(1.0, threads=2)
    assert list(res.ok) == [True, True, False, True]
    assert "trajectory two" in res.errors[2] and res.t[2] == 0
    assert np.array_equal(res.q[2], Q0[2])
    Q0[1, 0] = np.nan
    res = erkn.Ensemble(M, "sine", q0=Q0, p0=P0, h=0.05).integrate(1.0, threads=2)
    assert list(res.ok) == [True, False, True, True] and "q[0]" in res.errors[1]


def test_ensemble_of_systems_one_per_trajectory():
    omegas = [1.0, 4.0, 9.0]
    systems = [erkn.system(w, "duffing", 1) for w in omegas]
    res = erkn.Ensemble(systems=systems, q0=np.full((3, 1), 0.2), p0=np.zeros((3, 1)),
                        h=0.01).integrate(2.0)
    for i, w in enumerate(omegas):
        sol = erkn.solve(w, "duffing", q0=[0.2], p0=[0.0], t_span=(0, 2), h=0.01)
        assert np.array_equal(res.q[i], sol.q[-1])
    with pytest.raises(erkn.Error, match="2 systems for 3 trajectories"):
        erkn.Ensemble(systems=systems[:2], q0=np.zeros((3, 1)), p0=np.zeros((3, 1)), h=0.01)
    with pytest.raises(erkn.Error, match="either M and grad, or systems"):
        erkn.Ensemble(1.0, "sine", systems=systems, q0=np.zeros((3, 1)), p0=np.zeros((3, 1)),
                      h=0.01)


def test_ensemble_with_builtin_potentials_releases_the_gil(chain, longest_stall):
    M = chain[0]
    Q0, P0 = initial_data(4, 4)
    ens = erkn.Ensemble(M, "sine", q0=Q0, p0=P0, h=1e-3)
    # Holding the GIL for the run would stall this thread for about `alone`.
    t_end, alone = 1.0, 0.0
    while alone < 0.1:  # a run long enough to see a stall (0.02 to 0.7 s per 5.0 measured)
        t_end *= 2
        gap, alone = longest_stall(lambda: ens.integrate(t_end, threads=1))
    assert gap < 0.5 * alone, (gap, alone)
