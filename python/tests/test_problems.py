# erkn.problems: the C++ problems library's definitions, one line each; their invariants are
# conserved by short runs to the method's order, and they agree with the built-in potentials.
import numpy as np
import pytest

import erkn

# (constructor, step sizes (halving), span): the spans are short, the steps resolve the
# nonlinear parts so that the energy error shows the method's order above round-off.
PROBLEMS = [
    (erkn.problems.fpu, 0.04, 2.0),
    (erkn.problems.henon_heiles, 0.2, 10.0),
    (lambda: erkn.problems.sine_gordon(16), 0.1, 2.0),
    (lambda: erkn.problems.duffing(5.0), 0.04, 2.0),
    (lambda: erkn.problems.stellar_orbits(0.1), 0.2, 5.0),
    (lambda: erkn.problems.klein_gordon(7, 2), 0.1, 1.0),
    (lambda: erkn.problems.sine_gordon_2d(8), 0.1, 1.0),
]


def explicit_of_order(order):
    return next(m["name"] for m in erkn.methods()
                if m["kind"] == "explicit" and m["order"] == order)


@pytest.mark.parametrize("make,h,t1", PROBLEMS, ids=lambda x: getattr(x, "__name__", ""))
def test_energy_is_conserved_to_the_methods_order(make, h, t1):
    p = make()
    assert p.q0.shape == p.p0.shape == (p.dim,) and p.invariant_names[0] == "H"
    assert p.exact_invariant["H"]
    for order in (2, 4):
        method = explicit_of_order(order)
        errors = []
        for k in range(3):
            sol = p.solve(h=h / 2**k, method=method, t_span=(0, t1), every=1)
            H = p.invariants(sol.q, sol.p)["H"]
            errors.append(np.abs(H - H[0]).max() / max(abs(H[0]), 1.0))
        slope = np.polyfit(np.log(h / 2.0 ** np.arange(3)), np.log(errors), 1)[0]
        assert errors[-1] > 1e-13, f"{p.key} {method}: round-off, no slope ({errors})"
        assert abs(slope - order) <= 0.5, f"{p.key} {method}: slope {slope:.2f}, {errors}"
    # negative control: H at a perturbed state is not H at the start
    H0 = p.invariants(p.q0, p.p0)["H"]
    assert abs(p.invariants(p.q0, 1.01 * p.p0 + 0.01)["H"] - H0) > 1e-6


def test_fpu_layout_and_its_oscillatory_energies():
    m, omega = 3, 50.0
    p = erkn.problems.fpu(m, omega)
    assert p.invariant_names == ["H", "I_1", "I_2", "I_3", "I"]
    assert not p.exact_invariant["I"]
    assert np.array_equal(p.M.eigenvalues, np.r_[np.zeros(m), np.full(m, omega**2)])
    assert p.q0[0] == 1 and p.p0[0] == 1 and p.q0[m] == 1 / omega and p.p0[m] == 1
    inv = p.invariants(p.q0, p.p0)
    assert inv["I_1"] == pytest.approx(0.5 * (1 + omega**2 / omega**2)) and inv["I_2"] == 0
    assert inv["I"] == pytest.approx(inv["I_1"] + inv["I_2"] + inv["I_3"])
    # I is adiabatic: it stays within O(1/omega) while energy flows from I_1 to I_2, I_3
    sol = p.solve(h=0.01, method=explicit_of_order(4), t_span=(0, 200), every=100)
    I = p.invariants(sol.q, sol.p)
    assert np.abs(I["I"] - I["I"][0]).max() < 10 / omega
    assert I["I_2"].max() > 0.05  # (negative control: the single I_j are not conserved)


def test_the_problems_potentials_are_the_built_in_ones():
    rng = np.random.default_rng(3)
    cases = [(erkn.problems.fpu(4), "fpu"), (erkn.problems.sine_gordon(8), "sine"),
             (erkn.problems.duffing(0.5), erkn.potential("duffing", k=0.5))]
    for p, builtin in cases:
        q = rng.standard_normal(p.dim)
        s = erkn.system(p.M, builtin, p.dim)
        assert np.array_equal(s.gradient(q), p.grad.gradient(q))
        assert s.potential(q) == p.grad.potential(q)
        assert np.array_equal(s.hessian(q), p.grad.hessian(q))


def test_duffing_exact_solution_and_klein_gordon_layout():
    p = erkn.problems.duffing()
    assert p.has_exact and p.exact(0.0)[0] == 0
    sol = p.solve(h=0.001, method=explicit_of_order(4), t_eval=[1.0, 2.0])
    assert np.abs(sol.q - p.exact(np.array([1.0, 2.0]))).max() < 1e-8
    with pytest.raises(erkn.Error, match="no exact solution"):
        erkn.problems.fpu().exact(1.0)
    kg = erkn.problems.klein_gordon(5, 2)
    x = np.arange(1, 6) / 6
    u0 = 2 * np.outer(np.sin(np.pi * x), np.sin(np.pi * x)) + np.exp(
        -100 * ((x[:, None] - 0.3) ** 2 + (x[None, :] - 0.4) ** 2))
    assert np.abs(kg.q0 - u0.ravel()).max() < 1e-14  # row-major, the last axis fastest
    assert kg.M.structure == "grid" and kg.M.dim == 25


def test_bad_parameters_are_refused_with_erkn_errors():
    with pytest.raises(erkn.Error, match="Henon-Heiles energy"):
        erkn.problems.henon_heiles(0.5)
    with pytest.raises(erkn.Error, match="dims = 1, 2 or 3"):
        erkn.problems.klein_gordon(4, 5)
    with pytest.raises(erkn.Error, match="dimension 2; q0 has 3"):
        p = erkn.problems.henon_heiles()
        erkn.solve(p.M, p.grad, q0=[0, 0, 0], p0=[0, 0, 0], t_span=(0, 1), h=0.1)


def test_the_python_guide_examples_run(tmp_path, monkeypatch):
    # (the sine-Gordon example, moved there from the README, writes its plot into the cwd)
    from conftest import SOURCE_DIR
    text = (SOURCE_DIR / "docs" / "python.md").read_text()
    blocks = [b.split("```", 1)[0] for b in text.split("```python\n")[1:]]
    assert len(blocks) == 3
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("MPLBACKEND", "Agg")
    scope = {}
    for block in blocks:
        exec(compile(block, "docs/python.md", "exec"), scope)
    assert (tmp_path / "sine_gordon.png").stat().st_size > 10000
    assert len(scope["section"][0]) > 100 and scope["I"]["I"].size > 1
