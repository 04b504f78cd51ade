// erkn_advisor_sweep [--steps N] [--points K] [--threads T] [OUT.md]: the step-size advisor's
// false-alarm and miss rates (docs/advisor.md is this program's output). For each scene (FPU,
// sine-Gordon P1, a 1-D (n = 15) and a 2-D (7^2) Dirichlet wave grid with a cubic force: small
// enough that the implicit methods' dense Newton fallback, which large h needs on every step,
// keeps 1e5-step runs affordable; the n = 255 grid is tests/runtime/advisor_state_test.cpp's) and
// every ERKN method of the registry (explicit splittings included), at h omega = 4 pi k / K,
// k = 1..K (omega = sqrt of M's largest eigenvalue):
//   verdict  advise_step_size(method, system, h, q0, p0) flags h: what Options::check_stability
//            and `erkn advise --problem` ask (Hessian range and mode energies at the start).
//   truth    the README's "runs clean" ("Resonances"): over N = 1e5 steps with the blow-up guard
//            off, the relative energy error max |H_n - H_0| / |H_0| (every 50 steps) is below 0.5
//            and at most 10 times the smaller of the errors at h (1 - 3 %) and h (1 + 3 %); a run
//            that stops with an erkn::Error (non-finite state, failed stage) is not clean.
// A false alarm is a flagged h that runs clean, a miss an unflagged h that does not; the rates are
// false alarms / clean runs and misses / unclean runs. Step sizes the integrator refuses at
// construction (h^2 lambda on a pole) are counted apart: no run, nothing to predict.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <numbers>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "erkn/erkn.hpp"
#include "erkn/problems.hpp"

namespace {

using namespace erkn;
using std::numbers::pi;

struct Scene {
  std::string name;
  System system;
  Eigen::VectorXd q0, p0;
  double omega = 0;  // sqrt of M's largest eigenvalue
};

Scene scene(std::string name, System system, Eigen::VectorXd q0, Eigen::VectorXd p0) {
  const double omega = std::sqrt(system.M.eigenvalues().maxCoeff());
  return {std::move(name), std::move(system), std::move(q0), std::move(p0), omega};
}

Scene from_library(const problems::Problem& p, std::string name) {
  return scene(std::move(name), problems::system(p), p.q0, p.p0);
}

// u_tt = Lap u - u^3 on (0, 1)^k, Dirichlet, n interior points per axis (k = 1, 2),
// u0 = prod sin(pi x_a), u_t(0) = 0.
Scene wave_grid(int n, int k) {
  const double dx = 1.0 / (n + 1);
  System s;
  s.M = Stiffness::grid(std::vector<GridAxis>(k, {n, dx, GridAxis::Boundary::dirichlet}));
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) { g = q.array().cube(); };
  s.potential = [](const Eigen::VectorXd& q) { return 0.25 * q.array().pow(4).sum(); };
  s.hessian = [](const Eigen::VectorXd& q, Eigen::MatrixXd& H) {
    H = (3 * q.array().square()).matrix().asDiagonal();
  };
  const Eigen::Index d = k == 1 ? n : n * n;
  Eigen::VectorXd q0(d);
  for (Eigen::Index i = 0; i < d; ++i)  // (row-major: i = i0 n + i1)
    q0[i] = std::sin(pi * (i % n + 1) * dx) * (k == 1 ? 1 : std::sin(pi * (i / n + 1) * dx));
  const std::string size = k == 1 ? std::to_string(n) : std::to_string(n) + "^2";
  return scene(std::to_string(k) + "-D wave grid, Dirichlet, n = " + size + ", u^3", s, q0,
               Eigen::VectorXd::Zero(d));
}

std::vector<Scene> scenes() {
  return {from_library(problems::fpu(3, 50), "FPU (m = 3, omega = 50)"),
          from_library(problems::sine_gordon(32), "sine-Gordon P1 (N = 32)"), wave_grid(15, 1),
          wave_grid(7, 2)};
}

