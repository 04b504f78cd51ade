#!/usr/bin/python3
"""Designs a plain-kick splitting method for cells of erkn_design_benchmark (a scene and a
tolerance each) from the scenes' own error, not the h -> 0 error constants: inside a family's
feasible set (splitting_family.py: s kicks, the conditions of the claimed order imposed), the
free parameters minimize max_k log(error_k / tol_k), error_k the max-norm error of q at the
scene's t_error after n_k steps (scene_runs.py, the scene's own data), and after every step
count up to the benchmark's first scan point >= n_k (its scan, n = ceil(2 * 2^(j/8)), stops at
the first passing point and bisects below it: a dip at n_k alone is not found). The step count
is an integer: a method with as many kicks that reaches tol in n - 1 steps where another needs
n costs (n - 1) / n of it. Several cells, of one scene or of several, make one design.

Deterministic: from a registry method of the family's stage count (projected onto the
conditions by Gauss-Newton), Nelder-Mead in the coordinates of the conditions' tangent space
at that point (each trial point projected back onto the conditions), restarted a fixed number
of times from the best point (the simplex halved after a restart that did not improve). Prints
the result as a methods.spec block (17 significant digits: erkn-generate polishes them onto the
conditions and certifies); generator/methods.spec (and, for those not in the registry,
generator/search/designed_at_tolerance.spec) hold the blocks it printed.

  PYTHONPATH=build/python /usr/bin/python3 generator/search/design_at_tolerance.py DESIGN

DESIGN is one of DESIGNS below. Needs the erkn Python module (the scenes' data and the start's
table), Debian's python3-numpy, python3-scipy.
"""
import argparse
import math
import os
import sys
from collections import namedtuple

import numpy as np
from scipy.linalg import null_space
from scipy.optimize import minimize

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import scene_runs  # noqa: E402
import search_core  # noqa: E402
import sen_conditions as sc  # noqa: E402
from splitting_family import Family  # noqa: E402

# A design: the family (stages, layout, order), the registry method it starts from, the cells it
# aims at, and its passes of Nelder-Mead: (objective, simplex size) each.
Design = namedtuple("Design", "stages layout order start targets passes")

# SDT = designed at a tolerance by this search; the family is classical order `order` only (the
# start's generalized or order-6 conditions released: six free directions for 9 kicks, four for
# 7, eight for SRKN11b's 12).
DESIGNS = {
    # SG2D at 1e-10 in 6 steps of 11 gradients (12 kicks, BAB; SRKN11b needs 8, PMLF6 14).
    "SDT11b(4)": Design(12, "BAB", 4, "SRKN11b", [("SG2D", 6, 1e-10)], [("worst", 0.01)]),
    # SG2D at 1e-10 in 8 steps of 9 kicks (SD9 needs 9; superseded by SDT11b(4)).
    "SDT9(4)": Design(9, "ABA", 4, "SD9(10,6,4)", [("SG2D", 8, 1e-10)], [("worst", 0.01)]),
    # SG2D at 1e-8 in 4 steps of 7 kicks (ABA864 needs 6, SRKN6b 6 of 6 gradients).
    "SDT7(4)": Design(7, "ABA", 4, "ABA864", [("SG2D", 4, 1e-8)], [("worst", 0.03)]),
    # SG2D at 1e-6 in 2 steps and at 1e-8 in 4 (7 kicks; ABA1064 needs 2 steps of 8, SRKN6b 6 of
    # 6): two passes on the worst ratio stall at 0.40 and 1.02, the third spends the first's
    # slack (1e-6 held at 0.9 tol).
    "SDT7x(4)": Design(7, "ABA", 4, "ABA864", [("SG2D", 2, 1e-6), ("SG2D", 4, 1e-8)],
                       [("worst", 0.1), ("worst", 0.1), ("last within", 0.01)]),
}


def next_scan(n):
    """erkn_design_benchmark's first scan point >= n (bench/design_benchmark.cpp)."""
    j = 0
    while math.ceil(2 * 2 ** (j / 8)) < n:
        j += 1
    return math.ceil(2 * 2 ** (j / 8))


class Problem:
    """The family's conditions and the scenes' errors at the targets."""

    def __init__(self, design):
        self.targets = design.targets
        self.fam = Family(design.stages, design.layout, design.order, [design.order])
        self.scenes = {key: scene_runs.SCENES[key]() for key, _, _ in self.targets}
        self.free = self.fam.free()

    def imposed(self, x):
        c, d = self.fam.method(list(x))
        return np.array(self.fam.imposed(sc.residuals(c, d, self.fam.max_power, kmax=3)))

    def ratios(self, x):
        """Per target, max error(n) / tol_k over n_k <= n <= next_scan(n_k)."""
        c, d = self.fam.method(list(x))
        return [max(self.scenes[key].error(c, d, m) for m in range(n, next_scan(n) + 1)) / tol
                for key, n, tol in self.targets]


