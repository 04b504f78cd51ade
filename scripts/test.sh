#!/usr/bin/env bash
# The test command of the README: installs dependencies, builds everything, checks that the
# regenerate command leaves generated/ unchanged, and runs every test with ctest.
#
# scripts/test.sh --sanitize: instead, builds the runtime, the CLI and their fast tests with
# AddressSanitizer and UndefinedBehaviorSanitizer (incl. float-cast-overflow; any finding fails)
# in build-sanitize/ and runs them.
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ "${1:-}" == "--sanitize" ]]; then
  build=${ERKN_SANITIZE_BUILD_DIR:-build-sanitize}
  flags="-O1 -g -fno-omit-frame-pointer -fsanitize=address,undefined,float-cast-overflow"
  flags+=" -fno-sanitize-recover=all"
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DERKN_BUILD_GENERATOR=OFF \
    -DERKN_BUILD_BENCHMARKS=OFF -DCMAKE_CXX_FLAGS="$flags" \
    -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" > /dev/null
  cmake --build "$build" -j 2 --target erkn erkn_runtime_tests erkn_cli_tests erkn_stability_tests
  export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1
  ctest --test-dir "$build" -j 2 --output-on-failure -R '^(runtime|cli|stability)[._]' \
    -E 'InstalledPackage|LargestBoundedStepSizeTable'
  exit 0
fi
bash scripts/install-deps.sh
build=${ERKN_BUILD_DIR:-build}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$build" -j 2
cmake --build "$build" --target regenerate
if git rev-parse --git-dir > /dev/null 2>&1; then
  git diff --exit-code -- generated/ || { echo "generated/ is stale: commit the regenerated files"; exit 1; }
fi
ctest --test-dir "$build" -j 2 --output-on-failure
