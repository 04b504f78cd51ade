#include "grid_scenes.hpp"

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <erkn/integrator.hpp>
#include <erkn/stiffness.hpp>
#include <fstream>
#include <stdexcept>
#include <thread>

#include "grid_problems.hpp"
#include "grid_scene_data.hpp"
#include "grid_sweep.hpp"
#include "progress.hpp"
#include "splitting.hpp"
#include "summary.hpp"

namespace ex {
namespace fs = std::filesystem;
namespace {

bool is_peer(const GridLine& l) { return l.solver->family() == Family::peer; }
bool is_paper(const GridLine& l) { return !is_peer(l) && l.solver->from_paper(); }

// Reference q(t_error): Blanes-Moan SRKN14a (order 6, exact linear flow), steps doubled from
// `steps` until two results agree to `tolerance`. (RKF7(8) would have to resolve omega_max.)
Reference reference(const Problem& pr, double tolerance, long steps) {
  const auto s = make_splitting(blanes_moan_srkn14a());
  const double T = pr.t_error;
  Vec coarse = s->run(pr, T / double(steps), steps, nullptr).q;
  for (int k = 0; k < 10; ++k) {
    steps *= 2;
    Vec fine = s->run(pr, T / double(steps), steps, nullptr).q;
    const double diff = (fine - coarse).lpNorm<Eigen::Infinity>();
    if (diff <= tolerance)
      return {fine, diff, steps, s->name() + ", " + std::to_string(steps) + " steps"};
    coarse.swap(fine);
  }
  throw std::runtime_error(pr.title + ": reference did not reach " + std::to_string(tolerance));
}

double omega_max(const Problem& pr) { return std::sqrt(pr.M.eigenvalues(pr.dim()).maxCoeff()); }

double d_log_d(double d) { return d * std::log2(d); }

// The line of a group cheapest at size index i among those that reached the tolerance there.
const GridLine* cheapest(const GridScene& sc, size_t i, bool (*in_group)(const GridLine&)) {
  const GridLine* best = nullptr;
  for (const GridLine& l : sc.lines)
    if (in_group(l) && i < l.cells.size() && l.cells[i].cpu &&
        (!best || *l.cells[i].cpu < *best->cells[i].cpu))
      best = &l;
  return best;
}
bool any_erkn(const GridLine& l) { return !is_peer(l); }

// Why line l does not run at size index i > 0 (empty: it runs): beyond the smallest N only the
// cheapest ERKN method, the cheapest paper method and the peers run, each only when it reached
// the tolerance at the previous N and its cost there, scaled by d log d, fits the budget.
std::string skip_reason(const GridScene& sc, const GridLine& l, size_t i, double budget) {
  if (i == 0) return "";
  const GridCell& prev = l.cells[i - 1];
  if (!is_peer(l) && &l != cheapest(sc, i - 1, any_erkn) && &l != cheapest(sc, i - 1, is_paper))
    return "not the cheapest ERKN or paper method at the previous N";
  if (!prev.cpu) return "did not reach the tolerance at the previous N";
  const double predicted =
      *prev.cpu * d_log_d(double(sc.dims[i])) / d_log_d(double(sc.dims[i - 1]));
  if (predicted <= budget) return "";
  char why[160];
  std::snprintf(why, sizeof why,
                "its cost at the previous N times the d log d ratio, %.3g s, is over the budget "
                "of %.3g s",
                predicted, budget);
  return why;
}

// First step count: near the tolerance from the previous N (the time error of a resolved wave
// hardly changes with N), at the smallest N 4 steps for an exact linear flow, else omega_max T.
long start_steps(const GridLine& l, const Problem& pr, size_t i) {
  const long resolve = l.solver->exact_for_linear_part()
                           ? 1L
                           : std::max(8L, long(std::ceil(omega_max(pr) * pr.t_error)));
  if (i > 0 && l.cells[i - 1].steps)
    return std::max(resolve, long(std::ceil(*l.cells[i - 1].steps)));
  return std::max(resolve, 4L);
}

GridCell measure_cell(const GridLine& l, const Problem& pr, const Reference& ref,
                      const GridSceneConfig& cfg, size_t i) {
  GridCell c;
  c.ran = true;
  try {
    c.runs =
        predicted_bracket(*l.solver, pr, ref.q, cfg.tolerance, start_steps(l, pr, i), cfg.sweep);
    const Cost cost = cost_to_tolerance(c.runs, cfg.tolerance);
    c.cpu = cost.cpu, c.steps = cost.steps;
    c.predicted_steps = predicted_steps(c.runs, cfg.tolerance, l.solver->order());
  } catch (const std::exception& e) {
    c.failure = e.what();
  }
  return c;
}

// Seconds per step at step size h: (best of 3 runs of 2k steps - best of 3 runs of k steps) / k,
// so that the setup (coefficients, plans) cancels; k doubles from 4 until a run of k steps takes
// 20 ms. A run that fails (a stage that does not converge: h^2 lambda near a pole of the method
// on a finer grid) halves h.
std::pair<double, long> seconds_per_step(const Solver& s, const Problem& pr, double& h) {
  for (int halvings = 0; halvings < 8; ++halvings, h /= 2) {
    try {
      auto best = [&](long steps) {
        double t = INFINITY;
        for (int r = 0; r < 3; ++r) {
          const double start = cpu_seconds();
          s.run(pr, h, steps, nullptr);
          t = std::min(t, cpu_seconds() - start);
        }
        return t;
      };
      long k = 4;
      double t1 = best(k);
      while (t1 < 0.02 && k < 4096) t1 = best(k *= 2);
      return {std::max(best(2 * k) - t1, 0.0) / double(k), k};
    } catch (const std::exception&) {
    }
  }
  throw std::runtime_error(s.name() + " fails on " + pr.title + " at every step size tried");
}

void fit(StepTimes& st, const std::vector<long>& dims) {
  double log_c = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, n = 0;
  for (size_t i = 0; i < dims.size(); ++i) {
    if (!st.seconds[i] || *st.seconds[i] <= 0) continue;
    const double d = double(dims[i]), x = std::log(d), y = std::log(*st.seconds[i]);
    log_c += y - std::log(d_log_d(d)), n += 1;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  if (n < 2) return;
  st.c = std::exp(log_c / n);
  st.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  st.deviation = 0;
  for (size_t i = 0; i < dims.size(); ++i)
    if (st.seconds[i] && *st.seconds[i] > 0)
      st.deviation =
          std::max(st.deviation, std::abs(*st.seconds[i] / (st.c * d_log_d(double(dims[i]))) - 1));
}

// Bytes the runtime's Integrator holds per unknown (malloc's bytes in use while it lives, after
// one step, less before; the problem's own q0 and p0 are not counted).
double bytes_per_unknown(const erkn::Method& m, const Problem& pr, double h) {
  const auto in_use = [] {
    const struct mallinfo2 mi = mallinfo2();
    return double(mi.uordblks + mi.hblkhd);
  };
  const double before = in_use();
  erkn::System system;
  system.M = erkn::problems::stiffness(pr.M);
  system.gradient = pr.grad_u;
  system.hessian_vector_product = pr.hessian_vector_u;
  erkn::Integrator integrator(m, std::move(system), h, pr.q0, pr.p0);
  integrator.step();
  return (in_use() - before) / double(pr.dim());
}

// The dense path a general sparse M falls back to: CPU seconds of Stiffness::dense (one
// symmetric eigendecomposition, O(d^3)) for a 1-D Dirichlet Laplacian of size d.
double dense_setup_seconds(int d) {
  const Eigen::MatrixXd m =
      erkn::Stiffness::grid({{d, 1.0, erkn::GridAxis::Boundary::dirichlet}}).to_dense(d);
  const double start = cpu_seconds();
  const erkn::Stiffness dense = erkn::Stiffness::dense(m);
  const double seconds = cpu_seconds() - start;
  if (dense.eigenvalues().size() != d) throw std::logic_error("dense M: wrong eigenvalue count");
  return seconds;
}

// The 1-minute load average (timings on a shared machine depend on it), "?" when unknown.
std::string load_average() {
  std::ifstream f("/proc/loadavg");
  std::string first;
  return f >> first ? first : "?";
}

using Save = std::function<void()>;

void run_sizes(GridScene& sc, const GridSceneConfig& cfg, Progress& progress, const Save& save) {
  for (size_t i = 0; i < sc.sizes.size(); ++i) {
    const std::string at = sc.key + " N=" + std::to_string(sc.sizes[i]);
    const Problem pr = sc.make(sc.sizes[i]);
    progress.label(at + " reference");
    sc.references.push_back(
        reference(pr, cfg.reference_tolerance, i ? sc.references.back().steps / 2 : 8));
    sc.dims.push_back(pr.dim());
    for (GridLine& l : sc.lines) l.cells.emplace_back();
    for (GridLine& l : sc.lines) {
      GridCell& cell = l.cells.back();
      cell.skipped = skip_reason(sc, l, i, cfg.line_budget);
      if (!cell.skipped.empty()) continue;
      progress.label(at + " " + l.solver->name());
      cell = measure_cell(l, pr, sc.references.back(), cfg, i);
      progress.advance(at);
      save();
    }
  }
}

// Time per step of the cheapest ERKN method, the cheapest paper method and the cheapest peer at
// the largest N, at the step size that reached the tolerance there.
void run_step_times(GridScene& sc, Progress& progress, const Save& save) {
  const size_t last = sc.dims.size() - 1;
  for (auto group : {any_erkn, is_paper, is_peer}) {
    const GridLine* l = cheapest(sc, last, group);
    if (!l || !l->cells[last].steps ||
        std::any_of(sc.step_times.begin(), sc.step_times.end(),
                    [&](const StepTimes& st) { return st.solver == l->solver; }))
      continue;
    StepTimes st;
    st.solver = l->solver;
    st.h = sc.make(sc.sizes[last]).t_error / *l->cells[last].steps;
    sc.step_times.push_back(st);
  }
  for (int n : sc.step_sizes) {
    const Problem pr = sc.make(n);
    sc.step_dims.push_back(pr.dim());
    for (StepTimes& st : sc.step_times) {
      progress.label(sc.key + " time per step N=" + std::to_string(n) + " " + st.solver->name());
      st.seconds.emplace_back(), st.steps_timed.emplace_back();
      try {
        const auto [seconds, k] = seconds_per_step(*st.solver, pr, st.h);
        st.seconds.back() = seconds, st.steps_timed.back() = k;
      } catch (const std::exception& e) {
        st.failure = e.what();
      }
      fit(st, sc.step_dims);
      progress.advance(sc.key + " time per step");
      save();
    }
  }
  const Problem largest = sc.make(sc.sizes[last]);
  for (StepTimes& st : sc.step_times)
    if (st.solver->family() != Family::peer)
      st.bytes_per_unknown =
          bytes_per_unknown(erkn::Method::by_name(st.solver->name()), largest, st.h);
}

void run_scene(GridScene& sc, const GridSceneConfig& cfg, Progress& progress, const Save& save,
               const fs::path& charts) {
  const auto start = std::chrono::steady_clock::now();
  try {
    run_sizes(sc, cfg, progress, save);
    run_step_times(sc, progress, save);
  } catch (const std::exception& e) {
    sc.failure = e.what();
  }
  sc.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  save();
  try {
    if (!sc.dims.empty()) chart_grid_scene(sc, charts, cfg.tolerance);
  } catch (const std::exception& e) {
    sc.failure += (sc.failure.empty() ? "" : "; ") + std::string("chart: ") + e.what();
  }
}

std::vector<GridScene> make_scenes(const GridSceneConfig& cfg, const SolverList& solvers) {
  std::vector<GridScene> scenes(2);
  scenes[0].key = "SG2D", scenes[0].title = "2-D sine-Gordon, periodic";
  scenes[0].make = sine_gordon_2d, scenes[0].sizes = cfg.sg_sizes;
  scenes[0].step_sizes = cfg.sg_step_sizes;
  scenes[1].key = "KG3D", scenes[1].title = "3-D Klein-Gordon phi^4, Dirichlet";
  scenes[1].make = klein_gordon_3d, scenes[1].sizes = cfg.kg_sizes;
  scenes[1].step_sizes = cfg.kg_step_sizes;
  // Solver::suits_grid: the ERKN methods, Verlet (resolves M's frequencies) and the exact-flow
  // splittings of orders 2, 4 and 6 (plain, force-gradient OMF4, processed PMLF6). Left out: the
  // RKN limits (must resolve M), Gauss2 (dense block solves), the Odeint RKN steppers (like Verlet,
  // slower per step), ABA(10,6,4) and the mollified impulse method (built for near-integrable and
  // resonant problems; their P1-P3 charts show them).
  for (GridScene& sc : scenes)
    for (const auto& s : solvers)
      if (s->suits_grid()) sc.lines.push_back({s.get(), {}});
  return scenes;
}

}  // namespace

GridSceneConfig grid_scene_config(bool full, const SweepPolicy& sweep) {
  GridSceneConfig c;
  c.sweep = sweep;
  c.sweep.timing.repeats = std::min(c.sweep.timing.repeats, 3);
  c.sweep.max_steps = full ? 16384 : 1024;
  c.line_budget = full ? 300 : 5;  // (the bracket takes 2-4 such runs)
  if (full) {
    c.sg_sizes = {128, 256, 512, 1024}, c.kg_sizes = {32, 64, 128};
    c.sg_step_sizes = {64, 128, 256, 512, 1024}, c.kg_step_sizes = {16, 32, 64, 128};
    c.dense_sizes = {256, 512, 1024, 2048, 4096};
  } else {
    c.sg_sizes = {64, 128, 256}, c.kg_sizes = {16, 32, 64};
    c.sg_step_sizes = {32, 64, 128, 256}, c.kg_step_sizes = {8, 16, 32, 64};
    c.dense_sizes = {256, 512, 1024};
  }
  return c;
}

bool run_grid_scenes(const GridSceneConfig& cfg, const SolverList& solvers, const fs::path& out,
                     const std::string& command) {
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = cpu_seconds();
  const std::string load_start = load_average();
  fs::create_directories(out / "charts");
  std::vector<GridScene> scenes = make_scenes(cfg, solvers);
  std::vector<std::pair<int, double>> dense;
  std::string status = "stopped before the end (the lines below are what it computed)";
  const Save save = [&] { write_grid_report(out, scenes, cfg, command, status, dense); };
#ifndef EX_WITH_FFTW
  // The peers' grid transforms are FFTW's (eigen_coordinates.cpp): without it, no comparison.
  status =
      "skipped: the experiments were built without FFTW (libfftw3-dev), which the peers' "
      "grid transforms need";
  scenes.clear();
  save();
  std::printf("grid scenes skipped: built without FFTW\n");
  return true;
#endif
  long units = 0;
  for (const GridScene& sc : scenes)
    units += long(sc.lines.size() + (sc.sizes.size() - 1) * 6 + 3 * sc.step_sizes.size());
  Progress progress(units);
  for (GridScene& sc : scenes) run_scene(sc, cfg, progress, save, out / "charts");
  progress.finish();
  bool ok = true;
  for (const GridScene& sc : scenes) {
    ok = ok && sc.failure.empty();
    for (const GridLine& l : sc.lines)
      for (const GridCell& c : l.cells) ok = ok && c.failure.empty();
    for (const StepTimes& st : sc.step_times) ok = ok && st.failure.empty();
  }
  try {
    for (int d : cfg.dense_sizes) dense.emplace_back(d, dense_setup_seconds(d));
  } catch (const std::exception& e) {
    ok = false;
    std::fprintf(stderr, "dense path: %s\n", e.what());
  }
  char spent[200];
  std::snprintf(spent, sizeof spent,
                " in %.0f s wall time, %.0f s CPU time of this process (load average %s at the "
                "start, %s at the end, on %u hardware threads)",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                cpu_seconds() - cpu_start, load_start.c_str(), load_average().c_str(),
                std::thread::hardware_concurrency());
  status = (ok ? "finished" : "finished with failures (recorded below)") + std::string(spent);
  save();
  std::printf("wrote %s (%s)\n", (out / "grids.md").c_str(), status.c_str());
  return ok;
}

}  // namespace ex
