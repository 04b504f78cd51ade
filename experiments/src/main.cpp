// erkn-experiments: the paper's three problems, FPU, Henon-Heiles, the sine-Gordon scaling scene, the
// stiff scene and the grids, swept, charted, summarised.
#include <chrono>
#include <cstdio>
#include <exception>
#include <iostream>
#include <set>

#include "charts.hpp"
#include "erkn/method.hpp"
#include "grid_scenes.hpp"
#include "options.hpp"
#include "raw_results.hpp"
#include "report.hpp"
#include "targets.hpp"

namespace {

using namespace ex;

bool matches(const std::string& wanted, const std::string& name) {
  const std::string w = slug(wanted), n = slug(name);
  return n == w || n.rfind(w + "_", 0) == 0 ||
         (n.size() > w.size() && n.compare(n.size() - w.size() - 1, w.size() + 1, "_" + w) == 0);
}

// A wanted name picks the solvers it matches; a registry method that is run under the name of an
// identical one (identical_registry_methods) picks that one.
SolverList select(const std::vector<std::string>& wanted) {
  SolverList all = all_solvers(), chosen;
  std::set<std::string> used;
  const std::vector<Twin> twins = identical_registry_methods();
  for (auto& s : all) {
    bool take = wanted.empty();
    for (const std::string& w : wanted) {
      bool hit = matches(w, s->name());
      for (const Twin& t : twins) hit = hit || (matches(w, t.name) && t.same_as == s->name());
      if (hit) take = true, used.insert(w);
    }
    if (take) chosen.push_back(std::move(s));
  }
  for (const std::string& w : wanted)
    if (!used.count(w)) throw std::invalid_argument("unknown method " + w + " (see --list)");
  return chosen;
}

void list() {
  std::printf(
      "problems: P1 (sine-Gordon, N = 32), P2 (Duffing), P3 (stellar orbits), scaling, stiff,\n"
      "          grids\n");
  std::printf("methods:\n");
  for (const auto& s : all_solvers())
    std::printf("  %s  (order %d)\n", s->name().c_str(), s->order());
  for (const Twin& t : identical_registry_methods())
    std::printf("  %s  (identical to %s: run under that name)\n", t.name.c_str(),
                t.same_as.c_str());
}

std::string command_line(int argc, char** argv) {
  std::string s = "erkn-experiments";
  for (int i = 1; i < argc; ++i) s += std::string(" ") + argv[i];
  return s;
}

// The --problems list: the paper's problem keys, and the scenes named by a word of their own.
struct Scenes {
  std::vector<std::string> keys;
  bool scaling = false, stiff = false, grids = false;
};

Scenes scenes_of(const std::vector<std::string>& problems) {
  Scenes s;
  for (const std::string& p : problems) {
    if (p == "scaling")
      s.scaling = true;
    else if (p == "stiff")
      s.stiff = true;
    else if (p == "grids")
      s.grids = true;
    else
      s.keys.push_back(p);
  }
  return s;
}

int run(const Options& o, const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  const SolverList solvers = select(o.methods);
  SolverList scaling_solvers;  // the RKN limits must resolve the fastest mode: left out there
  for (auto& s : select(o.methods))
    if (s->family() != Family::rkn) scaling_solvers.push_back(std::move(s));
  const auto [keys, scaling, stiff, grids] = scenes_of(o.problems);
  const StiffConfig stiff_config;

  Progress progress(long(keys.size() * solvers.size() +
                         (scaling ? o.config.scaling_sizes.size() * scaling_solvers.size() : 0) +
                         (stiff ? stiff_config.kappas.size() * solvers.size() : 0)));
  const std::filesystem::path charts = o.out / "charts";
  std::vector<ProblemResult> results;
  for (const std::string& key : keys) {
    results.push_back(run_problem(problem_by_key(key), solvers, o.config, progress));
    chart_problem(results.back(), charts);
  }
  std::optional<ScalingResult> scaled;
  if (scaling) {
    scaled = run_scaling(scaling_solvers, o.config, progress);
    chart_scaling(*scaled, charts);
  }
  std::vector<StiffResult> stiff_results;
  if (stiff) stiff_results = run_stiff(solvers, stiff_config, o.config, progress);
  for (const StiffResult& s : stiff_results) chart_stiff(s.result, s.kappa, charts);
  progress.finish();
  // results.md first: the grid scenes run last, and a failure there must not lose it.
  if (!keys.empty() || scaling || stiff) {
    std::filesystem::create_directories(charts);
    progress.write_unit_seconds(charts / "run_seconds.csv");
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::vector<ProblemResult> raw = results;  // the raw files list the stiff scene's sweeps too
    for (const StiffResult& s : stiff_results) raw.push_back(s.result);
    write_raw_results(charts, raw, scaled);
    RunInfo info{command, o.mode, wall, cpu_seconds(), o.config.sweep.timing.repeats, {}};
    for (const Twin& t : identical_registry_methods())
      info.identical.push_back(t.name + " = " + t.same_as);
    info.rounds = o.config.sweep.timing.rounds;
    write_report(o.out / "results.md", info, results, scaled, stiff_results);
    std::printf("%s\nwrote %s and %s/ in %.0f s\n",
                targets_markdown(target_scenes(results, scaled)).c_str(),
                (o.out / "results.md").c_str(), charts.c_str(), wall);
  }
  if (grids && !run_grid_scenes(grid_scene_config(o.mode == "full", o.config.sweep),
                                select(o.methods), o.out, command)) {
    std::fprintf(stderr, "erkn-experiments: the grid scenes failed in part (see %s)\n",
                 (o.out / "grids.md").c_str());
    return 1;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse_options(argc, argv);
    if (o.help) return std::cout << usage(), 0;
    for (const std::string& file : o.methods_files) erkn::Method::load(file);
    if (o.list) return list(), 0;
    return run(o, command_line(argc, argv));
  } catch (const std::invalid_argument& e) {
    std::cerr << "erkn-experiments: " << e.what() << "\n" << usage();
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "\nerkn-experiments: " << e.what() << "\n";
    return 1;
  }
}
