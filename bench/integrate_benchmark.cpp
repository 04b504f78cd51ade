// What users call against the loop a specialist writes (issue 17): for every explicit registry
// method, erkn::Integrator construction + integrate(t_end) against the specialist's splitting
// loop of the same method (bench/specialist_peer.hpp) doing the same steps from the same initial
// data, setup included on both sides (the peer's FFTW plans, like erkn's per-process plans, are
// made before timing). Three ratios per method and scene, erkn / peer:
//   plain    compensated summation off             target <= 1.0
//   default  erkn's default Options                target <= 1.05
//   output   default, integrate(t_end, times, observer) with 20 output times on the grid,
//            against the peer stopping there and transforming back          target <= 1.05
// and for every implicit registry method its CPU per grad U against the explicit path's (the
// median over explicit methods, same scene, same rounds; defaults) on P2, P3 and sine-Gordon
// N = 32 (target <= 1.2), and the fewest steps to 1e-6 of every explicit method in the peer and
// whether erkn accepts that step size (bench/integrate_steps.hpp). Scenes: Duffing (P2), stellar
// orbits (P3), sine-Gordon N = 32, 512, 2048, 8192 (problems::sine_gordon) and the 2-D periodic
// sine-Gordon 256^2.
//
//   erkn_integrate_benchmark [--short] [--markdown FILE] [--csv FILE] [--compare CSV]
//                            [--scene TEXT] [--method NAME]
//   erkn_integrate_benchmark --serve
// --short: fewer steps (down to 10 per run) and rounds (scripts/main.sh), every method and scene;
// --scene, --method: only scenes whose label contains TEXT, only that method (profiling);
// --csv: every cell's ratios; --compare: a previous run's csv, the per-cell spread reported;
// --serve: times C++ runs for bench/python_solve_benchmark.py, one per stdin line
// "KEY METHOD H STEPS REPS" (KEY: P2, P3 or SG<N>), answering CPU seconds per run.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include "integrate_cells.hpp"
#include "integrate_markdown.hpp"
#include "integrate_report.hpp"

namespace {

using bench::Config;

Config parse(int argc, char** argv) {
  Config cfg;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    const bool has_value = k + 1 < argc;
    if (a == "--serve") {
      cfg.serve = true;
    } else if (a == "--short") {
      cfg.short_mode = true;
    } else if (a == "--markdown" && has_value) {
      cfg.markdown = argv[++k];
    } else if (a == "--scene" && has_value) {
      cfg.scene = argv[++k];
    } else if (a == "--method" && has_value) {
      cfg.method = argv[++k];
    } else if (a == "--csv" && has_value) {
      cfg.csv = argv[++k];
    } else if (a == "--compare" && has_value) {
      cfg.compare = argv[++k];
    } else {
      std::fprintf(stderr, "erkn_integrate_benchmark: unknown or incomplete argument '%s'\n",
                   a.c_str());
      std::exit(2);
    }
  }
  cfg.command = "erkn_integrate_benchmark";
  for (int k = 1; k < argc; ++k) cfg.command += std::string(" ") + argv[k];
  return cfg;
}

}  // namespace

// Construct + integrate + read the final state of the problems library's System, reps times.
int serve() {
  std::string key, method;
  double h = 0;
  long steps = 0, reps = 0;
  while (std::cin >> key >> method >> h >> steps >> reps) {
    const erkn::problems::Problem p = key.rfind("SG", 0) == 0
                                          ? erkn::problems::sine_gordon(std::stoi(key.substr(2)))
                                          : erkn::problems::problem_by_key(key);
    const bench::Scene s{key, p, h, steps};
    const erkn::System sys = erkn::problems::system(p);
    const erkn::Method& m = erkn::Method::by_name(method);
    volatile double sink = 0;
    const double start = bench::thread_seconds();
    for (long k = 0; k < reps; ++k) bench::erkn_run(m, sys, s, {}, sink);
    std::cout << (bench::thread_seconds() - start) / double(reps) << std::endl;
  }
  return 0;
}

int main(int argc, char** argv) {
  const Config cfg = parse(argc, argv);
  if (cfg.serve) return serve();
  const bench::Results results = bench::measure_all(cfg);
  bench::print_text(results, cfg, stdout);
  std::optional<bench::StepsCheck> steps;
  if (cfg.scene.empty() && cfg.method.empty()) steps = bench::steps_to_target();
  if (steps)
    for (const bench::StepsCell& c : steps->cells)
      std::printf("steps to 1e-6, %s: peer %ld, erkn %s %.2e\n", c.method.c_str(), c.peer_steps,
                  c.erkn_accepts ? "accepts, error" : "refuses", c.erkn_error);
  if (!cfg.csv.empty()) bench::write_csv(results, cfg.csv);
  if (!cfg.markdown.empty()) bench::write_markdown(results, steps ? &*steps : nullptr, cfg);
  return 0;
}
