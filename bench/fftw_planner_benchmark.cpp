// Which FFTW planner flag pays for the grid transforms: FFTW_ESTIMATE or FFTW_MEASURE. Per grid,
// the planning time of a forward + inverse pair (MEASURE: first plan of the process, without
// wisdom) and the time of one forward + inverse pair (the integrator's per-iteration cost).
// The runtime plans once per Integrator, so MEASURE pays when
//   planning(MEASURE) - planning(ESTIMATE) < (pair(ESTIMATE) - pair(MEASURE)) * pairs per run.
#include <benchmark/benchmark.h>
#include <fftw3.h>

#include <chrono>
#include <vector>

namespace {

// The kinds of the scenes: 2-D periodic (R2HC/HC2R), 3-D Dirichlet (RODFT00 both ways).
struct Grid {
  std::vector<int> n;
  fftw_r2r_kind forward, inverse;
};

Grid grid_of(int64_t kind, int64_t n) {
  if (kind == 2) return {{int(n), int(n)}, FFTW_R2HC, FFTW_HC2R};
  return {{int(n), int(n), int(n)}, FFTW_RODFT00, FFTW_RODFT00};
}

void BM_TransformPair(benchmark::State& state) {
  const Grid g = grid_of(state.range(0), state.range(1));
  const unsigned flags = state.range(2) ? FFTW_MEASURE : FFTW_ESTIMATE;
  size_t d = 1;
  for (int n : g.n) d *= size_t(n);
  double *in = fftw_alloc_real(d), *out = fftw_alloc_real(d);
  std::vector<fftw_r2r_kind> fk(g.n.size(), g.forward), ik(g.n.size(), g.inverse);
  fftw_forget_wisdom();
  auto t0 = std::chrono::steady_clock::now();
  fftw_plan f = fftw_plan_r2r(int(g.n.size()), g.n.data(), in, out, fk.data(), flags);
  fftw_plan b = fftw_plan_r2r(int(g.n.size()), g.n.data(), out, in, ik.data(), flags);
  const double plan_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (size_t i = 0; i < d; ++i) in[i] = double(i % 17) - 8;
  for (auto _ : state) {
    fftw_execute(f);
    fftw_execute(b);
    benchmark::DoNotOptimize(in[0]);
  }
  state.counters["plan_ms"] = 1e3 * plan_seconds;
  state.counters["d"] = double(d);
  fftw_destroy_plan(f), fftw_destroy_plan(b);
  fftw_free(in), fftw_free(out);
}

}  // namespace

// (dimension, n, measure?)
BENCHMARK(BM_TransformPair)
    ->ArgsProduct({{2}, {256, 1024}, {0, 1}})
    ->ArgsProduct({{3}, {64, 128}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
