#!/usr/bin/python3
"""Designs symmetric plain-kick splitting methods for H = A + eps B: the free parameters of a
family (splitting_family.py) left after its imposed order conditions minimize the predicted
work to a tolerance (gradients per unit time at the step where sum_K eps^K C_K h^(g_K) = tol,
C_K the generator's generalized error constants). Deterministic (search_core.py): random
starts from a fixed seed, feasibility by Gauss-Newton (scipy least_squares), then SLSQP on
log(work) with the independent imposed conditions as equalities; the best feasible optimum is
printed as a methods.spec block (17 significant digits: erkn-generate polishes them onto the
conditions).

  /usr/bin/python3 generator/search/near_integrable.py DESIGN [--starts N]

DESIGN is one of DESIGNS below. Needs Debian's python3-numpy, python3-scipy.
"""
import argparse
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import search_core  # noqa: E402
import sen_conditions as sc  # noqa: E402
from splitting_family import Family, work  # noqa: E402

# name: (stages, layout, order, generalized, eps, tol). SD = designed by this search.
DESIGNS = {
    # 9 kicks, generalized order (10, 6, 4) (one more kick than ABA(10,6,4), one free
    # parameter), for the general case eps = 1 at tol = 1e-8: the sine-Gordon cells.
    "SD9(10,6,4)": (9, "ABA", 4, [10, 6, 4], 1.0, 1e-8),
    # One kick more (two free parameters), for tol = 1e-10 (the 2-D sine-Gordon cell).
    "SD10(10,6,4)": (10, "ABA", 4, [10, 6, 4], 1.0, 1e-10),
}


def residuals(fam, x):
    """The residuals the objective and the conditions read (trees with more than 3 f-vertices
    skipped unless the objective is the classical error constant, eps = 0)."""
    c, d = fam.method(list(x))
    return sc.residuals(c, d, fam.max_power, kmax=fam.kmax)


def objective(fam, x, eps, tol):
    """log of the predicted work; eps = 0: the general case, gradients * C^(1/order) with C the
    generator's error constant (all trees at power order + 1), the standard effective error."""
    res = residuals(fam, x)
    if eps == 0:
        return math.log(fam.gradients) + math.log(fam.error_constant(res)) / fam.order
    return math.log(work(fam.constants(res), fam.gradients, eps, tol))


class Problem:
    """The family at (eps, tol) as search_core.py searches it."""

    def __init__(self, fam, eps, tol):
        self.fam, self.eps, self.tol, self.free = fam, eps, tol, fam.free()

    def imposed(self, x):
        return np.array(self.fam.imposed(residuals(self.fam, x)))

    def objective(self, x):
        return objective(self.fam, x, self.eps, self.tol)

    def start(self, rng):
        return np.concatenate([rng.uniform(-0.2, 0.6, self.fam.n_nodes),
                               rng.uniform(-0.2, 0.5, self.fam.n_weights)])


def spec_block(name, fam, x, design, command):
    c, d = fam.method(list(x))
    g = ", ".join(str(v) for v in fam.generalized)
    fmt = lambda v: ", ".join("%.17g" % t for t in v)
    consts = fam.constants(residuals(fam, x))
    return "\n".join([
        "# %s: work %.4g gradients per unit time at eps = %g, tol = %g; C_K = %s" % (
            name, math.exp(objective(fam, x, design[4], design[5])), design[4], design[5],
            ", ".join("%.3g" % C for _, C, _ in consts)),
        "method    " + name, "kind      explicit",
        "source    this project: " + command, "stages    %d" % fam.s,
        "order     %d" % fam.order, "generalized " + g, "c         " + fmt(c),
        "kick      " + fmt(d)])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("design", choices=sorted(DESIGNS))
    ap.add_argument("--starts", type=int, default=40)
    a = ap.parse_args()
    s, layout, order, gen, eps, tol = DESIGNS[a.design]
    fam = Family(s, layout, order, gen, kmax=None if eps == 0 else max(3, len(gen)))
    best = search_core.search(Problem(fam, eps, tol), a.starts)
    if best is None:
        sys.exit("no feasible method from %d starts" % a.starts)
    command = "generator/search/near_integrable.py '%s' --starts %d (eps = %g, tol = %g)" % (
        a.design, a.starts, eps, tol)
    print(spec_block(a.design, fam, best[1], DESIGNS[a.design], command))


if __name__ == "__main__":
    main()
