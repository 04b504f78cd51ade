// The explicit stepper's finiteness checks ride on its passes over arrays (explicit_stepper.hpp,
// nonfinite_bits): a stage's q as the flow writes it, the gradient as the kick reads it, p after
// the last kick (with a fixed dimension: in registers). They must refuse what the separate checks
// refused, with the same messages, on every eigenbasis of M the array passes run in, for every
// explicit method: a non-finite value from the gradient (named by stage), a stage that overflows, a
// p that overflows; each leaves the state, t and the counts as they were, and the same run without
// the fault steps on (negative control).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "problems.hpp"
#include "refusals.hpp"

namespace erkn::test {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Basis {
  const char* name;
  Stiffness M;
};

// One of each eigenbasis with arrays of a dynamic size (d above the fixed-size limit of 4), and
// the identity basis at d = 2 and 4, whose steps run on fixed-size values in registers (their
// checks: the stage's Q and g at the gradient, p as the last kick makes it).
std::vector<Basis> bases() {
  using B = GridAxis::Boundary;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(16);
  col[0] = 2, col[1] = col[15] = -1;
  Eigen::VectorXd col3(3);
  col3 << 2, -1, -1;
  return {{"diagonal (identity basis)", Stiffness::diagonal(Eigen::VectorXd::LinSpaced(6, 1, 6))},
          {"dense", Stiffness::dense(rotated(Eigen::Vector3d(1, 2, 3)))},
          {"circulant N = 3 (Fourier basis)", Stiffness::circulant(col3)},
          {"circulant N = 16 (half spectrum)", Stiffness::circulant(col)},
          {"Dirichlet grid (real transform)",
           Stiffness::grid({{4, 0.5, B::dirichlet}, {3, 0.5, B::dirichlet}})},
          {"periodic grid (half spectrum)",
           Stiffness::grid({{4, 0.5, B::periodic}, {4, 0.5, B::periodic}})},
          {"diagonal d = 2 (fixed size)", Stiffness::diagonal(Eigen::Vector2d(1, 2))},
          {"diagonal d = 4 (fixed size)", Stiffness::diagonal(Eigen::Vector4d(1, 2, 3, 4))}};
}

// Arrays of more than 256 KiB, where a step of one pass overwrites its start when it cannot fail
// (explicit_stepper.hpp, in_place_steps).
std::vector<Basis> large_bases() {
  using B = GridAxis::Boundary;
  Eigen::VectorXd col = Eigen::VectorXd::Zero(1 << 16);
  col[0] = 2, col[1] = col[col.size() - 1] = -1;
  return {{"circulant N = 65536 (half spectrum, steps in place)", Stiffness::circulant(col)},
          {"periodic grid 256 x 256 (half spectrum, steps in place)",
           Stiffness::grid({{256, 0.5, B::periodic}, {256, 0.5, B::periodic}})}};
}

std::vector<Method> explicit_methods() {
  std::vector<Method> out;
  for (const Method& m : Method::all())
    if (m.is_explicit()) out.push_back(m);
  return out;
}

// Faulty (refusals.hpp) with the Hessian-vector product the modified kicks call.
constexpr Faulty kFaulty{.hessian = true};

// The k-th gradient call of a step is the stage that named it: stage k, or k + 1 when the
// method reuses the last gradient of the previous step (FSAL: one call fewer per step).
TEST(ExplicitChecks, NonFiniteGradientAtEveryStageIsNamedAndChangesNothing) {
  for (const Basis& basis : bases())
    for (const Method& m : explicit_methods())
      for (double fault : {kNaN, kInf}) {
        SCOPED_TRACE(std::string(basis.name) + ", " + std::string(m.name()));
        const Eigen::Index d = basis.M.dim();
        Faulty probe = kFaulty;
        Integrator counted(m, probe.system(basis.M), 0.05, sine_start(d, 0.1), sine_start(d, 0.7));
        counted.step();
        const long iterations = counted.statistics().stage_iterations;
        counted.step();  // (its gradient calls: its stage iterations; a processed method's pi not)
        const long calls = counted.statistics().stage_iterations - iterations;
        const int shift = calls == m.stages() - 1 ? 1 : 0;
        for (long k = 1; k <= calls; ++k) {
          const std::string message = refused_second_step(m, basis.M, kFaulty, fault, k);
          EXPECT_CONTAINS(message, "non-finite value at step 2");
          EXPECT_CONTAINS(message, "stage " + std::to_string(k + shift) + ";");
        }
      }
}

// integrate() runs its steps in batches inside the stepper (StepperBase::steps): a step that fails
// within one keeps the steps before it, as a failed step() does. A NaN at the first gradient call
// of step 6 of a 40-step integrate, or the gradient's own exception there: the error names step
// 6 (the NaN); t, the state (bit for bit) and the counts are those of a fault-free run after 5
// steps. Negative control: a finite value there runs to the end. (The large bases' steps 2-5
// are in place.)
TEST(ExplicitChecks, AFailedStepWithinIntegrateKeepsTheStepsBefore) {
  std::vector<Basis> cases = large_bases();
  cases.insert(cases.begin(), {bases()[0], bases()[3]});
  for (const Basis& basis : cases)
    for (const Method& m : explicit_methods()) {
      SCOPED_TRACE(std::string(basis.name) + ", " + std::string(m.name()));
      const Eigen::Index d = basis.M.dim();
      const double h = 0.05;
      Faulty clean = kFaulty;
      Integrator five(m, clean.system(basis.M), h, sine_start(d, 0.1), sine_start(d, 0.7));
      const long built = five.statistics().gradient_evaluations;  // (a processed method's pi^-1)
      five.step(5);  // (then a processed method's pi: the state read where the steps end)
      const long evaluations = built + five.statistics().stage_iterations;  // (before step 6's)
      for (double fault : {kNaN, kInf, 0.5}) {  // (kInf: the gradient throws)
        Faulty f = kFaulty;
        f.fault = fault, f.at = evaluations + 1, f.counting = true;
        System s = f.system(basis.M);
        if (fault == kInf)
          s.gradient = [g = s.gradient](const Eigen::VectorXd& q, Eigen::VectorXd& out) {
            g(q, out);
            if (!std::isfinite(out[0])) throw std::runtime_error("the user's own error");
          };
        Integrator run(m, s, h, sine_start(d, 0.1), sine_start(d, 0.7));
        std::string message;
        try {
          run.integrate(40 * h);
        } catch (const std::exception& e) {
          message = e.what();
        }
        if (fault == 0.5) {  // negative control
          EXPECT_EQ(message, "");
          EXPECT_EQ(run.statistics().steps, 40);
          continue;
        }
        EXPECT_CONTAINS(message,
                        fault == kInf ? "the user's own error" : "non-finite value at step 6");
        EXPECT_EQ(run.statistics().steps, 5);
        EXPECT_EQ(run.statistics().gradient_evaluations, five.statistics().gradient_evaluations);
        EXPECT_EQ(run.t(), five.t());
        EXPECT_EQ(run.q(), five.q());
        EXPECT_EQ(run.p(), five.p());
      }
    }
}

// A gradient of -1e308 in every entry: within a few steps p overflows (or the next stage does);
// the step is refused naming it, and nothing changes. Negative control: -1e150 steps on (on the
// large bases, in place from the second step: |p| and the force below 2^600).
TEST(ExplicitChecks, OverflowingKickIsRefusedAndChangesNothing) {
  std::vector<Basis> cases = bases();
  for (const Basis& b : large_bases()) cases.push_back(b);
  for (const Basis& basis : cases)
    for (const Method& m : explicit_methods()) {
      SCOPED_TRACE(std::string(basis.name) + ", " + std::string(m.name()));
      const Eigen::Index d = basis.M.dim();
      double size = -1e150;
      System s = Faulty(kFaulty).system(basis.M);
      s.gradient = [&size](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
        g = (q.array().sin() + size).matrix();
      };
      Options unguarded;  // (the guard would return to the start: the energy grows too far)
      unguarded.blowup_guard = false;
      Integrator run(m, s, 1.0, sine_start(d, 0.1), sine_start(d, 0.7), unguarded);
      EXPECT_NO_THROW(run.step(2));
      size = -1e308;
      std::string message;
      for (int n = 0; n < 8 && message.empty(); ++n) {
        // (a processed method's state is pi of its kernel's, and pi kicks with the gradient too:
        // pi may be what overflows, refused naming the processor; reading the state never fails)
        EXPECT_EQ(error_of([&] { run.q(); }), "");
        const Snapshot before(run);
        message = error_of([&] { run.step(); });
        if (message.empty()) continue;
        EXPECT_CONTAINS(message, "step " + std::to_string(before.steps + 1));
        EXPECT_TRUE(message.find("non-finite") != std::string::npos ||
                    message.find("not finite") != std::string::npos)
            << message;
        if (message.find("processor pi ") != std::string::npos) EXPECT_TRUE(m.is_processed());
        before.expect_same(run);
      }
      EXPECT_FALSE(message.empty());
    }
}

// U = 0 and a state near the largest double: the transform or the first flow overflows, so a stage
// is not finite, caught before the gradient is called (which would throw). Negative control: the
// state 1e8 times smaller (still above kStageBound, explicit_passes.hpp: its stages are scanned).
TEST(ExplicitChecks, OverflowingStageIsRefusedBeforeTheGradient) {
  for (const Basis& basis : bases())
    for (const Method& m : explicit_methods()) {
      SCOPED_TRACE(std::string(basis.name) + ", " + std::string(m.name()));
      const Eigen::Index d = basis.M.dim();
      System s;
      s.M = basis.M;
      s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
        if (!q.allFinite()) throw Error("the gradient was called with a non-finite q");
        g.setZero(q.size());
      };
      s.hessian_vector_product = [](const Eigen::VectorXd&, const Eigen::VectorXd& v,
                                    Eigen::VectorXd& hv) { hv.setZero(v.size()); };
      const Eigen::VectorXd big = Eigen::VectorXd::Constant(d, 1.79e308);
      Options unguarded;  // (the guard would stop first: the state's energy overflows)
      unguarded.blowup_guard = false;
      if (m.is_processed()) {  // pi^-1 kicks the state before the kernel's first stage
        EXPECT_CONTAINS(error_of([&] { Integrator(m, s, 1.0, big, big, unguarded); }),
                        "the processor pi^-1 of " + std::string(m.name()));
        EXPECT_NO_THROW(Integrator(m, s, 1.0, big / 1e8, big / 1e8, unguarded).step());
        continue;
      }
      Integrator run(m, s, 1.0, big, big, unguarded);
      const std::string message = error_of([&] { run.step(); });
      EXPECT_CONTAINS(message, "step 1");  // (the gradient's own error would not say so)
      EXPECT_TRUE(message.find("is not finite") != std::string::npos ||
                  message.find("non-finite") != std::string::npos)
          << message;
      EXPECT_EQ(run.q(), big);
      EXPECT_EQ(run.statistics().steps, 0);
      Integrator small(m, s, 1.0, big / 1e8, big / 1e8, unguarded);
      EXPECT_NO_THROW(small.step());
    }
}

}  // namespace
}  // namespace erkn::test
