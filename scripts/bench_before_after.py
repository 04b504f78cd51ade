#!/usr/bin/env python3
"""The cells of erkn_explicit_benchmark and erkn_implicit_benchmark in two builds side by side
(issue 19: every cell within 5 % of the numbers before the redesign, or faster).

Usage: bench_before_after.py OLD_BUILD NEW_BUILD [--rounds 5] [--min-time 0.5] [--cpu 1]
           [--filter REGEX] [--counts] [--own-plans] [--out DIR] [--table FILE]

Timing: both builds' benchmarks in alternated rounds (old first in odd rounds, new first in even
ones), each process pinned to one core (`taskset -c CPU`), `--benchmark_min_time`; per cell and
counter the median over rounds of the per-round ratio new / old, with its range. The load
(`uptime`) before and after each round goes into the table's header.

P1 (sine-Gordon N = 32) runs FFTW, whose FFTW_MEASURE planner times candidates: two processes
may plan differently, at different speeds. Every timed process therefore preloads
bench/fftw_wisdom_preload.c, which imports one wisdom file (in --out) and adds its plans to it:
after the first process all plan alike (--own-plans: each process for itself).

--counts: instructions (callgrind), which do not depend on the load, and allocations of the same
cells, from bench/cell_counts.cpp compiled against each build's sources and liberkn.a (the same
driver for both: it uses only the API both have). The Ir column counts erkn's instructions
outside libfftw3 (whose plans callgrind's slow clock chooses).

Cells: per grad U evaluation (PerEvaluation, ns) without and with compensated summation, and
(explicit methods) the setup: the Integrator's constructor alone (ctor) and System, Stiffness and
Integrator from the problem's definition (total), in us.
"""
import argparse
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

BENCHES = ("explicit", "implicit")
# cell kind -> (counter, how the benchmark's counters give it)
COUNTERS = {
    "PerEvaluation": {
        "plain": lambda c: c["erkn_ns/eval"],
        "kahan": lambda c: c.get("erkn_kahan_ns/eval", c["ratio_kahan"] * c["peer_ns/eval"]),
    },
    "Setup": {"ctor": lambda c: c["erkn_ctor_us"], "total": lambda c: c["erkn_us"]},
}
TARGET = 1.05
HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # (the checkout)
TRIGGER = "desc: Trigger: Client Request: "  # (a dump named by cell_counts)


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, text=True, capture_output=True, **kw).stdout


def binary(build, bench):
    return os.path.join(build, "bench", f"erkn_{bench}_benchmark")


def cell_names(build, bench, pattern):
    """The benchmark's cells (kind/problem/method, without the trailing argument)."""
    out = run([binary(build, bench), "--benchmark_list_tests"])
    names = [re.sub(r"/\d+$", "", line) for line in out.split()]
    return [n for n in names if re.search(pattern, n)]


def common_cells(args):
    cells = {}
    for bench in BENCHES:
        old, new = (set(cell_names(b, bench, args.filter)) for b in (args.old, args.new))
        cells[bench] = sorted(old & new)
    return cells


def load():
    return run(["uptime"]).strip().split("load average: ")[-1]


def time_rounds(args, cells):
    """Alternated rounds; returns {side: [{(bench, cell): counters} per round]}, the loads."""
    results, loads = {"old": [], "new": []}, []
    for r in range(1, args.rounds + 1):
        before = load()
        sides = ("old", "new") if r % 2 else ("new", "old")
        got = {s: {} for s in sides}
        for bench in BENCHES:
            if not cells[bench]:
                continue
            pattern = "^(" + "|".join(re.escape(c) for c in cells[bench]) + ")/"
            for side in sides:
                got[side].update(time_one(args, side, bench, pattern, r))
        for side in sides:
            results[side].append(got[side])
        loads.append((before, load()))
        print(f"round {r}: load {loads[-1][0]} -> {loads[-1][1]}", file=sys.stderr)
    return results, loads


def time_one(args, side, bench, pattern, r):
    build = args.old if side == "old" else args.new
    path = os.path.join(args.out, f"{bench}_{side}_{r}.json")
    run(["taskset", "-c", str(args.cpu), binary(build, bench), f"--benchmark_filter={pattern}",
         f"--benchmark_min_time={args.min_time}", f"--benchmark_out={path}",
         "--benchmark_out_format=json"], env=args.env)
    runs = json.load(open(path))["benchmarks"]
    return {(bench, re.sub(r"/\d+$", "", b["name"])): b for b in runs if b["run_type"] == "iteration"}


