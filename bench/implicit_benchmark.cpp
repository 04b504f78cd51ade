// The paper's implicit methods against the hand-written splitting peer, in the same run: thread
// CPU time per grad U evaluation of an erkn step of each implicit registry method, as a ratio to
// the peer's (bench/splitting_peer.hpp, same gradient code) of the registry's explicit method with
// the most stages; gradient evaluations per stage; and the share of erkn's step spent outside
// grad U (the gradient timed alone on the same states). Problems P1 sine-Gordon (N = 32), P2
// Duffing (d = 1), P3 stellar orbits (d = 2) at their paper step sizes (bench/bench_problems.hpp).
// Issue 9: the implicit runtime's CPU per grad U on tiny d against the explicit peer's.
//
// After the benchmarks, a summary table per method and problem: medians over the repetitions.
//
//   erkn_implicit_benchmark --benchmark_repetitions=5 [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <erkn/erkn.hpp>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "bench_problems.hpp"

namespace {

using bench::BatchTimes;
using bench::make_erkn;
using bench::make_peer;
using bench::seconds;
using bench::time_batches;

std::vector<erkn::Method> implicit_methods() {
  std::vector<erkn::Method> out;
  for (const erkn::Method& m : erkn::Method::all())
    if (!m.is_explicit()) out.push_back(m);
  return out;
}

// The peer's method: the explicit registry method with the most stages.
erkn::Method peer_method() {
  const erkn::Method* best = nullptr;
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed() &&
        (!best || m.stages() > best->stages()))
      best = &m;  // (the peer kicks with grad U only, without a processor)
  if (!best) throw erkn::Error("the registry has no explicit method for the peer");
  return *best;
}

// erkn (plain and compensated summation) and the peer in alternating batches of steps; the
// gradient alone on states of an untimed twin's trajectory.
template <class P>
void per_evaluation(benchmark::State& state) {
  const erkn::Method m = implicit_methods().at(size_t(state.range(0)));
  state.SetLabel(std::string(m.name()));
  erkn::Integrator plain = make_erkn<P>(m, false), kahan = make_erkn<P>(m, true);
  auto peer = make_peer<P>(peer_method());
  const erkn::Statistics s0 = plain.statistics();
  const long k0 = kahan.statistics().gradient_evaluations, p0 = peer.evaluations();
  erkn::Integrator twin = make_erkn<P>(m, false);
  const BatchTimes t = time_batches<P>(state, plain, kahan, peer, twin);
  const erkn::Statistics& s = plain.statistics();
  const double evals = double(s.gradient_evaluations - s0.gradient_evaluations);
  const double kahan_evals = double(kahan.statistics().gradient_evaluations - k0);
  const double peer_per_eval = t.peer / double(peer.evaluations() - p0);
  const double per_grad = t.grad / (double(state.iterations()) * BatchTimes::kBatch);
  state.counters["grad_ns"] = 1e9 * per_grad;
  state.counters["erkn_ns/eval"] = 1e9 * t.plain / evals;
  state.counters["peer_ns/eval"] = 1e9 * peer_per_eval;
  state.counters["ratio"] = t.plain / evals / peer_per_eval;
  state.counters["ratio_kahan"] = t.kahan / kahan_evals / peer_per_eval;
  state.counters["gradU/stage"] = evals / double(s.steps - s0.steps) / m.stages();
  state.counters["newton"] = double(s.newton_fallbacks - s0.newton_fallbacks);
  state.counters["erkn_outside_gradU"] = 1 - per_grad * evals / t.plain;
  benchmark::DoNotOptimize(peer.q().data());
}

// The console output, then per method and problem the medians over the repetitions.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const std::string& name = run.run_name.function_name;  // kind/problem/method
      const size_t a = name.find('/'), b = name.find('/', a + 1);
      auto& row = rows_[{name.substr(b + 1), name.substr(a + 1, b - a - 1)}];
      for (const auto& [counter, value] : run.counters) row[counter].push_back(value.value);
    }
    ConsoleReporter::ReportRuns(runs);
  }

  void Finalize() override {
    ConsoleReporter::Finalize();
    std::printf(
        "\nPer grad U evaluation, erkn's implicit step / the hand-written splitting peer of %s "
        "(medians over n runs):\n  same: erkn without compensated summation (the peer's "
        "arithmetic); default: compensated.\n\n",
        std::string(peer_method().name()).c_str());
    std::printf("%-14s %-3s %3s | %7s %7s | %8s %8s | %11s %7s\n", "method", "", "n", "same",
                "default", "erkn_ns", "peer_ns", "gradU/stage", "outside");
    for (const auto& [key, row] : rows_) {
      const auto median = [&](const std::string& name) {
        auto it = row.find(name);
        if (it == row.end() || it->second.empty()) return std::nan("");
        std::vector<double> v = it->second;
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
      };
      const auto it = row.find("ratio");
      std::printf("%-14s %-3s %3zu | %7.3f %7.3f | %8.1f %8.1f | %11.3f %7.3f\n", key.first.c_str(),
                  key.second.c_str(), it == row.end() ? size_t(0) : it->second.size(),
                  median("ratio"), median("ratio_kahan"), median("erkn_ns/eval"),
                  median("peer_ns/eval"), median("gradU/stage"), median("erkn_outside_gradU"));
    }
  }

 private:
  // (method, problem) -> counter -> one value per repetition
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::vector<double>>> rows_;
};

}  // namespace

// Registered in main: the methods come from the registry, which static initialisation of the
// benchmarks would read before it exists.
int main(int argc, char** argv) {
  const std::vector<erkn::Method> methods = implicit_methods();
  for (size_t i = 0; i < methods.size(); ++i) {
    const std::string name = std::string(methods[i].id_name());
    const auto add = [&](const char* problem, auto* function) {
      benchmark::RegisterBenchmark((std::string("PerEvaluation/") + problem + "/" + name).c_str(),
                                   function)
          ->Arg(long(i));
    };
    add("P1", per_evaluation<bench::P1>);
    add("P2", per_evaluation<bench::P2>);
    add("P3", per_evaluation<bench::P3>);
  }
  benchmark::Initialize(&argc, argv);
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
}