// max |H_n - H_0| / |H_0| over `steps` steps (every 50; the run stops at the first >= 0.5),
// infinity when the run stops with an erkn::Error; NaN when the integrator refuses h at
// construction.
double energy_error(const Method& m, const Scene& s, double h, long steps) {
  Options unguarded;
  unguarded.blowup_guard = false;
  std::unique_ptr<Integrator> run;
  try {
    run = std::make_unique<Integrator>(m, s.system, h, s.q0, s.p0, unguarded);
  } catch (const Error&) {
    return std::nan("");
  }
  const double H0 = run->energy();
  double worst = 0;
  try {
    for (long k = 1; k <= steps; ++k) {
      run->step();
      if (k % 50 == 0) worst = std::max(worst, std::abs(run->energy() - H0) / std::abs(H0));
      if (!(worst < 0.5)) break;  // (not clean already: the rest of the run cannot change that)
    }
  } catch (const Error&) {
    return INFINITY;
  }
  return std::isfinite(worst) ? worst : INFINITY;
}

struct Point {
  size_t scene = 0, method = 0;
  double h_omega = 0;
  bool flagged = false, refused = false, clean = false;
  double error = 0, neighbours = 0;  // (neighbours: NaN when not needed)
  std::string finding;               // the first finding, when flagged
};

// The advisor's verdict and the runs' truth at one point.
void measure(Point& pt, const Scene& s, const Method& m, long steps) {
  const double h = pt.h_omega / s.omega;
  AdvisorOptions verdict_only;
  verdict_only.max_change = 0;  // (no search for a suggestion: only the verdict at h counts)
  const StepSizeAdvice advice = advise_step_size(m, s.system, h, s.q0, s.p0, verdict_only);
  pt.flagged = !advice.safe();
  if (pt.flagged) {
    const std::string report = advice.report(m);
    const size_t line = report.find('\n') + 1;
    pt.finding = report.substr(line, report.find('\n', line) - line);
  }
  pt.error = energy_error(m, s, h, steps);
  pt.refused = std::isnan(pt.error);
  pt.neighbours = std::nan("");
  if (pt.refused || !(pt.error < 0.5)) return;
  // error <= 10 min(below, above) needs both; the second only when the first passes.
  const double below = energy_error(m, s, 0.97 * h, steps);
  pt.neighbours = below;
  if (!(pt.error <= 10 * below)) return;
  pt.neighbours = std::min(below, energy_error(m, s, 1.03 * h, steps));
  pt.clean = pt.error <= 10 * pt.neighbours;
}

struct Args {
  long steps = 100000;
  int points = 16, threads = 2;
  std::string out;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 < argc && arg == "--steps")
      a.steps = std::stol(argv[++i]);
    else if (i + 1 < argc && arg == "--points")
      a.points = std::stoi(argv[++i]);
    else if (i + 1 < argc && arg == "--threads")
      a.threads = std::stoi(argv[++i]);
    else
      a.out = arg;
  }
  if (a.steps < 1 || a.points < 1 || a.threads < 1)
    throw Error("erkn_advisor_sweep: --steps, --points and --threads must be >= 1");
  return a;
}

std::vector<Method> erkn_methods() {
  std::vector<Method> out;
  for (const Method& m : Method::all())
    if (m.kind() == Kind::erkn) out.push_back(m);
  return out;
}

