// The implicit stepper's fixed point on a half-spectrum basis checks the gradient and the next
// iterate on the sums it forms anyway (stage_fixed_point.hpp, checked_iterate) instead of scanning
// g and Q at every call. It must refuse what the scans refused, with the same message: a NaN or
// an infinity from the gradient at any call of a step, every fixed-point iteration included,
// names the step and a stage (stage 1 at the first call, never decreasing from call to call), and
// leaves the state, t and the counts as they were; the same run without the fault steps on
// (negative control). For every implicit registry method, circulant M and a periodic grid.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "refusals.hpp"

namespace erkn::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// Faulty (refusals.hpp) faulting entry 3.
constexpr Faulty kFaulty{.entry = 3};

// The stage a refusal names ("stage k;"), 0 if none.
int named_stage(const std::string& message) {
  const size_t at = message.rfind("stage ");
  return at == std::string::npos ? 0 : std::stoi(message.substr(at + 6));
}

void check_every_call(const Method& m, const Stiffness& M, double fault) {
  const Eigen::Index d = M.dim();
  Faulty probe = kFaulty;
  Integrator counted(m, probe.system(M), 0.05, sine_start(d, 0.1), sine_start(d, 0.7));
  counted.step();
  const long before_step = counted.statistics().gradient_evaluations;
  counted.step();
  const long calls = counted.statistics().gradient_evaluations - before_step;
  int last_stage = 1;
  for (long k = 1; k <= calls; ++k) {
    SCOPED_TRACE("call " + std::to_string(k) + " of " + std::to_string(calls));
    const std::string message = refused_second_step(m, M, kFaulty, fault, k);
    EXPECT_CONTAINS(message, "non-finite value at step 2");
    const int stage = named_stage(message);
    EXPECT_TRUE(stage >= last_stage && stage <= m.stages() && (k > 1 || stage == 1)) << message;
    last_stage = stage;
  }
}

TEST(ImplicitChecks, NonFiniteGradientAtEveryIterationIsNamedAndChangesNothing) {
  using B = GridAxis::Boundary;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(16);
  col[0] = 2, col[1] = col[15] = -1;
  const std::vector<std::pair<const char*, Stiffness>> bases{
      {"circulant", Stiffness::circulant(col)},
      {"periodic grid", Stiffness::grid({{4, 0.5, B::periodic}, {4, 0.5, B::periodic}})}};
  for (const auto& [name, M] : bases)
    for (const Method& m : Method::all())
      for (double fault : {kNaN, kInf}) {
        if (m.is_explicit() || m.kind() == Kind::rkn) continue;  // (RKN: the identity basis)
        SCOPED_TRACE(std::string(m.name()) + ", " + name);
        check_every_call(m, M, fault);
      }
}

}  // namespace
}  // namespace erkn::test
