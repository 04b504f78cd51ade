// Accuracy-driven runs (erkn/accuracy.hpp): erkn::solve with tol and no method or h reaches an
// error within [tol/100, 3 tol] at t_end; a given method or h is kept; bad requests are refused.
// (bench/accuracy_benchmark.cpp measures all problems and tolerances against a full sweep.)
#include "erkn/accuracy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "accuracy_pilot.hpp"  // runtime/src: the error shape the choice solves
#include "erkn/advisor.hpp"
#include "erkn/error.hpp"
#include "erkn/problems.hpp"

namespace erkn {
namespace {

double error_of(const Solution& s, const Eigen::VectorXd& reference) {
  return (s.q - reference).lpNorm<Eigen::Infinity>();
}

// The registry's explicit method of highest order (most stages on ties), at a step 16 times
// below the chosen one's: a reference by another route than the choice's pilot.
Eigen::VectorXd reference(const problems::Problem& p, double h) {
  const Method* best = nullptr;
  for (const Method& m : Method::all())
    if (m.is_explicit() && (!best || m.order() > best->order() ||
                            (m.order() == best->order() && m.stages() > best->stages())))
      best = &m;
  AccuracyRequest r;
  r.method = std::string(best->name()), r.h = h / 16;
  return solve(problems::system(p), p.q0, p.p0, 0, p.t_error, r).q;
}

TEST(Accuracy, AutoReachesTheToleranceWithinTheWindow) {
  for (const problems::Problem& p : {problems::duffing(), problems::stellar_orbits(),
                                     problems::sine_gordon(32), problems::henon_heiles()})
    for (double tol : {1e-4, 1e-8}) {
      AccuracyRequest r;
      r.tol = tol;
      const Solution s = solve(problems::system(p), p.q0, p.p0, 0, p.t_error, r);
      ASSERT_TRUE(s.choice.has_value());
      const Eigen::VectorXd ref = p.exact ? (*p.exact)(p.t_error) : reference(p, s.h);
      const double e = error_of(s, ref);
      EXPECT_LE(e, 3 * tol) << p.key << " tol " << tol << ": " << s.choice->reason;
      EXPECT_GE(e, tol / 100) << p.key << " tol " << tol << ": " << s.choice->reason;
      EXPECT_NEAR(s.t, p.t_error, 1e-12);
      EXPECT_FALSE(s.choice->reason.empty());
      EXPECT_GT(s.choice->pilot_gradient_evaluations, 0);
      // Negative control: the choice for 1000 tol takes a longer step and a larger error.
      r.tol = 1000 * tol;
      const Solution loose = solve(problems::system(p), p.q0, p.p0, 0, p.t_error, r);
      EXPECT_GT(loose.h, s.h) << p.key << " tol " << tol;
      EXPECT_GT(error_of(loose, ref), e) << p.key << " tol " << tol;
    }
}

// The step solve (Newton in ln h) lands on the level for every registry method's shape, at
// levels from 1e-14 to above shape(h_max), and for several perturbation sizes r.
TEST(Accuracy, ErrorShapeStepReachesTheLevel) {
  int solved = 0;
  for (const Method& m : Method::all())
    for (double r : {1.0, 1e-3}) {
      const detail::ErrorShape shape = detail::error_shape(m, r);
      if (shape.c.empty()) continue;
      for (double level : {1e-14, 1e-10, 1e-6, 1e-2}) {
        const double h_max = 10, h = shape.step_at(level, h_max);
        ASSERT_GT(h, 0) << m.name();
        ASSERT_LE(h, h_max) << m.name();
        if (shape(h_max) <= level) {
          EXPECT_EQ(h, h_max) << m.name();
          continue;
        }
        EXPECT_NEAR(shape(h) / level, 1, 1e-9) << m.name() << " r " << r << " level " << level;
        // Negative control: a step 1 % longer misses the level by more than the tolerance.
        EXPECT_GT(std::abs(shape(1.01 * h) / level - 1), 1e-3) << m.name();
        ++solved;
      }
    }
  EXPECT_GT(solved, 0);
}

// The choice asks the advisor about M's distinct eigenvalues only: on a grid (repeated
// eigenvalues) its verdict and suggestion equal those over all of them, for every explicit
// method and several h. Negative control: without the largest eigenvalue some verdict changes.
TEST(Accuracy, AdvisorVerdictOnDistinctEigenvaluesIsTheSame) {
  const problems::Problem p = problems::sine_gordon_2d(4);
  const System sys = problems::system(p);
  const Eigen::VectorXd all = sys.M.eigenvalues(), once = detail::distinct(all);
  ASSERT_LT(once.size(), all.size());
  const HessianBounds bounds = hessian_bounds_at(sys, p.q0);
  const auto same = [](const StepSizeAdvice& a, const StepSizeAdvice& b) {
    return a.safe() == b.safe() && (a.suggested_h == b.suggested_h ||
                                    (std::isnan(a.suggested_h) && std::isnan(b.suggested_h)));
  };
  int changed_without_top = 0;
  for (const Method& m : Method::all()) {
    if (!m.is_explicit()) continue;
    for (double h : {0.9, 2.5}) {
      const StepSizeAdvice full = advise_step_size(m, all, h, bounds);
      EXPECT_TRUE(same(full, advise_step_size(m, once, h, bounds))) << m.name() << " h " << h;
      changed_without_top +=
          !same(full, advise_step_size(m, once.head(once.size() - 1), h, bounds));
    }
  }
  EXPECT_GT(changed_without_top, 0);
}

// The growth probe (detail::growth_relief) measures how the error grows after the pilot
// interval: on every scene its relief (growth over the pilot's linear one) lies within 4x of the
// growth a high-order method's error shows against the same method at h/8 (the late half's
// envelope over the pilot interval's). Negative control: the linear growth the pilot assumes
// alone (relief 1) misses it by more than 4x on some scene (bounded error: sine-Gordon, Duffing).
TEST(Accuracy, GrowthProbeMeasuresTheErrorsGrowth) {
  const Method *probe = nullptr, *m = nullptr;  // the fewest stages; the highest order
  for (const Method& x : Method::all()) {
    if (!x.is_explicit() || x.has_modified_kicks()) continue;
    if (!probe || x.stages() < probe->stages()) probe = &x;
    if (!m || x.order() > m->order() || (x.order() == m->order() && x.stages() < m->stages()))
      m = &x;
  }
  struct Scene {
    problems::Problem p;
    double h;  // in the method's asymptotic range
  };
  int linear_misses = 0;
  for (const auto& [p, h] : {Scene{problems::sine_gordon(32), 0.05}, Scene{problems::fpu(), 0.02},
                             Scene{problems::henon_heiles(), 0.15}, Scene{problems::duffing(), 0.1},
                             Scene{problems::stellar_orbits(), 0.5}}) {
    const System sys = problems::system(p);
    const double span = p.t_error, pilot = span / 32;
    Integrator a(*m, sys, h, p.q0, p.p0), fine(*m, sys, h / 8, p.q0, p.p0);
    double early = 0, late = 0;  // error envelopes over [0, pilot] and [span / 2, span]
    for (long k = 1, n = a.steps_until(span); k <= n; ++k) {
      a.step(1), fine.step(8);
      const double e = (a.q() - fine.q()).lpNorm<Eigen::Infinity>(), t = double(k) * h;
      if (t <= pilot * (1 + 1e-12)) early = std::max(early, e);
      if (t >= span / 2) late = std::max(late, e);
    }
    const double truth = std::min(1.0, late / early * pilot / span);
    const detail::PilotRequest r{&sys, &p.q0, &p.p0, {}, span, pilot, {}};
    const double relief = detail::growth_relief(*probe, r, 2 * h, pilot).relief;
    EXPECT_GT(relief, truth / 4) << p.key;
    EXPECT_LT(relief, truth * 4) << p.key;
    linear_misses += 1 > 4 * truth;
  }
  EXPECT_GT(linear_misses, 0);
}

TEST(Accuracy, KeepsAGivenMethodAndAGivenStep) {
  const problems::Problem p = problems::duffing();
  for (const Method& m : Method::all()) {
    if (!m.is_explicit() || m.order() != 4) continue;
    AccuracyRequest r;
    r.tol = 1e-6, r.method = std::string(m.name());
    const Solution s = solve(problems::system(p), p.q0, p.p0, 0, p.t_error, r);
    EXPECT_EQ(s.method, m.name());
    EXPECT_LE(error_of(s, (*p.exact)(p.t_error)), 3e-6) << m.name();
    break;
  }
  AccuracyRequest r;
  r.tol = 1e-6, r.h = 0.01;
  const Solution s = solve(problems::system(p), p.q0, p.p0, 0, p.t_error, r);
  EXPECT_EQ(s.h, 0.01);
  EXPECT_LE(error_of(s, (*p.exact)(p.t_error)), 3e-6) << s.method;
}

TEST(Accuracy, RefusesBadRequestsByName) {
  const problems::Problem p = problems::duffing();
  const System sys = problems::system(p);
  const auto refused = [&](AccuracyRequest r, double t_end, const char* word) {
    try {
      solve(sys, p.q0, p.p0, 0, t_end, r);
      ADD_FAILURE() << "accepted: " << word;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
    }
  };
  AccuracyRequest r;
  refused(r, 1, "tol");  // auto without tol
  r.tol = -1;
  refused(r, 1, "tol");
  r.tol = NAN;
  refused(r, 1, "tol");
  r.tol = 1e-6;
  refused(r, 0, "t_end");
  r.pilot_fraction = 2;
  refused(r, 1, "pilot_fraction");
  r.pilot_fraction = 0.1, r.safety = 0;
  refused(r, 1, "safety");
  r.safety = 0.5, r.method = "NoSuchMethod";
  refused(r, 1, "NoSuchMethod");
}

}  // namespace
}  // namespace erkn