def timing_rows(results):
    """{(bench, cell, counter): (old median, new median, ratio median, lo, hi)}."""
    rows = {}
    for key in results["old"][0]:
        kind = key[1].split("/")[0]
        for counter, get in COUNTERS[kind].items():
            pairs = [(get(o[key]), get(n[key])) for o, n in zip(results["old"], results["new"])
                     if key in o and key in n]
            ratios = [n / o for o, n in pairs]
            rows[key + (counter,)] = (statistics.median(p[0] for p in pairs),
                                      statistics.median(p[1] for p in pairs),
                                      statistics.median(ratios), min(ratios), max(ratios))
    return rows


def shared_wisdom(args):
    """The environment of the timed processes: with bench/fftw_wisdom_preload.c preloaded, every
    process (both builds, every round) imports one FFTW wisdom file and adds its plans to it."""
    env = dict(os.environ)
    if args.own_plans:
        return env
    shim = os.path.join(args.out, "fftw_wisdom_preload.so")
    run(["cc", "-O2", "-shared", "-fPIC", "-o", shim,
         os.path.join(HERE, "bench", "fftw_wisdom_preload.c"), "-lfftw3"])
    env["LD_PRELOAD"] = shim
    env["ERKN_PRELOAD_WISDOM"] = os.path.join(args.out, "fftw.wisdom")
    return env


def source_dir(build):
    cache = open(os.path.join(build, "CMakeCache.txt")).read()
    return re.search(r"^CMAKE_HOME_DIRECTORY:INTERNAL=(.*)$", cache, re.M).group(1)


def compile_driver(build, out, name):
    src = source_dir(build)
    exe = os.path.join(out, f"cell_counts_{name}")
    run(["c++", "-O3", "-DNDEBUG", "-std=c++20", f"-I{src}/runtime/include",
         f"-I{src}/generated/include", "-isystem", "/usr/include/eigen3",
         os.path.join(HERE, "bench", "cell_counts.cpp"), "-o", exe,
         os.path.join(build, "runtime", "liberkn.a"), "-lbenchmark", "-lfftw3"])
    return exe


def dump_cost(path):
    """(the dump's cell name, Ir outside libfftw3) of one callgrind dump: the self costs (a cost
    line after calls= is the call's inclusive cost, counted in its callee already)."""
    name, total, fftw, ob, objects, call = None, 0, 0, "", {}, False
    for line in open(path):
        if line.startswith(TRIGGER):
            name = line[len(TRIGGER):].strip()
        elif line.startswith(("ob=", "cob=")):  # (both name objects: one table of names)
            m = re.match(r"c?ob=\((\d+)\)(?: (.*))?", line.strip())
            if m.group(2):
                objects[m.group(1)] = m.group(2)
            if line[0] == "o":
                ob = objects[m.group(1)]
        elif line.startswith("calls="):
            call = True
        elif line[:1].isdigit() or line[:1] in "+-*":
            fields = line.split()
            ir = int(fields[1]) if len(fields) > 1 and not call else 0
            total += ir
            fftw += ir if "libfftw3" in ob else 0
            call = False
    return name, total - fftw


def count_cells(args, cells):
    """{(side, cell counter key): (Ir per unit, mallocs per unit)} from callgrind runs."""
    counts = {}
    by_problem = {}
    for bench in BENCHES:
        for cell in cells[bench]:
            kind, problem, method = cell.split("/")
            by_problem.setdefault(problem, set()).add(method)
    for side, build in (("old", args.old), ("new", args.new)):
        exe = compile_driver(build, args.out, side)
        for problem, methods in sorted(by_problem.items()):
            counts.update(count_problem(args, side, exe, problem, sorted(methods)))
    return counts


def count_problem(args, side, exe, problem, methods):
    prefix = os.path.join(args.out, f"cg_{side}_{problem}")
    out = run(["valgrind", "--tool=callgrind", "--collect-atstart=no",
               f"--callgrind-out-file={prefix}.%p", exe, problem] + methods)
    units = {}
    for line in out.splitlines():  # cell units mallocs bytes
        name, n, mallocs, _ = line.split()
        units[name] = (int(n), int(mallocs))
    got = {}
    for path in glob.glob(prefix + ".*.*"):
        name, ir = dump_cost(path)
        if name in units:
            n, mallocs = units[name]
            got[(side, name)] = (ir / n, mallocs / n)
    return got


