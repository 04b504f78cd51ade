#!/usr/bin/env python3
"""erkn.solve with a built-in potential against C++ Integrator construction + integrate (issue 17,
target <= 1.1), for every explicit registry method on Duffing (P2, "duffing") and sine-Gordon
N = 32 and 2048 ("sine"): the same M, initial data, h and steps, output only at t0 and t_end
(every = steps). The C++ side runs in `erkn_integrate_benchmark --serve` (a child process that
times the runs it is asked for, thread CPU time); the two are interleaved in rounds, each ratio
the median over rounds of Python / C++ in that round. Four things make two runs agree
(python_solve_benchmark's 75 cells, two runs at load 8-9: 75 within 10 %, the largest 6.4 %):
- One CPU for both processes (the driver pins itself to the lowest CPU it may use before
  starting the server, which inherits that). On a shared machine the CPUs are not equally fast
  from one moment to the next, and two processes left to the scheduler each settle on one for
  seconds: Duffing's 25 cells, load 5-6, unpinned, 5 rounds of 2 ms, three runs: 24, 8 and 6
  cells within 10 % between two of them; pinned, 21 rounds: 25 in all three pairs.
- Rounds that visit every cell in turn, so that a cell's samples spread over the whole run.
  Slow spells of about a second slow the C++ loop more than the interpreter (four C++ servers
  asked in turn were slow together); a cell measured in one stretch of 0.1 s can fall into one
  (Duffing Strang 2.33 in one run, 1.27 in the next).
- One FFTW wisdom file (ERKN_FFTW_WISDOM, as scripts/main.sh sets it), so both processes use
  the same plans; without one each measures its own, and the N = 2048 cells moved by 10 %.
- The same glibc malloc thresholds in both processes (fixed, high). A run at N = 2048 grows the
  heap by ~230 KB and frees it; with glibc's default thresholds whether that is trimmed and
  faulted back in on every run depends on the process's history (a process that measured FFTW
  plans had raised them, one that planned from wisdom had not; erkn.solve's runs in the
  interpreter took 0.58 ms either way). The C++ server planning from wisdom took 1.7 ms per
  Strang run against 0.6-0.8 after measuring, so the N = 2048 cells (Strang, SABA2, ABA1064)
  read 0.47-0.83 on every run after the first with a fresh wisdom file; with these thresholds
  0.99-1.08 in four runs (fresh and reused wisdom file), and all 25 N = 2048 cells of --short
  0.99-1.05 in three runs from a fresh file (before: 0.64-1.07 in the first, 0.49-1.03 after).
Appends a section to the Markdown file.

    PYTHONPATH=build/python python3 bench/python_solve_benchmark.py \\
        --server build/bench/erkn_integrate_benchmark [--short] [--markdown docs/benchmarks.md]
"""

import argparse
import ctypes
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import erkn

TARGET = 1.1
PINNED = "both processes pinned to one CPU (the same core for both sides)"
WISDOM = "FFTW plans from one wisdom file (ERKN_FFTW_WISDOM)"
OWN_PLANS = "each process's own FFTW plans (no ERKN_FFTW_WISDOM)"


def scenes(short):
    """(label, key the C++ server knows, M, grad, q0, p0, h, steps)."""
    out = [("Duffing (P2)", "P2", 100.0, "duffing", np.zeros(1), np.full(1, 10.0), 1 / 100,
            200 if short else 1000)]
    for n, steps in ((32, 100 if short else 400), (2048, 20 if short else 100)):
        dx = 2.0 / n
        col = np.zeros(n)
        col[0], col[1], col[-1] = 2 / dx**2, -1 / dx**2, -1 / dx**2
        i = np.arange(1, n + 1)
        p0 = np.sqrt(n) * (0.01 + np.sin(2 * np.pi * i / n))
        h = 1 / 40 if n == 32 else 1 / 100
        out.append((f"sine-Gordon N = {n}", f"SG{n}", erkn.circulant(col), "sine",
                    np.full(n, np.pi), p0, h, steps))
    return out


def is_explicit(name):
    """Every abar_ii identically 0 (checked at v = 0, where an implicit method's is not)."""
    abar = np.asarray(erkn.tableau(name)["abar"])
    return not np.diag(abar).any()


def python_seconds(scene, method, reps):
    _, _, M, grad, q0, p0, h, steps = scene
    start = time.thread_time()
    for _ in range(reps):
        erkn.solve(M, grad, q0=q0, p0=p0, t_span=(0.0, h * steps), h=h, method=method,
                   every=steps)
    return (time.thread_time() - start) / reps


def cxx_seconds(server, scene, method, reps):
    _, key, _, _, _, _, h, steps = scene
    server.stdin.write(f"{key} {method} {h!r} {steps} {reps}\n")
    server.stdin.flush()
    line = server.stdout.readline()
    if not line:
        sys.exit("python_solve_benchmark: the C++ server stopped")
    return float(line)


def calibrate(server, cell, min_sample):
    """Warms both sides up; the runs per sample (at least min_sample seconds of C++ runs)."""
    scene, method = cell
    python_seconds(scene, method, 1), cxx_seconds(server, scene, method, 1)
    return max(1, int(np.ceil(min_sample / max(cxx_seconds(server, scene, method, 1), 1e-9))))


