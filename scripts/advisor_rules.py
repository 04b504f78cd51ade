#!/usr/bin/env python3
"""Scores candidate trial rules of the step-size advisor offline, on the training sweep's CSV
(`erkn_advisor_sweep --offset 0.5 --csv FILE`), without rerunning it: how the constants of
erkn/advisor.hpp ("Severity") were chosen. Usage: advisor_rules.py FILE [--grid].

A point's error curve (max_2^k: the largest relative energy error over the first 2^k steps of
its 1e5-step run) is what a trial of 2^k steps sees; the quiet-mode takeover and a failed trial
come from the sweep's own 8192-step trial. Rates over the ERKN methods and the explicit
splittings, as docs/advisor.md counts them; the cost is the mean trial length against the run.
"""
import csv
import itertools
import math
import sys

RUN = 100000
EARLY = 16  # E(n / 16) against E(n) gives the growth exponent


def load(path):
    rows = []
    for r in csv.DictReader(open(path)):
        if r["kind"] != "erkn" or r["outcome"] == "refused":
            continue
        curve = {int(k[4:]): float(v) for k, v in r.items() if k.startswith("max_")}
        takeover = float(r["mode_rate"]) > 0 and 8192 + float(r["takeover"]) <= RUN
        rows.append(dict(curve=curve, blew_up=r["outcome"] == "blew_up", pole=r["linear"] == "pole",
                         explained=r["linear"] in ("unstable", "resonance"), takeover=takeover,
                         failed=r["trial_failed"] == "1", scene=r["scene"]))
    return rows


def judge(r, n, c):
    """(flagged, ambiguous) for a trial of n steps under the constants c."""
    e, early = r["curve"][n], r["curve"][n // EARLY]
    saturated = e > 0 and e <= c["growth"] * early
    if saturated or e == 0:
        predicted = e
    else:
        alpha = min(max(math.log(e / early) / math.log(EARLY), 0), 1) if early > 0 else 1
        predicted = e * (RUN / n) ** alpha
    margin = (c["saturated"] if saturated else c["explained"] if r["explained"] else c["trial"])
    limit = 0.5 / margin
    return predicted >= limit, predicted >= limit / c["ambiguity"]


def verdict(r, c):
    """(flagged, trial steps)."""
    if r["failed"] or r["pole"] or r["takeover"]:
        return True, c["n"]
    flagged, ambiguous = judge(r, c["n"], c)
    if flagged or not ambiguous or c["extended"] <= c["n"]:
        return flagged, c["n"]
    return judge(r, c["extended"], c)[0], c["extended"]


def score(rows, c):
    fa = bounded = misses = blown = steps = 0
    for r in rows:
        f, n = verdict(r, c)
        steps += n
        if r["blew_up"]:
            blown, misses = blown + 1, misses + (not f)
        else:
            bounded, fa = bounded + 1, fa + f
    return fa / bounded, misses / blown, steps / len(rows) / RUN


CHOSEN = dict(n=8192, extended=32768, ambiguity=4, growth=1.5, saturated=1.125, explained=5 / 3,
              trial=16)
OLD = dict(n=8192, extended=0, ambiguity=1, growth=0, saturated=1, explained=2, trial=16)
GRID = dict(extended=[0, 16384, 32768], ambiguity=[2, 4, 8], growth=[0, 1.2, 1.5, 2],
            saturated=[1.125, 1.25, 2], explained=[1.25, 1.5, 5 / 3, 2], trial=[8, 16, 32])


def main():
    rows = load(sys.argv[1])
    for name, c in (("previous rule", OLD), ("chosen rule", CHOSEN)):
        fa, miss, cost = score(rows, c)
        print(f"{name}: false alarms {100 * fa:.1f} %, misses {100 * miss:.1f} %, "
              f"mean trial {100 * cost:.1f} % of a {RUN}-step run")
    if "--grid" not in sys.argv:
        return
    results = []
    for values in itertools.product(*GRID.values()):
        c = dict(CHOSEN, **dict(zip(GRID, values)))
        results.append((max(score(rows, c)[:2]), score(rows, c), c))
    for worst, (fa, miss, cost), c in sorted(results, key=lambda x: x[0])[:15]:
        print(f"{100 * fa:.1f} % / {100 * miss:.1f} %, cost {100 * cost:.1f} %: {c}")


if __name__ == "__main__":
    main()
