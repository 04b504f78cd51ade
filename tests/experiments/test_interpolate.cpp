// Cost to tolerance: exact on a power law, never extrapolated.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "interpolate.hpp"

namespace ex {
namespace {

std::vector<CurvePoint> power_law(std::vector<double> costs, int order) {
  std::vector<CurvePoint> pts;
  for (double c : costs) pts.push_back({c, std::pow(c, -order)});
  return pts;
}

TEST(CostToTolerance, ExactOnAPowerLaw) {
  const auto pts = power_law({10, 20, 40, 80, 160}, 4);
  const double tol = std::pow(33.0, -4);
  ASSERT_TRUE(cost_to_tolerance(pts, tol));
  EXPECT_NEAR(*cost_to_tolerance(pts, tol), 33.0, 1e-9);
}

TEST(CostToTolerance, NeverExtrapolates) {
  const auto pts = power_law({10, 20, 40}, 2);
  EXPECT_FALSE(cost_to_tolerance(pts, 1e-9));  // finer than the finest run
  EXPECT_FALSE(cost_to_tolerance(pts, 1.0));   // coarser than the coarsest run
}

TEST(CostToTolerance, UsesTheFirstCrossing) {
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<CurvePoint> pts = {{1, inf}, {2, 1e-2}, {4, 1e-4}, {8, 1e-3}, {16, 1e-8}};
  EXPECT_NEAR(*cost_to_tolerance(pts, 1e-3), std::sqrt(8.0), 1e-12);
}

TEST(CostToTolerance, AfterAFailedRunTakesTheCheapestRunWithinTolerance) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(*cost_to_tolerance({{1, inf}, {2, 1e-9}, {4, 1e-10}}, 1e-6), 2.0);
}

TEST(CostToTolerance, ACheaperRunWithinToleranceWins) {
  // Cost falls at the finer step (e.g. no Newton fallback there): the measured run is cheaper.
  const std::vector<CurvePoint> pts = {{50, 1e-5}, {40, 1e-7}, {8, 1e-8}};
  EXPECT_EQ(*cost_to_tolerance(pts, 1e-6), 8.0);
}

}  // namespace
}  // namespace ex
