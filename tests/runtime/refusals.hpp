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

}  // namespace erkn::test
