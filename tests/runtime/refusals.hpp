// What the refusal tests share: the message of an erkn::Error, a containment check, and the
// state a refused call must leave alone.
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

}  // namespace erkn::test
