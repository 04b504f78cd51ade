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
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "integrate_floor.hpp"
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
/// states: the host's state in each of the cell's rounds; peer_slow_fast: the peer's median
/// time in slow rounds over that in fast rounds (NaN unless both occur).
struct Cell {
  std::string scene, method;
  long steps = 0;
  double peer_ms = 0, plain = 0, deflt = 0, output = 0;
  double callback_peer = NAN, plain_cb = NAN, deflt_cb = NAN;
  RoundStates states;
  double peer_slow_fast = NAN;
};
/// One implicit method's CPU per grad U against the explicit path's on a scene; the ratio's
/// median also over the fast and over the slow rounds alone (NaN where none), and the explicit
/// path's median time in slow rounds over that in fast rounds; the floor's columns
/// (integrate_floor.hpp).
struct ImplicitCell {
  std::string scene, method;
  double us_per_grad = 0, explicit_us_per_grad = 0, ratio = 0;
  double ratio_fast = NAN, ratio_slow = NAN;
  RoundStates states;
  double explicit_slow_fast = NAN;
  FloorColumns floor;
};
struct Results {
  std::vector<Cell> cells;
  std::vector<ImplicitCell> implicit_cells;
  bool pinned = false;         // the timing thread on one CPU
  bool malloc_steady = false;  // glibc malloc without fastbins, trimming, mmap (steady_malloc)
  StateSplit host;             // the host's states in this run (host_state.hpp)
};

/// Median of x over slow rounds / median over fast rounds (NaN unless both occur).
inline double slow_over_fast(const std::vector<double>& x, const RoundStates& s) {
  const auto [fast, slow] = median_by_state(x, s);
  return slow / fast;
}

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

/// What a scene's contenders read while the Schedule runs (each holds it by shared_ptr).
template <class Basis, class Gradient>
struct SceneRuns {
  Scene s;
  Basis basis;
  Gradient g;
  erkn::System sys = erkn::problems::system(s.problem);
  erkn::System bare = without_gradient(sys);  // make_integrator's: the functor is the gradient
  Eigen::VectorXd times = output_times(s);
  volatile double sink = 0;  // what the runs and observers read, so no output is optimised away

  /// erkn's Integrator for a run (constructed within the timed run): through System::gradient,
  /// or with the peer's functor compiled in (erkn::make_integrator).
  erkn::Integrator make(const erkn::Method& m, bool templated, const erkn::Options& o) const {
    if (!templated) return erkn::Integrator(m, sys, s.h, s.problem.q0, s.problem.p0, o);
    return erkn::make_integrator(m, bare, on_vectors(g), s.h, s.problem.q0, s.problem.p0, o);
  }
  /// The peer's run of m with `gradient` (g inlined, or VectorCallback on System::gradient),
  /// transforming back after each of `segments` equal parts (one: the final state only).
  template <class G>
  void peer(const erkn::Method& m, G gradient, long segments) {
    specialist::Peer run(m.table().c, m.table().d, m.stages(), s.h, basis, gradient, s.problem.q0,
                         s.problem.p0);
    Eigen::VectorXd q, p;
    for (long k = 0; k < segments; ++k) {
      run.run(s.steps / segments);
      run.state(q, p);
      sink = sink + q[0] + p[0];
    }
  }
};

/// The rows of erkn with the peer's gradient compiled into its steps (erkn::make_integrator).
inline const std::string kCompiledRows = " with templated gradient";  // (no comma: csv)

