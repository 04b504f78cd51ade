// erkn::solve with tol (method "auto", no h) against an exhaustive sweep over the registry.
//
// For every scene (P1, P2, P3, FPU, Henon-Heiles, 2-D sine-Gordon 32^2) and tol = 1e-4, 1e-6,
// 1e-8, 1e-10: the achieved error of q at t_end (max norm, against the exact solution or a
// long-double RKF7(8) reference) must lie in [tol/100, 3 tol], and the CPU of the whole solve
// (choice with its pilots + run) must be <= 1.5x the cheapest (method, h) of the sweep whose
// error is <= tol. The sweep runs every registry method at h = t_end / n, n = 2 * 2^(k/4), from
// the coarsest step down until the error is below the smallest tol or the run costs twice the
// best known for every tol it has not met. The final ratio is re-timed interleaved (auto, best,
// auto, ...: 7 rounds, median of per-round ratios), with the cost of one pilot attempt (the
// least a choice that measures the problem can spend). Thread CPU time; the machine is shared.
//
//   erkn_accuracy_benchmark [--markdown FILE] [--scene KEY]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <erkn/accuracy.hpp>
#include <erkn/error.hpp>
#include <erkn/problems.hpp>
#include <erkn/problems/reference.hpp>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "tolerance_scenes.hpp"

