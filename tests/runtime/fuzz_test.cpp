// A bounded fuzz of the API (fixed seed): random structures and sizes of M, states of random
// size with non-finite entries, extreme step sizes and times, through the constructor,
// set_state, set_step_size, step, integrate (with and without output times) and state_at. Every
// call either succeeds or throws erkn::Error (nothing else), a refused call changes nothing, a
// run that fails on the way keeps its steps, and an accepted state stays finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
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
  s.hessian_vector_product = [](const Eigen::VectorXd& q, const Eigen::VectorXd& v,
                                Eigen::VectorXd& hv) {
    hv = 3 * q.array().square() * v.array();
    for (Eigen::Index i = 0; i + 1 < q.size(); ++i)
      hv[i] += 0.3 * v[i + 1], hv[i + 1] += 0.3 * v[i];
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

// A time to integrate to from t(): mostly within 40 steps, sometimes one that must be refused.
double end_time(Fuzzer& f, const Integrator& run) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const double odd[] = {std::numeric_limits<double>::quiet_NaN(), kInf, -kInf, run.t() - run.h(),
                        run.t() + 1e300};
  return f.index(5) == 0 ? odd[f.index(5)] : run.t() + run.h() * f.uniform(0, 40);
}

// integrate(t_end), with output times or without: a call refused before its first step changes
// nothing; one that fails on the way keeps the steps it took (t() between the start and t_end),
// or the blow-up guard returns to its last passed check (possibly made before the call);
// one that succeeds ends at t_end having called the observer once per output time, in order.
void fuzz_integrate(Fuzzer& f, Integrator& run, int& refused) {
  const Snapshot before(run);
  const double t_end = end_time(f, run);
  std::vector<double> times(size_t(f.index(4)));
  for (double& tau : times)
    tau = f.index(6) == 0 ? f.value() : run.t() + (t_end - run.t()) * f.uniform(0, 1);
  if (f.index(3) != 0) std::sort(times.begin(), times.end());
  std::vector<double> seen;
  const bool with_times = f.index(2) == 0;
  const bool ok = attempt(
      [&] {
        if (!with_times) return run.integrate(t_end);
        const Eigen::Map<const Eigen::VectorXd> at(times.data(), Eigen::Index(times.size()));
        run.integrate(t_end, at,
                      [&](double tau, const auto&, const auto&) { seen.push_back(tau); });
      },
      refused);
  if (ok) {
    // t_end itself off the grid; on it up to the round-off window, the grid point t0 + n h.
    const double window = 4 * std::numeric_limits<double>::epsilon() *
                          std::max({std::abs(before.t), std::abs(t_end), run.h()});
    EXPECT_LE(std::abs(run.t() - t_end), window);
    if (with_times) EXPECT_EQ(seen, times);
  } else if (run.statistics().steps == before.steps) {
    before.expect_same(run);
  } else if (run.statistics().steps < before.steps) {
    // The blow-up guard restored the state of its last passed check, made before this call
    // (Options::blowup_guard in erkn/integrator.hpp): an earlier time than the call's start.
    EXPECT_LT(run.t(), before.t);
  } else {
    EXPECT_GT(run.t(), before.t);
    EXPECT_LE(run.t(), t_end);
  }
}

// state_at never changes the integrator's state, whether it succeeds or not.
void fuzz_state_at(Fuzzer& f, Integrator& run, int& refused) {
  const Snapshot before(run);
  Eigen::VectorXd q, p;
  const double t = f.index(4) == 0 ? f.value() : run.t() + run.h() * f.uniform(-0.2, 1.2);
  if (attempt([&] { run.state_at(t, q, p); }, refused))
    EXPECT_TRUE(q.allFinite() && p.allFinite() && q.size() == before.q.size());
  before.expect_same(run);
}

// One random mutating call on run; a refused call changes nothing.
void fuzz_call(Fuzzer& f, Integrator& run, Eigen::Index d, int& refused) {
  const Snapshot before(run);
  bool ok = true;
  switch (f.index(5)) {
    case 0:
      ok = attempt([&] { run.step(); }, refused);
      break;
    case 1: {
      const Eigen::Index m = f.size(d);
      ok = attempt([&] { run.set_state(f.vector(m), f.vector(m), f.value(0, 10)); }, refused);
      break;
    }
    case 2:
      ok = attempt([&] { run.set_step_size(f.step_size()); }, refused);
      break;
    case 3:
      return fuzz_integrate(f, run, refused);
    default:
      return fuzz_state_at(f, run, refused);
  }
  if (!ok) before.expect_same(run);
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
    for (int k = 0; k < 6; ++k, ++calls) {
      SCOPED_TRACE(std::string(method.name()) + ", case " + std::to_string(n));
      fuzz_call(f, *run, d, refused);
      EXPECT_TRUE(run->q().allFinite() && run->p().allFinite() && std::isfinite(run->t()));
      EXPECT_EQ(run->q().size(), d);
    }
  }
  std::cout << calls << " calls (" << built << " integrators built), " << refused
            << " refused with erkn::Error\n";
  EXPECT_GT(built, 50);    // the fuzz reaches past the constructor
  EXPECT_GT(refused, 50);  // and its odd inputs are refused
}

}  // namespace
}  // namespace erkn::test