/// One cell's contenders in the schedule (peer, erkn plain, erkn defaults, the peer with output,
/// erkn with output times, and in the rows through System::gradient the peer through it); the
/// Cell at out.cells[index] gets their ratios.
template <class Runs>
void add_cell(std::shared_ptr<Runs> sc, const erkn::Method& m, bool templated, Schedule& schedule,
              Results& out) {
  const Scene& s = sc->s;
  const size_t index = out.cells.size();
  out.cells.push_back({s.label + (templated ? kCompiledRows : ""), std::string(m.name()), s.steps});
  erkn::Options plain_options;
  plain_options.compensated_summation = false;
  auto erkn_output = [sc, m, templated] {
    erkn::Integrator run = sc->make(m, templated, erkn::Options{});
    run.integrate(sc->times[sc->times.size() - 1], sc->times,
                  [&](double, const Eigen::VectorXd& q, const Eigen::VectorXd& p) {
                    sc->sink = sc->sink + q[0] + p[0];
                  });
  };
  Schedule::Contenders contenders = {
      [sc, m] { sc->peer(m, sc->g, 1); },
      [sc, m, templated, plain_options] {
        finish_run(sc->make(m, templated, plain_options), sc->s, sc->sink);
      },
      [sc, m, templated] { finish_run(sc->make(m, templated, {}), sc->s, sc->sink); },
      [sc, m] { sc->peer(m, sc->g, sc->s.outputs()); }, erkn_output};
  if (!templated)
    contenders.push_back([sc, m] { sc->peer(m, specialist::VectorCallback{sc->sys.gradient}, 1); });
  schedule.add(std::move(contenders),
               [&out, index](const Schedule::Seconds& t, const RoundStates& states) {
                 Cell& c = out.cells[index];
                 c.states = states, c.peer_slow_fast = slow_over_fast(t[0], states);
                 c.peer_ms = 1e3 * median(t[0]);
                 c.plain = median_ratio(t[1], t[0]), c.deflt = median_ratio(t[2], t[0]);
                 c.output = median_ratio(t[4], t[3]);
                 if (t.size() > 5)
                   c.callback_peer = median_ratio(t[5], t[0]),
                   c.plain_cb = median_ratio(t[1], t[5]), c.deflt_cb = median_ratio(t[2], t[5]);
               });
}

/// Every explicit method with a peer: erkn with the problems library's System (System::gradient,
/// a std::function, as users of the callback path call it; the peer through the same function
/// too), and also with the peer's gradient compiled in (erkn/compiled_gradient.hpp; rows
/// kCompiledRows).
template <class Basis, class Gradient>
void add_scene(const Scene& s, Basis basis, Gradient g, const Config& cfg, Schedule& schedule,
               Results& out) {
  const auto sc = std::make_shared<SceneRuns<Basis, Gradient>>(
      SceneRuns<Basis, Gradient>{s, std::move(basis), g});
  for (bool templated : {false, true}) {
    for (const erkn::Method& m : erkn::Method::all()) {
      // (The peer kicks with grad U only and has no processor: methods with modified kicks or a
      // processor have no peer here.)
      if (!m.is_explicit() || m.has_modified_kicks() || m.is_processed() ||
          (!cfg.method.empty() && cfg.method != m.name()))
        continue;
      add_cell(sc, m, templated, schedule, out);
    }
  }
}

/// The implicit cells of a scene from every registry method's seconds per run (defaults,
/// construct + integrate) and gradient evaluations per run: each implicit method's CPU per grad U
/// against the median over the explicit methods in the same round, over all rounds and over the
/// rounds of each state; and the floor's columns (none: not timed).
inline void implicit_ratios(const Scene& s, const std::vector<erkn::Method>& methods,
                            const std::vector<double>& evaluations, const Schedule::Seconds& t,
                            const RoundStates& states, const FloorGroup* floor, Results& out) {
  std::vector<size_t> explicit_methods;
  for (size_t i = 0; i < methods.size(); ++i)
    if (methods[i].is_explicit()) explicit_methods.push_back(i);
  const std::vector<double> explicit_ref = per_grad_median(t, evaluations, explicit_methods);
  size_t k = 0;  // implicit methods so far
  for (size_t i = 0; i < methods.size(); ++i) {
    if (methods[i].is_explicit()) continue;
    std::vector<double> grad = t[i];
    for (double& x : grad) x /= evaluations[i];
    const std::vector<double> ratio = ratios(grad, explicit_ref);
    ImplicitCell c{s.label, std::string(methods[i].name()), 1e6 * median(grad),
                   1e6 * median(explicit_ref), median(ratio)};
    std::tie(c.ratio_fast, c.ratio_slow) = median_by_state(ratio, states);
    c.states = states, c.explicit_slow_fast = slow_over_fast(explicit_ref, states);
    if (floor) c.floor = floor->columns(k, t, grad, explicit_ref);
    ++k;
    out.implicit_cells.push_back(std::move(c));
  }
}

