// erkn_implicit_floor's runs (bench/implicit_floor.cpp): per scene one Schedule group with, per
// round, erkn's explicit registry methods (System::gradient, defaults, construct + integrate),
// the explicit specialist peers (gradient inlined), and per implicit method erkn's run and the
// floor loop's (bench/implicit_floor.hpp) with the gradient inlined and through System::gradient
// (without and with erkn's compensated summation and finiteness checks).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <erkn/compiled_gradient.hpp>
#include <erkn/erkn.hpp>
#include <erkn/problems.hpp>
#include <memory>
#include <string>
#include <vector>

#include "implicit_floor.hpp"
#include "integrate_timing.hpp"
#include "scenes.hpp"

namespace bench::floor {

struct FloorScene {
  std::string label;
  erkn::problems::Problem problem;
  double h;
  long steps;
};
inline FloorScene duffing_scene(bool short_mode) {
  return {"Duffing (P2)", erkn::problems::duffing(), 1.0 / 100, short_mode ? 200 : 1000};
}
inline FloorScene stellar_scene(bool short_mode) {
  return {"stellar orbits (P3)", erkn::problems::stellar_orbits(), 1.0 / 40,
          short_mode ? 100 : 400};
}

/// One implicit method on a scene (ratios: medians over rounds of the per-round ratios of CPU per
/// grad U; "expl": erkn's explicit path, "peers": the specialist peers; cb: the floor loop through
/// System::gradient, inl: inlined, extras: through System::gradient with compensated summation and
/// finiteness checks; carry: Variant::carry).
struct MethodResult {
  std::string name;
  double erkn_per_step = 0, floor_per_step = 0, state_diff = 0;
  double inl_expl = 0, cb_expl = 0, extras_expl = 0, erkn_expl = 0, inl_peer = 0, cb_peer = 0,
         erkn_cb = 0, erkn_extras = 0, inl_carry_expl = 0, cb_carry_expl = 0;
  double cb_step_s = 0;  // the floor loop's CPU per step through System::gradient (median)
};
struct SceneResult {
  std::string label;
  double explicit_s = 0, peer_s = 0;  // seconds per grad U (medians)
  int explicit_methods = 0;
  std::vector<MethodResult> methods;
};

/// The floor loop's variants: as it is; with erkn's compensated summation and finiteness checks
/// (extras); with the next step's first Q_0 formed at the end of a step (carry: Loop's kCarry).
enum class Variant { plain, extras, carry };

/// What a scene's contenders read.
template <int D, class Gradient>
struct FloorRuns {
  using Arr = Eigen::Array<double, D, 1>;
  FloorScene s;
  Gradient g;
  Settings settings;
  erkn::System sys = erkn::problems::system(s.problem);
  Arr lambda = s.problem.M.eigenvalues(D).array(), q0 = s.problem.q0.array(),
      p0 = s.problem.p0.array();
  specialist::IdentityBasis<D> basis = identity_basis<D>(s.problem.M, D);
  volatile double sink = 0;