// Every point, measured on `threads` threads (each point is independent).
std::vector<Point> sweep(const std::vector<Scene>& sc, const std::vector<Method>& ms,
                         const Args& a) {
  std::vector<Point> points;
  for (size_t s = 0; s < sc.size(); ++s)
    for (size_t m = 0; m < ms.size(); ++m)
      for (int k = 1; k <= a.points; ++k) {
        Point p;
        p.scene = s, p.method = m, p.h_omega = 4 * pi * k / a.points;
        points.push_back(p);
      }
  std::atomic<size_t> next = 0, done = 0;
  auto work = [&] {
    for (size_t i; (i = next++) < points.size();) {
      measure(points[i], sc[points[i].scene], ms[points[i].method], a.steps);
      if (++done % 50 == 0) std::cerr << done << "/" << points.size() << " points\n";
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < a.threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  return points;
}

struct Counts {
  long clean_flagged = 0, clean_passed = 0, unclean_flagged = 0, unclean_passed = 0, refused = 0;
  void add(const Point& p) {
    if (p.refused)
      ++refused;
    else if (p.clean)
      ++(p.flagged ? clean_flagged : clean_passed);
    else
      ++(p.flagged ? unclean_flagged : unclean_passed);
  }
  double false_alarm() const { return double(clean_flagged) / (clean_flagged + clean_passed); }
  double miss() const { return double(unclean_passed) / (unclean_flagged + unclean_passed); }
};

std::string percent(long n, long of) {
  std::ostringstream s;
  s << n << " / " << of << " = " << (of ? 100.0 * n / of : 0.0) << " %";
  return s.str();
}

std::string row(const std::string& name, const Counts& c) {
  std::ostringstream s;
  s << "| " << name << " | " << c.clean_passed << " | " << c.clean_flagged << " | "
    << c.unclean_flagged << " | " << c.unclean_passed << " | " << c.refused << " | "
    << percent(c.clean_flagged, c.clean_flagged + c.clean_passed) << " | "
    << percent(c.unclean_passed, c.unclean_flagged + c.unclean_passed) << " |\n";
  return s.str();
}

std::string point_line(const Point& p, const std::vector<Scene>& sc,
                       const std::vector<Method>& ms) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "| %s | %s | %.4g | %.3g | %.3g | ", sc[p.scene].name.c_str(),
                std::string(ms[p.method].name()).c_str(), p.h_omega / pi, p.error, p.neighbours);
  return buf + (p.flagged ? p.finding : std::string("(not flagged)")) + " |\n";
}

std::string report(const std::vector<Point>& points, const std::vector<Scene>& sc,
                   const std::vector<Method>& ms, const Args& a) {
  std::ostringstream s;
  s << "# The step-size advisor against runs\n\nWritten by `erkn_advisor_sweep` (experiments/src/"
       "advisor_sweep.cpp; its header defines verdict, truth and rates): "
    << ms.size() << " ERKN methods of the registry x " << sc.size() << " scenes x " << a.points
    << " step sizes h omega = 4 pi k / " << a.points << ", runs of " << a.steps
    << " steps.\n\n| scene | clean, not flagged | clean, flagged (false alarm) | not clean, "
       "flagged | not clean, not flagged (miss) | refused at construction | false-alarm rate | "
       "miss rate |\n|---|---|---|---|---|---|---|---|\n";
  Counts all;
  for (size_t i = 0; i < sc.size(); ++i) {
    Counts c;
    for (const Point& p : points)
      if (p.scene == i) c.add(p), (void)0;
    s << row(sc[i].name, c);
  }
  for (const Point& p : points) all.add(p);
  s << row("all", all);
  s << "\nFalse alarms and misses (error: the run's relative energy error; neighbours: the smaller "
       "of h (1 -+ 3 %)'s, where measured):\n\n| scene | method | h omega / pi | error | "
       "neighbours | advisor |\n|---|---|---|---|---|---|\n";
  for (const Point& p : points)
    if (!p.refused && p.clean == p.flagged) s << point_line(p, sc, ms);
  return s.str();
}

}  // namespace

int main(int argc, char** argv) try {
  const Args a = parse(argc, argv);
  const std::vector<Scene> sc = scenes();
  const std::vector<Method> ms = erkn_methods();
  const std::string md = report(sweep(sc, ms, a), sc, ms, a);
  if (a.out.empty()) {
    std::cout << md;
  } else {
    std::ofstream(a.out) << md;
    std::cout << "wrote " << a.out << "\n";
  }
  return 0;
} catch (const std::exception& e) {
  std::cerr << "erkn_advisor_sweep: " << e.what() << "\n";
  return 1;
}
