// erkn's explicit path against a hand-written splitting integrator of the same method (built
// from the method's own nodes c and weights d, same gradient code; bench/splitting_peer.hpp), in
// the same run: time per grad U evaluation and setup time (thread CPU time), each as a ratio
// erkn / peer, and the share of a step spent outside grad U (the gradient timed alone on the same
// states). Problems: P1 sine-Gordon (N = 32, circulant M), P2 Duffing (d = 1), P3 stellar orbits
// (d = 2), docs/design.md §4. Methods: every explicit registry method.
//
// After the benchmarks, a summary table gives issue 9's three targets side by side per method
// and problem, as medians over the repetitions: the ratio per grad U evaluation (erkn with the
// peer's arithmetic, and with erkn's default compensated summation), the setup ratio, and the
// share outside grad U (erkn's default; the target is stated at N = 32, i.e. P1).
//
//   erkn_explicit_benchmark --benchmark_repetitions=9 [--benchmark_filter=...]
//       [--summary_markdown=docs/benchmarks.md]   (the summary also as Markdown; scripts/main.sh
//                                                  runs a short mode of it for docs/benchmarks.md)
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <erkn/erkn.hpp>
#include <map>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "bench_problems.hpp"

namespace {

using bench::BatchTimes;
using bench::make_erkn;
using bench::make_peer;
using bench::make_system;
using bench::P1;
using bench::P2;
using bench::P3;
using bench::seconds;
using bench::time_batches;

std::vector<erkn::Method> explicit_methods() {
  std::vector<erkn::Method> out;
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed())
      out.push_back(m);  // (the peer's kicks, no processor)
  return out;
}

// Per grad U evaluation: erkn (plain and compensated summation) and the peer, in alternating
// batches of steps. The gradient timed alone gives the share outside it: on a batch of states of
// the trajectory (one per step of an untimed twin), so its inputs vary as they do in a run.
template <class P>
void per_evaluation(benchmark::State& state) {
  const erkn::Method m = explicit_methods().at(size_t(state.range(0)));
  state.SetLabel(std::string(m.name()));
  erkn::Integrator plain = make_erkn<P>(m, false), kahan = make_erkn<P>(m, true);
  auto peer = make_peer<P>(m);
  long e0 = plain.statistics().gradient_evaluations, p0 = peer.evaluations();
  erkn::Integrator twin = make_erkn<P>(m, false);
  const BatchTimes t = time_batches<P>(state, plain, kahan, peer, twin);
  const double evals = double(plain.statistics().gradient_evaluations - e0);
  const double peer_evals = double(peer.evaluations() - p0);
  const double per_grad = t.grad / (double(state.iterations()) * BatchTimes::kBatch);
  state.counters["grad_ns"] = 1e9 * per_grad;
  state.counters["erkn_ns/eval"] = 1e9 * t.plain / evals;
  state.counters["erkn_kahan_ns/eval"] = 1e9 * t.kahan / evals;
  state.counters["peer_ns/eval"] = 1e9 * t.peer / peer_evals;
  state.counters["ratio"] = (t.plain / evals) / (t.peer / peer_evals);
  state.counters["ratio_kahan"] = (t.kahan / evals) / (t.peer / peer_evals);
  state.counters["erkn_outside_gradU"] = 1 - per_grad * evals / t.plain;
  state.counters["erkn_kahan_outside_gradU"] = 1 - per_grad * evals / t.kahan;
  state.counters["peer_outside_gradU"] = 1 - per_grad * peer_evals / t.peer;
  benchmark::DoNotOptimize(peer.q().data());
}

// Setup: constructing the integrator (default options) against constructing the peer, each
// from the problem's definition (erkn: System and Stiffness included); and the Integrator's
// constructor alone, from a System and initial state built beforehand.
template <class P>
void setup(benchmark::State& state) {
  const erkn::Method m = explicit_methods().at(size_t(state.range(0)));
  state.SetLabel(std::string(m.name()));
  const int batch = 16;
  const erkn::System system = make_system<P>();
  const Eigen::VectorXd q0 = P::q0(), p0 = P::p0();
  double t_erkn = 0, t_peer = 0, t_ctor = 0;
  for (auto _ : state) {
    t_ctor += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        erkn::Integrator run(m, system, P::h, q0, p0);
        benchmark::DoNotOptimize(&run);
      }
    });
    t_erkn += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        erkn::Integrator run = make_erkn<P>(m, true);
        benchmark::DoNotOptimize(&run);
      }
    });
    t_peer += seconds([&] {
      for (int k = 0; k < batch; ++k) {
        auto peer = make_peer<P>(m);
        benchmark::DoNotOptimize(&peer);
      }
    });
  }
  const double n = double(state.iterations()) * batch;
  state.counters["erkn_us"] = 1e6 * t_erkn / n;
  state.counters["peer_us"] = 1e6 * t_peer / n;
  state.counters["ratio"] = t_erkn / t_peer;
  state.counters["erkn_ctor_us"] = 1e6 * t_ctor / n;
  state.counters["ratio_ctor"] = t_ctor / t_peer;
}

