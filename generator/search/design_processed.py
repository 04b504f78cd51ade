#!/usr/bin/python3
"""Designs symmetric splitting kernels with modified kicks, processed or not
(processed_family.py): the free parameters left after psi's order conditions minimize the
predicted work, cost * C^(1/order) (search_core.py: fixed seed, least_squares, SLSQP). Prints
the best optimum as a methods.spec block (17 significant digits: erkn-generate polishes them
onto the conditions in 60 digits and certifies psi = pi o K o pi^-1).

  /usr/bin/python3 generator/search/design_processed.py DESIGN [--starts N] [--seed S]

DESIGN is one of DESIGNS below. Needs Debian's python3-numpy, python3-scipy.
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import search_core  # noqa: E402
from processed_family import ProcessedFamily  # noqa: E402

# PMLF6 as this family writes it (methods.spec's digits, hannorein/rebound
# src/integrator_eos.c @ 0c7d40c89524e48cdbaa0f38c10a798f7c2b9798): kernel (first drift, first
# kick, middle modified), then pre_drift, pre_kick, pre_modified.
PMLF6 = ([-0.0682610383918630, 0.2621129352517028, -0.0164011128160783],
         [0.07943288242455420, 0.02974829169467665, -0.7057074964815896, 0.3190423451260838,
          -0.2869147334299646, 0.564398710666239478150885],
         [1.3599424487455264, -0.6505973747535132, -0.033542814598338416,
          -0.040129915275115030, 0.044579729809902803, -0.680252073928462652752103],
         [0.034841228074994859, -0.031675672097525204, 0.005661054677711889,
          -0.004262222269023640, -0.005, 0.005])

# name: (stages, layout, order, modified stages, processor kicks, pre_modified, g_cost[,
# a published method to start from first, its processor padded with zero kicks]).
# SDPp(s,m): designed, processed, effective order p, s kernel kicks, m processor kicks.
DESIGNS = {
    # Strang with a modified kick (PMLF4's kernel class) and 3 modified processor kicks: the
    # kernel's least error constant (0.00788; 3 plain kicks as PMLF4's: 0.0121 at best).
    "SDP4(1,3)": (1, "ABA", 4, [0], 3, True, 0.3),
    # 3 kicks, the middle one modified (PMLF6's kernel class), and an 8-kick processor.
    # Tried, not shipped (docs/design-search.md): PMLF6 with a searched 8-kick processor;
    "SDP6(3,8)": (3, "ABA", 6, [1], 8, True, 0.3, PMLF6),
    # 4 kicks, the middle pair modified, and 2 force evaluations per step (FSAL, both modified);
    "SDP6(4,6)": (4, "ABA", 6, [1], 6, True, 0.3),
    "SDP6(3B,6)": (3, "BAB", 6, [0, 1], 6, True, 0.3),
    # effective order 8: 5 kicks, all modified.
    "SDP8(5,10)": (5, "ABA", 8, [0, 1, 2], 10, True, 0.3),
}


class Problem:
    def __init__(self, fam):
        self.fam, self.free = fam, fam.free()

    def imposed(self, x):
        return np.array(self.fam.imposed(self.fam.residuals(x)))

    def objective(self, x):
        return self.fam.log_work(self.fam.residuals(x))

    def start(self, rng):
        return self.fam.start(rng)

    def leading(self, x):
        return np.array(self.fam.leading(self.fam.residuals(x)))


def published_start(fam, method):
    """The free parameters of a published method of the family, its processor padded with
    zero drifts and kicks to the family's m."""
    kernel, *pre = method
    pad = [list(p) + [0.0] * (fam.m - len(p)) for p in pre]
    return kernel + [v for p in pad for v in p]


def spec_block(name, fam, x, command):
    c, d, e = fam.kernel(list(x))
    drifts = [c[0]] + [c[i + 1] - c[i] for i in range(fam.s - 1)] + [1 - c[-1]]
    fmt = lambda v: ", ".join("%.17g" % t for t in v)
    res = fam.residuals(x)
    lines = ["# %s: cost %.3g per step, error constant %.4g, work %.4g" % (
        name, fam.cost(), fam.error_constant(res), np.exp(fam.log_work(res))),
        "method    " + name, "kind      explicit", "source    this project: " + command,
        "stages    %d" % fam.s, "order     %d" % fam.order, "drift     " + fmt(drifts),
        "kick      " + fmt(d)]
    if any(e):
        lines.append("modified  " + fmt(e))
    if fam.m:
        z, y, v = fam.processor(x)
        lines += ["pre_drift " + fmt(z), "pre_kick  " + fmt(y)]
        if v is not None:
            lines.append("pre_modified " + fmt(v))
    return "\n".join(lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("design", choices=sorted(DESIGNS))
    ap.add_argument("--starts", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--verbose", action="store_true")
    a = ap.parse_args()
    design = DESIGNS[a.design]
    fam = ProcessedFamily(*design[:7])
    first = None if len(design) < 8 else published_start(fam, design[7])
    report = (lambda n, f: print("start %d: work %.5g" % (n, np.exp(f)), file=sys.stderr)) \
        if a.verbose else None
    best = search_core.search(Problem(fam), a.starts, a.seed, report=report, penalty=True,
                              first=first)
    if best is None:
        sys.exit("no feasible method from %d starts" % a.starts)
    command = "generator/search/design_processed.py '%s' --starts %d --seed %d" % (
        a.design, a.starts, a.seed)
    print(spec_block(a.design, fam, best[1], command))


if __name__ == "__main__":
    main()
