// A bounded fuzz of the API (fixed seed): random structures and sizes of M, states of random
// size with non-finite entries, extreme step sizes, through the constructor, set_state,
// set_step_size and step. Every call either succeeds or throws erkn::Error (nothing else), a
// refused call changes nothing, and an accepted state stays finite.
#include <gtest/gtest.h>

#include <limits>
#include <optional>
#include <random>

#include "problems.hpp"
#include "refusals.hpp"

namespace erkn::test {
namespace {

struct Fuzzer {
  std::mt19937 rng{20261123};
  int index(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng); }
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  }

  // Mostly ordinary values, sometimes the ones that break code.
  double value(double lo = -2, double hi = 2) {
    constexpr double kOdd[] = {std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::denorm_min(),
                               -1e300,
                               1e-300,
                               0.0};
    return index(12) == 0 ? kOdd[index(8)] : uniform(lo, hi);
  }
  double step_size() {
    constexpr double kOdd[] = {0.0,
                               -0.1,
                               1e-300,
                               1e300,
                               1e6,
                               1e-12,
                               1.0,
                               10.0,
                               std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity()};
    return index(3) == 0 ? kOdd[index(10)] : uniform(1e-3, 0.5);
  }
  Eigen::VectorXd vector(Eigen::Index d) {
    Eigen::VectorXd v(d);
    for (Eigen::Index i = 0; i < d; ++i) v[i] = value();
    return v;
  }
  Eigen::Index size(Eigen::Index d) { return index(8) == 0 ? index(6) : d; }  // (sometimes wrong)

  Stiffness stiffness(Eigen::Index d) {
    switch (index(4)) {
      case 0:
        return Stiffness::scalar(value(0, 50));
      case 1: {
        Eigen::VectorXd m = vector(d).cwiseAbs() * 20;
        if (index(10) == 0) m[0] = -1;
        return Stiffness::diagonal(m);
      }
      case 2: {
        Eigen::VectorXd col = Eigen::VectorXd::Zero(d);
        col[0] = value(0, 40);
        if (d > 1) col[1] = col[d - 1] = -std::abs(value(0, 10));
        return Stiffness::circulant(col);
      }
      default: {
        const Eigen::MatrixXd a = Eigen::MatrixXd::NullaryExpr(d, d, [&] { return value(); });
        return Stiffness::dense(index(6) == 0 ? a : Eigen::MatrixXd(a * a.transpose()));
      }
    }
  }
};

// U = sum q_i^4 / 4 + 0.3 sum q_i q_{i+1}: finite gradient for finite q.
System quartic(const Stiffness& M) {
  System s;
  s.M = M;
  s.gradient = [](const Eigen::VectorXd& q, Eigen::VectorXd& g) {
    g = q.array().cube();
    for (Eigen::Index i = 0; i + 1 < q.size(); ++i) g[i] += 0.3 * q[i + 1], g[i + 1] += 0.3 * q[i];
  };
  s.potential = [](const Eigen::VectorXd& q) {
    double u = 0.25 * q.array().pow(4).sum();
    for (Eigen::Index i = 0; i + 1 < q.size(); ++i) u += 0.3 * q[i] * q[i + 1];
    return u;
  };
  return s;
}

// Runs f: true if it succeeded, false if it threw erkn::Error; anything else fails the test.
template <class F>
bool attempt(F&& f, int& refused) {
  try {
    f();
    return true;
  } catch (const Error&) {
    ++refused;
    return false;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not an erkn::Error: " << e.what();
    return false;
  }
}

TEST(Fuzz, ApiCallsSucceedOrRefuseWithoutSideEffects) {
  Fuzzer f;
  int built = 0, refused = 0, calls = 0;
  for (int n = 0; n < 400; ++n) {
    const Method& method = Method::all()[f.index(int(Method::all().size()))];
    const Eigen::Index d = 1 + f.index(6);
    std::optional<Integrator> run;
    ++calls;
    attempt(
        [&] {
          const System s = quartic(f.stiffness(d));
          run.emplace(method, s, f.step_size(), f.vector(f.size(d)), f.vector(f.size(d)));
        },
        refused);
    if (!run) continue;
    ++built;
    for (int k = 0; k < 6; ++k) {
      SCOPED_TRACE(std::string(method.name()) + ", case " + std::to_string(n));
      const Snapshot before(*run);
      bool ok = false;
      ++calls;
      switch (f.index(3)) {
        case 0:
          ok = attempt([&] { run->step(); }, refused);
          break;
        case 1: {
          const Eigen::Index m = f.size(d);
          ok = attempt([&] { run->set_state(f.vector(m), f.vector(m), f.value(0, 10)); }, refused);
          break;
        }
        default:
          ok = attempt([&] { run->set_step_size(f.step_size()); }, refused);
      }
      if (!ok) before.expect_same(*run);
      EXPECT_TRUE(run->q().allFinite() && run->p().allFinite() && std::isfinite(run->t()));
      EXPECT_EQ(run->q().size(), before.q.size());
    }
  }
  std::cout << calls << " calls (" << built << " integrators built), " << refused
            << " refused with erkn::Error\n";
  EXPECT_GT(built, 50);    // the fuzz reaches past the constructor
  EXPECT_GT(refused, 50);  // and its odd inputs are refused
}

}  // namespace
}  // namespace erkn::test