// The console output, and after it the summary table: per method and problem the medians over
// the repetitions of the counters the table shows.
class SummaryReporter : public benchmark::ConsoleReporter {
 public:
  static constexpr double kPerEvaluationTarget = 1.1, kSetupTarget = 1.5;

  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.run_type != Run::RT_Iteration || run.error_occurred) continue;
      const std::string& name = run.run_name.function_name;  // kind/problem/method
      const size_t a = name.find('/'), b = name.find('/', a + 1);
      auto& row = rows_[{name.substr(b + 1), name.substr(a + 1, b - a - 1)}];
      for (const auto& [counter, value] : run.counters)
        row[name.substr(0, a) + "." + counter].push_back(value.value);
    }
    ConsoleReporter::ReportRuns(runs);
  }

  // summary_path: where to write the summary as Markdown too (empty: nowhere).
  explicit SummaryReporter(std::string summary_path) : summary_path_(std::move(summary_path)) {}

  void Finalize() override {
    ConsoleReporter::Finalize();
    const std::string table = summary();
    std::printf("\n%s", table.c_str());
    if (summary_path_.empty()) return;
    std::FILE* out = std::fopen(summary_path_.c_str(), "w");
    if (!out) {
      std::fprintf(stderr, "cannot write %s\n", summary_path_.c_str());
      std::exit(1);
    }
    std::fprintf(out,
                 "<!-- Generated by erkn_explicit_benchmark (bench/explicit_benchmark.cpp) from "
                 "scripts/main.sh. Do not edit. -->\n# The explicit path against hand-written "
                 "splitting peers\n\nerkn's explicit methods against a hand-written splitting "
                 "integrator of the same method (same nodes, weights and gradient code; "
                 "bench/splitting_peer.hpp), thread CPU time, in one run of `%s`.\n\n```\n%s```\n",
                 command_.c_str(), table.c_str());
    std::fclose(out);
  }
  void set_command(std::string command) { command_ = std::move(command); }

 private:
  // The summary table: per method and problem the medians of the ratios, with the verdicts.
  std::string summary() const {
    std::string out;
    const auto add = [&](const char* format, auto... args) {
      char line[512];
      std::snprintf(line, sizeof line, format, args...);
      out += line;
    };
    add("Issue 9 targets, medians over repetitions (n = runs per cell).\n"
        "Per grad U evaluation, erkn / peer of the same method (target <= %.1f): same = erkn with "
        "the peer's arithmetic (no compensated summation), default = erkn's defaults "
        "(compensated).\n",
        kPerEvaluationTarget);
    add("Setup erkn / peer (target <= %.1f): total = System, Stiffness and Integrator from the "
        "problem's definition (the target), ctor = the Integrator's constructor alone.\n"
        "Outside grad U: erkn's default step (target <= 0.5 at N = 32: P1), the peer's in "
        "brackets.\n\n",
        kSetupTarget);
    add("%-10s %-3s %2s | %6s %7s %-7s | %6s %6s %-7s | %7s %7s\n", "method", "", "n", "same",
        "default", "", "total", "ctor", "", "outside", "(peer)");
    int met[2] = {0, 0}, cells[2] = {0, 0};
    for (const auto& [key, row] : rows_) {
      const auto median = [&](const std::string& name) {
        auto it = row.find(name);
        if (it == row.end() || it->second.empty()) return std::nan("");
        std::vector<double> v = it->second;
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
      };
      // "met" when the worse of the two cells is within the target.
      const auto verdict = [&](double a, double b, double target, int k) {
        if (std::isnan(a) || std::isnan(b)) return "";
        ++cells[k];
        if (std::max(a, b) > target) return "NOT met";
        ++met[k];
        return "met";
      };
      const double same = median("PerEvaluation.ratio"),
                   kahan = median("PerEvaluation.ratio_kahan");
      const double setup = median("Setup.ratio"), ctor = median("Setup.ratio_ctor");
      const auto it = row.find("PerEvaluation.ratio");
      add("%-10s %-3s %2zu | %6.3f %7.3f %-7s | %6.3f %6.3f %-7s | %7.3f (%5.3f)\n",
          key.first.c_str(), key.second.c_str(), it == row.end() ? size_t(0) : it->second.size(),
          same, kahan, verdict(same, kahan, kPerEvaluationTarget, 0), setup, ctor,
          verdict(setup, setup, kSetupTarget, 1), median("PerEvaluation.erkn_kahan_outside_gradU"),
          median("PerEvaluation.peer_outside_gradU"));
    }
    add("\nPer grad U (both columns) met in %d of %d cells; setup (total) in %d of %d.\n", met[0],
        cells[0], met[1], cells[1]);
    return out;
  }

  std::string summary_path_, command_;
  // (method, problem) -> "Kind.counter" -> one value per repetition
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::vector<double>>> rows_;
};

}  // namespace

// Registered in main: the methods come from the registry, which static initialisation of the
// benchmarks would read before it exists.
int main(int argc, char** argv) {
  const std::vector<erkn::Method> methods = explicit_methods();
  for (size_t i = 0; i < methods.size(); ++i) {
    const std::string name = std::string(methods[i].id_name());
    const auto add = [&](const std::string& kind, const char* problem, auto* function) {
      benchmark::RegisterBenchmark((kind + "/" + problem + "/" + name).c_str(), function)
          ->Arg(long(i));
    };
    add("PerEvaluation", "P1", per_evaluation<P1>);
    add("PerEvaluation", "P2", per_evaluation<P2>);
    add("PerEvaluation", "P3", per_evaluation<P3>);
    add("Setup", "P1", setup<P1>);
    add("Setup", "P2", setup<P2>);
    add("Setup", "P3", setup<P3>);
  }
  // Our own flag, taken out before Google Benchmark reads the rest.
  std::string summary_path, command = "erkn_explicit_benchmark";
  const std::string flag = "--summary_markdown=";
  int kept = 1;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg.rfind(flag, 0) == 0) {
      summary_path = arg.substr(flag.size());
      continue;
    }
    command += " " + arg;
    argv[kept++] = argv[k];
  }
  argc = kept;
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  SummaryReporter reporter(summary_path);
  reporter.set_command(command);
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
}
