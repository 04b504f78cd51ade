# Modified kicks from Python: the built-in potentials' Hessian-vector products (closed forms)
# against finite differences of |grad U|^2, a Python hessian_vector_product= callable, and the
# refusal of a system without one. Methods are taken from erkn.methods() by property.
import numpy as np
import pytest

import erkn

MODIFIED = [m["name"] for m in erkn.methods() if m["modified"]]
PLAIN_EXPLICIT = [m["name"] for m in erkn.methods() if m["kind"] == "explicit" and not m["modified"]]


def test_the_registry_lists_methods_with_modified_kicks():
    assert MODIFIED and PLAIN_EXPLICIT
    for m in erkn.methods():
        assert m["modified"] == [] or (m["kind"] == "explicit" and len(m["modified"]) == m["stages"])


def grad_norm2_derivative(system, q, e=1e-3):
    """d/dq_i |grad U|^2 by fourth-order central differences."""
    out = np.empty_like(q)
    for i in range(q.size):
        def at(k):
            x = q.copy()
            x[i] += k * e
            return float(np.sum(system.gradient(x) ** 2))
        out[i] = (8 * (at(1) - at(-1)) - (at(2) - at(-2))) / (12 * e)
    return out


@pytest.mark.parametrize("name", sorted(erkn.builtin_potentials()))
def test_builtin_closed_form_is_the_gradient_of_the_squared_gradient_norm(name):
    d = 6
    system = erkn.system(np.eye(d), name, d)
    q = np.random.default_rng(3).uniform(-1, 1, d)
    G = 2 * system.hessian_vector_product(q, system.gradient(q))
    fd = grad_norm2_derivative(system, q)
    scale = np.max(np.abs(G))
    assert np.max(np.abs(G - fd)) < 1e-8 * scale
    # negative control: G off by 1e-4 (relative) fails the same check
    assert np.max(np.abs((1 + 1e-4) * G - fd)) > 3e-5 * scale
    # and Hess U v agrees with the Hessian for any v
    v = np.random.default_rng(4).uniform(-1, 1, d)
    assert np.allclose(system.hessian_vector_product(q, v), system.hessian(q) @ v, atol=1e-14)


def duffing_grad(q):
    return 0.09 * (q - 2 * q**3)


def duffing_hvp(q, v):
    return 0.09 * (1 - 6 * q**2) * v


@pytest.mark.parametrize("method", MODIFIED)
def test_a_python_hessian_vector_product_runs_as_the_builtin_does(method):
    M, q0, p0 = np.array([100.0, 50.0]), np.array([0.3, -0.2]), np.array([10.0, 1.0])
    builtin = erkn.solve(M, erkn.potential("duffing", k=0.3), q0=q0, p0=p0, t_span=(0, 1), h=0.02,
                         method=method)
    ours = erkn.solve(M, duffing_grad, q0=q0, p0=p0, t_span=(0, 1), h=0.02, method=method,
                      hessian_vector_product=duffing_hvp)
    assert np.allclose(ours.q, builtin.q, rtol=0, atol=1e-13)
    assert ours.stats["hessian_vector_products"] == builtin.stats["hessian_vector_products"] > 0
    # control: a plain method forms no G
    plain = erkn.solve(M, duffing_grad, q0=q0, p0=p0, t_span=(0, 1), h=0.02,
                       method=PLAIN_EXPLICIT[0], hessian_vector_product=duffing_hvp)
    assert plain.stats["hessian_vector_products"] == 0


def test_a_system_without_the_modified_force_is_refused_naming_what_is_missing():
    for method in MODIFIED:
        with pytest.raises(erkn.Error, match="hessian_vector_product"):
            erkn.Integrator(100.0, duffing_grad, q0=[0.1], p0=[1.0], h=0.01, method=method)
    erkn.Integrator(100.0, duffing_grad, q0=[0.1], p0=[1.0], h=0.01, method=PLAIN_EXPLICIT[0])
    with pytest.raises(erkn.Error, match="hessian_vector_product must be a callable"):
        erkn.Integrator(100.0, duffing_grad, q0=[0.1], p0=[1.0], h=0.01, method=MODIFIED[0],
                        hessian_vector_product=3.0)


def test_a_bad_hessian_vector_product_fails_the_step_naming_it():
    with pytest.raises(erkn.Error, match=r"hessian_vector_product\(q, v\) must return"):
        erkn.solve(100.0, duffing_grad, q0=[0.1], p0=[1.0], t_span=(0, 0.1), h=0.01,
                   method=MODIFIED[0], hessian_vector_product=lambda q, v: np.zeros(3))
