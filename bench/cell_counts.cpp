// Instruction and allocation counts of the cells of erkn_explicit_benchmark and
// erkn_implicit_benchmark, for comparing two builds whose timings are too noisy to decide (issue
// 19: the cells against the numbers before the redesign). Compiled by
// scripts/bench_before_after.py against each build's headers and liberkn.a, so it uses only the
// API both have; run under `valgrind --tool=callgrind --collect-atstart=no`, each cell is one
// toggled region followed by a dump named after it (instructions do not depend on the load).
//
//   cell_counts PROBLEM METHOD_ID...   (PROBLEM: P1, P2 or P3; the ids as the benchmarks name them)
//
// Per method, the cells the benchmarks time, with the same objects:
//   plain, kahan: kSteps steps of Integrator::step() (compensated summation off / on) after
//     kWarmSteps untimed ones, the benchmark's steady state; prints the gradient evaluations.
//   ctor: kBuilds constructions of the Integrator alone from a System built beforehand.
//   total: kBuilds constructions with System and Stiffness from the problem's definition.
// Each line printed: "<cell> <gradient evaluations or constructions> <mallocs> <bytes>", the
// allocations counted by the malloc family below (every allocation of the process: Eigen's,
// operator new's and FFTW's all go through them).
#include <valgrind/callgrind.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <erkn/erkn.hpp>
#include <string>
#include <string_view>

#include "bench_problems.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
}

namespace {
std::size_t allocations = 0, allocated_bytes = 0;

void* counted(void* block, std::size_t bytes) {
  ++allocations, allocated_bytes += bytes;
  return block;
}
}  // namespace

// The malloc family, counting (free and the rest stay glibc's).
extern "C" {
void* malloc(std::size_t n) { return counted(__libc_malloc(n), n); }
void* calloc(std::size_t k, std::size_t n) { return counted(__libc_calloc(k, n), k * n); }
void* realloc(void* p, std::size_t n) { return counted(__libc_realloc(p, n), n); }
void* memalign(std::size_t a, std::size_t n) { return counted(__libc_memalign(a, n), n); }
void* aligned_alloc(std::size_t a, std::size_t n) { return memalign(a, n); }
int posix_memalign(void** out, std::size_t a, std::size_t n) {
  *out = memalign(a, n);
  return *out ? 0 : 12;  // (ENOMEM)
}
}

namespace {
constexpr int kWarmSteps = 1024, kSteps = 512, kBuilds = 64;

// Runs f as the cell `name` (one callgrind region and dump) and prints its counts; count: what f
// returns (gradient evaluations or constructions).
template <class F>
void cell(const std::string& name, F&& f) {
  const std::size_t a0 = allocations, b0 = allocated_bytes;
  CALLGRIND_TOGGLE_COLLECT;
  const long count = f();
  CALLGRIND_TOGGLE_COLLECT;
  const std::size_t a = allocations - a0, b = allocated_bytes - b0;
  CALLGRIND_DUMP_STATS_AT(name.c_str());
  std::printf("%s %ld %zu %zu\n", name.c_str(), count, a, b);
}

template <class P>
void steps(const std::string& name, const erkn::Method& m, bool compensated) {
  erkn::Integrator run = bench::make_erkn<P>(m, compensated);
  for (int k = 0; k < kWarmSteps; ++k) run.step();
  const long e0 = run.statistics().gradient_evaluations;
  cell(name, [&] {
    for (int k = 0; k < kSteps; ++k) run.step();
    return run.statistics().gradient_evaluations - e0;
  });
}

template <class P>
void builds(const std::string& name, const erkn::Method& m, bool from_definition) {
  const erkn::System system = bench::make_system<P>();
  const Eigen::VectorXd q0 = P::q0(), p0 = P::p0();
  cell(name, [&] {
    for (int k = 0; k < kBuilds; ++k) {
      if (from_definition) {
        erkn::Integrator run = bench::make_erkn<P>(m, true);
        benchmark::DoNotOptimize(&run);
      } else {
        erkn::Integrator run(m, system, P::h, q0, p0);
        benchmark::DoNotOptimize(&run);
      }
    }
    return long(kBuilds);
  });
}

template <class P>
void cells(std::string_view problem, const erkn::Method& m) {
  const std::string prefix = std::string(problem) + "/" + std::string(m.id_name()) + "/";
  steps<P>(prefix + "plain", m, false);
  steps<P>(prefix + "kahan", m, true);
  builds<P>(prefix + "ctor", m, false);
  builds<P>(prefix + "total", m, true);
}

const erkn::Method* find(std::string_view id) {
  for (const erkn::Method& m : erkn::Method::all())
    if (m.id_name() == id) return &m;
  return nullptr;
}
}  // namespace

int main(int argc, char** argv) {
  const std::string_view problem = argc > 1 ? argv[1] : "";
  if (argc < 3 || (problem != "P1" && problem != "P2" && problem != "P3")) {
    std::fprintf(stderr, "usage: cell_counts P1|P2|P3 METHOD_ID...\n");
    return 2;
  }
  for (int k = 2; k < argc; ++k) {
    const erkn::Method* m = find(argv[k]);
    if (!m) {
      std::fprintf(stderr, "cell_counts: no method with id %s\n", argv[k]);
      return 2;
    }
    if (problem == "P1") cells<bench::P1>(problem, *m);
    if (problem == "P2") cells<bench::P2>(problem, *m);
    if (problem == "P3") cells<bench::P3>(problem, *m);
  }
}
