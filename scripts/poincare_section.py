#!/usr/bin/env python3
"""A Poincare section of Henon-Heiles from erkn.solve's events (issue 20, item 5): orbits of one
energy, each crossing of q1 = 0 with q1' > 0 (event g = q1, direction +1) plotted as (q2, q2').
Writes <charts>/data/poincare_hh.{dat,gp}, draws <charts>/poincare_hh.png with gnuplot, and
writes <markdown> with the run's numbers (scripts/main.sh: docs/charts, docs/poincare.md).

    PYTHONPATH=build/python python3 scripts/poincare_section.py --charts docs/charts \\
        --markdown docs/poincare.md
"""

import argparse
import pathlib
import subprocess
import time

import numpy as np

import erkn

ENERGY = 0.125  # (1/8: regular islands and a chaotic sea side by side)


def crossing(t, q, p):
    return q[0]


crossing.direction = 1


def orbit_starts(hh, count):
    """States of energy ENERGY on the section q1 = 0, p2 = 0: q2 spread over the allowed range."""
    starts = []
    for y in np.linspace(-0.32, 0.52, count):
        kinetic = 2 * (ENERGY - (y * y / 2 - y**3 / 3))
        if kinetic > 0:
            starts.append((np.array([0.0, y]), np.array([np.sqrt(kinetic), 0.0])))
    return starts


def run(method, h, t1, count):
    hh = erkn.problems.henon_heiles(ENERGY)
    rows, drift, evaluations = [], 0.0, 0
    start = time.process_time()
    for k, (q0, p0) in enumerate(orbit_starts(hh, count)):
        sol = erkn.solve(hh.M, hh.grad, q0=q0, p0=p0, t_span=(0, t1), h=h, method=method,
                         every=1000, events=[crossing])
        H = hh.invariants(sol.q, sol.p)["H"]
        drift = max(drift, np.abs(H - ENERGY).max())
        evaluations += sol.stats["gradient_evaluations"] + sol.stats["events"][
            "gradient_evaluations"]
        rows.append((k, sol.q_events[0][:, 1], sol.p_events[0][:, 1]))
    return rows, drift, evaluations, time.process_time() - start


def write_chart(charts, rows, method, h):
    data = charts / "data"
    data.mkdir(parents=True, exist_ok=True)
    with open(data / "poincare_hh.dat", "w") as f:
        for k, q2, p2 in rows:
            f.write(f"# orbit {k}\n")
            f.writelines(f"{a:.10g} {b:.10g}\n" for a, b in zip(q2, p2))
            f.write("\n\n")
    (data / "poincare_hh.gp").write_text(
        "set terminal pngcairo size 800,700 enhanced font 'DejaVu Sans,11'\n"
        "set output 'poincare_hh.png'\n"
        f"set title 'Henon-Heiles, H = {ENERGY}: section q1 = 0, p1 > 0 ({method}, h = {h})' "
        "noenhanced\n"
        "set xlabel 'q_2'\nset ylabel 'p_2'\nset key off\nset grid lc rgb '#dddddd'\n"
        "plot 'data/poincare_hh.dat' u 1:2:(column(-2)) w p pt 7 ps 0.25 lc variable\n")
    subprocess.run(["gnuplot", "data/poincare_hh.gp"], cwd=charts, check=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--charts", default="docs/charts")
    ap.add_argument("--markdown", default="docs/poincare.md")
    ap.add_argument("--method", default="ABA864")
    ap.add_argument("--h", type=float, default=0.05)
    ap.add_argument("--t1", type=float, default=3000.0)
    ap.add_argument("--orbits", type=int, default=24)
    a = ap.parse_args()
    rows, drift, evaluations, cpu = run(a.method, a.h, a.t1, a.orbits)
    write_chart(pathlib.Path(a.charts), rows, a.method, a.h)
    points = sum(len(q2) for _, q2, _ in rows)
    pathlib.Path(a.markdown).write_text(
        "# Hénon–Heiles Poincaré section (written by scripts/poincare_section.py)\n\n"
        f"![Poincaré section](charts/poincare_hh.png)\n\n"
        f"{len(rows)} orbits of energy H = {ENERGY} on q1 = 0, each to t = {a.t1:g} with "
        f"{a.method} at h = {a.h}; a crossing (q1 rising through 0) is an event "
        "(`erkn.solve(events=[g])`, g.direction = 1), located on the method's own shorter "
        f"step from the step before it. {points} section points; max |H - H0| over all steps "
        f"{drift:.1e}; {evaluations} gradient evaluations (event location included); "
        f"{cpu:.2f} s CPU in this process.\n")
    print(f"poincare: {len(rows)} orbits, {points} points, max |H - H0| {drift:.1e}, "
          f"{cpu:.2f} s CPU")


if __name__ == "__main__":
    main()
