// The clocks of Statistics::wall_time / cpu_time and of the accuracy pilot (accuracy.cpp).
#pragma once

#include <chrono>
#include <ctime>

namespace erkn::detail {

// (Linux: CLOCK_MONOTONIC, which steady_clock reads too, so that coarse_wall_seconds compares
// with it.)
inline double wall_seconds() {
#ifdef CLOCK_MONOTONIC_COARSE
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
#else
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
#endif
}

/// wall_seconds() as of the clock's last tick (Linux: CLOCK_MONOTONIC_COARSE; it lags by up to a
/// tick, 1-4 ms, and never leads): 9 ns a read on the benchmark machine against 62-66 ns for
/// wall_seconds(). Elsewhere wall_seconds() itself.
inline double coarse_wall_seconds() {
#ifdef CLOCK_MONOTONIC_COARSE
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC_COARSE, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
#else
  return wall_seconds();
#endif
}

/// CPU time of the calling thread: an Ensemble's trajectories on other threads do not count.
inline double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

}  // namespace erkn::detail
