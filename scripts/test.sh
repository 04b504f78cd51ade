#!/usr/bin/env bash
# The test command of the README: installs dependencies, builds everything, checks that the
# regenerate command leaves generated/ unchanged, and runs every test with ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
build=${ERKN_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" -j 2
cmake --build "$build" --target regenerate
if git rev-parse --git-dir > /dev/null 2>&1; then
  git diff --exit-code -- generated/ || { echo "generated/ is stale: commit the regenerated files"; exit 1; }
fi
ctest --test-dir "$build" -j 2 --output-on-failure
