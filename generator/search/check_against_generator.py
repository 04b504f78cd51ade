#!/usr/bin/python3
"""Checks sen_conditions.py against the generator: for every plain-kick explicit method of
generated/src/tables.cpp, its error constant and generalized error constants recomputed in
double from the tabulated c, d must agree with the generator's (printed to 6 digits) within
1e-4 relative. Exit status 1 on a disagreement; a negative control (c_1 moved by 1e-3) must
disagree.

Usage: /usr/bin/python3 generator/search/check_against_generator.py [generated/src/tables.cpp]
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import sen_conditions as sc  # noqa: E402


def floats(text):
    return [float(x) for x in text.split(",") if x.strip()]


def explicit_methods(tables):
    """name -> (c, d, order, error constant, generalized orders, generalized constants)."""
    out = {}
    rows = re.findall(r'\{"([^"]+)", "([^"]*)", (\d+), (\d+), ([^,]+), (\w+), (\w+), (\w+),',
                      tables)
    for name, ns, _, order, const, _, explicit, _ in rows:
        block = tables[tables.index("namespace " + ns + " {"):]
        grab = lambda key: floats(re.search(key + r"\[\] = \{([^}]*)\}", block).group(1))
        if explicit == "false" or "modified" in block[:block.index("coefficients(")]:
            continue
        out[name] = (grab("c"), grab("d"), int(order), float(const), [int(g) for g in grab(
            "generalized_order")], grab("generalized_error_constant"))
    return out


def recomputed(c, d, order, gorders, fast=False):
    max_power = max(order + 1, 10, *(g + 1 for g in gorders))
    powers = [(0, order + 1)] + [(K + 1, g + 1) for K, g in enumerate(gorders)]
    norms = sc.leading_norms(c, d, powers, max_power, fast=fast)
    return norms[(0, order + 1)], [norms[(K + 1, g + 1)] for K, g in enumerate(gorders)]


def numpy_agrees(c, d, order, gorders):
    """The search's numpy path against the plain one (True without numpy: not checked)."""
    try:
        import numpy  # noqa: F401
    except ImportError:
        return True
    a, ga = recomputed(c, d, order, gorders)
    b, gb = recomputed(c, d, order, gorders, fast=True)
    return agree(b, a) and all(agree(x, y) for x, y in zip(gb, ga))


def agree(a, b):
    return abs(a - b) <= 1e-4 * abs(b) + 1e-12


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "..", "generated", "src", "tables.cpp")
    methods = explicit_methods(open(path).read())
    bad = 0
    for name, (c, d, order, const, gorders, gconsts) in methods.items():
        if order >= 10:
            continue
        mine, gmine = recomputed(c, d, order, gorders)
        ok = agree(mine, const) and all(agree(a, b) for a, b, g in zip(gmine, gconsts, gorders)
                                        if g < 10) and numpy_agrees(c, d, order, gorders)
        bad += not ok
        print("%-10s order %d  C %.6g (generator %.6g)  %s" % (name, order, mine, const,
                                                               "ok" if ok else "DIFFERS"))
    c, d, order, const, gorders, _ = methods["SABA4"]
    moved = recomputed([c[0] + 1e-3] + c[1:], d, order, gorders)[0]
    control = agree(moved, const)
    print("negative control (SABA4, c_1 + 1e-3): %.6g vs %.6g, %s" %
          (moved, const, "agrees: the check cannot fail" if control else "differs, as it must"))
    sys.exit(1 if bad or control else 0)


if __name__ == "__main__":
    main()