def table(cells, rows, counts, loads, args):
    """The Markdown table: per cell and counter the timing (when run) and the counts (--counts);
    met: the time ratio within TARGET, or without timing the instruction ratio."""
    head = [f"Old: {args.old}; new: {args.new}."]
    if loads:
        head.append(f"{args.rounds} alternated rounds, --benchmark_min_time={args.min_time}, "
                    f"taskset -c {args.cpu}; 1-min load before -> after each round: " +
                    ", ".join(f"{a.split(',')[0]} -> {b.split(',')[0]}" for a, b in loads) +
                    "; FFTW plans: " + ("each process its own." if args.own_plans else
                                        "one wisdom file shared by every process."))
        head.append("Time: median over rounds (ns per grad U, us per setup); ratio: median over "
                    "rounds of new / old [range].")
    if counts:
        head.append("Ir: callgrind instructions per grad U or per construction (outside FFTW), "
                    "bench/cell_counts.cpp; mallocs per construction.")
    lines = ["| cell | counter | old | new | ratio [range] | Ir old | Ir new | Ir ratio | "
             "mallocs old/new | met |", "|---|---|---|---|---|---|---|---|---|---|"]
    met = total = 0
    for bench in BENCHES:
        for cell in cells[bench]:
            kind, problem, method = cell.split("/")
            for counter in COUNTERS[kind]:
                row = rows.get((bench, cell, counter))
                c_old, c_new = (counts.get((side, f"{problem}/{method}/{counter}"))
                                for side in ("old", "new"))
                time = (f"{row[0]:.4g} | {row[1]:.4g} | {row[2]:.3f} [{row[3]:.2f}-{row[4]:.2f}]"
                        if row else " | | ")
                ir = (f"{c_old[0]:.0f} | {c_new[0]:.0f} | {c_new[0] / c_old[0]:.3f} | "
                      f"{c_old[1]:g} / {c_new[1]:g}" if c_old and c_new else " | | | ")
                ratio = row[2] if row else (c_new[0] / c_old[0] if c_old and c_new else None)
                if ratio is None:
                    continue
                total += 1
                met += ratio <= TARGET
                lines.append(f"| {bench} {cell} | {counter} | {time} | {ir} | "
                             f"{'yes' if ratio <= TARGET else 'NO'} |")
    head.append(f"Met (ratio <= {TARGET}): {met} / {total}.")
    return "\n".join(head) + "\n\n" + "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("old"), p.add_argument("new")
    p.add_argument("--rounds", type=int, default=5, help="timing rounds (0: counts only)")
    p.add_argument("--min-time", type=float, default=0.5)
    p.add_argument("--cpu", type=int, default=1)
    p.add_argument("--filter", default=".", help="regex on kind/problem/method")
    p.add_argument("--counts", action="store_true", help="callgrind instruction counts too")
    p.add_argument("--own-plans", action="store_true",
                   help="each process plans FFTW for itself (default: one shared wisdom file)")
    p.add_argument("--out", default=None, help="folder for the runs' files (default: a new one)")
    p.add_argument("--table", default=None, help="write the table there too")
    args = p.parse_args()
    if args.rounds < 0 or args.min_time <= 0 or (args.rounds == 0 and not args.counts):
        p.error("--rounds must be >= 0 (0: --counts alone) and --min-time > 0")
    for build in (args.old, args.new):
        for need in [binary(build, b) for b in BENCHES] + [os.path.join(build, "CMakeCache.txt")]:
            if not os.path.exists(need):
                p.error(f"{build} is not a build of erkn's benchmarks: no {need}")
    if args.counts and not shutil.which("valgrind"):
        p.error("--counts needs valgrind (apt-get install valgrind)")
    args.out = args.out or tempfile.mkdtemp(prefix="before_after_")
    os.makedirs(args.out, exist_ok=True)
    cells = common_cells(args)
    counts = count_cells(args, cells) if args.counts else {}
    rows, loads = {}, []
    if args.rounds:
        args.env = shared_wisdom(args)
        results, loads = time_rounds(args, cells)
        rows = timing_rows(results)
    text = table(cells, rows, counts, loads, args)
    print(text)
    if args.table:
        open(args.table, "w").write(text)


if __name__ == "__main__":
    main()
