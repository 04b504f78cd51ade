// What the refusal tests share: the message of an erkn::Error, a containment check, the state a
// refused call must leave alone, and a gradient that fails on request.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <erkn/erkn.hpp>
#include <functional>
#include <string>

namespace erkn::test {

/// The message of the erkn::Error f throws ("" if it throws none).
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_CONTAINS(text, part)                          \
  EXPECT_NE(std::string(text).find(part), std::string::npos) \
      << "'" << (text) << "' lacks '" << (part) << "'"

/// Everything a refused call must leave alone.
struct Snapshot {
  Eigen::VectorXd q, p;
  double t, h;
  long steps;
  explicit Snapshot(const Integrator& r)
      : q(r.q()), p(r.p()), t(r.t()), h(r.h()), steps(r.statistics().steps) {}
  void expect_same(const Integrator& r) const {
    EXPECT_EQ(r.q(), q);
    EXPECT_EQ(r.p(), p);
    EXPECT_EQ(r.t(), t);
    EXPECT_EQ(r.h(), h);
    EXPECT_EQ(r.statistics().steps, steps);
  }
};

/// sin q, whose `fault` replaces entry `entry` of the gradient at call number `at` (1-based,
/// counted from `counting` on); with `hessian`, the Hessian-vector product of modified kicks too.
struct Faulty {
  double fault = 0;
  long at = 0, calls = 0;
  bool counting = false;
  Eigen::Index entry = 0;
  bool hessian = false;
  System system(const Stiffness& M) {
    System s;
    s.M = M;
    s.gradient = [this](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
      g = q.array().sin().matrix();
      if (counting && ++calls == at) g[entry] = fault;
    };
    if (hessian)
      s.hessian_vector_product = [](const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                    Eigen::VectorXd& hv) {
        hv = (q.array().cos() * v.array()).matrix();
      };
    return s;
  }
};

/// sin(x + phase) at d points x in [0, 1]: the faulty tests' start.
inline Eigen::VectorXd sine_start(Eigen::Index d, double phase) {
  return (Eigen::VectorXd::LinSpaced(d, 0, 1).array() + phase).sin().matrix();
}

/// Two steps of m (h = 0.05) on M from sine_start, the second with f's `fault` at its gradient
/// call k: returns the refusal's message, having checked that the refused step left the state,
/// t and the counts as they were, and that the same step with a finite value steps on (the
/// negative control).
inline std::string refused_second_step(const Method& m, const Stiffness& M, Faulty f, double fault,
                                       long k) {
  const Eigen::Index d = M.dim();
  f.fault = fault, f.at = k;
  Integrator run(m, f.system(M), 0.05, sine_start(d, 0.1), sine_start(d, 0.7));
  run.step();
  const Snapshot before(run);
  const long evaluations = run.statistics().gradient_evaluations;
  f.counting = true;
  const std::string message = error_of([&] { run.step(); });
  before.expect_same(run);
  EXPECT_EQ(run.statistics().gradient_evaluations, evaluations);
  f.fault = 0.5, f.calls = 0;  // negative control: a finite value steps on
  EXPECT_NO_THROW(run.step());
  EXPECT_EQ(run.statistics().steps, before.steps + 1);
  return message;
}

}  // namespace erkn::test
