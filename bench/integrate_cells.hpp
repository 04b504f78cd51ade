// erkn_integrate_benchmark's measurements: the scenes, and per scene and method the timed
// contenders (bench/integrate_timing.hpp) and their ratios.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <erkn/compiled_gradient.hpp>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <functional>
#include <string>
#include <vector>

#include "integrate_timing.hpp"
#include "scenes.hpp"

namespace bench {

struct Config {
  bool short_mode = false, serve = false;
  std::string markdown, csv, compare, command;
  std::string scene, method;  // filters: label substring, method name (empty: all)
  TimingPlan plan() const { return short_mode ? TimingPlan{7, 4e-3} : TimingPlan{9, 1e-2}; }
};

/// Output times per run of the output column (on the grid), where the steps allow.
inline constexpr long kOutputs = 20;

struct Scene {
  std::string label;
  erkn::problems::Problem problem;
  double h;
  long steps;  // a multiple of outputs()
  long outputs() const { return std::min(steps, kOutputs); }
};

/// The scenes; --short takes fewer steps (down to 10), never fewer methods or scenes.
inline std::vector<Scene> scenes(bool short_mode) {
  namespace pr = erkn::problems;
  auto steps = [&](long full, long brief) { return short_mode ? brief : full; };
  return {{"Duffing (P2)", pr::duffing(), 1.0 / 100, steps(1000, 200)},
          {"stellar orbits (P3)", pr::stellar_orbits(), 1.0 / 40, steps(400, 100)},
          {"sine-Gordon N = 32", pr::sine_gordon(32), 1.0 / 40, steps(400, 100)},
          {"sine-Gordon N = 512", pr::sine_gordon(512), 1.0 / 100, steps(200, 40)},
          {"sine-Gordon N = 2048", pr::sine_gordon(2048), 1.0 / 100, steps(100, 20)},
          {"sine-Gordon N = 8192", pr::sine_gordon(8192), 1.0 / 100, steps(40, 10)},
          {"2-D sine-Gordon 256^2", pr::sine_gordon_2d(256), 1.0 / 40, steps(20, 10)}};
}

/// One explicit method on one scene: the contenders' median CPU ms per run and the ratios; for
/// erkn through System::gradient also the peer through the same std::function (callback_peer:
/// its time over the inlined peer's) and erkn's plain and default runs over that peer's (NaN in
/// the rows with the gradient compiled in).
struct Cell {
  std::string scene, method;
  long steps = 0;
  double peer_ms = 0, plain = 0, deflt = 0, output = 0;
  double callback_peer = NAN, plain_cb = NAN, deflt_cb = NAN;
};
/// One implicit method's CPU per grad U against the explicit path's on a scene.
struct ImplicitCell {
  std::string scene, method;
  double us_per_grad = 0, explicit_us_per_grad = 0, ratio = 0;
};
struct Results {
  std::vector<Cell> cells;
  std::vector<ImplicitCell> implicit_cells;
};

/// integrate(t_end) and read the final state of a run just constructed; returns the gradient
/// evaluations.
inline long finish_run(erkn::Integrator run, const Scene& s, volatile double& sink) {
  run.integrate(s.h * double(s.steps));
  sink = sink + run.q()[0] + run.p()[0];
  return run.statistics().gradient_evaluations;
}
/// construct + integrate(t_end) with the given options and read the final state (one whole
/// run, as a user calls it); returns the gradient evaluations.
inline long erkn_run(const erkn::Method& m, const erkn::System& sys, const Scene& s,
                     const erkn::Options& o, volatile double& sink) {
  return finish_run(erkn::Integrator(m, sys, s.h, s.problem.q0, s.problem.p0, o), s, sink);
}

/// t_end k / outputs, k = 1..outputs.
inline Eigen::VectorXd output_times(const Scene& s) {
  Eigen::VectorXd t(s.outputs());
  for (long k = 0; k < s.outputs(); ++k) t[k] = s.h * double(s.steps / s.outputs() * (k + 1));
  return t;
}

/// make(options): erkn's Integrator for the run (constructed within the timed run); callback:
/// System::gradient for a sixth contender, the peer through it (none: nullptr).
template <class Basis, class Gradient, class Make>
Cell measure_cell(const Scene& s, const erkn::Method& m, const Basis& basis, Gradient g, Make make,
                  const TimingPlan& plan, const std::string& label_suffix,
                  const erkn::System* callback) {
  erkn::Options plain_options;
  plain_options.compensated_summation = false;
  const Eigen::VectorXd times = output_times(s);
  volatile double sink = 0;  // what the observers read, so no output is optimised away
  auto peer = [&](auto gradient, long segments) {
    specialist::Peer run(m.table().c, m.table().d, m.stages(), s.h, basis, gradient, s.problem.q0,
                         s.problem.p0);
    Eigen::VectorXd q, p;
    for (long k = 0; k < segments; ++k) {  // (one segment: the final state only)
      run.run(s.steps / segments);
      run.state(q, p);
      sink = sink + q[0] + p[0];
    }
  };
  auto erkn_output = [&] {
    erkn::Integrator run = make(erkn::Options{});
    run.integrate(times[times.size() - 1], times,
                  [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
                    sink = sink + q[0] + p[0];
                  });
  };
  std::vector<std::function<void()>> contenders = {
      [&] { peer(g, 1); }, [&] { finish_run(make(plain_options), s, sink); },
      [&] { finish_run(make({}), s, sink); }, [&] { peer(g, s.outputs()); }, erkn_output};
  if (callback)
    contenders.push_back([&] { peer(specialist::VectorCallback{callback->gradient}, 1); });
  const std::vector<std::vector<double>> t = time_rounds(contenders, plan);
  Cell c{s.label + label_suffix,  std::string(m.name()),    s.steps,
         1e3 * median(t[0]),      median_ratio(t[1], t[0]), median_ratio(t[2], t[0]),
         median_ratio(t[4], t[3])};
  if (callback)
    c.callback_peer = median_ratio(t[5], t[0]), c.plain_cb = median_ratio(t[1], t[5]),
    c.deflt_cb = median_ratio(t[2], t[5]);
  return c;
}

/// The rows of erkn with the peer's gradient compiled into its steps (erkn::make_integrator).
inline const std::string kCompiledRows = " with templated gradient";  // (no comma: csv)

/// Every explicit method with a peer: erkn with the problems library's System (System::gradient,
/// a std::function, as users of the callback path call it; the peer through the same function
/// too), and also with the peer's gradient compiled in (erkn/compiled_gradient.hpp; rows
/// kCompiledRows).
template <class Basis, class Gradient>
void measure_scene(const Scene& s, const Basis& basis, Gradient g, const Config& cfg,
                   Results& out) {
  const erkn::System sys = erkn::problems::system(s.problem);
  erkn::System bare = sys;  // (make_integrator's: the compiled functor is the gradient)
  bare.gradient = nullptr;
  const auto compiled = [g](const auto& q, auto& out) {  // (the peer's functor, on arrays)
    auto a = out.array();
    g(q.array(), a);
  };
  for (bool templated : {false, true}) {
    for (const erkn::Method& m : erkn::Method::all()) {
      // (The peer kicks with grad U only and has no processor: methods with modified kicks or a
      // processor have no peer here.)
      if (!m.is_explicit() || m.has_modified_kicks() || m.is_processed() ||
          (!cfg.method.empty() && cfg.method != m.name()))
        continue;
      auto make = [&](const erkn::Options& o) {
        if (templated)
          return erkn::make_integrator(m, bare, compiled, s.h, s.problem.q0, s.problem.p0, o);
        return erkn::Integrator(m, sys, s.h, s.problem.q0, s.problem.p0, o);
      };
      out.cells.push_back(measure_cell(s, m, basis, g, make, cfg.plan(),
                                       templated ? kCompiledRows : "", templated ? nullptr : &sys));
      std::fprintf(stderr, ".");
    }
  }
}

/// CPU per grad U of every registry method with erkn's defaults (construct + integrate), and
/// each implicit method's ratio to the median over the explicit methods, per round.
inline void measure_implicit(const Scene& s, const TimingPlan& plan, Results& out) {
  const erkn::System sys = erkn::problems::system(s.problem);
  std::vector<erkn::Method> methods(erkn::Method::all().begin(), erkn::Method::all().end());
  std::vector<std::function<void()>> runs;
  std::vector<double> evaluations;
  volatile double sink = 0;
  for (const erkn::Method& m : methods) {
    evaluations.push_back(double(erkn_run(m, sys, s, {}, sink)));
    runs.push_back([&, m] { erkn_run(m, sys, s, {}, sink); });
  }
  std::vector<std::vector<double>> t = time_rounds(runs, plan);
  std::vector<double> explicit_ref(size_t(plan.rounds));  // per round
  for (size_t r = 0; r < explicit_ref.size(); ++r) {
    std::vector<double> per_grad;
    for (size_t i = 0; i < methods.size(); ++i)
      if (methods[i].is_explicit()) per_grad.push_back(t[i][r] / evaluations[i]);
    explicit_ref[r] = median(per_grad);
  }
  for (size_t i = 0; i < methods.size(); ++i) {
    if (methods[i].is_explicit()) continue;
    for (double& x : t[i]) x /= evaluations[i];
    out.implicit_cells.push_back({s.label, std::string(methods[i].name()), 1e6 * median(t[i]),
                                  1e6 * median(explicit_ref), median_ratio(t[i], explicit_ref)});
  }
}

/// Every scene: the identity basis for scalar and diagonal M, FFTW r2c/c2r otherwise.
inline Results measure_all(const Config& cfg) {
  using Kind = erkn::problems::LinearPart::Kind;
  Results out;
  for (const Scene& s : scenes(cfg.short_mode)) {
    if (s.label.find(cfg.scene) == std::string::npos) continue;
    std::fprintf(stderr, "%s ", s.label.c_str());
    const Kind kind = s.problem.M.kind;
    if (kind == Kind::scalar) {
      measure_scene(s, identity_basis<1>(s.problem.M, 1), DuffingGradient{}, cfg, out);
    } else if (kind == Kind::diagonal) {
      measure_scene(s, identity_basis<2>(s.problem.M, 2), StellarGradient{}, cfg, out);
    } else {
      const specialist::FourierBasis basis = fourier_basis(s.problem.M);
      measure_scene(s, basis, SineGordonGradient{}, cfg, out);
    }
    if (s.problem.dim() <= 32 && cfg.method.empty()) measure_implicit(s, cfg.plan(), out);
    std::fprintf(stderr, "\n");
  }
  return out;
}

}  // namespace bench
