// One step of SERKN3s4(1) on sine-Gordon (problem 1, docs/design.md §4) with N grid points,
// M circulant (FFT) or dense (eigenbasis): time per step, grad U evaluations per step, and the
// share of the step spent outside grad U (the integrator's own work).
//
// h = 0.8/N keeps h^2 lambda_max = 0.64 for every N (h = 1/40 at N = 32, the paper's step);
// a fixed h would push h^2 lambda_max ~ N^2 h^2 past the poles' table for large N.
//
//   erkn_step_benchmark [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <erkn/erkn.hpp>
#include <map>
#include <numbers>

namespace {

using Clock = std::chrono::steady_clock;

enum Path { kCirculant, kDense };

// Cached: Google Benchmark calls a benchmark several times, and the dense setup is O(N^3).
const erkn::Stiffness& sine_gordon_M(int N, Path path) {
  static std::map<std::pair<int, Path>, erkn::Stiffness> cache;
  if (auto it = cache.find({N, path}); it != cache.end()) return it->second;
  const double dx = 2.0 / N;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(N);
  col[0] = 2 / (dx * dx);
  col[1] = col[N - 1] = -1 / (dx * dx);
  const erkn::Stiffness circ = erkn::Stiffness::circulant(col);
  return cache
      .emplace(std::pair{N, path},
               path == kCirculant ? circ : erkn::Stiffness::dense(circ.to_dense(N)))
      .first->second;
}

void step(benchmark::State& state, Path path, bool compensated) {
  const int N = int(state.range(0));
  const double pi = std::numbers::pi;
  Eigen::VectorXd q0 = Eigen::VectorXd::Constant(N, pi), p0(N);
  for (int i = 0; i < N; ++i) p0[i] = std::sqrt(N) * (0.01 + std::sin(2 * pi * (i + 1) / N));
  Clock::duration in_gradient{};
  erkn::System sys;
  sys.M = sine_gordon_M(N, path);
  sys.gradient = [&](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    const auto start = Clock::now();
    g = q.array().sin();
    in_gradient += Clock::now() - start;
  };
  erkn::Options options;
  options.compensated_summation = compensated;
  erkn::Integrator run(erkn::Method::by_name("SERKN3s4(1)"), sys, 0.8 / N, q0, p0, options);
  for (int k = 0; k < 10; ++k) run.step();  // warm-up: starting guesses from a previous step
  const erkn::Statistics before = run.statistics();
  in_gradient = {};
  const auto start = Clock::now();
  for (auto _ : state) run.step();
  const double total = std::chrono::duration<double>(Clock::now() - start).count();
  const erkn::Statistics& after = run.statistics();
  const double steps = double(after.steps - before.steps);
  state.counters["gradU/step"] =
      double(after.gradient_evaluations - before.gradient_evaluations) / steps;
  state.counters["gradU/stage"] = state.counters["gradU/step"] / 3;
  state.counters["outside_gradU"] = 1 - std::chrono::duration<double>(in_gradient).count() / total;
  state.counters["newton"] = double(after.newton_fallbacks - before.newton_fallbacks);
  state.SetComplexityN(N);
}

void BM_StepCirculant(benchmark::State& s) { step(s, kCirculant, true); }
void BM_StepDense(benchmark::State& s) { step(s, kDense, true); }
void BM_StepCirculantUncompensated(benchmark::State& s) { step(s, kCirculant, false); }
void BM_StepDenseUncompensated(benchmark::State& s) { step(s, kDense, false); }

// Setup cost at small d (problem 3: diagonal M = diag(4, 1), d = 2): constructing the
// integrator, alone and followed by the ~10 steps that reach 1e-6 there.
void construct(benchmark::State& state, int steps) {
  const erkn::Method& method = erkn::Method::by_name("SERKN2s3");
  const double eps = 1e-3;
  const Eigen::Vector2d q0(1, 1), p0(0, 0);
  for (auto _ : state) {
    erkn::System sys;
    sys.M = erkn::Stiffness::diagonal(Eigen::Vector2d(4, 1));
    sys.gradient = [eps](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
      g.resize(2);
      g[0] = -eps * q[1] * q[1];
      g[1] = -2 * eps * q[0] * q[1];
    };
    sys.potential = [eps](const Eigen::VectorXd& q) { return -eps * q[0] * q[1] * q[1]; };
    erkn::Integrator run(method, std::move(sys), 1.0 / 8, q0, p0);
    for (int k = 0; k < steps; ++k) run.step();
    benchmark::DoNotOptimize(run.q().data());
  }
}

void BM_ConstructDiagonal2(benchmark::State& s) { construct(s, 0); }
void BM_ConstructDiagonal2And10Steps(benchmark::State& s) { construct(s, 10); }

BENCHMARK(BM_ConstructDiagonal2);
BENCHMARK(BM_ConstructDiagonal2And10Steps);
BENCHMARK(BM_StepCirculant)->RangeMultiplier(2)->Range(32, 4096)->Complexity(benchmark::oNLogN);
BENCHMARK(BM_StepDense)->Arg(32)->Arg(256)->Arg(4096)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_StepCirculantUncompensated)->Arg(32)->Arg(256)->Arg(4096);
BENCHMARK(BM_StepDenseUncompensated)->Arg(32)->Arg(256);

}  // namespace

BENCHMARK_MAIN();
