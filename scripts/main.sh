#!/usr/bin/env bash
# The main job of the README: installs dependencies, regenerates the tableaux, builds, runs
# the experiments and the stability analysis, and writes the charts and tables under docs/.
# Extra arguments go to the experiments (e.g. --full for the long sweep).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build=${ERKN_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" --target regenerate
cmake --build "$build" -j 2
"$build"/bin/erkn list
"$build"/bin/erkn run --out docs "$@"
"$build"/bin/erkn stability all --out docs/charts
"$build"/experiments/erkn_stability_hmax docs/stability.md
"$build"/experiments/erkn_advisor_sweep --offset 0.25 docs/advisor.md  # the advisor against 1e5-step runs (constants chosen at --offset 0.5)
"$build"/scaling/erkn-ensemble-speedup --out docs
# What users call (Integrator construction + integrate) against the loop a specialist writes
# (issue 17; built with FFTW), short mode, twice: the second run writes docs/benchmarks.md with
# its per-cell spread against the first. Both plan their FFTW transforms from one wisdom file
# (ERKN_FFTW_WISDOM, runtime/src/fftw_backend.cpp), so their implicit runs do the same
# iterations rather than differ at round-off with each process's FFTW_MEASURE plans.
if [ -x "$build"/bench/erkn_integrate_benchmark ]; then
  export ERKN_FFTW_WISDOM="$build"/fftw_wisdom
  "$build"/bench/erkn_integrate_benchmark --short --csv "$build"/benchmarks_first.csv > /dev/null
  "$build"/bench/erkn_integrate_benchmark --short --csv "$build"/benchmarks_second.csv \
    --compare "$build"/benchmarks_first.csv --markdown docs/benchmarks.md > /dev/null
  if [ -d "$build"/python/erkn ]; then  # erkn.solve against C++ integrate: a second table
    python=$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' "$build"/CMakeCache.txt)
    PYTHONPATH="$build"/python "${python:-python3}" bench/python_solve_benchmark.py --short \
      --server "$build"/bench/erkn_integrate_benchmark --markdown docs/benchmarks.md > /dev/null
  fi
fi
# A Henon-Heiles Poincare section from erkn.solve's events (docs/poincare.md, the README's picture).
if [ -d "$build"/python/erkn ]; then
  python=$(sed -n 's/^Python_EXECUTABLE:FILEPATH=//p' "$build"/CMakeCache.txt)
  PYTHONPATH="$build"/python "${python:-python3}" scripts/poincare_section.py --charts docs/charts \
    --markdown docs/poincare.md
fi
# erkn.solve(tol) (method and h chosen) against the cheapest (method, h) of a sweep over the
# registry: error window and CPU ratio per scene and tolerance (issue 20).
if [ -x "$build"/bench/erkn_accuracy_benchmark ]; then
  "$build"/bench/erkn_accuracy_benchmark --markdown docs/accuracy.md 2> /dev/null
  python3 scripts/readme_tables.py  # the README's "Choosing a method" table from that run
fi
# The best modified-kick method against the best plain-kick one, CPU to a tolerance (issue 18).
if [ -x "$build"/bench/erkn_modified_kick_benchmark ]; then
  "$build"/bench/erkn_modified_kick_benchmark --markdown docs/modified_kicks.md > /dev/null 2>&1
  # Processed methods against the best unprocessed one, and what output costs them.
  "$build"/bench/erkn_modified_kick_benchmark --processing docs/processing.md \
    --against "SRKN14a,OMF6(5F3G)" > /dev/null 2>&1
fi
if [ -x "$build"/mpi/erkn-mpi ]; then  # MPI scaling on 1, 2 and 4 ranks (erkn::mpi built)
  [ "$(id -u)" -ne 0 ] || export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  export OMPI_MCA_btl_vader_single_copy_mechanism=none  # (CMA fails in containers)
  rm -f docs/mpi_scaling.tsv
  for ranks in 1 2 4; do
    mpirun -np "$ranks" --oversubscribe "$build"/mpi/erkn-mpi scaling --table docs/mpi_scaling.tsv
  done
  # One rank against the serial library, per method (explicit: the cheapest and the default).
  mpirun -np 1 "$build"/mpi/erkn-mpi versus --table docs/mpi_scaling.tsv \
    --methods "Strang;SD9(10,6,4);SERKN2s4"
  "$build"/mpi/erkn-mpi report --table docs/mpi_scaling.tsv --out docs/mpi.md
fi
