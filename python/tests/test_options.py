# erkn.Options: every field of erkn::Options reaches the C++ integrator, with C++'s validation;
# a refused value names the field and changes nothing.
import math
import re
import time

import numpy as np
import pytest

import erkn
from conftest import SOURCE_DIR

# Per field: a valid value other than the default, and values the C++ validation refuses (or,
# for a flag, a value of the wrong type).
VALID = {"tolerance": 1e-10, "roundoff_level": 1e-10, "max_fixed_point_iterations": 5,
         "max_theta": 0.5, "max_newton_iterations": 3, "compensated_summation": False,
         "pole_tolerance": 1e-3, "energy_tolerance": 1e-3, "check_stability": True,
         "blowup_guard": False}
INVALID = {"tolerance": [1.0, -1e-3, math.nan], "roundoff_level": [0.0, 1.0],
           "max_fixed_point_iterations": [0, -2], "max_theta": [1.0, 0.0, math.inf],
           "max_newton_iterations": [0], "compensated_summation": [1, "yes"],
           "pole_tolerance": [0.0, 1.5], "energy_tolerance": [-1.0, math.inf],
           "check_stability": [0, None], "blowup_guard": [1, "yes"]}


def cxx_fields():
    """The fields of struct Options in erkn/integrator.hpp."""
    header = (SOURCE_DIR / "runtime/include/erkn/integrator.hpp")
    body = header.read_text().split("struct Options {", 1)[1].split("};", 1)[0]
    return re.findall(r"^\s*(?:bool|int|double)\s+(\w+)\s*=", body, re.M)


def test_every_cxx_field_is_an_option_and_covered_here():
    assert list(erkn.Options.fields) == cxx_fields()
    assert set(VALID) == set(erkn.Options.fields) == set(INVALID)


@pytest.mark.parametrize("field", erkn.Options.fields)
def test_each_field_reaches_the_integrator(field, chain):
    M, q0, p0 = chain
    default = getattr(erkn.Options(), field)
    assert VALID[field] != default
    opts = erkn.Options(**{field: VALID[field]})
    assert getattr(opts, field) == VALID[field]
    run = erkn.Integrator(M, "sine", q0=q0, p0=p0, h=0.05, options=opts)
    assert getattr(run.options, field) == VALID[field]   # read back from the C++ Integrator
    assert run.options == opts
    other = erkn.Integrator(M, "sine", q0=q0, p0=p0, h=0.05, options={field: VALID[field]})
    assert other.options == opts
    assert getattr(erkn.Integrator(M, "sine", q0=q0, p0=p0, h=0.05).options, field) == default


@pytest.mark.parametrize("field", erkn.Options.fields)
def test_a_refused_value_names_the_field_and_changes_nothing(field, chain):
    M, q0, p0 = chain
    opts = erkn.Options(**{field: VALID[field]})
    for bad in INVALID[field]:
        with pytest.raises(erkn.Error, match=f"Options::{field}"):
            setattr(opts, field, bad)
        assert opts == erkn.Options(**{field: VALID[field]})
        with pytest.raises(erkn.Error, match=f"Options::{field}"):
            erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 1), h=0.1, options={field: bad})


def test_unknown_fields_and_wrong_containers_are_refused():
    with pytest.raises(erkn.Error, match="no field 'tol'"):
        erkn.Options(tol=1e-8)
    opts = erkn.Options()
    with pytest.raises(erkn.Error, match="no field 'max_thetta'"):
        opts.max_thetta = 0.5
    with pytest.raises(erkn.Error, match="erkn.Options or a dict"):
        erkn.solve(1.0, "sine", q0=[0.1], p0=[0.0], t_span=(0, 1), h=0.1, options=[1e-8])


def test_stage_solver_fields_change_the_work(chain):
    M, q0, p0 = chain
    kw = dict(q0=q0, p0=p0, t_span=(0, 5), h=0.2, method="SERKN2s4")
    base = erkn.solve(M, "sine", **kw)
    loose = erkn.solve(M, "sine", options=erkn.Options(tolerance=1e-4), **kw)
    assert loose.stats["stage_iterations"] < base.stats["stage_iterations"]
    assert base.stats["newton_fallbacks"] == 0
    newton = erkn.solve(M, "sine", options=dict(max_fixed_point_iterations=1), **kw)
    assert newton.stats["newton_fallbacks"] > 0
    assert np.abs(newton.q - base.q).max() < 1e-11
    plain = erkn.solve(M, "sine", options=dict(compensated_summation=False), **kw)
    assert not np.array_equal(plain.q, base.q) and np.abs(plain.q - base.q).max() < 1e-12


def pole_setup():
    """A method with a pole, and h with h^2 lambda 1e-4 (relative) above its first pole."""
    m = next(m for m in erkn.methods() if m["poles"])
    lam = 4.0
    return m["name"], lam, math.sqrt(m["poles"][0] * (1 + 1e-4) / lam)


def test_pole_tolerance_and_check_stability_refuse_an_h_the_defaults_accept():
    method, lam, h = pole_setup()
    kw = dict(q0=[0.1], p0=[0.0], h=h, method=method)
    erkn.Integrator(lam, "phi4", **kw)  # default pole_tolerance 1e-6: accepted
    with pytest.raises(erkn.Error, match="pole"):
        erkn.Integrator(lam, "phi4", options=erkn.Options(pole_tolerance=1e-3), **kw)
    with pytest.raises(erkn.Error, match="check_stability"):
        erkn.Integrator(lam, "phi4", check_stability=True, **kw)


def test_energy_tolerance_stops_a_run_that_drifts_and_keeps_its_output(chain):
    M, q0, p0 = chain
    kw = dict(q0=q0, p0=p0, t_span=(0, 5), h=0.2)
    free = erkn.solve(M, "sine", **kw)  # the run's own relative energy drift, step by step
    drift = np.abs(free.energy - free.energy[0]).max() / abs(free.energy[0])
    assert drift > 0
    assert erkn.solve(M, "sine", energy_tolerance=10 * drift, **kw).t[-1] == 5  # passes
    with pytest.raises(erkn.Error, match="energy monitor") as failure:
        erkn.solve(M, "sine", energy_tolerance=drift / 10, **kw)
    assert 0 < failure.value.solution.t.size < 26
    with pytest.raises(erkn.Error, match="needs System::potential"):
        erkn.solve(M, np.sin, energy_tolerance=1e-9, **kw)


def test_statistics_carry_the_wall_and_cpu_time_of_integrate_and_step(chain):
    M, q0, p0 = chain
    run = erkn.Integrator(M, "sine", q0=q0, p0=p0, h=0.1)
    assert run.statistics["wall_time"] == 0 and run.statistics["cpu_time"] == 0
    start = time.perf_counter()
    run.integrate(0.5, observer=lambda t, q, p: time.sleep(0.01))
    outside = time.perf_counter() - start
    st = run.statistics
    assert 0.05 <= st["wall_time"] <= outside
    assert st["cpu_time"] < 0.5 * st["wall_time"]  # asleep in the observer
    run.step(100)
    assert run.statistics["wall_time"] > st["wall_time"]
    sol = erkn.solve(M, "sine", q0=q0, p0=p0, t_span=(0, 10), h=0.01)
    assert 0 < sol.stats["cpu_time"] and 0 < sol.stats["wall_time"]
