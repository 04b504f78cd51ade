#!/usr/bin/env python3
"""Finds SERKN4s6, a 4-stage diagonal implicit symplectic ERKN method of order 6 with constant
diagonal abar_ii (entire coefficients, no poles). The generator certifies it (order 6); it is not
in methods.spec yet because the runtime order test cannot resolve order 6 (issue 8 notes).

Its V -> 0 limit is a symplectic diagonally implicit RKN method: b = d, bbar = d (1 - c),
a_ij = d_j (c_i - c_j) (j < i), a_ii free. This script solves the classical order conditions of
that limit, sum_i d_i Phi_i(t) = 1/gamma(t) over the special Nystrom trees t of order <= 6, for a
symmetric method c = (x1, x2, 1-x2, 1-x1), d = (y1, 1/2-y1, 1/2-y1, y1), a = (z1, z2, z2, z1):
Levenberg-Marquardt in double from random starts, then Newton in 100 digits (mpmath). The
generator certifies the ERKN method built from it over the SEN-trees (generated/derivation.md):
with constant abar_ii the conditions at higher powers of V hold as well.

Usage: python3 order6_four_stages.py [starts]   (needs mpmath; Debian: python3-mpmath)
"""
import functools
import itertools
import random
import sys

from mpmath import mp, mpf


@functools.lru_cache(None)
def trees(rho):
    """Special Nystrom trees of order rho: (p-leaves, sorted subtrees under meagre vertices)."""
    def costs(n, largest):  # multisets of subtree costs 1 + rho(sub) >= 2 summing to n
        if n == 0:
            yield ()
            return
        for first in range(min(n, largest), 1, -1):
            for rest in costs(n - first, first):
                yield (first,) + rest
    out = set()
    for leaves in range(rho):
        for cs in costs(rho - 1 - leaves, rho - 1 - leaves):
            for subs in itertools.product(*[trees(c - 1) for c in cs]):
                out.add((leaves, tuple(sorted(subs))))
    return sorted(out)


def order(t):
    return 1 + t[0] + sum(1 + order(s) for s in t[1])


def gamma(t):
    g = order(t)
    for s in t[1]:
        g *= (1 + order(s)) * gamma(s)
    return g


def method(x, one):
    x1, x2, y1, z1, z2 = x
    c = [x1, x2, one - x2, one - x1]
    d = [y1, one / 2 - y1, one / 2 - y1, y1]
    a = [z1, z2, z2, z1]
    A = [[d[j] * (c[i] - c[j]) if j < i else (a[i] if j == i else 0 * one) for j in range(4)]
         for i in range(4)]
    return c, d, A


def residuals(x, one):
    c, d, A = method(x, one)
    memo = {}

    def phi(t):  # elementary weights Phi_i(t)
        if t not in memo:
            v = [c[i] ** t[0] for i in range(4)]
            for s in t[1]:
                w = phi(s)
                v = [v[i] * sum(A[i][j] * w[j] for j in range(i + 1)) for i in range(4)]
            memo[t] = v
        return memo[t]
    return [sum(d[i] * phi(t)[i] for i in range(4)) - one / gamma(t)
            for rho in range(1, 7) for t in trees(rho)]


def solve(M, g):
    """Gaussian elimination with partial pivoting (floats or mpf)."""
    n = len(g)
    M = [row[:] + [g[i]] for i, row in enumerate(M)]
    for col in range(n):
        piv = max(range(col, n), key=lambda r: abs(M[r][col]))
        if M[piv][col] == 0:
            return None
        M[col], M[piv] = M[piv], M[col]
        for r in range(col + 1, n):
            f = M[r][col] / M[col][col]
            M[r] = [a - f * b for a, b in zip(M[r], M[col])]
    x = [0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (M[r][n] - sum(M[r][k] * x[k] for k in range(r + 1, n))) / M[r][r]
    return x


def newton(x, one, steps, damping=0.0):
    """Gauss-Newton (Levenberg-Marquardt for damping > 0) on the least-squares residual."""
    for _ in range(steps):
        r = residuals(x, one)
        h = one / 10 ** (7 if one == 1.0 else 60)
        J = []
        for k in range(5):
            xp = list(x)
            xp[k] += h
            J.append([(a - b) / h for a, b in zip(residuals(xp, one), r)])
        M = [[sum(a * b for a, b in zip(J[i], J[j])) * (1 + (damping if i == j else 0))
              for j in range(5)] for i in range(5)]
        dx = solve(M, [-sum(a * b for a, b in zip(J[i], r)) for i in range(5)])
        if dx is None:
            return x
        x = [x[k] + dx[k] for k in range(5)]
    return x


def main():
    starts = int(sys.argv[1]) if len(sys.argv) > 1 else 200
    random.seed(1)
    for _ in range(starts):
        x = [random.uniform(0, 1), random.uniform(0, 1), random.uniform(0, 0.5),
             random.uniform(0, 0.1), random.uniform(0, 0.1)]
        try:
            x = newton(newton(x, 1.0, 20, damping=1e-2), 1.0, 20)
        except (OverflowError, ZeroDivisionError):
            continue
        if max(abs(v) for v in residuals(x, 1.0)) < 1e-10 and 0 < x[0] < x[1] < 1:
            break
    else:
        sys.exit("no solution with 0 < x1 < x2 < 1 from %d starts" % starts)
    mp.dps = 100
    x = newton([mpf(v) for v in x], mpf(1), 12)
    print("max residual over the %d trees: %s" % (sum(len(trees(r)) for r in range(1, 7)),
                                                mp.nstr(max(abs(v) for v in residuals(x, mpf(1))), 3)))
    for name, v in zip(["x1", "x2", "y1", "z1", "z2"], x):
        print(name, mp.nstr(v, 70))


if __name__ == "__main__":
    main()
