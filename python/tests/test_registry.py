# The registry, tables and stability matrix, checked by properties over every method.
import json
import os
import subprocess

import numpy as np
import pytest

import erkn


def test_methods_lists_the_registry_with_unique_names():
    ms = erkn.methods()
    assert len(ms) >= 2
    names = [m["name"] for m in ms]
    assert len(set(names)) == len(names)
    for m in ms:
        assert m["kind"] in ("explicit", "erkn", "rkn")
        assert 1 <= m["stages"] and 2 <= m["order"]
        assert m["kind"] != "rkn" or m["poles"] == []
        # explicit methods are entire (no pole); the generalized order starts at the order
        assert m["kind"] != "explicit" or m["poles"] == []
        assert m["kind"] == "rkn" or m["generalized_order"][0] >= m["order"]


@pytest.mark.skipif("ERKN_CLI" not in os.environ, reason="the erkn CLI's path is not given")
def test_methods_carry_the_same_fields_and_values_as_erkn_list_json():
    listed = json.loads(subprocess.run([os.environ["ERKN_CLI"], "list", "--json"], check=True,
                                       capture_output=True, text=True).stdout)
    ours = erkn.methods()
    assert [m["name"] for m in ours] == [m["name"] for m in listed]
    for a, b in zip(ours, listed):
        assert set(a) == set(b), a["name"]
        for key in a:
            assert a[key] == pytest.approx(b[key], rel=1e-15) if key == "poles" else a[key] == b[key]


@pytest.mark.parametrize("m", erkn.methods(), ids=lambda m: m["name"])
def test_tableau_at_zero_meets_the_first_order_conditions(m):
    t = erkn.tableau(m["name"], 0.0)
    assert t["abar"].shape == (m["stages"], m["stages"])
    assert np.allclose(np.triu(t["abar"], 1), 0)
    assert t["b"].sum() == pytest.approx(1.0, abs=1e-13)      # b^T e = phi1(0)
    assert t["bbar"].sum() == pytest.approx(0.5, abs=1e-13)   # bbar^T e = phi2(0)
    assert t["b"] @ t["c"] == pytest.approx(0.5, abs=1e-13)   # b^T c = phi2(0)


def test_tableau_refuses_a_pole_and_a_negative_v():
    m = next(m for m in erkn.methods() if m["poles"])
    with pytest.raises(erkn.Error, match="pole"):
        erkn.tableau(m["name"], m["poles"][0])
    with pytest.raises(erkn.Error, match="negative"):
        erkn.tableau(m["name"], -1.0)
    with pytest.raises(erkn.Error, match="unknown method"):
        erkn.tableau("NoSuchMethod", 0.0)


@pytest.mark.parametrize("m", erkn.methods(), ids=lambda m: m["name"])
def test_stability_matrix_is_symplectic_and_classified(m):
    V, z = np.meshgrid(np.linspace(0, 2, 9), np.linspace(-0.2, 0.5, 5))
    st = erkn.stability(m["name"], V, z)
    assert st["S"].shape == V.shape + (2, 2)
    ok = np.isfinite(st["det"])
    assert np.abs(st["det"][ok] - 1).max() < 1e-10
    periodic = st["class"] == "periodic"
    assert periodic.any()
    assert np.all(np.abs(st["trace"][periodic]) < 2)
    assert np.all(st["rho"][periodic] == pytest.approx(1.0, abs=1e-6))
    # Negative control: V + z < 0 (the exact solution grows), at small h, is unstable.
    assert erkn.stability(m["name"], 0.1, -0.15)["class"] == "unstable"


def test_tableau_shows_the_processor_of_processed_methods():
    # pi^-1 as erkn tableau prints it: npre + 1 drifts, npre kicks, and the kernel's order; an
    # unprocessed method has none of these keys (negative control).
    processed = [m for m in erkn.methods() if m["processed"]]
    assert processed
    for m in erkn.methods():
        t = erkn.tableau(m["name"], 0.0)
        if not m["processed"]:
            assert "pre_drift" not in t, m["name"]
            continue
        assert t["kernel_order"] == m["kernel_order"] < m["order"]
        assert len(t["pre_drift"]) == len(t["pre_kick"]) + 1 == len(t["pre_modified"]) + 1
        assert any(x != 0 for x in t["pre_kick"])
