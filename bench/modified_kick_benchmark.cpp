// Modified kicks against plain kicks (issue 18's table): for each scene and tolerance, every
// explicit registry method runs with h = t_end / n, n = 2 * 2^(k/8), from coarse to fine until
// its error of q at t_end (max norm, against the exact solution or a long-double RKF7(8)
// reference) is <= tol; the cheapest such run per group (plain kicks, modified kicks:
// Method::has_modified_kicks) is the group's best. The two bests are then re-timed interleaved
// (plain, modified, plain, ...: 9 rounds; construction + integrate as a user calls them, thread
// CPU time; the machine is shared) and the median per-round ratio reported.
//
// Processed methods are left out of those groups; --processing FILE instead writes their table
// (processing_cells.hpp) for P1 (sine-Gordon N = 32) at 1e-6 and 1e-9 and the cost of output.
//
//   erkn_modified_kick_benchmark [--markdown FILE] [--processing FILE [--against A,B,...]]
// (--against: unprocessed methods timed beside the processed ones, e.g. the bests of earlier
// runs.)
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <erkn/erkn.hpp>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "processing_cells.hpp"
#include "tolerance_scenes.hpp"

namespace {

using bench::kInf;
using bench::Run;
using bench::ToleranceScene;
using erkn::problems::Problem;

struct Cell {
  ToleranceScene scene;
  double tol;
};

// Calls of System::gradient and of System::hessian_vector_product in one run of m at h.
std::string evaluations(const Cell& c, const erkn::Method& m, double h) {
  const erkn::problems::Problem& p = c.scene.problem;
  erkn::Integrator it(m, erkn::problems::system(p), h, p.q0, p.p0);
  it.integrate(p.t_error);
  return std::to_string(it.statistics().gradient_evaluations) + " + " +
         std::to_string(it.statistics().hessian_vector_products);
}

// The method's coarsest run with error <= tol (timed as the median of 3), or none (cpu inf).
Run cheapest(const Cell& c, const erkn::Method& m) {
  for (int k = 0;; ++k) {
    const double n = std::ceil(2 * std::pow(2.0, k / 8.0));
    if (n > 2e5) return Run{std::string(m.name())};
    const double h = c.scene.problem.t_error / n;
    Run r = bench::fixed_run(c.scene, m, h);
    if (!(r.error <= c.tol)) continue;
    std::vector<double> cpu = {r.cpu, bench::fixed_run(c.scene, m, h).cpu,
                               bench::fixed_run(c.scene, m, h).cpu};
    std::sort(cpu.begin(), cpu.end());
    r.cpu = cpu[1];
    return r;
  }
}

// The cheapest run over the unprocessed explicit methods with (or without) modified kicks.
Run best_of(const Cell& c, bool modified) {
  Run best;
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_explicit() && m.has_modified_kicks() == modified && !m.is_processed())
      if (const Run r = cheapest(c, m); r.cpu < best.cpu) best = r;
  return best;
}

double median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

struct Row {
  std::string scene;
  double tol = 0;
  Run plain, modified;
  double plain_cpu = kInf, modified_cpu = kInf, ratio = kInf;  // interleaved medians
};

// The two bests re-timed interleaved: 9 rounds, medians of the CPU times and of the ratios.
void interleave(const Cell& c, Row& row) {
  if (!std::isfinite(row.plain.cpu) || !std::isfinite(row.modified.cpu)) return;
  const erkn::Method &a = erkn::Method::by_name(row.plain.method),
                     &b = erkn::Method::by_name(row.modified.method);
  std::vector<double> ta, tb, ratio;
  for (int round = 0; round < 9; ++round) {
    ta.push_back(bench::fixed_run(c.scene, a, row.plain.h).cpu);
    tb.push_back(bench::fixed_run(c.scene, b, row.modified.h).cpu);
    ratio.push_back(tb.back() / ta.back());
  }
  row.plain_cpu = median(ta), row.modified_cpu = median(tb), row.ratio = median(ratio);
}

