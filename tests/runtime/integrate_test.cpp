// integrate(t_end, observer) on the grid takes whole steps, reports every one, and matches step()
// (off-grid ends and output times: output_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <thread>

#include "clock.hpp"
#include "problems.hpp"

namespace erkn::test {
namespace {

TEST(Integrate, ObserverSeesEveryStepAndTheResultEqualsSteppingByHand) {
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::Vector3d q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  Integrator a(m, polynomial_system(), 0.1, q0, p0), b(m, polynomial_system(), 0.1, q0, p0);
  std::vector<double> times;
  a.integrate(3.0, [&](double t, const Eigen::VectorXd& q, const Eigen::VectorXd&) {
    times.push_back(t);
    EXPECT_EQ(q.size(), 3);
  });
  ASSERT_EQ(times.size(), 30u);
  for (size_t k = 0; k < times.size(); ++k) EXPECT_DOUBLE_EQ(times[k], 0.1 * double(k + 1));
  for (int k = 0; k < 30; ++k) b.step();
  EXPECT_EQ(a.q(), b.q());
  EXPECT_EQ(a.p(), b.p());
  EXPECT_EQ(a.t(), 3.0);
  EXPECT_EQ(a.statistics().steps, 30);
  EXPECT_GE(a.statistics().gradient_evaluations, 30 * m.stages());
}

TEST(Integrate, SetStateAndSetStepSizeRestartFromTheNewValues) {
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::Vector3d q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  Integrator a(m, polynomial_system(), 0.1, q0, p0), b(m, polynomial_system(), 0.05, q0, p0);
  a.integrate(1.0);
  a.set_state(q0, p0, 0.0);
  a.set_step_size(0.05);
  a.integrate(1.0);
  b.integrate(1.0);
  EXPECT_EQ(a.q(), b.q());
  EXPECT_EQ(a.t(), 1.0);
}

// integrate(t_end) keeps the state in M's eigen coordinates: it transforms back only when q() or
// p() asks (once), and an observer's calls load it once each (the negative control: the same
// steps with an observer every step load it every step); the result is bit-identical either way.
// A processed method loads it (pi) once where each call ends, which q() and p() then reuse.
TEST(Integrate, WithoutAnObserverTheStateIsTransformedBackOnlyWhenAskedFor) {
  const Eigen::Vector3d q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  for (const Method& m : Method::all()) {
    SCOPED_TRACE(m.name());
    Integrator quiet(m, polynomial_system(), 0.1, q0, p0);
    Integrator watched(m, polynomial_system(), 0.1, q0, p0);
    quiet.integrate(2.95);                         // (29 steps and a shorter one)
    EXPECT_EQ(quiet.statistics().state_loads, 1);  // (by step_to, for the shorter step)
    long calls = 0;
    watched.integrate(2.95,
                      [&](double, const Eigen::VectorXd&, const Eigen::VectorXd&) { ++calls; });
    EXPECT_EQ(calls, 30);
    EXPECT_EQ(watched.statistics().state_loads, 29);  // (the shorter step's stepper has it)
    EXPECT_EQ(quiet.q(), watched.q());
    EXPECT_EQ(quiet.p(), watched.p());
    EXPECT_EQ(quiet.statistics().steps, watched.statistics().steps);
    quiet.integrate(4.05);                       // (11 steps on the grid that restarted at 2.95)
    const long read = m.is_processed() ? 1 : 0;  // (where the call ends)
    EXPECT_EQ(quiet.statistics().state_loads, 1 + read);
    const long loads = quiet.statistics().state_loads;
    quiet.q(), quiet.p(), quiet.q();
    EXPECT_EQ(quiet.statistics().state_loads, loads + 1 - read);
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// wall_time counts what integrate() spends (the observer's sleep included) once, even through
// the nested integrate of output times; cpu_time does not count sleeping; step() is not timed.
TEST(Integrate, WallAndCpuTimeCountEachIntegrateCallOnce) {
  const Method& m = Method::by_name("SERKN2s4");
  const Eigen::Vector3d q0(0.6, -0.4, 0.3), p0(0.2, 0.5, -0.7);
  Integrator a(m, polynomial_system(), 0.1, q0, p0);
  const auto nap = [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  };
  const auto start = std::chrono::steady_clock::now();
  a.integrate(1.0, Eigen::VectorXd::LinSpaced(5, 0.05, 0.85), nap);
  const double outside = seconds_since(start);
  const Statistics& s = a.statistics();
  EXPECT_GE(s.wall_time, 0.05);              // five naps of 10 ms
  EXPECT_LE(s.wall_time, outside);           // counted once, not once per nested integrate
  EXPECT_LT(s.cpu_time, 0.5 * s.wall_time);  // asleep, not computing
  EXPECT_GE(s.cpu_time, 0.0);
  const double before = s.wall_time;
  a.step();
  EXPECT_EQ(s.wall_time, before);
  EXPECT_THROW(a.step(-1), Error);
  EXPECT_EQ(a.statistics().steps, 11);
  a.step(1000);
  EXPECT_GT(s.wall_time, before);
  EXPECT_EQ(a.statistics().steps, 1011);
}

// integrate(t_end) without an observer is timed too (it was not: wall_time stayed 0).
TEST(Integrate, IntegrateToAnEndTimeIsTimed) {
  Integrator a(Method::by_name("SERKN2s4"), polynomial_system(), 0.01, Eigen::Vector3d(0.6, 0, 0),
               Eigen::Vector3d(0, 0.5, 0));
  const auto start = std::chrono::steady_clock::now();
  a.integrate(100.0);
  const double outside = seconds_since(start);
  EXPECT_GT(a.statistics().wall_time, 0.0);
  EXPECT_LE(a.statistics().wall_time, outside);
  EXPECT_GT(a.statistics().cpu_time, 0.0);
  EXPECT_LE(a.statistics().cpu_time, a.statistics().wall_time + 1e-3);
  // A short call (10 steps x 3 < kCpuClockWork) counts its wall time as CPU time.
  const Statistics before = a.statistics();
  a.integrate(100.1);
  const double wall = a.statistics().wall_time - before.wall_time;
  EXPECT_GT(wall, 0.0);
  EXPECT_NEAR(a.statistics().cpu_time - before.cpu_time, wall, 1e-12);
}

// The coarse clock short calls look at before observer calls lags the wall clock (by up to a
// tick) but never leads it, so a call never switches to the CPU clock before kCpuClockDelay.
// (Negative control: a coarse clock of another epoch, CLOCK_REALTIME_COARSE, leads it.)
TEST(Integrate, TheCoarseClockNeverLeadsTheWallClock) {
  double largest_lag = 0;
  for (int k = 0; k < 20000; ++k) {
    const double coarse = detail::coarse_wall_seconds(), after = detail::wall_seconds();
    EXPECT_LE(coarse, after);
    largest_lag = std::max(largest_lag, after - coarse);
  }
  EXPECT_LT(largest_lag, 0.05);  // (a tick is 1-4 ms; 50 ms allows for preemption)
#ifdef CLOCK_REALTIME_COARSE
  timespec ts{};
  clock_gettime(CLOCK_REALTIME_COARSE, &ts);
  EXPECT_GT(double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec), detail::wall_seconds());
#endif
}

// A short call with output times or an observer reads no CPU clock while it lasts less than
// kCpuClockDelay (its wall time is its CPU time), and a refused call adds no time at all.
TEST(Integrate, ShortCallsWithObserversCountWallTimeUntilTheDelay) {
  Integrator a(Method::by_name("SERKN2s4"), polynomial_system(), 0.01, Eigen::Vector3d(0.6, 0, 0),
               Eigen::Vector3d(0, 0.5, 0));
  const auto nothing = [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {};
  int under_the_delay = 0;
  for (int k = 0; k < 20; ++k) {  // (a preempted call may outlast the delay: it reads the clock)
    const Statistics before = a.statistics();
    const Eigen::VectorXd times = Eigen::VectorXd::Constant(1, a.t() + 0.025);
    if (k % 2 == 0)
      a.integrate(a.t() + 0.05, times, nothing);
    else
      a.integrate(a.t() + 0.05, nothing);
    const double wall = a.statistics().wall_time - before.wall_time;
    EXPECT_GT(wall, 0.0);
    if (wall >= Integrator::kCpuClockDelay) continue;
    ++under_the_delay;
    EXPECT_EQ(a.statistics().cpu_time - before.cpu_time, wall);
  }
  EXPECT_GT(under_the_delay, 0);
  const Statistics before = a.statistics();
  EXPECT_THROW(a.integrate(a.t() - 1, nothing), Error);
  EXPECT_THROW(a.integrate(a.t() - 1, Eigen::VectorXd::Zero(1), nothing), Error);
  EXPECT_EQ(a.statistics().wall_time, before.wall_time);
  EXPECT_EQ(a.statistics().cpu_time, before.cpu_time);
}

// CPU seconds of the calling thread, the clock Statistics::cpu_time reads.
double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

// An observer that computes for 10 ms of its own CPU time at each of 5 steps: cpu_time counts
// those 50 ms (it would stay near 0 if it were not measured) and never exceeds wall_time. (CPU
// rather than wall time per call: on a loaded machine 10 ms of wall time can be 2 ms of CPU.)
TEST(Integrate, CpuTimeCountsComputation) {
  Integrator a(Method::by_name("SERKN2s4"), polynomial_system(), 0.1, Eigen::Vector3d(0.6, 0, 0),
               Eigen::Vector3d(0, 0.5, 0));
  a.integrate(0.5, [](double, const Eigen::VectorXd&, const Eigen::VectorXd&) {
    const double start = thread_cpu_seconds();
    while (thread_cpu_seconds() - start < 0.01) {
    }
  });
  EXPECT_GE(a.statistics().cpu_time, 0.05);
  EXPECT_LE(a.statistics().cpu_time, a.statistics().wall_time + 1e-3);
}

}  // namespace
}  // namespace erkn::test