  /// erkn construct + integrate with its defaults; gradient evaluations, final state in q, p.
  long erkn(const erkn::Method& m, Eigen::VectorXd* q = nullptr, Eigen::VectorXd* p = nullptr) {
    return finish(erkn::Integrator(m, sys, s.h, s.problem.q0, s.problem.p0), q, p);
  }
  /// The same with g compiled into erkn's steps (erkn::make_integrator).
  long erkn_compiled(const erkn::Method& m) {
    return finish(erkn::make_integrator(m, without_gradient(sys), on_vectors(g), s.h, s.problem.q0,
                                        s.problem.p0),
                  nullptr, nullptr);
  }
  long finish(erkn::Integrator run, Eigen::VectorXd* q, Eigen::VectorXd* p) {
    run.integrate(s.h * double(s.steps));
    sink = sink + run.q()[0] + run.p()[0];
    if (q) *q = run.q(), *p = run.p();
    return run.statistics().gradient_evaluations;
  }
  /// The floor loop with gradient G (construct + run), as `variant` says; evaluations, final state
  /// in q, p.
  template <class G>
  long floor(const erkn::Method& m, const G& gradient, Variant variant = Variant::plain,
             Eigen::VectorXd* q = nullptr, Eigen::VectorXd* p = nullptr) {
    Settings st = settings;
    st.compensated = st.checks = variant == Variant::extras;
    auto run = [&](auto& loop) {
      loop.run(s.steps);
      sink = sink + loop.q()[0] + loop.p()[0];
      if (q) *q = loop.q().matrix(), *p = loop.p().matrix();
      return loop.evaluations();
    };
    if (variant == Variant::carry)
      return with_loop<D, G, decltype(run)&, 1, true>(m, lambda, s.h, gradient, q0, p0, st, run);
    return with_loop<D>(m, lambda, s.h, gradient, q0, p0, st, run);
  }
  long peer(const erkn::Method& m) {
    specialist::Peer run(m.table().c, m.table().d, m.stages(), s.h, basis, g, s.problem.q0,
                         s.problem.p0);
    run.run(s.steps);
    Eigen::VectorXd q, p;
    run.state(q, p);
    sink = sink + q[0] + p[0];
    return run.evaluations();
  }
  Callback<D> callback() const { return Callback<D>{sys.gradient}; }
};

/// max |a - b| over q and p.
inline double state_diff(const Eigen::VectorXd& qa, const Eigen::VectorXd& pa,
                         const Eigen::VectorXd& qb, const Eigen::VectorXd& pb) {
  return std::max((qa - qb).cwiseAbs().maxCoeff(), (pa - pb).cwiseAbs().maxCoeff());
}

/// The floor loop's final state agrees with erkn's when they differ by at most kAgree relative to
/// erkn's largest |q_k|, |p_k|: both converge every stage to 1e-14 (relative), so the states
/// differ by what the steps accumulate of that (measured <= 1.7e-10 at |p| ~ 10, RKN4s6 on P2);
/// 1e-8 relative leaves room, and every control (1e-2 in U) misses it by more than 50x.
inline constexpr double kAgree = 1e-8;
/// max |floor - erkn| over q and p relative to erkn's largest entry (agreement: <= kAgree).
inline double relative_diff(const Eigen::VectorXd& qe, const Eigen::VectorXd& pe,
                            const Eigen::VectorXd& qf, const Eigen::VectorXd& pf) {
  return state_diff(qe, pe, qf, pf) / std::max(qe.cwiseAbs().maxCoeff(), pe.cwiseAbs().maxCoeff());
}

/// seconds per grad U of contender c, per round.
inline std::vector<double> per_grad(const Schedule::Seconds& t, const std::vector<double>& ev,
                                    size_t c) {
  std::vector<double> x = t[c];
  for (double& v : x) v /= ev[c];
  return x;
}

/// The ratios of the implicit methods' contenders (kPerMethod each from `first`: erkn, floor
/// inlined, floor through System::gradient, the same with extras, the carry variant inlined and
/// through System::gradient) against the references.
inline constexpr size_t kPerMethod = 6;
inline void implicit_ratios(const Schedule::Seconds& t, const std::vector<double>& ev,
                            const std::vector<double>& expl, const std::vector<double>& peers,
                            size_t first, long steps, SceneResult& out) {
  for (size_t k = 0; k < out.methods.size(); ++k) {
    MethodResult& m = out.methods[k];
    const size_t c = first + kPerMethod * k;
    const auto erkn = per_grad(t, ev, c), inl = per_grad(t, ev, c + 1), cb = per_grad(t, ev, c + 2),
               extras = per_grad(t, ev, c + 3);
    m.erkn_expl = median_ratio(erkn, expl), m.inl_expl = median_ratio(inl, expl);
    m.cb_expl = median_ratio(cb, expl), m.extras_expl = median_ratio(extras, expl);
    m.inl_peer = median_ratio(inl, peers), m.cb_peer = median_ratio(cb, peers);
    m.erkn_cb = median_ratio(erkn, cb), m.erkn_extras = median_ratio(erkn, extras);
    m.inl_carry_expl = median_ratio(per_grad(t, ev, c + 4), expl);
    m.cb_carry_expl = median_ratio(per_grad(t, ev, c + 5), expl);
    m.cb_step_s = median(t[c + 2]) / double(steps);
  }
}

/// The scene's group: every contender run once untimed here (evaluations, the floor loop's
/// final state against erkn's).
template <int D, class Gradient>
void add_scene(FloorScene s, Gradient g, const Settings& settings, Schedule& schedule,
               SceneResult& out) {
  auto sc = std::make_shared<FloorRuns<D, Gradient>>(FloorRuns<D, Gradient>{s, g, settings});
  out.label = s.label;
  Schedule::Contenders runs;
  std::vector<double> ev;
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_explicit()) {
      ev.push_back(double(sc->erkn(m))), runs.push_back([sc, m] { sc->erkn(m); });
      ++out.explicit_methods;
    }
  const size_t peers_from = runs.size();
  for (const erkn::Method& m : erkn::Method::all())
    if (m.is_explicit() && !m.has_modified_kicks() && !m.is_processed())
      ev.push_back(double(sc->peer(m))), runs.push_back([sc, m] { sc->peer(m); });
  const size_t implicit_from = runs.size();
  for (const erkn::Method& m : erkn::Method::all()) {
    if (m.is_explicit()) continue;
    Eigen::VectorXd qe, pe, qf, pf;
    const long e = sc->erkn(m, &qe, &pe), f = sc->floor(m, sc->g, Variant::plain, &qf, &pf);
    out.methods.push_back({std::string(m.name()), double(e) / double(s.steps),
                           double(f) / double(s.steps), state_diff(qe, pe, qf, pf)});
    const double fx = double(sc->floor(m, sc->g, Variant::extras)),
                 fc = double(sc->floor(m, sc->g, Variant::carry));
    ev.insert(ev.end(), {double(e), double(f), double(f), fx, fc, fc});
    runs.push_back([sc, m] { sc->erkn(m); });
    for (Variant v : {Variant::plain, Variant::carry}) {
      runs.push_back([sc, m, v] { sc->floor(m, sc->g, v); });
      runs.push_back([sc, m, v] { sc->floor(m, sc->callback(), v); });
      if (v == Variant::plain)
        runs.push_back([sc, m] { sc->floor(m, sc->callback(), Variant::extras); });
    }
  }
  schedule.add(std::move(runs), [=, &out](const Schedule::Seconds& t, const RoundStates&) {
    const auto expl = per_grad_median(t, ev, contender_range(0, peers_from));
    const auto peers = per_grad_median(t, ev, contender_range(peers_from, implicit_from));
    out.explicit_s = median(expl), out.peer_s = median(peers);
    implicit_ratios(t, ev, expl, peers, implicit_from, s.steps, out);
  });
}

}  // namespace bench::floor