// The 1-minute load average (the machine is shared), "?" when unknown.
std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string first;
  return f >> first ? first : "?";
}

std::string fmt(const char* f, double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

std::string describe(const Cell& c, const Run& r, double cpu) {
  if (!std::isfinite(r.cpu)) return "none reaches tol | | | | |";
  return r.method + " | " + fmt("%.3g", r.h) + " | " + fmt("%.2e", r.error) + " | " +
         evaluations(c, erkn::Method::by_name(r.method), r.h) + " | " + fmt("%.1f", 1e6 * cpu) +
         " |";
}

std::string markdown_row(const Cell& c, const Row& r) {
  return "| " + r.scene + " | " + fmt("%.0e", r.tol) + " | " + describe(c, r.plain, r.plain_cpu) +
         " " + describe(c, r.modified, r.modified_cpu) + " " + fmt("%.2f", r.ratio) + " |\n";
}

// One processing cell: the unprocessed best and every processed method's cheapest run, re-timed
// interleaved; then the best processed one against the unprocessed best with an observer every
// k steps.
std::string processing_rows(const Cell& c, const std::vector<std::string>& against,
                            std::string& output_rows) {
  std::vector<Run> runs = {std::min(best_of(c, false), best_of(c, true),
                                    [](const Run& a, const Run& b) { return a.cpu < b.cpu; })};
  for (const std::string& name : against)
    if (name != runs[0].method) runs.push_back(cheapest(c, erkn::Method::by_name(name)));
  const size_t first_processed = runs.size();
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_processed()) runs.push_back(cheapest(c, m));
  std::vector<std::function<double()>> timed;
  for (const Run& r : runs)
    timed.push_back([&c, r] {
      return std::isfinite(r.cpu)
                 ? bench::fixed_run(c.scene, erkn::Method::by_name(r.method), r.h).cpu
                 : kInf;
    });
  const bench::Interleaved t = bench::interleaved(timed, 15);
  std::string rows;
  size_t best = first_processed;
  for (size_t i = 0; i < runs.size(); ++i) {
    rows += "| " + c.scene.problem.title + " | " + fmt("%.0e", c.tol) + " | " +
            describe(c, runs[i], t.cpu[i]) + " " + fmt("%.2f", t.ratio[i]) + " |\n";
    if (i > first_processed && t.cpu[i] < t.cpu[best]) best = i;
  }
  if (best >= runs.size() || !std::isfinite(runs[best].cpu)) return rows;
  for (long every : {1L, 4L, 16L, 64L, 0L}) {
    auto run = [&c, every](const Run& r) {
      return [&c, every, r] {
        return bench::observed_run(c.scene, erkn::Method::by_name(r.method), r.h, every);
      };
    };
    const bench::Interleaved o = bench::interleaved({run(runs[0]), run(runs[best])}, 9);
    output_rows += "| " + c.scene.problem.title + " | " + fmt("%.0e", c.tol) + " | " +
                   (every ? std::to_string(every) : std::string("end only")) + " | " +
                   runs[0].method + " | " + fmt("%.1f", 1e6 * o.cpu[0]) + " | " +
                   runs[best].method + " | " + fmt("%.1f", 1e6 * o.cpu[1]) + " | " +
                   fmt("%.2f", o.ratio[1]) + " |\n";
  }
  return rows;
}

