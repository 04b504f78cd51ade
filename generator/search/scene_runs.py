"""A plain-kick splitting method run on a scene of erkn_design_benchmark
(bench/tolerance_scenes.hpp) in numpy, for a design objective at the scene's own tolerance: the
error at t_error after n steps.

q0, p0 and t_error are erkn.problems' (the C++ problems library's), so the erkn Python module
must be importable (PYTHONPATH=build/python); M's eigenvalues are formed as bench/scenes.hpp's
fourier_basis forms them. The run is the specialist's loop (bench/specialist_peer.hpp) in numpy:
the state in M's eigenbasis, the exact flow of q'' + M q = 0 over h (c_(i+1) - c_i), kicks
p -= h d_i grad U(Q_i), the last drift of a step merged with the first of the next (BAB's kicks
are not merged: the same error up to round-off). The reference is
the same run of SRKN14a, the steps doubled from 64 until two runs agree to 1e-13 (the
benchmark's reference is erkn's, to 1e-12). Scenes: SG2D and P1, the benchmark's scenes with a
Fourier basis; on P1 the fewest steps of ABA864, ABA1064, SD9(10,6,4), SRKN14a and SDT7(4) at
1e-4, 1e-6, 1e-8 are the benchmark's.
"""
import math

import numpy as np


class Scene:
    """lam: M's eigenvalues per spectral coefficient; forward/inverse: the eigenbasis transforms;
    grad: grad U in physical coordinates."""

    def __init__(self, key, lam, forward, inverse, grad, q0, p0, t_error):
        self.key, self.lam, self.forward, self.inverse = key, lam, forward, inverse
        self.grad, self.q0, self.p0, self.t_error = grad, q0, p0, t_error
        self.omega = np.sqrt(np.maximum(lam, 0.0))
        self.reference = None

    def flow(self, tau):
        """(cos, sin/omega, -omega sin) of the exact flow over tau, per coefficient
        (omega = 0: the free drift)."""
        w = self.omega
        wt = w * tau
        s_over_w = np.where(w > 0, np.sin(wt) / np.where(w > 0, w, 1.0), tau)
        return np.cos(wt), s_over_w, -w * np.sin(wt)

    def run(self, c, d, n):
        """q at t_error after n steps of the method (c, d)."""
        h = self.t_error / n
        s = len(c)
        drifts = [c[0]] + [c[i] - c[i - 1] for i in range(1, s)] + [1 - c[-1]]
        flows, Q, P = {}, self.forward(self.q0), self.forward(self.p0)
        for step in range(n):
            for i in range(s + 1):
                tau = drifts[i] * h
                if i == 0 and step > 0:  # merged into the previous step's last drift
                    tau = 0
                if i == s and step < n - 1:
                    tau += drifts[0] * h
                if tau != 0:
                    if tau not in flows:
                        flows[tau] = self.flow(tau)
                    a, b, e = flows[tau]
                    Q, P = a * Q + b * P, e * Q + a * P
                if i < s:
                    P = P - h * d[i] * self.forward(self.grad(self.inverse(Q)))
        return self.inverse(Q)

    def error(self, c, d, n):
        """Max norm of q - reference at t_error (inf if not finite)."""
        if self.reference is None:
            self.reference = reference(self)
        e = float(np.max(np.abs(self.run(c, d, n) - self.reference)))
        return e if math.isfinite(e) else math.inf

    def fewest_steps(self, c, d, tol, nmax=400):
        """The fewest n with error <= tol (None beyond nmax)."""
        for n in range(1, nmax + 1):
            if self.error(c, d, n) <= tol:
                return n
        return None


def reference(scene):
    import erkn
    t = erkn.tableau("SRKN14a")
    c, d = list(t["c"]), list(t["d"])
    n, last = 64, scene.run(c, d, 64)
    while True:
        n *= 2
        q = scene.run(c, d, n)
        if np.max(np.abs(q - last)) < 1e-13 or n > 8192:
            return q
        last = q


def sg2d():
    """2-D sine-Gordon 32^2 (problems.cpp's sine_gordon_2d): M = -Lap_h, periodic, L = 12."""
    import erkn
    pr = erkn.problems.sine_gordon_2d()
    n, dx = 32, 12.0 / 32
    k0 = np.arange(n)[:, None]
    k1 = np.arange(n // 2 + 1)[None, :]
    lam = 4 / dx**2 * (np.sin(np.pi * k0 / n) ** 2 + np.sin(np.pi * k1 / n) ** 2)
    return Scene("SG2D", lam, lambda q: np.fft.rfft2(q.reshape(n, n)),
                 lambda y: np.fft.irfft2(y, s=(n, n)).reshape(-1), np.sin,
                 np.asarray(pr.q0, float), np.asarray(pr.p0, float), pr.t_span[1])


def p1():
    """1-D sine-Gordon N = 32 (problems.cpp's sine_gordon): M the circulant of the periodic
    second difference, dx = 2 / N, t_error = 10."""
    import erkn
    pr = erkn.problems.sine_gordon(32)
    n, dx = 32, 2.0 / 32
    lam = (2 - 2 * np.cos(2 * np.pi * np.arange(n // 2 + 1) / n)) / dx**2
    return Scene("P1", lam, np.fft.rfft, lambda y: np.fft.irfft(y, n), np.sin,
                 np.asarray(pr.q0, float), np.asarray(pr.p0, float), pr.t_span[1])


SCENES = {"SG2D": sg2d, "P1": p1}
