// Problem 3 (stellar orbits) over 10^6 steps (h = 1e-3, t in [0, 1000]): the energy error of
// every method stays bounded (the last tenth of the run is no worse than the first), while a
// method with one coefficient nudged drifts.
#include <gtest/gtest.h>

#include "problems.hpp"

namespace erkn::test {
namespace {

constexpr long kSteps = 1000000;

System stellar() { return problems::system(problems::stellar_orbits(1e-3)); }

struct Drift {
  double first, last;  // max |H - H0| over the first and the last tenth of the run
};

Drift energy_error(const Method& m) {
  Integrator run(m, stellar(), 1e-3, Eigen::Vector2d(1, 1), Eigen::Vector2d(0, 0));
  const double H0 = run.energy();
  Drift d{0, 0};
  for (long n = 1; n <= kSteps; ++n) {
    run.step();
    if (n % 100 != 0) continue;
    const double err = std::abs(run.energy() - H0);
    if (n <= kSteps / 10) d.first = std::max(d.first, err);
    if (n > kSteps - kSteps / 10) d.last = std::max(d.last, err);
  }
  return d;
}

TEST(Energy, ErrorStaysBoundedOverAMillionStepsOfProblem3) {
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(std::string(m.name()));
    const Drift d = energy_error(m);
    EXPECT_LE(d.last, 2 * d.first + 1e-14) << "first tenth " << d.first << ", last " << d.last;
  }
}

TEST(Energy, NudgedMethodDrifts) {
  const Drift d = energy_error(perturbed(Method::by_name("SERKN2s4")));
  EXPECT_GE(d.last, 5 * d.first) << "first tenth " << d.first << ", last " << d.last;
}

}  // namespace
}  // namespace erkn::test