namespace {

using bench::fixed_run;
using bench::kInf;
using bench::Run;
using bench::sci;
using erkn::problems::Problem;
using Scene = bench::ToleranceScene;
constexpr double kTols[] = {1e-4, 1e-6, 1e-8, 1e-10};

// The whole accuracy-driven solve: choice (pilots, advisor) + run.
Run automatic(const Scene& s, double tol) {
  erkn::AccuracyRequest r;
  r.tol = tol;
  const double t0 = bench::thread_seconds();
  const erkn::Solution sol = erkn::solve(erkn::problems::system(s.problem), s.problem.q0,
                                         s.problem.p0, 0, s.problem.t_error, r);
  Run out{sol.method,
          sol.h,
          (sol.q - s.reference).lpNorm<Eigen::Infinity>(),
          bench::thread_seconds() - t0,
          sol.choice->pilot_cpu,
          sol.choice->estimated_error};
  return out;
}

// The cheapest run with error <= tol, per tol, over every method and step of the sweep.
using Best = std::map<double, Run>;

// Has this method still a tol whose best is unknown or more than half its current cost?
bool worth_finer(const Best& best, double error, double cpu) {
  for (double tol : kTols)
    if (error > tol && (!best.count(tol) || cpu < 2 * best.at(tol).cpu)) return true;
  return false;
}

// The cheapest run with error <= tol per method (sweep_method fills it; pruned methods miss
// tolerances they could not reach within twice the best cost known then).
using PerMethod = std::map<std::string, Best>;

void sweep_method(const Scene& s, const erkn::Method& m, Best& best, PerMethod& own, long& runs) {
  Best& mine = own[std::string(m.name())];
  for (int k = 0;; ++k) {
    const double n = std::ceil(2 * std::pow(2.0, k / 4.0));
    if (n > 4e6) return;
    const Run r = fixed_run(s, m, s.problem.t_error / n);
    ++runs;
    for (double tol : kTols) {
      if (r.error <= tol && (!best.count(tol) || r.cpu < best.at(tol).cpu)) best[tol] = r;
      if (r.error <= tol && (!mine.count(tol) || r.cpu < mine.at(tol).cpu)) mine[tol] = r;
    }
    if (r.error <= kTols[3] || (std::isfinite(r.cpu) && r.cpu > 2.0)) return;
    if (std::isfinite(r.cpu) && !worth_finer(best, r.error, r.cpu)) return;
  }
}

// Every registry method, highest order first (they set the bounds that prune the others).
Best sweep(const Scene& s, PerMethod& own, long& runs) {
  std::vector<const erkn::Method*> methods;
  for (const erkn::Method& m : erkn::Method::all()) methods.push_back(&m);
  std::stable_sort(methods.begin(), methods.end(),
                   [](auto* a, auto* b) { return a->order() > b->order(); });
  Best best;
  for (const erkn::Method* m : methods) sweep_method(s, *m, best, own, runs);
  return best;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

// The least any pilot could cost: one step-doubling attempt of the chosen method and h over
// t_end/32 (two integrators built, h and h/2), no search, no advisor. Thread CPU seconds.
double one_pilot_attempt(const Scene& s, const Run& chosen) {
  const double t0 = bench::thread_seconds();
  const erkn::Method& m = erkn::Method::by_name(chosen.method);
  const auto system = erkn::problems::system(s.problem);
  erkn::Integrator a(m, system, chosen.h, s.problem.q0, s.problem.p0);
  erkn::Integrator b(m, system, chosen.h / 2, s.problem.q0, s.problem.p0);
  const long n = std::max(2L, long(std::ceil(s.problem.t_error / 32 / chosen.h)));
  a.step(n), b.step(2 * n);
  return bench::thread_seconds() - t0;
}

// Medians of 7 interleaved rounds (auto, best, one pilot attempt): CPU ratios to the best run.
struct Ratios {
  double whole = kInf, choice = kInf, one_pilot = kInf;
};

Ratios interleaved_ratios(const Scene& s, double tol, const Run& best, Run& last_auto) {
  std::vector<double> whole, choice, one_pilot;
  for (int round = 0; round < 7; ++round) {
    last_auto = automatic(s, tol);
    const Run b = fixed_run(s, erkn::Method::by_name(best.method), best.h);
    whole.push_back(last_auto.cpu / b.cpu), choice.push_back(last_auto.choice_cpu / b.cpu);
    one_pilot.push_back(one_pilot_attempt(s, last_auto) / b.cpu);
  }
  return {median(whole), median(choice), median(one_pilot)};
}

struct Row {
  std::string scene;
  double tol = 0;
  Run automatic, best;
  Ratios ratios;
  bool window = false, cheap = false;
};

std::string fixed_digits(double x, int digits = 2) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::string markdown_row(const Row& r) {
  return "| " + r.scene + " | " + sci(r.tol, 0) + " | " + r.automatic.method + " | " +
         sci(r.automatic.h) + " | " + sci(r.automatic.error) + " | " +
         fixed_digits(r.automatic.estimate / r.automatic.error) + " | " +
         (r.window ? "met" : "**NOT met**") + " | " + r.best.method + " | " + sci(r.best.h) +
         " | " + sci(r.best.error) + " | " + fixed_digits(r.ratios.choice) + " | " +
         fixed_digits(r.ratios.one_pilot) + " | " + fixed_digits(r.ratios.whole) + " | " +
         (r.cheap ? "met" : "**NOT met**") + " |\n";
}

}  // namespace

namespace {

// Per method, its cheapest run's CPU over the cell's cheapest, one entry per cell (inf where it
// did not reach tol within the sweep's pruning bound).
using Tally = std::map<std::string, std::vector<double>>;

void tally_cell(const PerMethod& own, double tol, const Run& best, Tally& tally) {
  for (const auto& [name, mine] : own)
    tally[name].push_back(mine.count(tol) ? mine.at(tol).cpu / best.cpu : kInf);
}

std::vector<Row> rows_of(const Scene& s, std::string& notes, Tally& tally) {
  long runs = 0;
  const double t0 = bench::thread_seconds();
  PerMethod own;
  const Best best = sweep(s, own, runs);
  notes += "- " + s.problem.key + " (" + s.problem.title +
           ", t_end = " + fixed_digits(s.problem.t_error, 0) +
           ", d = " + std::to_string(s.problem.dim()) + "): reference " + s.reference_note +
           "; sweep " + std::to_string(runs) + " runs, " +
           fixed_digits(bench::thread_seconds() - t0) + " s CPU.\n";
  std::vector<Row> out;
  for (double tol : kTols) {
    Row r{s.problem.key, tol};
    if (!best.count(tol)) {
      notes += "- " + s.problem.key + ", tol " + sci(tol, 0) + ": no swept run reached it.\n";
      continue;
    }
    r.best = best.at(tol);
    tally_cell(own, tol, r.best, tally);
    r.ratios = interleaved_ratios(s, tol, r.best, r.automatic);
    r.window = r.automatic.error <= 3 * tol && r.automatic.error >= tol / 100;
    r.cheap = r.ratios.whole <= 1.5;
    std::cerr << markdown_row(r);
    out.push_back(r);
  }
  return out;
}

// Which single method comes closest to the cheapest over all cells (the default method's data):
// cells within 1.25x and 2x of the cheapest, and the median ratio (inf counts as above it).
std::string tally_table(const Tally& tally) {
  std::vector<std::pair<double, std::string>> rows;
  for (const auto& [name, ratios] : tally) {
    const int near =
        int(std::count_if(ratios.begin(), ratios.end(), [](double x) { return x <= 1.25; }));
    const int within =
        int(std::count_if(ratios.begin(), ratios.end(), [](double x) { return x <= 2; }));
    const double med = median(ratios);
    if (within == 0) continue;
    rows.emplace_back(
        med, "| " + name + " | " + std::to_string(near) + " | " + std::to_string(within) + " | " +
                 (std::isfinite(med) ? fixed_digits(med) : std::string("> 2")) + " |\n");
  }
  std::sort(rows.begin(), rows.end());
  std::string out =
      "\n## One method for every problem: the sweep per method\n\nEach method's cheapest "
      "swept run reaching tol, over the cheapest of all methods, per cell (" +
      std::to_string(tally.empty() ? 0 : tally.begin()->second.size()) +
      " cells; single sweep timings, not re-timed; a method pruned before reaching tol counts "
      "as above 2x). Methods never within 2x are left out.\n\n| method | cells <= 1.25x | "
      "cells <= 2x | median ratio |\n|---|---|---|---|\n";
  for (const auto& row : rows) out += row.second;
  return out;
}

std::string markdown(const std::vector<Row>& rows, const std::string& notes, const Tally& tally) {
  int window = 0, cheap = 0;
  for (const Row& r : rows) window += r.window, cheap += r.cheap;
  std::string out =
      "# Accuracy-driven runs: erkn::solve(tol) against the cheapest swept (method, h)\n\n"
      "<!-- Written by bench/accuracy_benchmark.cpp (erkn_accuracy_benchmark --markdown), run "
      "by scripts/main.sh. Do not edit. -->\n\n"
      "erkn::solve with tol, method \"auto\" and no h (erkn/accuracy.hpp: error constants, a "
      "pilot with step doubling, the advisor) against an exhaustive sweep over the registry "
      "(every method at h = t_end/n, n = 2 * 2^(k/4), pruned where it cannot win). Error: "
      "max norm of q at t_end against the reference. Targets: error in [tol/100, 3 tol]; CPU "
      "of the whole solve (choice + run) <= 1.5x the cheapest swept run with error <= tol "
      "(construction + integrate), re-timed interleaved, median of 7 per-round ratios; thread "
      "CPU time on a shared machine. 'choice CPU / best': the choice alone (pilot, Hessian "
      "bounds, advisor; a continued pilot's h run counts here) over the best run. 'one pilot "
      "attempt / "
      "best': the least a choice that measures the problem can spend (one step-doubling "
      "attempt of the chosen method and h over t_end/32: two integrators built, no search, no "
      "advisor) over the best run; where it exceeds 0.5, 1.5x needs a run cheaper than the "
      "best, i.e. is out of reach for such a choice. 'estimate / error': the choice's estimated "
      "error at t_end (the pilot's step-doubling estimate grown linearly over t_end, or as the "
      "growth probe measured where it ran, carried to the chosen h by the error model) over the "
      "achieved error; above 1 the step is smaller than tol needs.\n\n"
      "Error window met in " +
      std::to_string(window) + " / " + std::to_string(rows.size()) + " cases, CPU <= 1.5x in " +
      std::to_string(cheap) + " / " + std::to_string(rows.size()) +
      ".\n\n| scene | tol | auto | h | error | estimate / error | window | sweep's best | h | "
      "error | choice CPU / best | one pilot attempt / best | CPU ratio | <= 1.5x "
      "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) out += markdown_row(r);
  return out + "\n" + notes + tally_table(tally);
}

}  // namespace

int main(int argc, char** argv) {
  std::string markdown_file, only;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--markdown")
      markdown_file = argv[i + 1];
    else if (a == "--scene")
      only = argv[i + 1];
    else {
      std::cerr << "usage: erkn_accuracy_benchmark [--markdown FILE] [--scene KEY]\n";
      return 2;
    }
  }
  std::vector<Row> rows;
  std::string notes;
  Tally tally;
  for (Problem& p : bench::tolerance_problems(only)) {
    const Scene s = bench::tolerance_scene(std::move(p));
    for (Row& r : rows_of(s, notes, tally)) rows.push_back(r);
  }
  const std::string md = markdown(rows, notes, tally);
  if (markdown_file.empty()) {
    std::cout << md;
  } else {
    std::ofstream(markdown_file) << md;
  }
  return 0;
}