def measure(server, cells, rounds, min_sample):
    """(median Python / C++, median C++ seconds) of each cell over `rounds` rounds, each round
    one sample of every cell in turn (the side timed first alternating), so that a cell's
    samples spread over the whole run rather than over one stretch of it."""
    reps = [calibrate(server, cell, min_sample) for cell in cells]
    ratios, cxx = [[] for _ in cells], [[] for _ in cells]
    for r in range(rounds):
        for k, ((scene, method), n) in enumerate(zip(cells, reps)):
            if r % 2 == 0:
                py = python_seconds(scene, method, n)
                c = cxx_seconds(server, scene, method, n)
            else:
                c = cxx_seconds(server, scene, method, n)
                py = python_seconds(scene, method, n)
            ratios[k].append(py / c)
            cxx[k].append(c)
    return [(statistics.median(x), statistics.median(c)) for x, c in zip(ratios, cxx)]


# glibc's mallopt parameters and the thresholds set (bytes): nothing is trimmed from the heap's
# top below 64 MiB, blocks below 32 MiB (glibc's largest mmap threshold) come from the heap.
M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
TRIM_THRESHOLD, MMAP_THRESHOLD = 64 << 20, 32 << 20
SAME_MALLOC = ("the same glibc malloc thresholds in both (trim 64 MiB, mmap 32 MiB: no run "
               "trims the heap and faults it back)")


def same_malloc_thresholds():
    """Sets this process's malloc thresholds and returns the environment that gives the server
    the same (GLIBC_TUNABLES), or None where there is no glibc mallopt."""
    mallopt = getattr(ctypes.CDLL(None), "mallopt", None)
    if mallopt is None or not (mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD)
                               and mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)):
        return None
    tunables = (f"glibc.malloc.trim_threshold={TRIM_THRESHOLD}:"
                f"glibc.malloc.mmap_threshold={MMAP_THRESHOLD}")
    return dict(os.environ, GLIBC_TUNABLES=tunables)


def pin_to_one_cpu():
    """This process, and the server it starts (which inherits it), on its lowest allowed CPU
    (Linux; elsewhere the scheduler's choice, and the header says so)."""
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--server", required=True)
    ap.add_argument("--short", action="store_true")
    ap.add_argument("--markdown")
    args = ap.parse_args()
    rounds, min_sample = (41, 1e-3) if args.short else (61, 2e-3)
    pin_to_one_cpu()
    explicit = [m["name"] for m in erkn.methods() if is_explicit(m["name"])]
    cells = [(scene, method) for scene in scenes(args.short) for method in explicit]
    env = same_malloc_thresholds()
    server = subprocess.Popen([args.server, "--serve"], stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True, env=env)
    rows = []
    for (scene, method), (ratio, cxx) in zip(cells, measure(server, cells, rounds, min_sample)):
        rows.append((scene[0], method, scene[7], 1e3 * cxx, ratio))
        print(f"{scene[0]:22s} {method:9s} C++ {1e3 * cxx:9.4f} ms  Python / C++ {ratio:.3f}")
    server.stdin.close()
    server.wait()
    if args.markdown:
        write_markdown(args, rows, rounds, min_sample, env is not None)


def write_markdown(args, rows, rounds, min_sample, same_malloc):
    met = sum(r[4] <= TARGET for r in rows)
    command = "python3 bench/python_solve_benchmark.py " + " ".join(sys.argv[1:])
    with open(args.markdown, "a") as f:
        f.write("\n## Python: erkn.solve with a built-in potential against C++ integrate\n\n"
                f"Generated by `{command}` (scripts/main.sh). `erkn.solve(M, \"sine\" or "
                "\"duffing\", ..., every=steps)` against C++ Integrator construction + "
                "integrate(t_end) + reading the final state on the same scene (the problems "
                "library's System), thread CPU time, the C++ runs in a child process "
                "(`erkn_integrate_benchmark --serve`), "
                f"{PINNED if hasattr(os, 'sched_setaffinity') else 'not pinned'}; "
                f"{WISDOM if os.environ.get('ERKN_FFTW_WISDOM') else OWN_PLANS}; "
                f"{SAME_MALLOC if same_malloc else 'each process its own malloc thresholds'}; "
                f"median over {rounds} rounds of Python / C++, a round one sample of each "
                "side for every cell in turn (a cell's samples spread over the whole run), "
                f"each sample at least {1e3 * min_sample:.0f} ms of C++ runs. "
                f"Cells met (target <= {TARGET}): {met} / {len(rows)}.\n\n"
                "| scene | method | steps | C++ ms per run | Python / C++ | |\n"
                "|---|---|--:|--:|--:|---|\n")
        for scene, method, steps, ms, ratio in rows:
            verdict = "met" if ratio <= TARGET else "NOT met"
            f.write(f"| {scene} | {method} | {steps} | {ms:.4f} | {ratio:.3f} | {verdict} |\n")


if __name__ == "__main__":
    main()