/// CPU per grad U of every registry method with erkn's defaults (construct + integrate) on a
/// scene, one group of the schedule, with the floor's contenders (null: not timed); its implicit
/// cells are appended when the schedule has run.
inline void add_implicit(const Scene& s, std::shared_ptr<FloorGroup> floor, Schedule& schedule,
                         Results& out) {
  struct Runs {
    erkn::System sys;
    volatile double sink = 0;
  };
  const auto sc = std::make_shared<Runs>(Runs{erkn::problems::system(s.problem)});
  std::vector<erkn::Method> methods(erkn::Method::all().begin(), erkn::Method::all().end());
  Schedule::Contenders runs;
  std::vector<double> evaluations;
  for (const erkn::Method& m : methods) {
    evaluations.push_back(double(erkn_run(m, sc->sys, s, {}, sc->sink)));
    runs.push_back([sc, m, s] { erkn_run(m, sc->sys, s, {}, sc->sink); });
  }
  if (floor) floor->add(methods, runs);
  schedule.add(std::move(runs), [s, methods, evaluations, floor, &out](const Schedule::Seconds& t,
                                                                       const RoundStates& states) {
    implicit_ratios(s, methods, evaluations, t, states, floor.get(), out);
  });
}

/// The host state probe (host_state.hpp): the explicit path's CPU ns per grad U, the median over
/// every explicit registry method with plain kicks (unprocessed) of one run each on Duffing (P2,
/// erkn's defaults, construct + 200 steps); ~0.3 ms per reading.
struct ExplicitPathProbe {
  Scene s{"probe", erkn::problems::duffing(), 1.0 / 100, 200};
  erkn::System sys = erkn::problems::system(s.problem);
  std::vector<erkn::Method> methods = plain_explicit();
  volatile double sink = 0;

  static std::vector<erkn::Method> plain_explicit() {
    std::vector<erkn::Method> out;
    for (const erkn::Method& m : erkn::Method::all())
      if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed()) out.push_back(m);
    return out;
  }
  double read() {
    std::vector<double> ns;
    for (const erkn::Method& m : methods) {
      const double start = thread_seconds();
      const long grads = erkn_run(m, sys, s, {}, sink);
      ns.push_back(1e9 * (thread_seconds() - start) / double(grads));
    }
    return median(ns);
  }
};

/// Every scene: the identity basis for scalar and diagonal M, FFTW r2c/c2r otherwise; all cells
/// timed in one Schedule (a cell's rounds spread over the whole run), the thread on one CPU,
/// malloc steady (integrate_timing.hpp: steady_malloc), the host's state probed before every
/// sample (host_state.hpp).
inline Results measure_all(const Config& cfg) {
  using Kind = erkn::problems::LinearPart::Kind;
  Results out;
  out.pinned = pin_to_one_cpu();
  out.malloc_steady = steady_malloc();
  Schedule schedule;
  for (const Scene& s : scenes(cfg.short_mode)) {
    if (s.label.find(cfg.scene) == std::string::npos) continue;
    const Kind kind = s.problem.M.kind;
    const floor::FloorScene fs{s.label, s.problem, s.h, s.steps};
    std::shared_ptr<FloorGroup> floor;  // (the floor loop: scalar and diagonal M, D = 1, 2)
    if (kind == Kind::scalar) {
      add_scene(s, identity_basis<1>(s.problem.M, 1), DuffingGradient{}, cfg, schedule, out);
      floor = std::make_shared<FloorGroupOf<1, DuffingGradient>>(fs, DuffingGradient{});
    } else if (kind == Kind::diagonal) {
      add_scene(s, identity_basis<2>(s.problem.M, 2), StellarGradient{}, cfg, schedule, out);
      floor = std::make_shared<FloorGroupOf<2, StellarGradient>>(fs, StellarGradient{});
    } else {
      add_scene(s, fourier_basis(s.problem.M), SineGordonGradient{}, cfg, schedule, out);
    }
    if (s.problem.dim() <= 32 && cfg.method.empty()) add_implicit(s, floor, schedule, out);
  }
  std::fprintf(stderr, "%zu cells, %d rounds\n", out.cells.size(), cfg.plan().rounds);
  ExplicitPathProbe probe;
  out.host = schedule.run(cfg.plan(), [&probe] { return probe.read(); });
  return out;
}

}  // namespace bench