def start_point(problem, name):
    """The registry method's first-half nodes (without c_1 = 0 for BAB) and weights."""
    import erkn
    t = erkn.tableau(name)
    c, d, fam = list(t["c"]), list(t["d"]), problem.fam
    first = 1 if fam.layout == "BAB" else 0
    x = np.array(c[first:first + fam.n_nodes] + d[:fam.n_weights])
    return search_core.onto_conditions(problem, x)


def tangent(problem, x, h=1e-7):
    """An orthonormal basis of the null space of the independent conditions' Jacobian at x."""
    rows = search_core.independent_rows(problem, x)
    r0 = problem.imposed(x)
    J = np.array([(problem.imposed(x + h * e) - r0) / h for e in np.eye(len(x))]).T
    return null_space(J[rows])


def worst(ratios):
    """The objective of most passes: the largest log(error / tol) over the targets."""
    return max(math.log(r) for r in ratios)


def last_within(ratios, hold=0.9):
    """The last target's log(error / tol), the others held at hold * tol (a penalty of weight 10
    on the excess): max() stalls where the largest ratio changes hands, with slack left on the
    other targets; this spends that slack."""
    return math.log(ratios[-1]) + 10 * sum(max(0.0, math.log(r / hold)) for r in ratios[:-1])


OBJECTIVES = {"worst": worst, "last within": last_within}


def design(problem, x0, size, of_ratios=worst, rounds=12):
    """Nelder-Mead on of_ratios(ratios) over x0 + N y projected onto the conditions."""
    N = tangent(problem, x0)

    def point(y):
        return search_core.onto_conditions(problem, x0 + N @ y)

    def objective(y):
        x = point(y)
        if np.max(np.abs(problem.imposed(x))) > 1e-11:
            return 50.0  # off the conditions: the projection failed
        return of_ratios(problem.ratios(x))

    y, best = np.zeros(N.shape[1]), objective(np.zeros(N.shape[1]))
    for _ in range(rounds):
        simplex = np.vstack([y] + [y + size * e for e in np.eye(len(y))])
        out = minimize(objective, y, method="Nelder-Mead",
                       options={"initial_simplex": simplex, "xatol": 1e-7, "fatol": 1e-4,
                                "maxfev": 800})
        if out.fun < best - 1e-3:
            y, best = out.x, out.fun
        else:
            size *= 0.5
    return point(y)


def passes(problem, spec):
    """The design's passes in turn, each from the last one's result projected onto the
    conditions (as if restarted from its printed digits)."""
    x = start_point(problem, spec.start)
    for i, (objective, size) in enumerate(spec.passes):
        if i:
            x = search_core.onto_conditions(problem, x)
        x = design(problem, x, size, OBJECTIVES[objective])
    return x


def scene_keys(targets):
    return list(dict.fromkeys(key for key, _, _ in targets))


def summary(problem, c, d, ratios):
    """Per scene: the error at its targets and the fewest steps at the benchmark's tolerances."""
    parts = []
    for key in scene_keys(problem.targets):
        cells = ", ".join("%d steps %.3g (tol %g)" % (n, r * tol, tol)
                          for (k, n, tol), r in zip(problem.targets, ratios) if k == key)
        steps = ", ".join("%s at %g" % (problem.scenes[key].fewest_steps(c, d, tol), tol)
                          for tol in (1e-4, 1e-6, 1e-8, 1e-10))
        parts.append("on %s: error %s; fewest steps %s" % (key, cells, steps))
    return "; ".join(parts)


def spec_block(name, problem, x, command):
    c, d = problem.fam.method(list(x))
    fmt = lambda v: ", ".join("%.17g" % t for t in v)
    return "\n".join([
        "# %s %s" % (name, summary(problem, c, d, problem.ratios(x))),
        "method    " + name, "kind      explicit", "source    this project: " + command,
        "stages    %d" % problem.fam.s, "order     %d" % problem.fam.order,
        "c         " + fmt(c), "kick      " + fmt(d)])


def command_of(name, spec):
    """The command and what it designs for, as the spec's source line gives it."""
    start, targets = spec.start, spec.targets
    keys = scene_keys(targets)
    if len(keys) == 1:
        what = "%s, from %s, %s" % (keys[0], start,
                                   ", ".join("%d steps to %g" % t[1:] for t in targets))
    else:
        what = "from %s, %s" % (start, ", ".join("%s %d steps to %g" % t for t in targets))
    return "generator/search/design_at_tolerance.py '%s' (%s)" % (name, what)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("design", choices=sorted(DESIGNS))
    name = ap.parse_args().design
    spec = DESIGNS[name]
    problem = Problem(spec)
    x = passes(problem, spec)
    print(spec_block(name, problem, x, command_of(name, spec)))


if __name__ == "__main__":
    main()