int processing_main(const std::string& markdown, const std::vector<std::string>& against) {
  namespace pr = erkn::problems;
  std::string table =
      "| scene | tol | method | h | error | gradients + G | CPU us | / unprocessed best |\n"
      "|---|---|---|---|---|---|---|---|\n";
  std::string output =
      "| scene | tol | output every k steps | unprocessed best | CPU us | processed best | CPU us "
      "| processed / unprocessed |\n|---|---|---|---|---|---|---|---|\n";
  for (double tol : {1e-6, 1e-9}) {
    const Cell c{bench::tolerance_scene(pr::sine_gordon(32)), tol};
    table += processing_rows(c, against, output);
    std::cerr << table << output;
  }
  std::string against_note;
  for (const std::string& a : against)
    against_note += (against_note.empty() ? " --against " : ",") + a;
  std::ofstream out(markdown);
  out << "<!-- Written by bench/modified_kick_benchmark.cpp (erkn_modified_kick_benchmark "
         "--processing docs/processing.md); do not edit. -->\n\n"
      << "# Processed methods\n\n"
      << "Run: erkn_modified_kick_benchmark --processing docs/processing.md" << against_note
      << ".\n\n"
      << "Each processed method (psi = pi o K o pi^-1: the kernel K steps, pi^-1 runs once at the "
         "start, pi at every state looked at) against the best unprocessed method of the "
         "registry (the cheapest run to tol over the explicit methods with plain or modified "
         "kicks), the methods named by --against, each one's coarsest n = 2 * 2^(k/8) with error "
         "of q at t_end <= tol, re-timed "
         "interleaved, 15 rounds, medians of the CPU times (construction + integrate + q(), "
         "thread CPU) and of the per-round ratios. \"gradients + G\": calls of System::gradient "
         "and System::hessian_vector_product per run (the processor's included). 1-minute load "
         "average at the end of the run: "
      << load_average() << " (2 cores).\n\n"
      << table
      << "\n## The cost of output\n\nThe best processed method and the unprocessed best at "
         "their h above, with an observer every k steps (every observed state costs pi: "
         "Statistics::processor_applications), 9 interleaved rounds, medians.\n\n"
      << output;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string markdown, processing;
  std::vector<std::string> against;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--markdown") markdown = value;
    if (key == "--processing") processing = value;
    for (size_t b = 0, e = 0; key == "--against" && b <= value.size(); b = e + 1) {
      e = std::min(value.find(',', b), value.size());
      against.push_back(value.substr(b, e - b));
    }
  }
  if (!processing.empty()) return processing_main(processing, against);
  namespace pr = erkn::problems;
  const std::vector<std::pair<Problem, double>> cells = {
      {pr::sine_gordon(32), 1e-6},  {pr::sine_gordon(32), 1e-9},  {pr::duffing(), 1e-9},
      {pr::stellar_orbits(), 1e-9}, {pr::sine_gordon(128), 1e-6}, {pr::sine_gordon(512), 1e-6}};
  std::string table =
      "| scene | tol | best plain-kick method | h | error | gradients + G | CPU us | best "
      "modified-kick method | h | error | gradients + G | CPU us | modified / plain |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& [problem, tol] : cells) {
    const Cell c{bench::tolerance_scene(problem), tol};
    Row row{problem.title, tol, best_of(c, false), best_of(c, true)};
    interleave(c, row);
    table += markdown_row(c, row);
    std::cerr << markdown_row(c, row);
  }
  std::cout << table;
  if (!markdown.empty()) {
    std::ofstream out(markdown);
    out << "<!-- Written by bench/modified_kick_benchmark.cpp (erkn_modified_kick_benchmark "
           "--markdown docs/modified_kicks.md); do not edit. -->\n\n"
        << "# Modified kicks against plain kicks\n\n"
        << "Each cell: the cheapest run (construction + integrate, thread CPU time) whose error "
           "of q at t_end is <= tol, over the explicit methods with plain kicks and over those "
           "with modified kicks (h = t_end / n, n = 2 * 2^(k/8)); the two re-timed interleaved, "
           "9 rounds, medians (CPU us and the per-round ratio). \"gradients + G\": calls of "
           "System::gradient and System::hessian_vector_product per run. 1-minute load "
           "average at the end of the run: "
        << load_average() << " (2 cores).\n\n"
        << table;
  }
  return 0;
}
