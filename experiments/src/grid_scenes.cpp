#include "grid_scenes.hpp"

#include <malloc.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <erkn/integrator.hpp>
#include <erkn/stiffness.hpp>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "charts.hpp"
#include "grid_problems.hpp"
#include "progress.hpp"
#include "reference.hpp"
#include "splitting.hpp"
#include "summary.hpp"

extern char** environ;

namespace ex {
namespace fs = std::filesystem;
namespace {

// The peers that suit a large grid: Verlet (resolves M's frequencies) and the exact-flow
// splittings of orders 2, 4 and 6. Left out: Gauss2 (dense block solves), the Odeint RKN steppers
// (like Verlet, slower per step), ABA(10,6,4) and the mollified impulse method (built for
// near-integrable and resonant problems; their P1-P3 charts show them).
bool suits_grid(const Solver& s) {
  if (s.family() == Family::erkn) return true;  // the RKN limits must resolve M: left out
  const std::string n = s.name();
  return s.family() == Family::peer && (n == "Störmer–Verlet" || n.rfind("Strang", 0) == 0 ||
                                        n.find("SRKN") != std::string::npos);
}

struct Line {
  const Solver* solver;
  std::vector<std::optional<double>> cpu;  ///< to the tolerance, per size
  std::vector<bool> ran;                   ///< per size (not all lines run beyond the first)
  std::vector<std::vector<Measurement>> runs;
};

struct StepTimes {
  std::string name;
  std::vector<double> seconds;  ///< per step, per size
  double c = 0;                 ///< fit t = c d log2 d
  double deviation = 0;         ///< max |t / fit - 1|
  double slope = 0;             ///< least-squares slope of log t against log d
};

struct Scene {
  std::string key, title;
  std::function<Problem(int)> make;
  std::vector<int> sizes, step_sizes;
  std::vector<long> dims, step_dims;
  std::vector<Reference> references;
  std::vector<Line> lines;
  std::vector<StepTimes> step_times;
  double bytes_per_unknown = 0;
  std::string memory_method;
};

// Reference q(t_error): Blanes-Moan SRKN14a (order 6, exact linear flow), steps doubled until two
// results agree to `tolerance`. (RKF7(8) would have to resolve omega_max ~ 2 sqrt(k) / dx.)
Reference reference(const Problem& pr, double tolerance) {
  const auto s = make_splitting(blanes_moan_srkn14a());
  const double T = pr.t_error;
  long steps = 8;
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

// Seconds per step at step size h: (best of 3 runs of 2k steps - best of 3 runs of k steps) / k,
// so that the setup (coefficients, plans) cancels. A run that fails (a stage that does not
// converge: V = h^2 lambda near a pole of the method on a finer grid) halves h.
double seconds_per_step(const Solver& s, const Problem& pr, double h, long k) {
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
      const double t1 = best(k), t2 = best(2 * k);
      return std::max(t2 - t1, 0.0) / double(k);
    } catch (const std::exception&) {
    }
  }
  throw std::runtime_error(s.name() + " fails on " + pr.title + " at every step size tried");
}

// The step size of the cheapest run within the tolerance at the largest size.
double step_at_tolerance(const Line& l, double tolerance) {
  double h = 0;
  for (const Measurement& m : l.runs.back())
    if (m.ok() && m.error <= tolerance) h = std::max(h, m.h);
  return h;
}

void fit(StepTimes& st, const std::vector<long>& dims) {
  double log_c = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(dims.size());
  for (size_t i = 0; i < dims.size(); ++i) {
    const double d = double(dims[i]), x = std::log(d), y = std::log(st.seconds[i]);
    log_c += (y - std::log(d * std::log2(d))) / n;
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  st.c = std::exp(log_c);
  st.slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  for (size_t i = 0; i < dims.size(); ++i) {
    const double d = double(dims[i]);
    st.deviation = std::max(st.deviation, std::abs(st.seconds[i] / (st.c * d * std::log2(d)) - 1));
  }
}

// Bytes the runtime's Integrator holds per unknown (malloc's bytes in use while it lives, after
// one step, less before; the problem's own q0 and p0 are not counted).
double bytes_per_unknown(const erkn::Method& m, const Problem& pr) {
  const auto in_use = [] {
    const struct mallinfo2 mi = mallinfo2();
    return double(mi.uordblks + mi.hblkhd);
  };
  const double before = in_use();
  erkn::System system;
  system.M = erkn::problems::stiffness(pr.M);
  system.gradient = pr.grad_u;
  erkn::Integrator integrator(m, std::move(system), pr.t_error / 16, pr.q0, pr.p0);
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

// The line of the family (peers or ERKN methods) cheapest at size index i (the largest size
// when i < 0) among those that reached the tolerance there.
const Line* cheapest(const Scene& sc, bool peers, int i = -1) {
  const Line* best = nullptr;
  for (const Line& l : sc.lines) {
    const size_t k = i < 0 ? l.cpu.size() - 1 : size_t(i);
    if ((l.solver->family() == Family::peer) != peers || k >= l.cpu.size() || !l.cpu[k]) continue;
    if (!best || *l.cpu[k] < *best->cpu[i < 0 ? best->cpu.size() - 1 : size_t(i)]) best = &l;
  }
  return best;
}

void run_scene(Scene& sc, const GridSceneConfig& cfg, Progress& progress) {
  for (size_t i = 0; i < sc.sizes.size(); ++i) {
    const int n = sc.sizes[i];
    const Problem pr = sc.make(n);
    sc.dims.push_back(pr.dim());
    progress.label(sc.key + " N=" + std::to_string(n) + " reference");
    sc.references.push_back(reference(pr, cfg.reference_tolerance));
    // Every ERKN method at the smallest N; beyond it the cheapest of them and the peers.
    const Line* best = i > 0 ? cheapest(sc, false, 0) : nullptr;
    for (Line& l : sc.lines) {
      const bool run = i == 0 || l.solver->family() == Family::peer || !best || &l == best;
      l.ran.push_back(run);
      l.runs.emplace_back();
      l.cpu.emplace_back();
      if (run) {
        progress.label(sc.key + " N=" + std::to_string(n) + " " + l.solver->name());
        const long start = l.solver->exact_for_linear_part()
                               ? 4L
                               : std::max(8L, long(std::ceil(omega_max(pr) * pr.t_error)));
        l.runs.back() = bracket(*l.solver, pr, pr.t_error, sc.references.back().q, cfg.tolerance,
                                start, cfg.sweep);
        l.cpu.back() = cost_to_tolerance(l.runs.back(), cfg.tolerance).cpu;
      }
      progress.advance(sc.key + " N=" + std::to_string(n));
    }
  }
  // Time per step of the cheapest ERKN method and the cheapest peer at the largest N.
  std::vector<const Line*> timed;
  for (bool peers : {false, true})
    if (const Line* l = cheapest(sc, peers)) timed.push_back(l);
  for (const Line* l : timed) sc.step_times.push_back({l->solver->name(), {}, 0, 0, 0});
  for (int n : sc.step_sizes) {
    const Problem pr = sc.make(n);
    sc.step_dims.push_back(pr.dim());
    for (size_t i = 0; i < timed.size(); ++i) {
      progress.label(sc.key + " time per step N=" + std::to_string(n) + " " +
                     timed[i]->solver->name());
      sc.step_times[i].seconds.push_back(
          seconds_per_step(*timed[i]->solver, pr, step_at_tolerance(*timed[i], cfg.tolerance), 4));
      progress.advance(sc.key + " time per step");
    }
  }
  for (StepTimes& st : sc.step_times) fit(st, sc.step_dims);
  // Memory of the cheapest ERKN method (else the first in the registry) at the largest N.
  const Line* erkn_line = cheapest(sc, false);
  const erkn::Method& m =
      erkn_line ? erkn::Method::by_name(erkn_line->solver->name()) : erkn::Method::all()[0];
  sc.memory_method = std::string(m.name());
  sc.bytes_per_unknown = bytes_per_unknown(m, sc.make(sc.sizes.back()));
}

// gnuplot runs without a shell: posix_spawnp("gnuplot", script).
void gnuplot(const fs::path& script) {
  const std::string path = script.string();
  char* argv[] = {const_cast<char*>("gnuplot"), const_cast<char*>(path.c_str()), nullptr};
  pid_t pid;
  if (posix_spawnp(&pid, "gnuplot", nullptr, nullptr, argv, environ) != 0)
    throw std::runtime_error("cannot start gnuplot for " + path);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("gnuplot failed on " + path);
}

std::string quoted(const std::string& s) { return "'" + s + "'"; }

void chart(const Scene& sc, const fs::path& charts, double tolerance) {
  const fs::path data = charts / "data";
  fs::create_directories(data);
  const std::string stem = "grid_" + slug(sc.key);
  std::string plot = "plot ";
  for (const Line& l : sc.lines) {
    const fs::path dat = data / (stem + "_" + slug(l.solver->name()) + ".dat");
    std::ofstream f(dat);
    f << "# N cpu_seconds_to_" << tolerance << "\n";
    for (size_t i = 0; i < sc.sizes.size(); ++i)
      if (l.cpu[i]) f << sc.sizes[i] << ' ' << *l.cpu[i] << '\n';
    const bool peer = l.solver->family() == Family::peer;
    plot += (plot == "plot " ? "" : ", \\\n  ") + quoted(dat.string()) + " u 1:2 w lp lw 2 " +
            (peer ? "dt (2,4) pt 4" : "dt 1 pt 7") + " t " + quoted(l.solver->name());
  }
  std::string steps = "plot ";
  for (const StepTimes& st : sc.step_times) {
    const fs::path dat = data / (stem + "_step_" + slug(st.name) + ".dat");
    std::ofstream f(dat);
    f << "# d seconds_per_step fit_c_d_log2_d\n";
    for (size_t i = 0; i < sc.step_dims.size(); ++i) {
      const double d = double(sc.step_dims[i]);
      f << sc.step_dims[i] << ' ' << st.seconds[i] << ' ' << st.c * d * std::log2(d) << '\n';
    }
    steps += (steps == "plot " ? "" : ", \\\n  ") + quoted(dat.string()) +
             " u 1:2 w p pt 7 ps 1.3 t " + quoted(st.name) + ", " + quoted(dat.string()) +
             " u 1:3 w l lw 1.5 t " + quoted(st.name + ": fit c d log2 d");
  }
  const fs::path gp = data / (stem + ".gp");
  std::ofstream g(gp);
  const auto outputs = [&](const std::string& name, const std::string& body) {
    for (const char* ext : {"png", "svg"}) {
      g << (std::string(ext) == "png"
                ? "set terminal pngcairo size 1000,620 font 'DejaVu Sans,11'\n"
                : "set terminal svg size 1000,620 dynamic font 'DejaVu Sans,11'\n")
        << "set output " << quoted((charts / (name + "." + ext)).string()) << "\n"
        << body << "\n";
    }
    g << "unset output\n";
  };
  g << "set logscale xy\nset grid lc rgb '#dddddd'\nset key outside right top noenhanced\n";
  g << "set title "
    << quoted(sc.title + ": CPU time to error " + std::to_string(tolerance).substr(0, 8))
    << " noenhanced\n"
    << "set xlabel 'N (points per axis)'\nset ylabel 'CPU time (s)'\nset logscale x 2\n";
  outputs(stem + "_cpu", plot);
  g << "set title " << quoted(sc.title + ": time per step against d") << " noenhanced\n"
    << "set xlabel 'd (unknowns)'\nset ylabel 'seconds per step'\nset logscale x 10\n";
  outputs(stem + "_step", steps);
  g.close();
  gnuplot(gp);
}

std::string number(double x, int digits = 3) {
  std::ostringstream s;
  s.precision(digits);
  s << x;
  return s.str();
}

void report(std::ostream& md, const Scene& sc, const GridSceneConfig& cfg) {
  const double tolerance = cfg.tolerance;
  const std::string stem = "grid_" + slug(sc.key);
  md << "\n## " << sc.title.substr(0, sc.title.rfind(',')) << "\n\n"
     << "CPU time (s, best of repeats, setup included) to reach max-norm error " << tolerance
     << " in q at t = 1, interpolated between bracketing step counts; — where not reached "
        "within the sweep (at most "
     << cfg.sweep.max_steps
     << " steps), · where not run: every "
        "ERKN method runs at the smallest N, beyond it the cheapest of them and the peers.\n\n| "
        "method |";
  for (int n : sc.sizes) md << " N = " << n << " |";
  md << "\n|---|";
  for (size_t i = 0; i < sc.sizes.size(); ++i) md << "---:|";
  md << "\n";
  for (const Line& l : sc.lines) {
    md << "| " << l.solver->name() << (l.solver->family() == Family::peer ? " (peer)" : "") << " |";
    for (size_t i = 0; i < l.cpu.size(); ++i)
      md << " " << (l.cpu[i] ? number(*l.cpu[i]) : l.ran[i] ? "—" : "·") << " |";
    md << "\n";
  }
  md << "\nReferences: ";
  for (size_t i = 0; i < sc.sizes.size(); ++i)
    md << (i ? "; " : "") << "N = " << sc.sizes[i] << ": " << sc.references[i].method
       << " (agreement " << number(sc.references[i].accuracy, 2) << ")";
  md << ".\n\n![CPU time to tolerance](charts/" << stem << "_cpu.png)\n\n"
     << "Time per step against d (CPU s, (best of 3 runs of 8 steps - best of 3 of 4) / 4, at "
        "the step size that reached the tolerance at the largest N, halved where a finer grid "
        "makes a stage fail): fit t = c d log2 d.\n\n| d |";
  for (const StepTimes& st : sc.step_times) md << " " << st.name << " (s) |";
  md << "\n|---:|";
  for (size_t i = 0; i < sc.step_times.size(); ++i) md << "---:|";
  md << "\n";
  for (size_t i = 0; i < sc.step_dims.size(); ++i) {
    md << "| " << sc.step_dims[i] << " |";
    for (const StepTimes& st : sc.step_times) md << " " << number(st.seconds[i]) << " |";
    md << "\n";
  }
  md << "\n";
  for (const StepTimes& st : sc.step_times)
    md << "- " << st.name << ": c = " << number(st.c) << " s, largest deviation from c d log2 d "
       << number(100 * st.deviation, 2) << " %, log-log slope " << number(st.slope) << "\n";
  md << "\n![time per step](charts/" << stem << "_step.png)\n\n"
     << "Memory of erkn::Integrator (" << sc.memory_method << ", N = " << sc.sizes.back()
     << ", d = " << sc.dims.back() << "): " << number(sc.bytes_per_unknown)
     << " bytes per unknown (" << number(sc.bytes_per_unknown / 8, 3)
     << " doubles; malloc's bytes in use while it lives).\n";
}

}  // namespace

GridSceneConfig grid_scene_config(bool full, const SweepPolicy& sweep) {
  GridSceneConfig c;
  c.sweep = sweep;
  c.sweep.timing.repeats = std::min(c.sweep.timing.repeats, 3);
  c.sweep.max_steps = full ? 16384 : 256;  // (order-2 methods and Verlet are the costly lines)
  if (full) {
    c.sg_sizes = {128, 256, 512, 1024}, c.kg_sizes = {32, 64, 128};
    c.sg_step_sizes = {64, 128, 256, 512, 1024}, c.kg_step_sizes = {16, 32, 64, 128};  // (<= sizes)
    c.dense_sizes = {256, 512, 1024, 2048, 4096};
  } else {
    c.sg_sizes = {64, 128, 256}, c.kg_sizes = {16, 32, 64};
    c.sg_step_sizes = {32, 64, 128, 256}, c.kg_step_sizes = {8, 16, 32, 64};
    c.dense_sizes = {256, 512, 1024};
  }
  return c;
}

void run_grid_scenes(const GridSceneConfig& cfg, const SolverList& solvers, const fs::path& out,
                     const std::string& command) {
#ifndef EX_WITH_FFTW
  // The peers' grid transforms are FFTW's (eigen_coordinates.cpp): without it, no comparison.
  std::ofstream(out / "grids.md") << "# Large grid scenes\n\nSkipped: the experiments were built "
                                     "without FFTW (libfftw3-dev), which the peers' grid "
                                     "transforms need.\n";
  std::printf("grid scenes skipped: built without FFTW\n");
  return;
#endif
  const auto start = std::chrono::steady_clock::now();
  std::vector<Scene> scenes(2);
  scenes[0].key = "SG2D", scenes[0].title = "2-D sine-Gordon, periodic";
  scenes[0].make = sine_gordon_2d, scenes[0].sizes = cfg.sg_sizes;
  scenes[0].step_sizes = cfg.sg_step_sizes;
  scenes[1].key = "KG3D", scenes[1].title = "3-D Klein-Gordon phi^4, Dirichlet";
  scenes[1].make = klein_gordon_3d, scenes[1].sizes = cfg.kg_sizes;
  scenes[1].step_sizes = cfg.kg_step_sizes;
  long units = 0;
  for (Scene& sc : scenes) {
    for (const auto& s : solvers)
      if (suits_grid(*s)) sc.lines.push_back({s.get(), {}, {}, {}});
    units += long(sc.sizes.size() * sc.lines.size() + 2 * sc.step_sizes.size());
  }
  Progress progress(units);
  for (Scene& sc : scenes) run_scene(sc, cfg, progress);
  progress.finish();
  for (Scene& sc : scenes) chart(sc, out / "charts", cfg.tolerance);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ofstream md(out / "grids.md");
  md << "# Large grid scenes\n\nWritten by `" << command << "` in " << number(wall, 3)
     << " s wall time. M is the shifted discrete Laplacian of a tensor grid (erkn::Stiffness::grid,"
        " FFTW r2r transforms); the peers use their own FFTW transforms. The RKN limits are left "
        "out (they must resolve omega_max ~ 2 sqrt(k)/dx).\n";
  for (const Scene& sc : scenes) report(md, sc, cfg);
  md << "\n## General sparse M: the dense path\n\nerkn does not apply functions of V to a general "
        "sparse M matrix-free (README, \"General sparse M\"); such an M goes through "
        "`Stiffness::dense`, whose setup is one symmetric eigendecomposition (O(d^3) time, 2 d^2 "
        "doubles) and whose transforms are d x d products (O(d^2) per transform). Setup CPU time "
        "measured in this run:\n\n| d | eigendecomposition (s) | matrices (MB) "
        "|\n|---:|---:|---:|\n";
  for (int d : cfg.dense_sizes)
    md << "| " << d << " | " << number(dense_setup_seconds(d)) << " | "
       << number(2.0 * 8 * double(d) * double(d) / 1e6) << " |\n";
  if (!md) throw std::runtime_error("cannot write " + (out / "grids.md").string());
  std::printf("wrote %s in %.0f s\n", (out / "grids.md").c_str(), wall);
}

}  // namespace ex
