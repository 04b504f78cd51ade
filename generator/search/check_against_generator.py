#!/usr/bin/python3
"""Checks sen_conditions.py against the generator: for every explicit method of
generated/src/tables.cpp (plain kicks, modified kicks, processed: the composition pi^-1, K, pi),
its error constant and generalized error constants recomputed in double from the tabulated
c, d, modified and pre_* must agree with the generator's (printed to 6 digits) within 1e-4
relative. Exit status 1 on a disagreement; negative controls must disagree: SABA4 with c_1
moved by 1e-3, PMLF6 with its kernel's modified coefficient moved by 1e-3, and PMLF6 with the
processor left out.

Usage: /usr/bin/python3 generator/search/check_against_generator.py [generated/src/tables.cpp]
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sen_conditions as sc  # noqa: E402


def floats(text):
    return [float(x) for x in text.split(",") if x.strip()]


class Tabulated:
    """An explicit method as generated/src/tables.cpp lists it."""

    def __init__(self, block, order, const):
        head = block[:block.index("constexpr const char* closed_forms")]
        self.grab = lambda key: floats(re.search(r"\b" + key + r"\[\] = \{([^}]*)\}",
                                                 block).group(1))
        has = lambda key: re.search(r"\b" + key + r"\[\] = ", head) is not None
        self.c, self.d = self.grab("c"), self.grab("d")
        self.e = self.grab("modified") if has("modified") else None
        self.pre = [self.grab(k) if has(k) else None
                    for k in ("pre_drift", "pre_kick", "pre_modified")]
        self.order, self.const = int(order), float(const)
        self.gorders = [int(g) for g in self.grab("generalized_order")]
        self.gconsts = self.grab("generalized_error_constant")

    def sequence(self, processed=True):
        """(c, d, e) the generator certifies: the kernel, or pi^-1, K, pi if processed."""
        drift, kick, mod = self.pre
        if not processed or kick is None:
            return self.c, self.d, self.e
        return sc.composition(self.c, self.d, self.e, drift, kick, mod)


def explicit_methods(tables):
    """name -> Tabulated, for every explicit method of the tables."""
    out = {}
    rows = re.findall(r'\{"([^"]+)", "([^"]*)", (\d+), (\d+), ([^,]+), (\w+), (\w+), (\w+),',
                      tables)
    for name, ns, _, order, const, _, explicit, _ in rows:
        if explicit == "true":
            block = tables[tables.index("namespace " + ns + " {"):]
            out[name] = Tabulated(block[:block.index("}  // namespace")], order, const)
    return out


def recomputed(seq, order, gorders, fast=False):
    c, d, e = seq
    max_power = max(order + 1, 10, *(g + 1 for g in gorders))
    powers = [(0, order + 1)] + [(K + 1, g + 1) for K, g in enumerate(gorders)]
    norms = sc.leading_norms(c, d, powers, max_power, fast=fast, e=e)
    return norms[(0, order + 1)], [norms[(K + 1, g + 1)] for K, g in enumerate(gorders)]


def numpy_agrees(seq, order, gorders):
    """The search's numpy path against the plain one (True without numpy: not checked)."""
    try:
        import numpy  # noqa: F401
    except ImportError:
        return True
    a, ga = recomputed(seq, order, gorders)
    b, gb = recomputed(seq, order, gorders, fast=True)
    return agree(b, a) and all(agree(x, y) for x, y in zip(gb, ga))


def agree(a, b):
    return abs(a - b) <= 1e-4 * abs(b) + 1e-12


def checks(m, seq=None):
    """(recomputed error constant, agrees with the generator's on every constant)."""
    seq = seq or m.sequence()
    mine, gmine = recomputed(seq, m.order, m.gorders)
    ok = agree(mine, m.const) and all(agree(a, b) for a, b, g in
                                      zip(gmine, m.gconsts, m.gorders) if g < 10)
    return mine, ok


def controls(methods):
    """Negative controls: each must disagree with the generator. Returns how many agree."""
    saba4, pmlf6 = methods["SABA4"], methods["PMLF6"]
    moved_e = list(pmlf6.e)
    moved_e[1] += 1e-3
    drift, kick, mod = pmlf6.pre
    cases = [("SABA4, c_1 + 1e-3", saba4, ([saba4.c[0] + 1e-3] + saba4.c[1:], saba4.d, None)),
             ("PMLF6, kernel e_2 + 1e-3", pmlf6,
              sc.composition(pmlf6.c, pmlf6.d, moved_e, drift, kick, mod)),
             ("PMLF6, kernel without its processor", pmlf6, pmlf6.sequence(processed=False))]
    agreeing = 0
    for label, m, seq in cases:
        moved, ok = checks(m, seq)
        agreeing += ok
        print("negative control (%s): %.6g vs %.6g, %s" % (
            label, moved, m.const, "agrees: the check cannot fail" if ok else
            "differs, as it must"))
    return agreeing


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "..", "generated", "src", "tables.cpp")
    methods = explicit_methods(open(path).read())
    bad = 0
    for name, m in methods.items():
        if m.order >= 10:
            continue
        mine, ok = checks(m)
        ok = ok and numpy_agrees(m.sequence(), m.order, m.gorders)
        bad += not ok
        kind = "processed" if m.pre[1] else "modified" if m.e else "plain"
        print("%-12s %-9s order %d  C %.6g (generator %.6g)  %s" % (
            name, kind, m.order, mine, m.const, "ok" if ok else "DIFFERS"))
    sys.exit(1 if bad or controls(methods) else 0)


if __name__ == "__main__":
    main()
