// The scenes of the accuracy-driven benchmarks (erkn_accuracy_benchmark, erkn_design_benchmark):
// a problem, its reference q at t_error, and one fixed-step run as a user calls it
// (construction + integrate, thread CPU time; error = max norm of q at t_error).
#pragma once

#include <cmath>
#include <cstdio>
#include <erkn/error.hpp>
#include <erkn/integrator.hpp>
#include <erkn/problems.hpp>
#include <erkn/problems/reference.hpp>
#include <limits>
#include <string>
#include <vector>

#include "thread_seconds.hpp"

namespace bench {

inline constexpr double kInf = std::numeric_limits<double>::infinity();

inline std::string sci(double x, int digits = 2) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*e", digits, x);
  return buf;
}

struct ToleranceScene {
  erkn::problems::Problem problem;
  Eigen::VectorXd reference;
  std::string reference_note;
};

inline ToleranceScene tolerance_scene(erkn::problems::Problem p) {
  namespace pr = erkn::problems;
  pr::Reference r = p.force_ld
                        ? pr::reference_solution(p, p.t_error, 1e-13)
                        : pr::reference_solution(p, p.t_error, 1e-12, pr::Precision::double_);
  return {
      std::move(p), r.q,
      r.method + (r.accuracy > 0 ? ", last halving changed " + sci(r.accuracy, 1) : std::string())};
}

/// P1, P2, P3, FPU, Henon-Heiles, 2-D sine-Gordon 32^2 (only `only`'s key if not empty).
inline std::vector<erkn::problems::Problem> tolerance_problems(const std::string& only) {
  namespace pr = erkn::problems;
  std::vector<pr::Problem> all = {pr::sine_gordon(32), pr::duffing(),      pr::stellar_orbits(),
                                  pr::fpu(),           pr::henon_heiles(), pr::sine_gordon_2d(32)};
  std::vector<pr::Problem> out;
  for (pr::Problem& p : all)
    if (only.empty() || p.key == only) out.push_back(std::move(p));
  return out;
}

struct Run {
  std::string method;
  double h = 0, error = kInf, cpu = kInf;
  double choice_cpu = 0;  // of erkn::solve: the choice (pilot, Hessian bounds, advisor) within cpu
  double estimate = 0;    // of erkn::solve: the choice's estimated error at t_end
};

/// One fixed-step run as a user calls it: construction + integrate; error at t_error.
inline Run fixed_run(const ToleranceScene& s, const erkn::Method& m, double h) {
  Run out{std::string(m.name()), h};
  const double t0 = thread_seconds();
  try {
    erkn::Integrator it(m, erkn::problems::system(s.problem), h, s.problem.q0, s.problem.p0);
    it.integrate(s.problem.t_error);
    out.error = (it.q() - s.reference).lpNorm<Eigen::Infinity>();
    if (!std::isfinite(out.error)) out.error = kInf;
  } catch (const erkn::Error&) {  // a pole, a failed stage: no result at this h
    return out;
  }
  out.cpu = thread_seconds() - t0;
  return out;
}

}  // namespace bench
